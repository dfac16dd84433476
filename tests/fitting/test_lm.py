"""The projected Levenberg-Marquardt solver (vcor.fitting.spectrum.lm) with and without geodesic
acceleration (Transtrum & Sethna 2012, arXiv:1201.5885): the finite-difference curvature against its
analytic value, the same minimum in fewer iterations on problems with a known minimum, and the box
respected with the acceleration on."""

import numpy as np
import pytest

from vcor.fitting.spectrum.lm import GEODESIC_ALPHA, GEODESIC_H, curvature_gradient, levenberg_marquardt

#: sample times (s) and true parameters (amplitude Pa, rate 1/s, offset Pa) of the exponential-decay fit
T = np.linspace(0.0, 4.0, 30)
DECAY = np.array([2.0, 1.5, 0.3])


#: Rosenbrock's valley as residuals (A (x2 - x1^2), 1 - x1): minimum (1, 1), a parabolic valley of width
#: ~1/A; the classic function has A = 10, the narrower valleys are those a plain step crosses in zig-zags
VALLEYS = (100.0, 1000.0)


def _rosenbrock(A):
    def value(x):
        return np.array([A * (x[1] - x[0] ** 2), 1.0 - x[0]])

    def jacobian(x):
        return np.array([[-2.0 * A * x[0], A], [-1.0, 0.0]])
    return value, jacobian


def _decay(x):
    return x[0] * np.exp(-x[1] * T) + x[2] - (DECAY[0] * np.exp(-DECAY[1] * T) + DECAY[2])


def _decay_jacobian(x):
    e = np.exp(-x[1] * T)
    return np.column_stack([e, -x[0] * T * e, np.ones_like(T)])


def _solve(value, jacobian, x0, *, geodesic, lo=None, hi=None, seen=None):
    """levenberg_marquardt on sum r^2 (``seen`` collects every point the cost is evaluated at)."""
    def cost(x):
        if seen is not None:
            seen.append(x.copy())
        r = value(x)
        return float(r @ r), r

    def normal(x, r):
        J = jacobian(x)
        return J.T @ J, J.T @ r

    def curvature(x, r, v):
        return curvature_gradient(value, jacobian(x), x, r, v, lo=lo, hi=hi)

    return levenberg_marquardt(cost, normal, x0, lo=lo, hi=hi, max_iter=2000, tol=1e-20,
                               curvature=curvature if geodesic else None)


def test_the_finite_difference_curvature_is_exact_for_a_quadratic_residual():
    """For r quadratic in x the difference (2/h)((r(x+hv) - r)/h - Jv) is r_vv exactly: J^T r_vv matches the
    analytic value to rounding, for any h; clipped to a box, x + hv is evaluated inside it."""
    rng = np.random.default_rng(3)
    Q = rng.standard_normal((5, 3, 3))
    Q = Q + Q.transpose(0, 2, 1)
    L = rng.standard_normal((5, 3))

    def value(x):
        return L @ x + 0.5 * np.einsum("kij,i,j->k", Q, x, x)

    x, v = rng.standard_normal(3), rng.standard_normal(3)
    J = L + np.einsum("kij,j->ki", Q, x)
    exact = J.T @ np.einsum("kij,i,j->k", Q, v, v)
    for h in (GEODESIC_H, 1.0):
        got = curvature_gradient(value, J, x, value(x), v, h=h)
        assert np.allclose(got, exact, rtol=1e-9, atol=1e-9 * np.abs(exact).max())
    seen = []
    curvature_gradient(lambda y: seen.append(y) or value(y), J, x, value(x), 1e3 * v, lo=x - 1.0, hi=x + 1.0)
    assert np.all(np.abs(seen[0] - x) <= 1.0 + 1e-12)


@pytest.mark.parametrize("A", VALLEYS)
@pytest.mark.parametrize("x0", [(-1.2, 1.0), (-1.5, 3.0), (2.0, -1.0), (0.0, 0.0)])
def test_acceleration_reaches_the_same_minimum_in_fewer_iterations(A, x0):
    """Rosenbrock's narrow valleys from four starts: both solvers converge to the known minimum (1, 1)
    within 1e-10, the accelerated one in fewer iterations (the curved valley is what the acceleration
    follows; on the classic A = 10 the two take about as many)."""
    value, jacobian = _rosenbrock(A)
    x_plain, n_plain, ok_plain = _solve(value, jacobian, np.array(x0), geodesic=False)
    x_geo, n_geo, ok_geo = _solve(value, jacobian, np.array(x0), geodesic=True)
    print(f"\nA {A:g}, start {x0}: plain {n_plain} iterations, geodesic {n_geo} (alpha {GEODESIC_ALPHA})")
    assert ok_plain and ok_geo
    assert np.allclose(x_plain, 1.0, rtol=0, atol=1e-10) and np.allclose(x_geo, 1.0, rtol=0, atol=1e-10)
    assert n_geo < n_plain


def test_the_decay_fit_reaches_its_known_minimum_with_acceleration():
    """A noise-free exponential decay from a rate 5x too high: the accelerated solver converges to the true
    parameters within 1e-10."""
    x, _, ok = _solve(_decay, _decay_jacobian, np.array([0.5, 8.0, 0.0]), geodesic=True)
    assert ok and np.allclose(x, DECAY, rtol=0, atol=1e-10)


def test_the_box_holds_with_acceleration():
    """The decay rate bounded below the true one (<= 1 1/s): with the acceleration on, every point the cost
    is evaluated at lies in the box, the rate ends on its bound (an active variable, held there), and the
    constrained minimum is the plain solver's within 1e-8, reached along another path."""
    lo, hi = np.array([0.0, 0.1, -1.0]), np.array([10.0, 1.0, 1.0])
    x0 = np.array([5.0, 0.5, -0.5])
    seen = []
    x_geo, _, ok_geo = _solve(_decay, _decay_jacobian, x0, geodesic=True, lo=lo, hi=hi, seen=seen)
    seen_plain = []
    x_plain, _, ok_plain = _solve(_decay, _decay_jacobian, x0, geodesic=False, lo=lo, hi=hi, seen=seen_plain)
    assert ok_geo and ok_plain
    n = min(len(seen), len(seen_plain))
    assert np.abs(np.array(seen[:n]) - np.array(seen_plain[:n])).max() > 1e-3   # the acceleration took steps
    pts = np.array(seen)
    assert np.all(pts >= lo) and np.all(pts <= hi)
    assert x_geo[1] == hi[1]
    assert np.allclose(x_geo, x_plain, rtol=0, atol=1e-8)
    g = _decay_jacobian(x_geo).T @ _decay(x_geo)
    assert g[1] < 0                     # the gradient pushes the rate out of the box: the bound is active
