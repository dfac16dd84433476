"""Measured DMA data (issue 12, part 3): pyvisco's file conventions, bad data, time-temperature
superposition, WLF. README, "Measured DMA data"."""

from pathlib import Path

import numpy as np
import pytest

import vcor
from vcor import dma

DATA = Path(__file__).resolve().parents[1] / "data/pyvisco"


def test_reads_pyvisco_files_in_si():
    raw = dma.read_table(DATA / "freq_user_raw.csv")  # starts with a byte-order mark; MPa
    assert raw.kind == "frequency" and raw.is_raw
    assert raw.columns["E_stor"][0] == pytest.approx(8097.175545e6)
    assert len(np.unique(raw.columns["Set"])) == 21
    sh = dma.read_table(DATA / "freq_user_master__shift_factors.csv")
    assert sh.kind == "shift" and sh.columns["log_aT"][list(sh.columns["T"]).index(-5.0)] == 0.0
    master = dma.read_table(DATA / "freq_user_master.csv")
    assert master.kind == "frequency" and not master.is_raw


RAW_HEAD = "f,E_stor,E_loss,T,Set\nHz, MPa, MPa, C, -\n"
BAD = [
    ("f,E_stor,T,Set\n1,2,20,0\n", ["line 1", "expected f,E_stor,E_loss"]),
    ("f,E_stor,E_los,T,Set\n1,2,3,20,0\n", ["line 1", "misspelt", "E_los"]),
    (RAW_HEAD + "0.1,8000,90,20,0\n0.2,soft,90,20,0\n", ["line 4, column 'E_stor'", "'soft' is not a number"]),
    (RAW_HEAD + "0.1,8000,0,20,0\n", ["line 3, column 'E_loss'", "must be > 0"]),
    (RAW_HEAD + "0.1,-8000,90,20,0\n", ["line 3, column 'E_stor'", "must be > 0"]),
    ("f,E_stor,E_loss\nHz, MPa, psi\n1,2,3\n", ["line 2, column 'E_loss'", "unknown unit 'psi'"]),
    ("f,E_stor,E_loss,T\n1,2,3,20\n", ["needs both T and Set"]),
    ("T,log_aT\nC, -\n0,1\n10,0\n20,0.5\n", ["column 'log_aT'", "monotone"]),
    ("f,E_stor,E_loss,T,Set\n1,2,3\n", ["line 2", "3 cells"]),
]


@pytest.mark.parametrize("text, words", BAD)
def test_bad_data_names_file_line_and_column(tmp_path, text, words):
    path = tmp_path / "dma.csv"
    path.write_text(text)
    with pytest.raises(ValueError) as err:
        dma.read_table(path)
    assert str(path) in str(err.value)
    for w in words:
        assert w in str(err.value), (w, str(err.value))


def test_superposition_needs_two_temperatures(tmp_path):
    path = tmp_path / "one.csv"
    path.write_text(RAW_HEAD + "".join(f"{f},{8000 + f},{90 + f},20,0\n" for f in (0.1, 1, 10)))
    with pytest.raises(ValueError, match="two or more temperatures, got 1"):
        dma.superpose(dma.read_table(path), 20.0)


TRUE = vcor.materials.Prony(2e6, (5e6, 20e6, 60e6, 150e6, 400e6), (1e1, 1e3, 1e5, 1e7, 1e9))
T_REF, C1, C2 = 20.0, 8.86, 101.6
TEMPS = (-10.0, 5.0, 20.0, 35.0, 50.0)


