"""``Material.first_step_second_moment``: int_0^dt E_reg(t) ((t - dt/2)^2 - dt^2/12) dt, the weight of the
curvature of u' over the adaptive march's newest step, against independent quadratures: mpmath at 40
digits for Prony terms (closed form and series, both sides of SECOND_SERIES_SWITCH), scipy's quad for
every other family (the fractional and Kelvin-Voigt closed forms, and the base class's Gauss-Legendre
rule for the CERF law and Eq. 1's two-body modulus)."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad

from vcor import materials as M
from vcor.materials.expsums import soe
from vcor.materials.prony import SECOND_SERIES_SWITCH

#: step sizes, s: the adaptive tables' range for contacts of microseconds to seconds
STEPS = np.geomspace(1e-10, 1.0, 21)


def prony_exact(material, dt):
    """The moment of a Prony series at 40 digits: per term E_k dt^3 phi(b_k dt),
    phi(x) = int_0^1 e^{-x y} ((y - 1/2)^2 - 1/12) dy by mpmath's quadrature."""
    _, e, b = material.prony_terms()
    with mpmath.workdps(40):
        total = mpmath.mpf(0)
        for ek, bk in zip(e, b, strict=True):
            x = mpmath.mpf(float(bk)) * mpmath.mpf(float(dt))
            phi = mpmath.quad(lambda y, x=x: mpmath.exp(-x * y) * ((y - mpmath.mpf(1) / 2) ** 2 - mpmath.mpf(1) / 12),
                              [0, 1])
            total += mpmath.mpf(float(ek)) * mpmath.mpf(float(dt)) ** 3 * phi
        return float(total)


def check_prony(material, steps, rtol):
    got = material.first_step_second_moment(np.asarray(steps))
    for dt, value in zip(steps, got, strict=True):
        exact = prony_exact(material, dt)
        assert abs(value - exact) <= rtol * abs(exact), (dt, value, exact)
    # one step and an array of them give the same numbers, to rounding
    assert float(material.first_step_second_moment(float(steps[0]))) == pytest.approx(got[0], rel=1e-14)


@pytest.mark.parametrize("name", ["sls", "butyl-prony3"])
def test_prony_presets_against_mpmath(name):
    """Relative 1e-13 (the result is (b dt)^2 / 360 E dt^3 for small steps: a relative test, not one
    against the scale of E dt^3), at step sizes on both sides of the series switch for every term."""
    material = M.get(name)
    b = np.asarray(material.prony_terms()[2])
    around_switch = [SECOND_SERIES_SWITCH * f / bk for bk in b for f in (0.5, 0.999, 1.0, 1.001, 2.0)]
    check_prony(material, np.concatenate((STEPS, around_switch)), 1e-13)


@settings(max_examples=40, deadline=None)
@given(e=st.lists(st.floats(1e3, 1e10), min_size=1, max_size=4),
       logb=st.lists(st.floats(-3.0, 9.0), min_size=4, max_size=4),
       logdt=st.floats(-9.0, 0.0), e_inf=st.floats(0.0, 1e9))
def test_prony_series_against_mpmath(e, logb, logdt, e_inf):
    """Random Prony series and steps (b dt from 1e-12 to 1e9, across the switch): relative 1e-12."""
    b = [10.0**lb for lb in logb[: len(e)]]
    material = M.Prony(E_inf=e_inf, E=tuple(e), beta=tuple(b))
    check_prony(material, [10.0**logdt], 1e-12)


def test_a_fitted_exponential_sum_against_mpmath():
    """The ~100-term exponential sum the adaptive march carries the CERF law on (a Prony series: the
    closed form and the series per term), relative 1e-13."""
    material = soe(M.get("butyl-cerf"), 1e-9, 1.0, 1e-10).material
    check_prony(material, STEPS[::5], 1e-13)


def quad_moment(material, dt):
    """int_0^dt E_reg(t) ((t - dt/2)^2 - dt^2/12) dt by scipy's quad in y = sqrt(t / dt) (where t^-1/2
    and sqrt(t) behaviour at 0 is smooth), with breakpoints at 10^-k to follow fast changes near 0;
    and the scale int_0^dt |E_reg| dt dt^2 / 12 of the result."""
    def f(y):
        t = dt * y * y
        return 2.0 * y * float(material.relaxation_modulus(t)) * ((y * y - 0.5) ** 2 - 1.0 / 12.0)

    points = [10.0**-k for k in range(1, 9)]
    size = quad(lambda y: 2.0 * y * abs(float(material.relaxation_modulus(dt * y * y))), 0.0, 1.0, points=points,
                epsrel=1e-10, limit=2000)[0] / 12.0
    value = quad(f, 0.0, 1.0, points=points, epsabs=1e-14 * size, epsrel=1e-13, limit=2000)[0]
    return value * dt**3, size * dt**3


def two_body(a, b):
    return M.EqOne(M.get(a), 1.0 / (1.0 - 0.3**2), M.get(b), 1.0 / (1.0 - 0.25**2))


#: every family the adaptive march meets: its presets, Eq. 1's two-body modulus of each viscoelastic law
#: with an SLS and with an elastic body, and a fitted exponential sum
OTHERS = {
    "butyl-fc": lambda: M.get("butyl-fc"),
    "butyl-cerf": lambda: M.get("butyl-cerf"),
    "kelvin-voigt": lambda: M.get("kelvin-voigt"),
    "elastic": lambda: M.get("elastic"),
    "eq1 sls/butyl-fc": lambda: two_body("sls", "butyl-fc"),
    "eq1 sls/butyl-cerf": lambda: two_body("sls", "butyl-cerf"),
    "eq1 elastic/sls": lambda: two_body("elastic", "sls"),
    "eq1 butyl-prony3/butyl-fc": lambda: two_body("butyl-prony3", "butyl-fc"),
}


@pytest.mark.parametrize("key", list(OTHERS))
def test_every_family_against_quad(key):
    """1e-13 of the scale int_0^dt |E_reg| dt dt^2 / 12 (the size of the curvature term's weight where it
    matters, against the newest step's other weights), on step sizes 1e-10..1 s."""
    material = OTHERS[key]()
    got = np.asarray(material.first_step_second_moment(STEPS))
    for dt, value in zip(STEPS, got, strict=True):
        exact, scale = quad_moment(material, dt)
        assert abs(value - exact) <= 1e-13 * scale, (dt, value, exact, scale)


def test_constant_and_sqrt_laws_in_closed_form():
    """A constant modulus gives 0 (the polynomial has zero mean on the step); E1 / sqrt(pi t) gives
    E1 dt^2.5 / (15 sqrt(pi))."""
    assert np.all(M.get("kelvin-voigt").first_step_second_moment(STEPS) == 0.0)
    fc = M.get("butyl-fc")
    e1 = fc.params()["E1"]
    assert fc.first_step_second_moment(1e-4) == pytest.approx(e1 * 1e-10 / (15.0 * math.sqrt(math.pi)), rel=1e-14)
