"""A job's log lines (vcor.io.joblog)."""

import ast
import os
import subprocess
import sys
import types
from pathlib import Path

import numpy as np
import pytest

from vcor.io.joblog import brief, is_workflow_job, job_log


def test_brief_rounds_numbers_and_keeps_the_structure():
    settings = {"model": "prony", "lam": 48.69675251658631, "n": np.int64(3), "ok": True, "start": None,
                "smoothing": {"mu": {"E_stor": np.float64(3.1622776601683795)}}, "components": [1.0, 0.25]}
    assert brief(settings) == ("{model: prony, lam: 48.7, n: 3, ok: True, start: None, "
                               "smoothing: {mu: {E_stor: 3.162}}, components: [1, 0.25]}")
    assert brief(1.23456789e-7, digits=3) == "1.23e-07"


ROOT = Path(__file__).resolve().parents[2]

JOB = """
import atexit, sys, types
from vcor.io.joblog import job_log
atexit.register(lambda: open({teardown!r}, "w").write("teardown ran"))
sys.stdout.write("printed by the job")  # no newline: still in the buffer when the block ends
with job_log(types.SimpleNamespace(log=[{log!r}], rule="demo"), end=True) as job:
    job.note("did the work")
    {body}
open({after!r}, "w").write("after the block")
"""


def _job(tmp_path, body="pass", stdout=subprocess.PIPE):
    paths = {name: str(tmp_path / name) for name in ("log", "teardown", "after")}
    code = JOB.format(body=body, **paths)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONUNBUFFERED"}  # stdout buffered, as by default
    out = subprocess.run([sys.executable, "-c", code], stdout=stdout, stderr=subprocess.PIPE, text=True, timeout=120,
                         check=False, env=env)
    return out, {name: Path(p) for name, p in paths.items()}


def test_a_workflow_job_ends_when_its_block_succeeds(tmp_path):
    out, paths = _job(tmp_path)
    assert out.returncode == 0, out.stderr
    assert out.stdout == "printed by the job"  # flushed before the process ended
    log = paths["log"].read_text()
    assert "did the work" in log and "job demo: start-up" in log
    assert not paths["teardown"].exists()  # Python's teardown skipped
    assert not paths["after"].exists()  # nothing after the block runs


@pytest.mark.skipif(not Path("/dev/full").exists(), reason="no /dev/full (a device on which every write fails)")
def test_output_that_cannot_be_flushed_is_an_exit_code_as_with_pythons_own_exit(tmp_path):
    with open("/dev/full", "w") as full:
        out, paths = _job(tmp_path, stdout=full)
    assert out.returncode == 120  # Python's exit code when it cannot flush standard output
    assert "job demo: start-up" in paths["log"].read_text()


def test_a_failing_job_still_exits_1_with_its_error_in_the_log(tmp_path):
    out, paths = _job(tmp_path, body='raise ValueError("bad input")')
    assert out.returncode == 1
    assert "vcor: job failed: ValueError: bad input" in paths["log"].read_text()
    assert "ValueError: bad input" in out.stderr


def test_only_snakemakes_script_object_ends_the_process():
    from snakemake.iocontainers import Snakemake

    assert is_workflow_job(Snakemake.__new__(Snakemake))
    assert not is_workflow_job(types.SimpleNamespace(log=[], rule="demo"))
    # in-process use (a test, a notebook) keeps the process
    with job_log(types.SimpleNamespace(log=[], rule="demo")) as job:
        job.note("in-process")


@pytest.mark.parametrize("script", sorted((ROOT / "workflow" / "scripts").glob("*.py")), ids=lambda p: p.name)
def test_every_workflow_script_ends_with_its_job_log_block(script):
    """The process ends when the block succeeds (vcor.io.joblog): a statement after it would never run."""
    last = ast.parse(script.read_text()).body[-1]
    assert isinstance(last, ast.With), f"{script.name}: the last statement is not the `with job_log(...)` block"
    call = last.items[0].context_expr
    assert isinstance(call, ast.Call) and getattr(call.func, "id", None) == "job_log", script.name
