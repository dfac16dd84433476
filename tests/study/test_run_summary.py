"""A run says what it did: a summary per scene at the end of Snakemake's output (successful or failed
run), job logs that say what each job computed, no ``Shell command: None`` lines, the core count the
command line asks for, and a report that names the scene's dataset and says when it has no figures."""

from __future__ import annotations

import re

import numpy as np
import pytest
import xarray as xr

from vcor import status as vstatus
from vcor.solvers import validity as vvalidity
from vcor.solvers.validity import FLAGS
from vcor.status import STATUS_CODES
from vcor.study.summary import outcome_of

#: one sweep of two impacts of the paper's SLS plate: 1 m/s (inside the model's range) and 50 m/s
#: (s_max / r and v0 / wave speed beyond the stated limits: flagged)
TINY = {"scenes": {"tiny": {"materials": ["sls"], "grid": {"v0": [1.0, 50.0]}}}}
HEADER = "vcor: what the results hold"


def test_outcome_counts_ok_flagged_and_failed_by_name():
    # six points: ok; ok + large_indentation; ok + large_indentation + fast_impact; no-separation with a
    # flag bit set (a bootstrap sample's flag: not ok, so failed, not flagged); step-budget; failed
    codes = [vstatus.code(s) for s in ("ok", "ok", "ok", "no-separation", "step-budget", "failed")]
    big, fast = FLAGS["large_indentation"], FLAGS["fast_impact"]
    flags = [0, big, big | fast, fast, 0, 0]
    ds = xr.Dataset({"status": ("p", np.array(codes, np.int8), vstatus.cf_attrs()),
                     "validity": ("p", np.array(flags, np.int8), vvalidity.cf_attrs())})
    out = outcome_of(ds)
    assert (out.points, out.ok, out.flagged, out.failed) == (6, 1, 2, 3)
    assert out.reasons == {"large_indentation": 2, "fast_impact": 1}
    assert out.statuses == {"no-separation": 1, "failed": 1, "step-budget": 1}
    assert out.text() == ("1 ok, 2 flagged (large_indentation 2, fast_impact 1), "
                          "3 failed (no-separation 1, failed 1, step-budget 1)")
    # without a validity variable every ok point counts as ok
    assert outcome_of(ds[["status"]]).text() == "3 ok, 0 flagged, 3 failed (no-separation 1, failed 1, step-budget 1)"


def test_a_file_is_counted_like_the_dataset_it_holds(tmp_path):
    """read_outcome reads status and validity with netCDF4 alone; the counts and names are those of the
    dataset, string variables (a message per point) and all; a file with no status is refused."""
    from vcor.io import netcdf
    from vcor.study.summary import read_outcome

    codes = np.array([vstatus.code(s) for s in ("ok", "ok", "step-budget", "ok")], np.int8)
    flags = np.array([0, FLAGS["large_indentation"], 0, FLAGS["fast_impact"]], np.int8)
    ds = xr.Dataset({"status": ("p", codes, vstatus.cf_attrs()), "validity": ("p", flags, vvalidity.cf_attrs()),
                     "message": ("p", np.array(["", "", "step budget reached", ""], dtype=object))})
    path = netcdf.write_dataset(ds, tmp_path / "sweep.nc", title="test")
    assert read_outcome(path) == outcome_of(ds)
    assert read_outcome(path).text() == "1 ok, 2 flagged (large_indentation 1, fast_impact 1), 1 failed (step-budget 1)"
    path = netcdf.write_dataset(ds[["message"]], tmp_path / "other.nc", title="test")
    with pytest.raises(ValueError, match="no variable 'status'"):
        read_outcome(path)


def test_a_work_precision_scene_is_summed_up_by_its_runs(tmp_path):
    """A work-precision dataset counts its runs: the cells of the method x ladder table with a ladder
    value; cells past a shorter ladder or of a method that does not apply are not runs."""
    import types

    from vcor.io import netcdf
    from vcor.study.summary import run_summary

    nan, ok, budget = np.nan, vstatus.code("ok"), vstatus.code("step-budget")
    off = vstatus.code("invalid-input")
    param = np.array([[250.0, 500.0, 1000.0], [1e-4, 1e-6, nan], [nan, nan, nan]])
    codes = np.array([[ok, ok, budget], [ok, ok, off], [off, off, off]], np.int8)
    ds = xr.Dataset({"status": (("solver", "level"), codes, vstatus.cf_attrs()),
                     "param": (("solver", "level"), param, {"units": "1", "long_name": "ladder value"})})
    netcdf.write_dataset(ds, tmp_path / "results/acc/convergence.nc", title="test")
    project = types.SimpleNamespace(scenes={"acc": None}, dem={},
                                    catalogue=types.SimpleNamespace(calibrations={}))
    lines = run_summary(project, tmp_path)
    assert lines[0].startswith(HEADER)
    assert lines[1:] == ["  scene acc (work-precision): 5 runs, 4 ok, 0 flagged, 1 failed (step-budget 1): "
                         "results/acc/convergence.nc"]


def test_time_histories_are_summed_up_by_their_runs(tmp_path):
    """A scene's time histories count their runs, a failed one by its status (a histories-only scene
    printed nothing however its runs ended)."""
    import types

    from vcor.io import netcdf
    from vcor.study import datasets
    from vcor.study.summary import outcome_of, run_summary

    ds = datasets.histories_dataset([("sls", "direct"), ("sls", "adaptive")], 3.0,
                                    options={"max_adaptive_steps": 100}, geometry={"h": 0.001})
    netcdf.write_dataset(ds, tmp_path / "results/h/histories.nc", title="test")
    project = types.SimpleNamespace(scenes={"h": None}, dem={}, catalogue=types.SimpleNamespace(calibrations={}))
    lines = run_summary(project, tmp_path)
    assert lines[1:] == [f"  scene h (time histories): 2 runs, {outcome_of(ds).text()}: results/h/histories.nc"]
    assert "2 failed (step-budget 2)" in lines[1]


