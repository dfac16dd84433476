"""The archive heals itself: outputs that are not what their writer wrote are moved aside and computed
again, and one workflow run at a time writes to a project.

* :func:`problems` lists the project's outputs that exist but must not be used (a missing or broken
  receipt, other bytes, another identity: :mod:`vcor.io.receipts`): datasets, material files and the
  shards of the current plans are checked before any job runs; :func:`heal` moves them aside
  (``<name>.invalid``) so that the workflow computes them again, and says why.
* :class:`ProjectLock` is a lock on the project folder (``fcntl.flock`` on ``.snakemake/vcor-run.lock``)
  held by the workflow's main process for its lifetime: a second run started in the same project stops
  at once with the first run's process id. The kernel releases it when the process ends, also after
  SIGKILL, so it never goes stale; and while it is held, no other run is active, so the Snakemake locks
  a killed run left behind are stale and :func:`remove_stale_snakemake_locks` removes them (what
  ``snakemake --unlock`` would do).
"""

from __future__ import annotations

import fcntl
import os
from pathlib import Path

from ..io import receipts
from . import paths
from .uncertainty import samples_identity

__all__ = ["LOCK_FILE", "ProjectLock", "heal", "problems", "remove_stale_snakemake_locks"]

#: the project lock, relative to the project folder
LOCK_FILE = Path(".snakemake") / "vcor-run.lock"


def _expected(project, base: Path):
    """(path, identity) of the project's outputs that jobs read: datasets of every scene, the material
    files of the catalogue (identity: the material's content identity), calibration records, DEM
    datasets."""
    cat = project.catalogue
    for scene, sc in project.scenes.items():
        for target in project.scene_targets(scene):
            if target.endswith(".nc") and not target.startswith(f"{cat.material_dir}/"):
                yield base / target, None
        for material in sc.config.get("convergence", {}).get("materials", []):
            yield base / paths.fmt(paths.CONVERGENCE_CASE, scene=scene, material_case=material), None
        for path, name in project.samples_of(scene):
            yield base / path, samples_identity(cat, name, sc.uncertainty)
    for name in project.dem:
        yield base / paths.fmt(paths.DEM, dem=name), None
    for name in [*cat.specs, *cat.fits, *cat.calibrations]:
        yield base / paths.material(cat.material_dir, name), cat.identity(name)
    for name in cat.calibrations:
        yield base / paths.fmt(paths.CALIBRATION, cal=name), cat.identity(name)


def problems(project, base=".") -> list[tuple[Path, str]]:
    """(path, reason) of every existing output of ``project`` that must not be used (module docstring)."""
    out = []
    for path, identity in _expected(project, Path(base)):
        if path.exists():
            reason = receipts.problem(path, identity)
            if reason is not None:
                out.append((path, reason))
    return out


def heal(project, base=".", *, apply: bool = True) -> list[str]:
    """Move every output :func:`problems` finds aside (unless ``apply`` is False: a dry run) and return
    one line per file saying why it is (or would be) computed again."""
    lines = []
    for path, reason in problems(project, base):
        if apply:
            moved = receipts.quarantine(path)
            lines.append(f"vcor: {path}: {reason}; moved to {moved.name}, it is computed again")
        else:
            lines.append(f"vcor: {path}: {reason}; a run (not a dry run) moves it aside and computes it again")
    return lines


class ProjectLock:
    """An exclusive lock on a project folder for the lifetime of this object's process (module
    docstring). :meth:`acquire` raises ValueError naming the process that holds it."""

    def __init__(self, base="."):
        self.path = Path(base) / LOCK_FILE
        self._fh = None

    def acquire(self) -> ProjectLock:
        self.path.parent.mkdir(parents=True, exist_ok=True)
        fh = open(self.path, "a+")  # noqa: SIM115 (kept open: the lock lives as long as the file is open)
        try:
            fcntl.flock(fh, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            fh.seek(0)
            holder = fh.read().strip() or "unknown"
            fh.close()
            raise ValueError(f"another workflow run is active in this project (process {holder}, lock "
                             f"{self.path}): wait for it to finish, or stop it, then run snakemake again") from None
        fh.seek(0)
        fh.truncate()
        fh.write(str(os.getpid()))
        fh.flush()
        self._fh = fh
        return self

    def release(self) -> None:
        if self._fh is not None:
            self._fh.close()
            self._fh = None


def remove_stale_snakemake_locks(base=".") -> list[str]:
    """Remove the lock files Snakemake keeps in ``.snakemake/locks`` (call only while holding the
    :class:`ProjectLock`: no other run is active, so they were left by a killed run); returns a line
    saying so, or nothing."""
    folder = Path(base) / ".snakemake" / "locks"
    stale = sorted(folder.glob("*.lock")) if folder.is_dir() else []
    for path in stale:
        path.unlink()
    return [(f"vcor: removed {len(stale)} stale Snakemake lock(s) of an interrupted run (no other run is "
            f"active in this project)")] if stale else []
