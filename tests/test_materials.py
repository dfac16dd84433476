"""Materials: closed forms against independent quadrature, limits, validation."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from vcor import materials as M

ALL = ["sls", "butyl-fc", "butyl-cerf", "butyl-prony3", "elastic", "kelvin-voigt"]


def test_presets_values():
    assert M.get("sls").relaxation_modulus(0.0) == pytest.approx(15e6)
    assert M.get("sls").rubbery == pytest.approx(15e6 / 4)
    assert M.get("butyl-prony3").glassy == pytest.approx(156.15e6)
    assert M.get("butyl-cerf").glassy == pytest.approx(0.442e6 + 0.6765e9)
    assert math.isinf(M.get("butyl-fc").glassy)
    assert M.get("butyl-fc").rubbery == pytest.approx(3 * 7.6e5)


mp = pytest.importorskip("mpmath")
mp.mp.dps = 30

# independent high-precision definitions of the presets' E(t) (Green Eqs. 14, 23b, 24, 26)
MP_E = {
    "sls": lambda t: mp.mpf(15e6) * (mp.mpf(1) / 4 + mp.mpf(3) / 4 * mp.exp(-1200 * t)),
    "butyl-fc": lambda t: mp.mpf(3 * 7.6e5) + mp.mpf(3 * 2.95e5) / mp.sqrt(mp.pi * t),
    "butyl-cerf": lambda t: mp.mpf(0.442e6) + mp.mpf(0.6765e9) * mp.exp(490000 * t) * mp.erfc(700 * mp.sqrt(t)),
    "butyl-prony3": lambda t: mp.mpf(10.421e6) + mp.mpf(20.181e6) * mp.exp(-972 * t)
    + mp.mpf(38.204e6) * mp.exp(-6426 * t) + mp.mpf(87.344e6) * mp.exp(-34221 * t),
}


@pytest.mark.parametrize("name", sorted(MP_E))
def test_step_integrals_and_moments_against_mpmath(name):
    mat, E = M.get(name), MP_E[name]
    dt = 2e-6
    W = mat.step_integrals(dt, 6)
    V = mat.step_moments(dt, 6)
    for i in (0, 1, 5):
        a, b = mp.mpf(i * dt), mp.mpf((i + 1) * dt)
        mid = (a + b) / 2
        assert W[i] == pytest.approx(float(mp.quad(E, [a, b])), rel=1e-12)
        assert V[i] == pytest.approx(float(mp.quad(lambda t: E(t) * (t - mid), [a, b])), rel=1e-7)


@pytest.mark.parametrize("name", sorted(MP_E))
def test_second_antiderivative_against_mpmath(name):
    mat, E = M.get(name), MP_E[name]
    for t in (1e-6, 3e-4):
        ref = mp.quad(lambda s: (mp.mpf(t) - s) * E(s), [0, mp.mpf(t)])  # int_0^t (t - s) E(s) ds
        assert float(mat.antiderivative(t, 2)) == pytest.approx(float(ref), rel=1e-11)
        assert float(mat.antiderivative(t, 1)) == pytest.approx(float(mp.quad(E, [0, mp.mpf(t)])), rel=1e-11)


@pytest.mark.parametrize("name", ["sls", "butyl-cerf", "butyl-prony3"])
def test_complex_modulus_is_transform_of_relaxation(name):
    """E*(w) = E_inf + i w int_0^inf (E(t) - E_inf) e^{-i w t} dt, by quadrature."""
    mat = M.get(name)
    e_inf = mat.rubbery
    for w in (1e3, 1e4, 1e5):
        f = lambda t: float(mat.relaxation_modulus(t)) - e_inf  # noqa: E731
        c = quad(f, 0, np.inf, weight="cos", wvar=w, limlst=200)[0]
        s = quad(f, 0, np.inf, weight="sin", wvar=w, limlst=200)[0]
        ref = e_inf + 1j * w * (c - 1j * s)
        assert mat.complex_modulus(w) == pytest.approx(ref, rel=2e-6)


def test_fractional_complex_modulus_half_derivative():
    mat = M.get("butyl-fc")
    w = 2e4
    assert mat.complex_modulus(w) == pytest.approx(mat.E0 + mat.E1 * math.sqrt(w) * (1 + 1j) / math.sqrt(2))


def test_erfcx_matches_paper_appendix_series():
    """The paper's Eq. A3 six-term asymptotic series is a test oracle for scipy's erfcx."""
    from scipy.special import erfcx

    for x in (26.0, 40.0, 100.0):
        y = 2 * x * x
        series = (1 - 1 / y + 3 / y**2 - 15 / y**3 + 105 / y**4 - 945 / y**5) / (x * math.sqrt(math.pi))
        assert erfcx(x) == pytest.approx(series, rel=1e-12)


@pytest.mark.parametrize("name", ALL)
def test_relaxation_non_increasing(name):
    t = np.logspace(-8, 0, 400)
    e = M.get(name).relaxation_modulus(t)
    assert np.all(np.diff(e) <= 1e-9 * e[:-1])
    assert np.all(M.get(name).relaxation_rate(t) <= 0)


def test_round_trip_dict(tmp_path):
    for name in ALL:
        mat = M.get(name)
        assert M.from_dict(mat.to_dict()) == mat
    p = tmp_path / "m.json"
    p.write_text(M.get("butyl-prony3").describe())
    assert M.from_file(p) == M.get("butyl-prony3")


def test_cerf_rate_accurate_for_large_argument():
    """x erfcx(x) - 1/sqrt(pi) cancels for large x (the paper's Appendix problem, one derivative
    further): the asymptotic branch keeps dE/dt accurate, which the plate mobility alpha'(t) needs."""
    c = M.Cerf(2.28e6, 6.45e16, 7.29e10)  # a CERF set indistinguishable from the fractional law
    for t in (1e-7, 1e-5, 1e-3):
        ref = mp.diff(lambda s: mp.mpf(c.E1) * mp.exp(mp.mpf(c.b1) ** 2 * s) * mp.erfc(mp.mpf(c.b1) * mp.sqrt(s)),
                      mp.mpf(t))
        assert float(c.relaxation_rate(t)) == pytest.approx(float(ref), rel=1e-12)
    # and it is the fractional law's rate
    fc = M.FractionalPower(2.28e6, 6.45e16 / 7.29e10)
    assert float(c.relaxation_rate(1e-4)) == pytest.approx(float(fc.relaxation_rate(1e-4)), rel=1e-9)