def _synthetic(path, seed):
    rng = np.random.default_rng(seed)
    f = np.geomspace(0.1, 100, 10)
    rows = ["f,E_stor,E_loss,T,Set", "Hz, MPa, MPa, C, -"]
    for k, T in enumerate(TEMPS):
        es = TRUE.complex_modulus(2 * np.pi * f * 10 ** dma.wlf_log_aT(T, T_REF, C1, C2))
        noise = 1 + 0.01 * rng.standard_normal((2, f.size))
        rows += [f"{fi:.17g},{e.real * n1 / 1e6:.17g},{e.imag * n2 / 1e6:.17g},{T},{k}" for fi, e, n1, n2 in zip(f, es, *noise)]
    path.write_text("\n".join(rows) + "\n")
    return dma.read_table(path)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_synthetic_prony_wlf_material_is_recovered(tmp_path, seed):
    """Issue 12 acceptance: five temperatures, 1 % noise: log shift factors within 0.1 of the true
    ones, and the COR at three temperatures within 1 % of the known material's."""
    sp = dma.superpose(_synthetic(tmp_path / "s.csv", seed), T_REF)
    true = dma.wlf_log_aT(sp.T, T_REF, C1, C2)
    assert np.max(np.abs(sp.log_aT - true)) <= 0.1, (sp.log_aT, true)
    c1, c2, _ = dma.wlf_fit(sp.T, sp.log_aT, T_REF)
    fit = dma.fit_master(sp)
    worst = 0.0
    for T in (0.0, 20.0, 40.0):
        got = vcor.simulate(dma.shifted(fit.material, float(dma.wlf_log_aT(T, T_REF, c1, c2))), 1.0,
                            method="adaptive", rigid=True).cor
        ref = vcor.simulate(dma.shifted(TRUE, float(dma.wlf_log_aT(T, T_REF, C1, C2))), 1.0,
                            method="adaptive", rigid=True).cor
        worst = max(worst, abs(got / ref - 1))
    print(f"\nseed {seed}: shift error {np.max(np.abs(sp.log_aT - true)):.3f}, WLF C1 {c1:.2f} C2 {c2:.1f} K, "
          f"COR worst {worst:.2%}, fit rms |E*| {fit.metrics['abs_E_star_rms']:.2%}")
    assert worst <= 0.01


def test_pyvisco_raw_sets_superposed_both_ways():
    """README table: our shift factors against pyvisco's, and how well each superposes E'."""
    raw = dma.read_table(DATA / "freq_user_raw.csv")
    ours = dma.superpose(raw, -5.0)
    theirs = dma.superpose(raw, -5.0, dma.read_table(DATA / "freq_user_master__shift_factors.csv"))
    print("\n T [C]  log_aT ours  pyvisco")
    for t, a, b in zip(ours.T, ours.log_aT, theirs.log_aT):
        print(f"{t:7.2f} {a:11.2f} {b:8.2f}")
    print(f"rms log10 E' mismatch in overlaps: ours {ours.overlap_rms:.4f}, pyvisco's factors {theirs.overlap_rms:.4f}")
    assert ours.overlap_rms < theirs.overlap_rms  # README: ours lay E' on one curve more tightly
    assert np.all(np.diff(ours.log_aT) < 0)  # a_T falls with temperature
    fit = dma.fit_master(ours)
    print(f"master-curve Prony fit ({len(fit.material.E)} terms): {fit.metrics}")
    assert fit.metrics["abs_E_star_rms"] < 0.1


def test_workflow_fits_measured_data_and_sweeps_temperature(tmp_path):
    """A fit to raw DMA sets in the config (superposition, WLF, Prony master curve): the material
    file carries its shift function, and a scene sweeps T with it."""
    import xarray as xr
    from test_workflow import make_project, smk

    cfg = {"shard_size": 100, "material_dir": "results/materials",
           "fits": {"measured": {"model": "prony", "data": {"file": "data/dma.csv", "T_ref": T_REF}}},
           "scenes": {"temp": {"materials": ["measured"], "grid": {"v0": [1.0], "T": [0.0, 20.0, 40.0]},
                               "geometry": {"rigid": True}, "figures": {"cor_temperature": {}}}}}
    path = make_project(tmp_path, cfg)
    (path / "data").mkdir()
    _synthetic(path / "data/dma.csv", 1)
    smk(path, "-j2")
    assert (path / "results/temp/figures/cor_temperature.png").stat().st_size > 0
    nc = path / "results/materials/measured.nc"
    shift = dma.shift_from_file(nc)
    assert shift.model == "wlf" and abs(shift.C1 - C1) < 0.5
    mat = vcor.materials.from_file(nc)
    ds = xr.open_dataset(path / "results/temp/sweep.nc")
    for T in (0.0, 20.0, 40.0):
        want = vcor.simulate(dma.shifted(mat, shift.log_aT(T)), 1.0, method="adaptive", rigid=True).cor
        assert ds["cor"].sel(material="measured", v0=1.0, T=T).item() == want
        true = vcor.simulate(dma.shifted(TRUE, float(dma.wlf_log_aT(T, T_REF, C1, C2))), 1.0, method="adaptive",
                             rigid=True).cor
        assert abs(want / true - 1) <= 0.01
