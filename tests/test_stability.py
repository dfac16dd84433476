"""Stability on stiff and extreme cases (README, "Stability"): every point of the config's stability
scenes is ok with a Richardson error estimate, or flagged with a status and its reason. The counts
per scene and the largest estimate are the README's numbers; a change of either fails here."""

import collections
from pathlib import Path

import numpy as np
import pytest
import yaml

from vcor import status
from vcor.study import runner, scene

CONFIG = yaml.safe_load((Path(__file__).resolve().parents[1] / "config.yaml").read_text())
SCENES = {k: v for k, v in CONFIG["scenes"].items() if k.startswith("stability-")}

#: README "Stability": statuses per scene with the default solver (direct, 2000 steps per t_c)
DOCUMENTED = {
    "stability-plate": {"ok": 84},
    "stability-relaxation": {"ok": 32},
    "stability-ratio": {"ok": 24},
    "stability-mass": {"ok": 32},
    "stability-limits": {"ok": 35},
}
#: README: largest Richardson estimate of the COR error over the ok points
MAX_COR_ERR = 4e-6
#: README: the points stopped by the step budget are thin plates, h <= 10 mm (grid h = 1, 3.16, 10 mm)
THIN = 1.0e-2 * (1 + 1e-12)


def test_there_are_stability_scenes():
    assert set(DOCUMENTED) == set(SCENES)


@pytest.mark.parametrize("name", sorted(SCENES))
def test_every_point_ok_or_flagged_with_its_reason(name):
    sc = SCENES[name]
    assert sc.get("error_estimate") is True
    points = scene.scene_points(sc)
    ds = runner.run_points(points, scene.settings_of(sc))
    names = [status.STATUS_NAMES[int(c)] for c in ds["status"].values]
    counts = dict(collections.Counter(names))
    ok = ds["status"].values == status.code("ok")
    err, msg = ds["cor_err"].values, ds["message"].values
    print(f"\n{name}: {counts}, max cor_err {np.nanmax(err[ok]):.2e}")
    assert counts == DOCUMENTED[name]
    assert np.all(ds["error_status"].values[ok] == status.code("ok"))
    assert np.all(np.isfinite(ds["cor"].values[ok])) and np.all(ds["cor"].values[ok] > 0)
    assert np.all(np.isfinite(err[ok])) and np.all(err[ok] <= MAX_COR_ERR)
    for i in np.where(~ok)[0]:
        assert names[i] == "step-budget", (names[i], msg[i])
        assert "step budget" in str(msg[i]) and "T_max" in str(msg[i])
        assert float(ds["h"].values[i]) <= THIN
        assert np.isnan(ds["cor"].values[i]) and np.isnan(err[i])


def test_richardson_estimate_tracks_the_true_error():
    """cor_err (dt and dt/2) against the true error of the dt run (reference: ive at rtol 1e-12)."""
    import vcor

    sc = {"materials": ["sls", "butyl-prony3"], "grid": {"v0": [1.0, 30.0]}, "error_estimate": True}
    ds = runner.run_points(scene.scene_points(sc), scene.settings_of(sc))
    for i in range(ds.sizes["point"]):
        mat, v0 = str(ds["material"].values[i]), float(ds["v0"].values[i])
        true = abs(ds["cor"].values[i] - vcor.simulate(mat, v0, method="ive", rtol=1e-12).cor)
        est = ds["cor_err"].values[i]
        assert 0.5 * true < est < 2.0 * true, (mat, v0, est, true)
        assert ds["t0_err"].values[i] > 0
