"""The march's erfcx (:mod:`vcor.solvers.erfcx`): a piecewise polynomial below the switch, the asymptotic
series above it, against scipy.special.erfcx and, for the slope, against mpmath at 40 digits."""

import math

import mpmath
import numba
import numpy as np
import pytest
import scipy.special

from vcor.solvers import erfcx as _erfcx


@numba.njit
def _evaluate(xs):
    out = np.empty((xs.size, 2))
    for j in range(xs.size):
        out[j, 0], out[j, 1] = _erfcx.erfcx_slope(xs[j])
    return out


def test_erfcx_to_a_few_ulp_across_the_table_and_the_switch():
    """Relative error <= 3e-15 on a dense grid over [0, 40] (every interval's edges and interior, both sides
    of the switch) and at random points; x = 0 gives 1 and the slope -2 / sqrt(pi)."""
    rng = np.random.default_rng(1)
    xs = np.concatenate([np.linspace(0.0, 40.0, 160_001), rng.uniform(0.0, _erfcx.SWITCH, 100_000),
                         np.nextafter(_erfcx.SWITCH, 0.0) * np.ones(1), [_erfcx.SWITCH, 1e3, 1e8]])
    got = _evaluate(xs)
    assert np.max(np.abs(got[:, 0] / scipy.special.erfcx(xs) - 1.0)) <= 3e-15
    assert got[0, 0] == pytest.approx(1.0, rel=1e-15) and got[0, 1] == pytest.approx(-2 / math.sqrt(math.pi), rel=1e-15)


def test_erfcx_slope_against_high_precision():
    """erfcx'(x) = 2 x erfcx(x) - 2 / sqrt(pi) within 2e-12 relative (its cancellation grows as 2 x^2 up to
    the switch, where the series takes over without it) at 400 points of [0, 40] and at 1e8."""
    mpmath.mp.dps = 40
    xs = np.concatenate([np.linspace(0.0, 40.0, 401)[1:], [1e8]])
    got = _evaluate(xs)[:, 1]
    for x, slope in zip(xs, got, strict=True):
        m = mpmath.mpf(float(x))
        exact = float(2 * m * mpmath.erfc(m) * mpmath.exp(m * m) - 2 / mpmath.sqrt(mpmath.pi))
        assert slope == pytest.approx(exact, rel=2e-12), x


def test_table_is_the_chebyshev_interpolant():
    """Each row reproduces erfcx at its interval's Chebyshev nodes (the interpolation conditions) to 2e-15,
    and a coarser table of the same construction is less accurate (the construction, not a lucky fit)."""
    nodes = np.cos(np.pi * (np.arange(_erfcx.DEGREE + 1) + 0.5) / (_erfcx.DEGREE + 1))
    for i in (0, 11, 57, _erfcx.TABLE.shape[0] - 1):
        centre = (i + 0.5) * _erfcx.WIDTH
        x = centre + 0.5 * _erfcx.WIDTH * nodes
        values = np.polynomial.polynomial.polyval(nodes, _erfcx.TABLE[i])
        np.testing.assert_allclose(values, scipy.special.erfcx(x), rtol=2e-15)
    coarse = _erfcx.erfcx_table(width=1.0, degree=6)
    xs = np.linspace(0.0, 0.999, 200)
    error = np.max(np.abs(np.polynomial.polynomial.polyval(2 * xs - 1, coarse[0]) / scipy.special.erfcx(xs) - 1))
    assert 1e-9 < error < 1e-4


def test_outside_the_domain_and_bad_table_parameters():
    """x < 0 (never passed by the march) gives NaN, not a wrong number; NaN gives NaN and +inf (0, 0); the
    table refuses a width, degree or switch outside its range, naming the parameter."""
    out = _evaluate(np.array([-1e-3, -1.0, math.nan, math.inf]))
    assert np.all(np.isnan(out[:3])) and list(out[3]) == [0.0, 0.0]
    for kwargs, name in (({"width": 0.0}, "width"), ({"degree": 0}, "degree"), ({"degree": 2.5}, "degree"),
                         ({"switch": 25.1}, "switch"), ({"switch": -1.0}, "switch")):
        with pytest.raises(ValueError, match=f"^{name} must be"):
            _erfcx.erfcx_table(**kwargs)
    assert _erfcx.erfcx_table(width=0.5, degree=4, switch=2.0).shape == (4, 5)
