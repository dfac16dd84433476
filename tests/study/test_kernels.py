"""Marks of compiled kernels (vcor.study.kernels): written back only in a project with results."""

import os
import subprocess
import sys

from vcor.study import kernels, paths


def test_no_marks_written_in_a_fresh_project(tmp_path):
    assert kernels.restore_marks(["adaptive"], tmp_path) == []
    assert not kernels.mark("adaptive", tmp_path).exists()


def test_missing_marks_written_back_when_results_exist(tmp_path):
    shard = tmp_path / paths.fmt(paths.SHARD, scene="s", shard="0123456789-0123456789ab")
    shard.parent.mkdir(parents=True)
    shard.write_bytes(b"")
    kernels.mark("direct", tmp_path).parent.mkdir(parents=True)
    kernels.mark("direct", tmp_path).write_text("compiled\n")
    script = tmp_path / "kernels.py"
    script.write_text("")
    lines = kernels.restore_marks(["adaptive", "direct", "adaptive"], tmp_path, script=script)
    assert len(lines) == 1 and "marks of adaptive written (the project holds results and no marks" in lines[0], lines
    after = kernels.mark("adaptive", tmp_path).stat().st_mtime_ns - script.stat().st_mtime_ns
    assert after == kernels.AFTER_SCRIPT  # newer than the script: the kernels job stays finished
    assert kernels.mark("direct", tmp_path).read_text() == "compiled\n"  # an existing mark is left alone
    assert kernels.restore_marks(["adaptive", "direct"], tmp_path) == []


def test_methods_without_numba_kernels_have_no_kernels_job(tmp_path):
    """``ive`` (scipy's solve_ivp) compiles nothing: it is not a compiled method (no job, no mark); a fresh
    process with an empty numba cache solves with it without a single numba signature."""
    from vcor.solvers.options import COMPILED_METHODS, METHOD_NAMES

    others = sorted(set(METHOD_NAMES) - set(COMPILED_METHODS))
    assert others == ["ive"]
    code = ("import gc; from numba.core.registry import CPUDispatcher; from vcor.solvers.backend import load_kernels; "
            "load_kernels(['ive']); print(sum(len(o.signatures) for o in gc.get_objects() "
            "if isinstance(o, CPUDispatcher)))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         env={**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)})
    assert out.stdout.strip() == "0", out
