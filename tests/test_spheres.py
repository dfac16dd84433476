"""Viscoelastic spheres: the solver's rigid-target Kelvin-Voigt limit against Ramirez et al. 1999
and Mueller & Poeschel 2011."""

import math

import numpy as np
import pytest

from vcor import spheres as S


def test_c1_closed_form_and_a_coefficients():
    from scipy.special import gamma

    assert math.sqrt(math.pi) * gamma(0.6) / (2 ** 0.2 * 5 ** 0.4 * gamma(2.1)) == S.C1_CLOSED_FORM  # Eq. 30
    assert pytest.approx(1.153449, abs=1e-6) == S.C1_CLOSED_FORM  # Eq. 67
    assert math.floor(S.C1_CLOSED_FORM * 1e5) / 1e5 == 1.15344  # Eq. 31 as printed (truncated)
    assert S.A_COEFFS[1] == pytest.approx(3 / 5, abs=1e-6)  # exact a2 (Eq. 69)
    assert S.A_COEFFS[2] == pytest.approx(0.315119, abs=1e-6) and S.A_COEFFS[3] == pytest.approx(0.161167, abs=1e-6)


def test_pade_coefficients_reproduce_table_1():
    d = S.pade_coefficients()
    truncated = tuple(math.floor(x * 1e4) / 1e4 for x in d)
    assert truncated == S.TABLE_I
    assert max(abs(a - b) for a, b in zip(d, S.TABLE_I)) < 1e-4


# docs/validation.md, "Viscoelastic spheres": each bound below is the page's number (measured values in comments)
@pytest.mark.parametrize("b, bound", [(1e-3, 2e-9), (3e-3, 2e-9), (1e-2, 2.5e-8)])
def test_overlap_rule_matches_four_term_series(b, bound):
    gap = abs(S.cor_numeric(b, "overlap") - S.cor_series(b, 4))  # 9.2e-10, 1.5e-9, 2.3e-8: O(b^5)
    print(f"\nb = {b}: |eps - 4-term series| = {gap:.2e}")
    assert gap < bound


def test_overlap_rule_matches_pade_to_0_111_percent():
    gaps = [abs(S.cor_numeric(b, "overlap") / S.cor_pade(b) - 1) for b in np.geomspace(1e-3, 0.3, 9)]
    print(f"\nmax |eps / Pade - 1| for b <= 0.3: {max(gaps):.4%}")  # 0.1108 %, at b = 0.3
    assert max(gaps) < 0.00111


@pytest.mark.parametrize("b, bound", [(1e-3, 1e-8), (1e-2, 1e-7), (3e-2, 2e-7), (0.1, 4e-7)])
def test_force_rule_matches_mueller_poeschel(b, bound):
    gap = abs(S.cor_numeric(b, "force") - S.cor_pade_force(b))  # 3.8e-9, 4.8e-8, 1.4e-7, 3.7e-7
    print(f"\nb = {b}: |eps_force - Mueller-Poeschel| = {gap:.2e}")
    assert gap < bound


def test_c1_c2_recovered_from_numerics():
    bs = np.geomspace(1e-3, 0.03, 12)
    eps = np.array([S.cor_numeric(b) for b in bs])
    A = np.vstack([bs**k for k in range(1, 5)]).T
    c = np.linalg.lstsq(A, eps - 1.0, rcond=None)[0]
    print(f"\nregression: C1 = {-c[0]:.6f}, C2 = {c[1]:.6f} (paper 1.153449, 0.798267)")
    # README: C1 = 1.153445, C2 = 0.79788 (the fit of four powers to b <= 0.03 limits the digits)
    assert abs(-c[0] - 1.153445) < 1e-6 and abs(c[1] - 0.79788) < 1e-5


def test_force_rule_separates_earlier_with_higher_eps():
    for b in (0.1, 1.0):
        assert S.cor_numeric(b, "force") > S.cor_numeric(b, "overlap")


