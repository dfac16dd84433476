"""Stability on stiff and extreme cases: every point of the config's stability scenes is ok with a
Richardson error estimate below 1e-4, or flagged with a non-ok status and a message."""

from pathlib import Path

import numpy as np
import pytest
import yaml

from vcor import sweep
from vcor.solvers import STATUS_CODES

CONFIG = yaml.safe_load((Path(__file__).resolve().parents[1] / "config.yaml").read_text())
SCENES = {k: v for k, v in CONFIG["scenes"].items() if k.startswith("stability-")}


def test_there_are_stability_scenes():
    assert {"stability-plate", "stability-relaxation", "stability-ratio", "stability-mass",
            "stability-limits"} <= set(SCENES)


@pytest.mark.parametrize("name", sorted(SCENES))
def test_every_point_ok_or_flagged(name):
    scene = SCENES[name]
    assert scene.get("error_estimate") is True
    points = sweep.scene_points(scene)
    ds = sweep.run_points(points, sweep.settings_of(scene))
    status, cor, err, msg = ds["status"].values, ds["cor"].values, ds["cor_err"].values, ds["message"].values
    ok = status == STATUS_CODES["ok"]
    print(f"\n{name}: {ok.sum()} of {len(points)} points ok, max cor_err {np.nanmax(err[ok]):.2e}; "
          f"flagged: {sorted({str(m)[:60] for m in msg[~ok]})}")
    assert np.all(np.isfinite(cor[ok])) and np.all(np.isfinite(err[ok]))
    assert np.all(err[ok] < 1e-4)
    assert np.all(cor[ok] > 0)
    assert all(len(str(m)) > 0 for m in msg[~ok])
    # no NaN without a status: every NaN COR belongs to a flagged point
    assert np.all(~np.isnan(cor) | ~ok)


def test_richardson_estimate_tracks_the_true_error():
    """cor_err (dt and dt/2) against the true error of the dt run (reference: ive at rtol 1e-12)."""
    import vcor

    scene = {"materials": ["sls", "butyl-prony3"], "grid": {"v0": [1.0, 30.0]}, "error_estimate": True}
    ds = sweep.run_points(sweep.scene_points(scene), sweep.settings_of(scene))
    for i in range(ds.sizes["point"]):
        mat, v0 = str(ds["material"].values[i]), float(ds["v0"].values[i])
        true = abs(ds["cor"].values[i] - vcor.simulate(mat, v0, method="ive", rtol=1e-12).cor)
        est = ds["cor_err"].values[i]
        assert 0.5 * true < est < 2.0 * true, (mat, v0, est, true)
        assert ds["t0_err"].values[i] > 0
