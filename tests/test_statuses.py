"""One status vocabulary (docs/user-guide/statuses.md): each status a row; a failed point or run never loses
the others; failed histories are NaN with their status; an error-estimate run has its own status."""

import math

import numpy as np
import pytest

import vcor
from vcor import status
from vcor.contact.impact import Impact
from vcor.study import datasets, runner, scene

SCENE = {"materials": ["sls"], "grid": {"v0": [1.0, 10.0]}}


def test_codes_are_stable_and_cf_encoded():
    # archived datasets keep their meaning: the codes never change
    assert status.STATUS_CODES == {"ok": 0, "no-separation": 1, "diverged": 2, "invalid-input": 3, "failed": 4,
                                   "step-budget": 5}
    attrs = status.cf_attrs()
    assert list(attrs["flag_values"]) == [0, 1, 2, 3, 4, 5]
    assert attrs["flag_meanings"] == "ok no_separation diverged invalid_input failed step_budget"
    with pytest.raises(ValueError, match="unknown status"):
        status.code("fine")


def test_ok():
    r = vcor.simulate("sls", 10.0)
    assert r.status == "ok" and r.ok and r.message == ""


def test_step_budget_is_not_no_separation():
    r = vcor.simulate("sls", 10.0, method="direct", max_steps=500)
    assert r.status == "step-budget" and not r.ok
    assert "step budget" in r.message and "T_max" in r.message and math.isnan(r.cor)


def test_solve_ivp_has_a_step_budget_too():
    """ive (scipy's solve_ivp) on a 10 um plate, whose contact creeps for hours: its steps are budgeted
    (max_steps, over all its horizons; 60000 by default, enough for the 1 mm plates that
    tests/solvers/test_soe.py and test_adaptive.py solve by ive) and the run ends with status
    step-budget and a message that says why and what to change. Here with a budget of 300 steps (the
    same path, cheaper)."""
    r = vcor.simulate("sls", 1.0, method="ive", h=1e-5, max_steps=300)
    assert r.status == "step-budget" and math.isnan(r.cor) and r.steps == 300
    for words in ("max_steps = 300", "without the contact force returning to zero", "raise max_steps",
                  "method adaptive"):
        assert words in r.message, (words, r.message)
    assert vcor.simulate("sls", 1.0, method="ive", max_steps=5000).ok  # the standard impact: about 900 steps


@pytest.mark.parametrize("method", ["direct", "ive-numba"])
def test_separation_in_the_last_step_before_the_budget_is_a_separation(method):
    full = vcor.simulate("sls", 10.0, method=method)
    n = int(full.steps)  # the step in which the force crossed zero
    last = vcor.simulate("sls", 10.0, method=method, max_steps=n)
    assert last.status == "ok" and last.cor == full.cor and last.t0 == full.t0
    assert vcor.simulate("sls", 10.0, method=method, max_steps=n - 1).status == "step-budget"


def test_diverged(monkeypatch):
    """A non-finite value in the march (here injected through the plate mobility) is `diverged`,
    with the step and time in the message."""
    real = Impact.alpha

    def poisoned(self, t):
        a = np.array(real(self, t), dtype=float, copy=True)
        return np.where(np.asarray(t) > 2e-4, np.nan, a)

    monkeypatch.setattr(Impact, "alpha", poisoned)
    r = vcor.simulate("sls", 10.0, method="direct", dt=1e-6)
    assert r.status == "diverged" and "non-finite" in r.message and "step" in r.message


def test_invalid_input_and_failed_points_keep_the_others(monkeypatch):
    points = scene.scene_points({**SCENE, "grid": {"v0": [1.0, 10.0, 20.0], "alpha": [-5.0, 250.0]}})
    real = runner.simulate

    def flaky(material, v0, **kw):
        if v0 == 20.0:
            raise RuntimeError("injected")
        return real(material, v0, **kw)

    monkeypatch.setattr(runner, "simulate", flaky)
    ds = runner.run_points(points, scene.settings_of(SCENE))
    names = np.array([status.STATUS_NAMES[int(c)] for c in ds["status"].values])
    alpha, v0 = ds["alpha"].values, ds["v0"].values
    assert np.all(names[alpha < 0] == "invalid-input")
    assert all("alpha" in str(m) for m in ds["message"].values[alpha < 0])
    assert np.all(names[(alpha > 0) & (v0 == 20.0)] == "failed")
    assert all("RuntimeError: injected" in str(m) for m in ds["message"].values[(alpha > 0) & (v0 == 20.0)])
    good = (alpha > 0) & (v0 < 20.0)
    assert np.all(names[good] == "ok") and np.all(np.isfinite(ds["cor"].values[good]))
    assert np.all(np.isnan(ds["cor"].values[~good]))


