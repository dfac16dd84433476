"""Start-free global superposition (vcor.fitting.dma.shifts): synthetic Prony + WLF sets recovered,
start-independence, refusal of sets that share no range, fall-back quantities, WLF/Arrhenius fits,
and the tabulated shift function (vcor.materials.shift)."""

import json
import math

import numpy as np
import pytest
from synthetic_dma import C1, C2, T_REF, TEMPS, TRUE, synthetic

from vcor.fitting import dma as sp
from vcor.materials.shift import GAS_CONSTANT, ZERO_CELSIUS, ShiftFunction, wlf_log_aT


def test_noise_free_synthetic_shifts_are_recovered():
    r = sp.global_shifts(synthetic(0, 0.0), T_REF)
    assert np.max(np.abs(r.log_aT - TRUE)) < 1e-3
    assert r.log_aT[2] == pytest.approx(0.0, abs=1e-12)  # the set at T_ref


@pytest.mark.parametrize("seed", [1, 2])
def test_noisy_synthetic_shifts_within_0p1_decade_with_plausible_errors(seed):
    r = sp.global_shifts(synthetic(seed), T_REF)
    err = np.abs(r.log_aT - TRUE)
    print(f"\nseed {seed}: worst shift error {err.max():.4f} decade, std {np.round(r.log_aT_std, 4)}")
    assert err.max() < 0.1
    free = r.log_aT_std > 0
    assert np.all(err[free] < 4 * r.log_aT_std[free])  # the linearised errors are of the right size
    assert set(r.set_rms) == {"E_stor"} and r.set_rms["E_stor"].shape == (5,)


def test_shifts_do_not_depend_on_the_start():
    data = synthetic(5)
    base = sp.global_shifts(data, T_REF)
    for start in (np.zeros(5), 2 * TRUE, -TRUE):
        r = sp.global_shifts(data, T_REF, start=start)
        assert np.max(np.abs(r.log_aT - base.log_aT)) < 1e-3, start


def test_sets_sharing_no_range_are_refused_with_their_temperatures():
    data = synthetic(0, 0.0, temps=np.array([-40.0, 20.0]))  # 60 K apart: no common E', E'' or tan delta
    with pytest.raises(ValueError, match=r"-40 and 20 deg C share no range of E_stor, tan_delta, E_loss"):
        sp.global_shifts(data, T_REF)


def test_a_fallback_quantity_bridges_sets_whose_primary_ranges_do_not_overlap():
    sets = sp.split_sets(synthetic(0, 0.0))
    _, info = sp.pairwise_shifts(sets, quantities=("E_loss",), fallback=("E_stor",))
    assert all("E_loss" in p["quantities"] for p in info)
    # E'' (rising over the whole band) shares no range between the two colder sets: E' is added there
    r = sp.global_shifts(synthetic(0, 0.0), T_REF, quantities=("E_loss",), fallback=("tan_delta", "E_stor"))
    assert np.max(np.abs(r.log_aT - TRUE)) < 0.05


def test_split_sets_errors():
    data = synthetic(0, 0.0)
    with pytest.raises(ValueError, match="two or more temperatures, got 1"):
        sp.split_sets({k: v[:10] for k, v in data.items()})
    with pytest.raises(ValueError, match="missing 'Set'"):
        sp.split_sets({k: v for k, v in data.items() if k != "Set"})
    with pytest.raises(ValueError, match="> 0"):
        sp.split_sets(dict(data, E_loss=-data["E_loss"]))


def test_anchor_puts_zero_at_T_ref_between_sets():
    T, s = np.array([0.0, 10.0, 20.0]), np.array([3.0, 1.0, -2.0])
    a = sp.anchor_matrix(T, 5.0) @ s
    assert np.interp(5.0, T, a) == pytest.approx(0.0) and np.allclose(np.diff(a), np.diff(s))


def test_wlf_and_arrhenius_fits_recover_their_constants():
    T = np.linspace(-10, 60, 8)
    w = sp.wlf_fit(T, wlf_log_aT(T, 20.0, C1, C2), 20.0)
    assert w["C1"] == pytest.approx(C1, rel=1e-6) and w["C2"] == pytest.approx(C2, rel=1e-6)
    y = 150e3 / (GAS_CONSTANT * math.log(10)) * (1 / (T + ZERO_CELSIUS) - 1 / (20 + ZERO_CELSIUS))
    a = sp.arrhenius_fit(T, y, 20.0)
    assert a["E_a"] == pytest.approx(150e3, rel=1e-9) and a["rms"] < 1e-12