def test_root_of_eq27_is_exact_to_second_order():
    for b in (1e-3, 1e-2):
        assert abs(S.cor_root(b) - S.cor_series(b, 2)) < 5 * b**3


def test_sls_tends_to_kelvin_voigt_when_relaxation_is_fast():
    for b in (0.01, 0.1):
        kv = S.cor_numeric(b)
        gaps = [abs(S.cor_numeric_sls(b, tr) - kv) for tr in (1.0, 0.1, 0.01, 0.001)]
        assert gaps == sorted(gaps, reverse=True)
        print(f"\nb = {b}: |eps_SLS - eps_KV| at tau = 1e-3 t_c: {gaps[-1]:.2e}")  # 1.5e-6, 1.0e-6
        assert gaps[-1] < 1.6e-6  # README: 1.5e-6 at b = 0.01


def test_dimensional_and_dimensionless_agree():
    pair = {"R1": 0.01, "R2": 0.02, "m1": 0.03, "m2": 0.05, "E": 1e7, "nu": 0.3, "A": 2e-5}
    for g in (0.5, 5.0):
        b = S.b_group(**pair, g=g)
        # one direct run (2000 steps per contact) against the Richardson-extrapolated eps(b): the gap is
        # that run's discretisation error (3.9e-7, 5.6e-7), 16 times smaller at 4x the steps (second order)
        coarse = abs(S.cor_spheres(**pair, g=g, options={"method": "direct"}) - S.cor_numeric(b))
        fine = abs(S.cor_spheres(**pair, g=g, options={"method": "direct", "steps_per_contact": 8000})
                   - S.cor_numeric(b))
        assert coarse < 1e-6 and fine < coarse / 10, (coarse, fine)
        # the default method (adaptive) is within its default accuracy of the dimensionless eps
        assert abs(S.cor_spheres(**pair, g=g) - S.cor_numeric(b)) < 1e-6
    wall = {"R1": 0.01, "R2": math.inf, "m1": 0.03, "m2": math.inf, "E": 1e7, "nu": 0.3, "A": 2e-5}
    assert abs(S.cor_spheres(**wall, g=2.0, rule="force") - S.cor_numeric(S.b_group(**wall, g=2.0), "force")) < 1e-6


def test_dissipative_constant_eq4():
    # eta1 = 0: A = eta2 (1 - nu^2)(1 - 2 nu) / (E nu^2)
    assert S.dissipative_constant(0.0, 2.0, 1e7, 0.25) == pytest.approx(2.0 * (1 - 0.0625) * 0.5 / (1e7 * 0.0625))


@pytest.mark.parametrize(
    "call, word",
    [
        (lambda: S.cor_numeric(-0.1), "b must"),
        (lambda: S.cor_series(float("nan")), "b must"),
        (lambda: S.cor_pade(-1.0), "b must"),
        (lambda: S.cor_series(0.1, 5), "order"),
        (lambda: S.cor_numeric(0.1, "touch"), "rule"),
        (lambda: S.b_group(R1=0.01, R2=0.01, m1=0.0, m2=0.1, E=1e7, nu=0.3, A=1e-5, g=1.0), "m1"),
        (lambda: S.b_group(R1=0.01, R2=0.01, m1=0.1, m2=-1.0, E=1e7, nu=0.3, A=1e-5, g=1.0), "m2"),
        (lambda: S.b_group(R1=0.01, R2=0.01, m1=0.1, m2=0.1, E=1e7, nu=0.3, A=1e-5, g=0.0), "g must"),
        (lambda: S.cor_spheres(R1=0.01, R2=0.01, m1=0.1, m2=0.1, E=1e7, nu=0.3, A=1e-5, g=-2.0), "g must"),
        (lambda: S.dissipative_constant(1.0, 1.0, 1e7, 0.6), "nu"),
    ],
)
def test_bad_input(call, word):
    with pytest.raises(ValueError, match=word):
        call()