def _expected_line(path, scene: str) -> str:
    """The summary line of ``scene`` as counted here from its sweep dataset's status and validity."""
    with xr.open_dataset(path / f"results/{scene}/sweep.nc") as ds:
        status, flags = ds["status"].values.ravel(), ds["validity"].values.ravel()
    ok = status == STATUS_CODES["ok"]
    flagged = ok & (flags != 0)
    reasons = [f"{name} {np.count_nonzero(flagged & (flags & mask != 0))}" for name, mask in FLAGS.items()
               if np.any(flagged & (flags & mask != 0))]
    failed = [f"{name} {np.count_nonzero(status == c)}" for name, c in STATUS_CODES.items()
              if name != "ok" and np.any(status == c)]
    text = (f"{np.count_nonzero(ok & ~flagged)} ok, {np.count_nonzero(flagged)} flagged"
            + (f" ({', '.join(reasons)})" if reasons else "")
            + f", {np.count_nonzero(~ok)} failed" + (f" ({', '.join(failed)})" if failed else ""))
    return f"  scene {scene}: {status.size} points, {text}: results/{scene}/sweep.nc"


def _tail(text: str) -> list[str]:
    """The lines from the summary's header to the end of the output."""
    lines = text.splitlines()
    starts = [i for i, line in enumerate(lines) if line.startswith(HEADER)]
    assert len(starts) == 1, text[-3000:]
    return lines[starts[0]:]


def _summary_is_last(text: str, scene_lines: list[str]) -> None:
    """The summary's lines come after every job, followed only by Snakemake's closing lines."""
    tail = _tail(text)
    assert tail[1:1 + len(scene_lines)] == scene_lines, "\n".join(tail)
    rest = tail[1 + len(scene_lines):]
    allowed = ("Complete log(s):", "Elapsed time:", "WorkflowError:", "At least one job did not complete")
    assert all(line.startswith(allowed) for line in rest if line.strip()), "\n".join(tail)


@pytest.mark.slow
def test_summary_logs_and_cores(make_project, smk, tmp_path):
    path = make_project(tmp_path / "p", TINY)
    out = smk(path)  # the profile's 2 cores
    text = out.stdout + out.stderr
    assert "Provided cores: 2" in text, text[-3000:]
    assert "Shell command: None" not in text
    line = _expected_line(path, "tiny")
    # the 50 m/s impact is flagged (s_max / r > 0.1), the 1 m/s one is not: the line shows both kinds
    assert " 1 ok, 1 flagged (large_indentation 1" in line, line
    _summary_is_last(text, [line])
    # the shard's job log says what it solved, with the same counts and its time
    (log,) = (path / "results/tiny/logs/shards").glob("*.log")
    note = line.split(": ", 1)[1].rsplit(": ", 1)[0].removeprefix("2 points, ")
    # the lines: the kernels (loaded or compiled), what it solved, and where the job's time went
    kernels, solved, timed = log.read_text().splitlines()
    assert re.fullmatch(r"numba kernels of method adaptive ready \(loaded or compiled\) in \S+ s", kernels)
    assert re.fullmatch(rf"solved 2 points of scene tiny: {re.escape(note)}, in \S+ s", solved)
    assert re.fullmatch(r"job sweep_shard: start-up [\d.]+ s, work [\d.]+ s", timed)
    assert "in results/tiny/MANIFEST.txt" in (path / "results/tiny/logs/manifest.log").read_text()

    out = smk(path, "-j1", "--forcerun", "manifest")
    text = out.stdout + out.stderr
    assert re.search(r"^Provided cores: 1\b", text, re.M), text[-3000:]
    assert "Provided cores: 2" not in text and "Shell command: None" not in text
    _summary_is_last(text, [line])

    # the report of a scene without figures says it has none and names the scene's dataset
    smk(path, "--report", "report.html")
    html = (path / "report.html").read_text(errors="replace")
    assert "This report holds no figures" in html and "figures below" not in html
    assert "results/tiny/sweep.nc" in html and "results/tiny/MANIFEST.txt" in html


@pytest.mark.slow
def test_summary_after_a_failed_job(make_project, smk, tmp_path):
    # a fit to a single measured frequency cannot succeed: its job fails, the sweep of the other scene runs
    cfg = {"fits": {"broken": {"model": "prony", "data": {"file": "data/one-point.csv", "T_ref": 20}}},
           "scenes": {**TINY["scenes"], "uses-broken": {"materials": ["broken"], "grid": {"v0": [1.0]}}}}
    path = make_project(tmp_path / "p", cfg)
    (path / "data/one-point.csv").write_text("f,E_stor,E_loss\n1,1e6,1e5\n")
    out = smk(path, "-j1", check=False)
    text = out.stdout + out.stderr
    assert out.returncode != 0 and "Error in rule fit_material" in text, text[-3000:]
    _summary_is_last(text, [_expected_line(path, "tiny")])


@pytest.mark.slow
def test_no_summary_without_a_dataset(make_project, smk, tmp_path):
    # a run that builds no sweep, DEM entry or calibration prints no summary header
    path = make_project(tmp_path / "p", {"fits": {"cerf": {"model": "cerf"}}})
    out = smk(path, "-j1")
    assert HEADER not in out.stdout + out.stderr
