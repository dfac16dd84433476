"""Scenes with uncertainty (vcor.study.uncertainty): the checks, the bootstrap axis, the reduction of
samples to median and band, and the whole chain from measured data to a band that covers the truth."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from vcor import status as st
from vcor.io.netcdf import read_dataset
from vcor.study import scene as vscene
from vcor.study.config import load_project
from vcor.study.uncertainty import reduce_samples

DATA = "data/pyvisco/freq_user_raw.csv"


def _config(**uncertainty):
    return {"fits": {"pv": {"model": "prony", "data": {"file": DATA, "T_ref": -5}}},
            "scenes": {"u": {"materials": ["pv"], "grid": {"v0": [1, 10], "T": [-20, 20]},
                             "uncertainty": uncertainty}}}


@pytest.mark.parametrize("unc, words", [
    ({"bootstrap": 1}, ["scenes.u.uncertainty.bootstrap", "[2, 1000]"]),
    ({"bootstrap": 20, "level": 1.0}, ["scenes.u.uncertainty.level", "(0, 1)"]),
    ({"bootstrap": 20, "seed": -1}, ["scenes.u.uncertainty.seed", ">= 0"]),
    ({"bootstrap": 20, "samples": 3}, ["scenes.u.uncertainty", "unknown keys ['samples']"]),
], ids=["one sample", "level 1", "negative seed", "unknown key"])
def test_bad_uncertainty_settings_are_refused_naming_the_key(unc, words):
    with pytest.raises(ValueError) as err:
        load_project(_config(**unc), ".")
    for w in words:
        assert w in str(err.value), (w, str(err.value))


def test_a_material_without_measured_data_is_refused():
    cfg = _config(bootstrap=10)
    cfg["scenes"]["u"]["materials"] = ["pv", "sls"]
    cfg["scenes"]["u"]["grid"] = {"v0": [1, 10]}
    with pytest.raises(ValueError, match=r"scenes.u.uncertainty: material 'sls' is not a fit to measured data"):
        load_project(cfg, ".")


def test_the_bootstrap_axis_and_the_files_a_scene_needs():
    project = load_project(_config(bootstrap=7, seed=3), ".")
    scene = project.scenes["u"]
    assert scene.grid.values()["sample"] == [float(k) for k in range(7)]
    assert scene.grid.axis("sample").role == "sample" and scene.grid.size == 1 * 2 * 2 * 7
    assert vscene.point_count(scene.config) == scene.grid.size
    assert scene.settings["uncertainty"] == {"bootstrap": 7, "seed": 3, "level": 0.95}
    assert "results/materials/samples/pv-b7-s3.nc" in project.material_files_of("u")
    assert "results/materials/samples/pv-b7-s3.nc" in project.scene_targets("u")
    plain = load_project({"scenes": {"p": {"materials": ["sls"], "grid": {"v0": [1, 2]}}}}, ".").scenes["p"]
    assert "sample" not in plain.grid.names and "uncertainty" not in plain.settings


def test_the_samples_are_split_over_jobs_with_identities_of_their_own():
    """SAMPLE_JOBS part files (one job each) make the samples file; each part's identity names its share,
    the merged file's does not depend on the split (sample i is the same in any part), and every identity
    follows the fit's."""
    from vcor.study import paths
    from vcor.study.uncertainty import MIN_BOOTSTRAP, SAMPLE_JOBS, samples_identity

    assert 2 <= SAMPLE_JOBS <= MIN_BOOTSTRAP
    parts = paths.samples_parts("results/materials", SAMPLE_JOBS, "pv", 7, 3)
    assert parts == [f"results/materials/samples/pv-b7-s3-p{k}of{SAMPLE_JOBS}.nc" for k in range(SAMPLE_JOBS)]
    assert paths.samples("results/materials", "pv", 7, 3) == "results/materials/samples/pv-b7-s3.nc"
    cat = load_project(_config(bootstrap=7, seed=3), ".").catalogue
    spec = {"bootstrap": 7, "seed": 3}
    ids = {samples_identity(cat, "pv", spec, (k, SAMPLE_JOBS)) for k in range(SAMPLE_JOBS)}
    merged = samples_identity(cat, "pv", spec)
    assert len(ids) == SAMPLE_JOBS and merged not in ids
    assert samples_identity(cat, "pv", {"bootstrap": 7, "seed": 4}) != merged
    other = _config(bootstrap=7, seed=3)
    other["fits"]["pv"]["data"]["T_ref"] = 0
    assert samples_identity(load_project(other, ".").catalogue, "pv", spec) != merged


