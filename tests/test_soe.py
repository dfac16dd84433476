"""Sums of exponentials (issue 11, part 1): every kernel as internal variables, within its bound."""

import math

import numpy as np
import pytest

from vcor import materials as M
from vcor import soe as S

T_MIN, T_MAX = 4e-7, 0.4  # dt = 0.4 us to 1e6 steps


@pytest.mark.parametrize("name", ["sls", "butyl-prony3", "elastic", "kelvin-voigt"])
def test_prony_type_kernels_are_exact(name):
    mat = M.get(name)
    rep = S.soe(mat, T_MIN, T_MAX)
    assert rep.exact and rep.checked_error == 0.0
    t = np.geomspace(1e-9, 1.0, 50)
    np.testing.assert_array_equal(rep.material.relaxation_modulus(t), M.Prony(*mat.prony_terms()).relaxation_modulus(t))


@pytest.mark.parametrize("name", ["butyl-fc", "butyl-cerf"])
@pytest.mark.parametrize("tol", [1e-6, 1e-8, 1e-10])
def test_kernel_within_tolerance_on_the_interval(name, tol):
    """Independent check on times between the built-in check's (5x denser, offset): the transient's
    relative error stays below tol; for the fractional law also below the a-priori bound."""
    mat = M.get(name)
    rep = S.soe(mat, T_MIN, T_MAX, tol)
    t = np.geomspace(T_MIN, T_MAX, 20_011)
    e_inf = mat.E0
    err = np.max(np.abs((rep.material.relaxation_modulus(t) - e_inf) / (mat.relaxation_modulus(t) - e_inf) - 1))
    print(f"\n{name} tol {tol:g}: {rep.n_terms} terms, error {err:.2e}, a-priori bound {rep.bound:.2e}")
    assert err <= tol
    if name == "butyl-fc":
        assert err <= rep.bound <= tol
    # terms grow like log(t_max / t_min) and log(1 / tol): about 60 at 1e-8 over six decades
    assert rep.n_terms < 20 * math.log10(T_MAX / T_MIN / tol)


@pytest.mark.parametrize("name", ["butyl-fc", "butyl-cerf"])
def test_step_integrals_within_tolerance(name):
    """The step integrals W_m (what the march uses) from step 1 on, against the exact ones."""
    mat = M.get(name)
    dt, n = T_MIN, 1_000_000
    rep = S.soe(mat, dt, dt * n, 1e-10)
    w_exact = mat.step_integrals(dt, n)[1:] - mat.E0 * dt
    w_soe = rep.material.step_integrals(dt, n)[1:] - mat.E0 * dt
    err = np.max(np.abs(w_soe / w_exact - 1))
    print(f"\n{name}: max relative error of the transient's step integrals, steps 1..1e6: {err:.2e}")
    assert err <= 1e-10


def test_bad_interval_is_refused():
    with pytest.raises(ValueError, match="t_max must be in"):
        S.soe(M.get("butyl-fc"), 1e-3, 1e-4)
    with pytest.raises(ValueError, match="tol must be in"):
        S.soe(M.get("butyl-fc"), 1e-6, 1.0, tol=0.5)