def test_shift_laws_through_as_many_sets_as_constants_state_no_error():
    """Three sets, one at T_ref (which every WLF curve and Arrhenius line passes through): the two WLF
    constants go exactly through the other two shifts, so the residual scatter says nothing of their errors:
    inf, not 0; a fourth set gives finite errors that cover a perturbed shift. Arrhenius likewise with two sets."""
    rng = np.random.default_rng(3)
    T = np.array([0.0, 20.0, 40.0])
    y = wlf_log_aT(T, 20.0, C1, C2) + np.array([0.01, 0.0, -0.01])
    w = sp.wlf_fit(T, y, 20.0)
    assert w["C1_std"] == w["C2_std"] == math.inf and w["rms"] < 1e-9
    T4 = np.array([0.0, 20.0, 40.0, 60.0])
    w4 = sp.wlf_fit(T4, wlf_log_aT(T4, 20.0, C1, C2) + rng.normal(0.0, 0.01, 4) * (T4 != 20.0), 20.0)
    assert 0.0 < w4["C1_std"] < math.inf and 0.0 < w4["C2_std"] < math.inf
    a = sp.arrhenius_fit(np.array([20.0, 40.0]), np.array([0.0, -1.0]), 20.0)
    assert a["E_a_std"] == math.inf
    assert 0.0 < sp.arrhenius_fit(T, np.array([1.1, 0.0, -1.0]), 20.0)["E_a_std"] < math.inf


def test_master_curve_and_superposition_rms():
    data = synthetic(0, 0.0)
    mc = sp.master_curve(data, TRUE)
    assert np.all(np.diff(mc.f_red) >= 0) and mc.f_red.size == 50
    off = TRUE + [0, 0, 0, 0, 1]
    assert sp.superposition_rms(data, TRUE)["E_stor"] < 1e-3 < sp.superposition_rms(data, off)["E_stor"]


def test_tabulated_shift_function():
    """PCHIP between the sets: through every set, monotone, 0.5 K beyond the end sets and no further (the
    error names the range); on WLF shifts 15 K apart it is within 0.02 decade of WLF where straight lines
    are 0.10 off; to_dict / from_spec round-trip; the other models keep theirs."""
    from scipy.interpolate import PchipInterpolator

    s = ShiftFunction.table(20.0, TEMPS, TRUE)
    assert s.log_aT(20.0) == pytest.approx(0.0, abs=1e-12)
    assert [s.log_aT(float(T)) for T in TEMPS] == pytest.approx(TRUE, abs=1e-12)
    assert s.valid_range() == (-10.5, 50.5)
    dense = np.linspace(-10.5, 50.5, 611)
    got = np.array([s.log_aT(float(T)) for T in dense])
    assert got == pytest.approx(PchipInterpolator(TEMPS, TRUE)(dense), abs=1e-12)
    assert np.all(np.diff(got) < 0)                     # WLF shifts fall with T: so does the table
    exact = wlf_log_aT(dense, T_REF, C1, C2)
    lin, cub = np.max(np.abs(np.interp(dense, TEMPS, TRUE) - exact)), np.max(np.abs(got - exact))
    print(f"table vs WLF, sets 15 K apart: linear {lin:.3f}, PCHIP {cub:.4f} decades (max over -10.5..50.5 deg C)")
    assert cub < 0.02 and lin > 5 * cub
    for T in (-11.0, 51.0, math.nan):
        with pytest.raises(ValueError, match=r"\[-10.5, 50.5\] deg C .* not extrapolated"):
            s.log_aT(T)
    spec = json.loads(json.dumps(s.to_dict()))
    assert spec["model"] == "table" and ShiftFunction.from_spec(spec) == s
    bad = [({**spec, "T": [0, 0, 1, 2, 3]}, "strictly increasing"), ({**spec, "log_aT": [1, 2]}, "equal length"),
           ({**spec, "T_ref": 80}, "outside the table"), ({k: v for k, v in spec.items() if k != "T"}, "missing")]
    for b, words in bad:
        with pytest.raises(ValueError, match=words):
            ShiftFunction.from_spec(b, "materials.m.shift")
    w = ShiftFunction(model="wlf", T_ref=20.0, C1=C1, C2=C2)
    assert ShiftFunction.from_spec(w.to_dict()) == w and w.log_aT(50.0) == pytest.approx(float(TRUE[4]))


def test_catalogue_at_temperature_with_a_tabulated_shift(tmp_path):
    """A config material with a tabulated shift: Catalogue.at(name, T=...) scales its rates by a_T."""
    from vcor.materials.catalogue import Catalogue

    spec = {"model": "sls", "E_glassy": 15e6, "alpha": 300.0, "beta": 1200.0,
            "shift": {"model": "table", "T_ref": 20.0, "T": list(TEMPS), "log_aT": list(TRUE)}}
    cat = Catalogue(specs={"m": spec}, base_dir=str(tmp_path))
    hot = cat.at("m", T=50.0)
    assert hot.relaxation_modulus(np.array([1e-3]))[0] == pytest.approx(
        cat.material("m").relaxation_modulus(np.array([1e-3 / 10 ** TRUE[4]]))[0], rel=1e-12)
    with pytest.raises(ValueError, match="not extrapolated"):
        cat.at("m", T=80.0)
