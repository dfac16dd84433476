"""Marks of the numba kernels compiled for a project, which order the workflow's jobs.

The rule ``kernels`` compiles one solver method's kernels (:func:`vcor.solvers.backend.load_kernels`)
in a job of its own and writes the method's mark, ``results/.kernels/<method>.ready``
(:data:`vcor.study.paths.KERNELS`). Every job that solves with that method takes the mark as an
input. In a fresh project the compile therefore runs first, on one core, while jobs without kernels
(fits) run on the other, and the jobs that solve load compiled kernels instead of waiting for one
another's compile.

The mark is an ordinary input, not Snakemake's ``ancient``: when the kernels job runs again (the code
changed, or its script), every job that takes the mark runs again too. With ``ancient`` Snakemake
(9.x) would skip the jobs downstream of the kernels job that need to run for reasons of their own
(it marks them as following that job, then drops them because the ancient input exists), and a run
could end with stale results.

A mark missing while the project holds results (an archive restored without ``results/.kernels``)
would make every finished job that takes it run again. :func:`restore_marks` writes such marks back
before Snakemake plans (in a dry run too: a mark is bookkeeping, not a result), dated one second
after the kernels job's script was last changed: Snakemake re-runs a job whose output is not newer
than its script, and a job whose input is newer than its output, so results computed since that
script changed stay finished. Kernels then compile on first use, each method under its lock.
"""

from __future__ import annotations

import os
from pathlib import Path

from . import paths

__all__ = ["AFTER_SCRIPT", "RESULT_PATTERNS", "mark", "restore_marks"]

#: how much later than the kernels job's script a mark written back is dated (ns)
AFTER_SCRIPT = 1_000_000_000
#: outputs of the jobs that solve: a project holding any of them has run with kernels
RESULT_PATTERNS = (paths.SHARD, paths.DATASET, paths.CONVERGENCE_CASE, paths.DEM)


def mark(method: str, base=".") -> Path:
    """The mark of ``method``'s kernels in the project folder ``base``."""
    return Path(base) / paths.fmt(paths.KERNELS, method=method)


def _glob(pattern: str) -> str:
    """A path pattern with every ``{wildcard}`` replaced by ``*``."""
    out, depth = "", 0
    for ch in pattern:
        if ch == "{":
            depth += 1
            if depth == 1:
                out += "*"
        elif ch == "}":
            depth -= 1
        elif depth == 0:
            out += ch
    return out


def _has_results(base: Path) -> bool:
    return any(next(base.glob(_glob(p)), None) is not None for p in RESULT_PATTERNS)


def restore_marks(methods, base=".", *, script=None) -> list[str]:
    """Write the missing marks of ``methods`` when the project folder ``base`` already holds results
    (module docstring), dated :data:`AFTER_SCRIPT` after ``script`` (the kernels job's script; None:
    1970); one line naming them, or none."""
    base = Path(base)
    missing = [m for m in dict.fromkeys(methods) if not mark(m, base).exists()]
    if not missing or not _has_results(base):
        return []
    dated = 0 if script is None else Path(script).stat().st_mtime_ns + AFTER_SCRIPT
    for method in missing:
        path = mark(method, base)
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(f"numba kernels of method {method}: mark written again for a project with results; "
                        f"they compile on first use\n")
        os.utime(path, ns=(dated, dated))
    where = mark(missing[0], base).parent.relative_to(base)
    return [f"vcor: {where}: marks of {', '.join(missing)} written (the project holds results and no marks for "
            f"them; no action needed: finished jobs stay finished, these kernels compile on first use)"]