def test_a_failing_error_estimate_has_its_own_status():
    """dt fits the step budget, dt/2 does not: the point stays ok, the estimate is step-budget."""
    sc = {**SCENE, "grid": {"v0": [10.0]}, "error_estimate": True,
          "solver": {"method": "direct", "steps_per_contact": 200, "max_steps": 250}}
    ds = runner.run_points(scene.scene_points(sc), scene.settings_of(sc))
    assert status.STATUS_NAMES[int(ds["status"].values[0])] == "ok" and np.isfinite(ds["cor"].values[0])
    assert status.STATUS_NAMES[int(ds["error_status"].values[0])] == "step-budget"
    assert "step budget" in str(ds["error_message"].values[0])
    assert np.isnan(ds["cor_err"].values[0])


def test_an_error_estimate_at_the_smallest_rtol_runs_and_one_that_raises_keeps_the_point():
    """ive at rtol 1e-12: the estimate's run at rtol / 100 would be below RTOL_MIN; it runs at RTOL_MIN and
    the point and its estimate are ok."""
    sc = {**SCENE, "grid": {"v0": [10.0]}, "error_estimate": True, "solver": {"method": "ive", "rtol": 1e-12}}
    ds = runner.run_points(scene.scene_points(sc), scene.settings_of(sc))
    assert [status.STATUS_NAMES[int(ds[k].values[0])] for k in ("status", "error_status")] == ["ok", "ok"]
    assert np.isfinite(ds["cor_err"].values[0]) and ds["cor_err"].values[0] < 1e-9


def test_an_error_estimate_that_raises_keeps_the_point(monkeypatch):
    """A second run that raises is stored as the estimate's status and message; the point keeps its own."""
    calls = []
    simulate = runner.simulate

    def second_raises(*args, **kwargs):
        calls.append(1)
        if len(calls) == 2:
            raise ValueError("the second run's own refusal")
        return simulate(*args, **kwargs)

    monkeypatch.setattr(runner, "simulate", second_raises)
    sc = {**SCENE, "grid": {"v0": [10.0]}, "error_estimate": True}
    ds = runner.run_points(scene.scene_points(sc), scene.settings_of(sc))
    assert status.STATUS_NAMES[int(ds["status"].values[0])] == "ok" and np.isfinite(ds["cor"].values[0])
    assert status.STATUS_NAMES[int(ds["error_status"].values[0])] == "invalid-input"
    assert str(ds["error_message"].values[0]) == "the second run's own refusal"


def test_failed_history_is_nan_with_its_status_and_rule_is_honoured():
    runs = [("sls", "direct"), ("butyl-fc", "ive"), ("sls", "ive")]
    ds = datasets.histories_dataset(runs, 10.0, options={"method": "direct", "max_steps": 1000})
    names = [status.STATUS_NAMES[int(c)] for c in ds["status"].values]
    assert names == ["step-budget", "invalid-input", "ok"]
    assert "Prony" in str(ds["message"].values[1])
    for i in (0, 1):
        assert np.all(np.isnan(ds["F"].values[i])) and np.isnan(ds["cor"].values[i])
    assert np.all(np.isfinite(ds["F"].values[2]))
    assert ds["status"].attrs["flag_meanings"] == status.cf_attrs()["flag_meanings"]
    # the separation rule reaches the histories: overlap separates later than force
    force = datasets.histories_dataset([("sls", "direct")], 10.0, options={"rule": "force"})
    overlap = datasets.histories_dataset([("sls", "direct")], 10.0, options={"rule": "overlap"})
    assert float(overlap["t0"].values[0]) > float(force["t0"].values[0]) * 1.01


def test_separation_uses_the_root_inside_the_step():
    """Force rule, s already negative a step before F crosses zero: the root of F is used (it lies
    in the step), not an extrapolated root of s; a target that does not change sign is an error."""
    from vcor.solvers.common import separation

    t = np.arange(6.0)
    s = np.array([0.0, 1.0, 0.5, -0.1, -0.5, -1.0])
    F = np.array([0.0, 2.0, 1.5, 1.0, -0.5, -1.0])
    g = np.gradient(s, t)
    J = np.cumsum(F)
    out = separation(t, s, g, F, J, 4, "force", 1.0, 1.0)
    assert 3.0 < out["t0"] < 4.0 and out["message"] == ""
    with pytest.raises(RuntimeError, match="does not change sign"):
        separation(t, s, g, np.abs(F) + 1.0, J, 4, "force", 1.0, 1.0)