def _sweep(cor, status):
    """A sweep with dims (material, v0, sample) as the aggregate builds it before the reduction."""
    cor, status = np.asarray(cor, float), np.asarray(status, np.int8)
    dims = ("material", "v0", "sample")
    n = cor.shape[-1]
    msg = np.where(status == 0, "", "Newton failed").astype(str)
    return xr.Dataset({
        "cor": (dims, cor, {"units": "1", "long_name": "coefficient of restitution"}),
        "t0": (dims, 1e-3 * cor, {"units": "s", "long_name": "contact time"}),
        "status": (dims, status, st.cf_attrs()),
        "message": (dims, msg),
        "validity": (dims, np.zeros(cor.shape, np.int8)),
        "validity_message": (dims, np.full(cor.shape, "", dtype=str)),
    }, coords={"material": ["m"], "v0": [1.0, 10.0], "sample": np.arange(n, dtype=float)})


def test_reduction_gives_median_band_and_samples_and_an_honest_status():
    rng = np.random.default_rng(0)
    cor = rng.uniform(0.5, 0.9, size=(1, 2, 41))
    status = np.zeros_like(cor, dtype=np.int8)
    status[0, 1, 5] = st.code("diverged")
    red = reduce_samples(_sweep(cor, status), 0.9)
    assert red["cor"].dims == ("material", "v0") and red["cor_lo"].dims == red["cor"].dims
    np.testing.assert_allclose(red["cor"].values[0, 0], np.median(cor[0, 0]))
    np.testing.assert_allclose([red["cor_lo"].values[0, 0], red["cor_hi"].values[0, 0]],
                               np.quantile(cor[0, 0], [0.05, 0.95]))
    good = np.delete(cor[0, 1], 5)
    np.testing.assert_allclose(red["cor"].values[0, 1], np.median(good))  # the failed sample left out
    assert red["status"].values.tolist() == [[0, st.code("diverged")]]
    assert red["message"].values[0, 1].startswith("1 of 41 bootstrap samples not ok; sample 5: Newton failed")
    assert red["samples_ok"].values.tolist() == [[41, 40]]
    np.testing.assert_array_equal(red["cor_samples"].values, cor)
    assert red["t0_lo"].attrs["units"] == "s" and red.attrs["uncertainty_level"] == 0.9


def test_significant_reversals_count_the_turns_the_band_supports():
    from vcor.study.uncertainty import significant_reversals

    T = np.linspace(-50, 100, 31)
    valley = 0.9 - 0.4 * np.exp(-((T - 20) / 30) ** 2)                   # one minimum
    assert significant_reversals(valley, 0.01) == 1
    wiggly = valley + 0.004 * np.sin(T / 3)                               # ripple of 0.008 peak to peak
    assert significant_reversals(wiggly, 0.005) == 1                      # inside the band: not counted
    assert significant_reversals(wiggly, 0.001) >= 3                      # a narrow band: the ripple counts
    bump = valley + 0.05 * np.exp(-((T + 30) / 5) ** 2)                    # a real bump on the cold side
    # the bump's top and the minimum count; the dip just before the bump falls by 0.004 on its cold side
    assert significant_reversals(bump, 0.01) == 2 and significant_reversals(bump, 0.1) == 1
    assert significant_reversals(np.linspace(0.5, 0.9, 10), 0.0) == 0     # monotone
    assert significant_reversals([0.5, 0.5, 0.6, 0.6, 0.5], 0.05) == 1    # flat steps skipped


