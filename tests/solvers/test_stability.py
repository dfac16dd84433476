"""Stability on stiff and extreme cases (docs, "Stability"): every point of the config's stability
scenes is ok with a Richardson error estimate and its validity flags. The counts per scene, the
bound on the largest estimate and the flag counts are the documented numbers; a change of any
fails here."""

import collections
from pathlib import Path

import numpy as np
import pytest
import yaml

from vcor import status
from vcor.solvers.validity import FLAGS, SOLVER_FLAGS
from vcor.study import runner, scene

CONFIG = yaml.safe_load((Path(__file__).resolve().parents[2] / "config.yaml").read_text())
SCENES = {k: v for k, v in CONFIG["scenes"].items() if k.startswith("stability-")}

#: docs, "Stability": per scene with the default solver (adaptive): the statuses, the bound on the
#: largest Richardson estimate of the COR error over the ok points without a solver flag (grids_disagree,
#: uncertain_extrapolation: they say their error is not held to the method's accuracy; the documented number, the
#: largest estimate rounded up to two digits), and how many ok points carry each validity flag
DOCUMENTED = {
    "stability-plate": ({"ok": 84}, 8.5e-9, {"large_indentation": 38, "fast_impact": 26, "no_rebound": 10,
                                              "grids_disagree": 11}),
    "stability-relaxation": ({"ok": 32}, 1.5e-8, {"large_indentation": 20, "fast_impact": 12,
                                                  "uncertain_extrapolation": 2}),
    "stability-ratio": ({"ok": 24}, 5.2e-9, {"large_indentation": 12, "fast_impact": 10, "no_rebound": 1,
                                             "uncertain_extrapolation": 1}),
    "stability-mass": ({"ok": 32}, 6.5e-9, {"large_indentation": 14, "fast_impact": 9}),
    "stability-limits": ({"ok": 35}, 8.1e-9, {"large_indentation": 15, "fast_impact": 15}),
}


def test_there_are_stability_scenes():
    assert set(DOCUMENTED) == set(SCENES)


@pytest.mark.parametrize("name", sorted(SCENES))
def test_every_point_ok_with_its_error_estimate_and_validity(name):
    """Every point of the scene has the documented status, an error estimate within the documented
    bound, and the documented validity flags (a change of any count fails)."""
    sc = SCENES[name]
    assert sc.get("error_estimate") is True and "solver" not in sc  # the default method
    ds = runner.run_points(scene.scene_points(sc), scene.settings_of(sc))
    counts = dict(collections.Counter(status.STATUS_NAMES[int(c)] for c in ds["status"].values))
    ok = ds["status"].values == status.code("ok")
    err, validity = ds["cor_err"].values, ds["validity"].values
    flags = {f: int(((validity[ok] & m) != 0).sum()) for f, m in FLAGS.items()}
    held = ok & ((validity & SOLVER_FLAGS) == 0)
    print(f"\n{name}: {counts}, max cor_err {np.nanmax(err[held]):.3e} (with a solver flag: "
          f"{np.nanmax(err[ok & ~held], initial=0.0):.3e}), validity flags {flags}")
    statuses, bound, documented_flags = DOCUMENTED[name]
    assert counts == statuses
    assert np.all(ds["error_status"].values[ok] == status.code("ok"))
    assert np.all(np.isfinite(ds["cor"].values[ok])) and np.all(ds["cor"].values[ok] > 0)
    assert np.all(np.isfinite(err[ok])) and np.nanmax(err[held]) <= bound
    assert {f: n for f, n in flags.items() if n} == documented_flags
    flagged = validity != 0
    assert all(bool(m) for m in ds["validity_message"].values[flagged])
    assert not any(str(m) for m in ds["validity_message"].values[~flagged])


def test_a_thin_plate_beyond_the_direct_horizon_is_flagged_with_its_reason():
    """``direct`` (O(N^2) history, a fixed step budget) cannot reach the contact of a 1 mm plate: the
    point is step-budget with a message naming the budget and T_max, and no number; the default
    method solves it."""
    import vcor

    r = vcor.simulate("butyl-fc", 10.0, h=1e-3, method="direct")
    assert r.status == "step-budget" and not r.ok
    assert "step budget" in r.message and "T_max" in r.message
    assert np.isnan(r.cor) and np.isnan(r.t0)
    assert vcor.simulate("butyl-fc", 10.0, h=1e-3).ok


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
