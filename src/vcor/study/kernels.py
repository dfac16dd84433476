"""Marks of the numba kernels compiled for a project, which order the workflow's jobs.

The rule ``kernels`` compiles one solver method's kernels (:func:`vcor.solvers.backend.load_kernels`)
in a job of its own and writes the method's mark, ``results/.kernels/<method>.ready``
(:data:`vcor.study.paths.KERNELS`). Every job that solves with that method takes the mark as an
``ancient`` input. In a fresh project the compile therefore runs first, on one core, while jobs without
kernels (fits) run on the other, and the jobs that solve load compiled kernels instead of waiting for
one another's compile. ``ancient``: a mark's time never makes a finished job run again.

A mark missing while the project holds results (an archive restored without ``results/.kernels``)
would make Snakemake run again every finished job that takes it as soon as any job needs it.
:func:`restore_marks` writes such marks back before Snakemake plans; kernels then compile on first
use, each method under its lock.
"""

from __future__ import annotations

from pathlib import Path

from . import paths

__all__ = ["RESULT_PATTERNS", "mark", "restore_marks"]

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


def restore_marks(methods, base=".") -> list[str]:
    """Write the missing marks of ``methods`` when the project folder ``base`` already holds results
    (module docstring); one line per mark written, saying why."""
    base = Path(base)
    missing = [m for m in dict.fromkeys(methods) if not mark(m, base).exists()]
    if not missing or not _has_results(base):
        return []
    lines = []
    for method in missing:
        path = mark(method, base)
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(f"numba kernels of method {method}: mark written again for a project with results; "
                        f"they compile on first use\n")
        lines.append(f"vcor: {path.relative_to(base)}: missing in a project with results; written again "
                     f"(finished jobs stay finished; kernels compile on first use)")
    return lines