@pytest.mark.slow
def test_workflow_carries_every_sample_through_the_sweep(make_project, smk, tmp_path):
    """A fit to synthetic DMA data (the instrument lag fitted) with 4 bootstrap samples: the samples file
    (with every sample's lag), the sample axis in the shards, the reduced sweep (median, band, samples;
    every sample's COR is vcor.simulate of that sample's material at its own shift), the band and the
    lag in the figure's title, and extending the grid solves only the new points."""
    import yaml
    from synthetic_dma import synthetic, write_csv

    import vcor
    from vcor.fitting.samples import sample_materials
    from vcor.materials import shift as tts

    cfg = {"shard_size": 100, "material_dir": "results/materials",
           "fits": {"measured": {"model": "prony", "data": {"file": "data/dma.csv", "T_ref": 20.0,
                                                            "instrument_lag": True}}},
           "scenes": {"band": {"materials": ["measured"], "grid": {"v0": [1.0, 3.0], "T": [0.0, 40.0]},
                               "geometry": {"rigid": True}, "uncertainty": {"bootstrap": 4, "seed": 2},
                               "figures": {"cor_temperature": {}, "master_curve": {"materials": ["measured"]}}}}}
    path = make_project(tmp_path, cfg)
    (path / "data").mkdir(exist_ok=True)
    write_csv(path / "data/dma.csv", synthetic(1))
    smk(path, "-j2")
    samples = read_dataset(path / "results/materials/samples/measured-b4-s2.nc")
    # fitted by SAMPLE_JOBS jobs side by side, each from the full-data fit's file, then merged
    from vcor.study.uncertainty import SAMPLE_JOBS

    parts = sorted(p.name for p in (path / "results/materials/samples").glob("measured-b4-s2-p*.nc"))
    assert parts == [f"measured-b4-s2-p{k}of{SAMPLE_JOBS}.nc" for k in range(SAMPLE_JOBS)]
    assert samples["sample"].values.tolist() == [0, 1, 2, 3]
    mats = sample_materials(samples)
    assert len(mats) == 4
    assert samples["lag"].attrs["units"] == "s" and np.all(np.isfinite(samples["lag"].values))
    assert np.unique(samples["lag"].values).size == 4          # refitted in every sample
    ds = read_dataset(path / "results/band/sweep.nc")
    assert ds["cor"].dims == ("material", "v0", "T") and ds["cor_samples"].dims == ("material", "v0", "T", "sample")
    assert (ds["status"] == 0).all() and (ds["samples_ok"] == 4).all()
    assert (ds["cor_lo"] <= ds["cor"]).all() and (ds["cor"] <= ds["cor_hi"]).all()
    assert (ds["cor_hi"] - ds["cor_lo"] > 0).all()  # noisy data: a band of non-zero width
    for k in (0, 3):
        material, shift = mats[k]
        want = vcor.simulate(tts.at_temperature(material, shift, 40.0), 3.0, rigid=True).cor
        assert ds["cor_samples"].sel(material="measured", v0=3.0, T=40.0, sample=float(k)).item() == want
    np.testing.assert_array_equal(ds["cor"].values, ds["cor_samples"].median("sample").values)
    # the master curve shades the samples' spectrum band (E', E'', tan delta)
    from matplotlib.collections import PolyCollection

    from vcor import plots

    assert (path / "results/band/figures/master_curve.png").stat().st_size > 0
    fit = read_dataset(path / "results/materials/measured.nc")
    fig = plots.draw("master_curve", {"material_fit": [fit], "material_samples": [samples]}, {})
    top, bottom = fig.axes[0], fig.axes[1]
    assert "95 % band over 4 bootstrap samples" in top.get_title()
    assert "instrument lag" in top.get_title() and "removed" in top.get_title()
    assert sum(isinstance(c, PolyCollection) for c in top.collections) == 2
    assert sum(isinstance(c, PolyCollection) for c in bottom.collections) == 1
    plain = plots.draw("master_curve", {"material_fit": [fit], "material_samples": []}, {})
    assert "bootstrap" not in plain.axes[0].get_title()
    shards = sorted((path / "results/band/shards").glob("*.nc"))
    cfg["scenes"]["band"]["grid"]["v0"] = [1.0, 3.0, 10.0]
    (path / "config.yaml").write_text(yaml.safe_dump(cfg))
    out = smk(path, "-j2")
    assert "sweep_shard" in out.stdout + out.stderr
    after = sorted((path / "results/band/shards").glob("*.nc"))
    assert set(shards) < set(after) and len(after) == len(shards) + 1  # the old shard kept, one new
    assert read_dataset(path / "results/band/sweep.nc").sizes["v0"] == 3
