"""Sums of exponentials: every kernel as internal variables, within its bound."""

import math

import numpy as np
import pytest

from vcor import materials as M
from vcor.materials import expsums as S

T_MIN, T_MAX = 4e-7, 0.4  # dt = 0.4 us to 1e6 steps


@pytest.mark.parametrize("name", ["sls", "butyl-prony3", "elastic", "kelvin-voigt"])
def test_prony_type_kernels_are_exact(name):
    mat = M.get(name)
    rep = S.soe(mat, T_MIN, T_MAX)
    assert rep.exact and rep.checked_error == 0.0
    t = np.geomspace(1e-9, 1.0, 50)
    np.testing.assert_array_equal(rep.material.relaxation_modulus(t), M.Prony(*mat.prony_terms()).relaxation_modulus(t))


def test_a_sum_above_the_largest_modulus_is_built():
    """The sum of a fractional law's modes grows as t_min^-1/2 without a bound: one above a material's largest
    modulus (MAX_MODULUS) is built, as a representation (ExponentialSum), not a material."""
    from vcor.materials.base import MAX_MODULUS

    rep = S.soe(M.FractionalPower(1e6, 1e17), 1e-12, 1e-3)
    assert rep.checked_error <= 1e-10 and rep.material.glassy > MAX_MODULUS
    assert rep.material.kind == "exponential-sum"


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


@pytest.mark.parametrize("name", [pytest.param("butyl-fc", marks=pytest.mark.slow), "butyl-cerf"])  # fc: ~5 s
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


# ----------------------------------------------------------------------------- the soe method
PRESETS = ["sls", "butyl-fc", "butyl-cerf", "butyl-prony3", "elastic", "kelvin-voigt"]


@pytest.mark.parametrize("name", PRESETS)
@pytest.mark.parametrize("v0", [0.001, 1.0, 10.0, 50.0, 300.0])
def test_soe_method_reproduces_direct(name, v0):
    """Same dt, same product integration: the exponential-sum history changes the numbers of the
    O(N^2) direct scheme by at most its tolerance (1e-10) times the history's share."""
    import vcor

    a = vcor.simulate(name, v0, method="direct")
    b = vcor.simulate(name, v0, method="soe")
    assert a.status == b.status == "ok", (a.message, b.message)
    assert b.dt == a.dt and b.steps == a.steps
    assert abs(b.cor / a.cor - 1) < 1e-10, (b.cor, a.cor)
    assert abs(b.t0 / a.t0 - 1) < 1e-10, (b.t0, a.t0)


#: the thinnest plates (1 and 2 mm) are the long contacts: seconds per case, so they run in the full
#: suite only (marked slow); 3.16 and 5 mm stay in the fast loop
THIN_PLATES = [pytest.param(1e-3, marks=pytest.mark.slow), pytest.param(2e-3, marks=pytest.mark.slow), 3.16e-3, 5e-3]


@pytest.mark.parametrize("h", THIN_PLATES)
@pytest.mark.parametrize("name", ["sls", "elastic"])
@pytest.mark.parametrize("v0", [1.0, 10.0])
def test_thin_plates_separate(h, name, v0):
    """Long contacts (up to 600 contact-time estimates at h = 1 mm) end ok with soe, and agree with
    scipy's Radau on the exact internal variables (rtol 1e-10): t0 to 1e-3 relative, COR to 1e-6."""
    import vcor

    r = vcor.simulate(name, v0, h=h, method="soe")
    ref = vcor.simulate(name, v0, h=h, method="ive")
    assert r.status == "ok" and ref.status == "ok", (r.message, ref.message)
    print(f"\nh = {h * 1e3:g} mm, {name}, v0 = {v0}: t0 {r.t0:.6g} s (Radau {ref.t0:.6g}), "
          f"COR {r.cor:.4e} (Radau {ref.cor:.4e}), {r.steps} steps")
    assert abs(r.t0 / ref.t0 - 1) < 1e-3
    assert abs(r.cor - ref.cor) < 1e-6


@pytest.mark.parametrize("option, value", [("soe_tol", 1e-8)])
def test_soe_options_belong_to_soe(option, value):
    import vcor

    with pytest.raises(ValueError, match=f"solver option {option} is not used by method 'direct'"):
        vcor.simulate("sls", 10.0, method="direct", **{option: value})
    with pytest.raises(ValueError, match="solver option volterra is not used by method 'soe'"):
        vcor.simulate("sls", 10.0, method="soe", volterra=True)
    with pytest.raises(ValueError, match="solver option form is not used by method 'soe'"):
        vcor.simulate("sls", 10.0, method="soe", form="b")
    looser = vcor.simulate("butyl-fc", 10.0, method="soe", soe_tol=1e-6)
    exact = vcor.simulate("butyl-fc", 10.0, method="direct")
    assert looser.ok and 1e-12 < abs(looser.cor / exact.cor - 1) < 1e-6
