"""What a run computed, in a few lines: the end-of-run summary and the job logs' counts.

For each scene whose sweep dataset exists, one line: its points, how many are ``ok`` and inside the
model's stated range, how many are ``ok`` but flagged (by validity reason, :mod:`vcor.solvers.validity`;
a point can carry several reasons, so the reasons' counts may add up to more than the flagged points),
how many did not finish ``ok`` (by status, :mod:`vcor.status`), and the dataset's path. Then one line
per scene whose time histories exist (its runs) and one per scene whose work-precision dataset exists
(its runs, counted alike: the cells of the method x ladder table that were run), one per DEM entry
whose dataset exists (its collisions) and one per calibration whose record exists (its path). The
workflow prints these lines when a run ends, successful or not (the Snakefile's ``onsuccess`` /
``onerror`` handlers); a run with nothing to do ends before them.

Only the ``status`` and ``validity`` variables (small integers) are read, with netCDF4 itself (xarray
would decode every string variable of the file, one string per point, before anything is read), so the
summary of a whole project costs about one file opening per scene and imports no xarray. The names
of codes and flags come from the dataset's own CF attributes (``flag_values`` / ``flag_masks`` with
``flag_meanings``), so an archived dataset is read with the vocabulary it was written with; a dataset
without them is read with vcor's.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .. import status as _status
from ..solvers import validity as _validity
from . import paths

__all__ = ["Outcome", "outcome_of", "read_outcome", "run_summary"]

_OK = _status.code("ok")


@dataclass(kw_only=True, frozen=True)
class Outcome:
    """Counts of a set of results: ``points`` in all; ``ok`` (status ok, no validity flag);
    ``flagged`` (status ok with a flag) and ``reasons`` (flag name -> points carrying it); ``failed``
    (status not ok) and ``statuses`` (status name -> points)."""

    points: int
    ok: int
    flagged: int
    failed: int
    reasons: dict = field(default_factory=dict)
    statuses: dict = field(default_factory=dict)

    def text(self) -> str:
        """``118 ok, 2 flagged (large_indentation 2), 0 failed`` (the parts in brackets only when not 0)."""
        def detail(counts):
            return f" ({', '.join(f'{k} {n}' for k, n in counts.items())})" if counts else ""

        return (f"{self.ok} ok, {self.flagged} flagged{detail(self.reasons)}, "
                f"{self.failed} failed{detail(self.statuses)}")


def _vocabulary(var, values_key: str, default: dict) -> dict:
    """{code or mask: name} from a variable's CF flag attributes (``default``, name -> code, without them)."""
    attrs = getattr(var, "attrs", {}) or {}
    values, meanings = attrs.get(values_key), attrs.get("flag_meanings")
    if values is None or not meanings:
        return {int(v): k for k, v in default.items()}
    names = str(meanings).split()
    return {int(v): n.replace("_", "-") if values_key == "flag_values" else n
            for v, n in zip(np.atleast_1d(values), names)}


def outcome_of(ds) -> Outcome:
    """The :class:`Outcome` of a dataset (or mapping) with a ``status`` and, optionally, a ``validity``
    variable; every element of ``status`` counts as one point."""
    status = np.asarray(ds["status"]).astype(np.int64).ravel()
    has_validity = "validity" in ds
    flags = np.asarray(ds["validity"]).astype(np.int64).ravel() if has_validity else np.zeros_like(status)
    ok = status == _OK
    flagged = ok & (flags != 0)
    status_names = _vocabulary(ds["status"], "flag_values", _status.STATUS_CODES)
    codes, counts = np.unique(status[~ok], return_counts=True)
    statuses = {status_names.get(int(c), f"status {int(c)}"): int(n) for c, n in zip(codes, counts)}
    reasons = {}
    if has_validity:
        masks = _vocabulary(ds["validity"], "flag_masks", _validity.FLAGS)
        reasons = {name: int(np.count_nonzero(flagged & ((flags & mask) != 0))) for mask, name in masks.items()}
        reasons = {k: n for k, n in reasons.items() if n}
    return Outcome(points=int(status.size), ok=int(np.count_nonzero(ok & ~flagged)),
                   flagged=int(np.count_nonzero(flagged)), failed=int(np.count_nonzero(~ok)),
                   reasons=reasons, statuses=statuses)


@dataclass(frozen=True)
class _Stored:
    """A variable as stored: its values and attributes (what :func:`outcome_of` reads of it)."""

    values: np.ndarray
    attrs: dict

    def __array__(self, dtype=None, copy=None):
        return np.asarray(self.values, dtype=dtype)


def read_outcome(path, *, runs_only: bool = False) -> Outcome:
    """The :class:`Outcome` of a dataset file, reading only its ``status`` and ``validity`` (module
    docstring). ``runs_only``: a work-precision dataset's cells with a ladder value (``param`` finite);
    the others are past a shorter ladder or of a method that does not apply, not runs (a dataset without
    ``param``, the time histories, is all runs)."""
    import netCDF4

    with netCDF4.Dataset(path) as nc:
        if "status" not in nc.variables:
            raise ValueError(f"{path}: no variable 'status'; a sweep dataset has one")
        nc.set_auto_maskandscale(False)
        keep = (np.isfinite(np.asarray(nc["param"][...], dtype=float)).ravel() if runs_only and "param" in nc.variables
                else slice(None))
        stored = {name: _Stored(np.asarray(nc[name][...]).ravel()[keep],
                                {a: nc[name].getncattr(a) for a in nc[name].ncattrs()})
                  for name in ("status", "validity") if name in nc.variables}
    return outcome_of(stored)


def _line(kind: str, name: str, path: Path, shown: str, *, runs: bool = False) -> str:
    """One summary line; a dataset that cannot be read says so (the end of a run must not fail on it)."""
    try:
        out = read_outcome(path, runs_only=runs)
    except Exception as exc:  # noqa: BLE001 - reported on the line, see the docstring
        return f"  {kind} {name}: cannot read {shown}: {type(exc).__name__}: {exc}"
    return f"  {kind} {name}: {out.points} {'runs' if runs else 'points'}, {out.text()}: {shown}"


def run_summary(project, base_dir=".") -> list[str]:
    """Lines saying what the project's results hold (module docstring); ``[]`` when no scene has a
    sweep, time-histories or work-precision dataset and no DEM entry or calibration has a dataset. ``project`` is a
    :class:`vcor.study.project.Project`; paths are shown relative to ``base_dir``."""
    base = Path(base_dir)
    lines = []
    for name in project.scenes:
        shown = paths.fmt(paths.SWEEP, scene=name)
        if (base / shown).is_file():
            lines.append(_line("scene", name, base / shown, shown))
        shown = paths.fmt(paths.DATASET, scene=name, dataset="histories")
        if (base / shown).is_file():
            lines.append(_line("scene", f"{name} (time histories)", base / shown, shown, runs=True))
        shown = paths.fmt(paths.DATASET, scene=name, dataset="convergence")
        if (base / shown).is_file():
            lines.append(_line("scene", f"{name} (work-precision)", base / shown, shown, runs=True))
    for name in project.dem:
        shown = paths.fmt(paths.DEM, dem=name)
        if (base / shown).is_file():
            lines.append(_line("DEM entry", name, base / shown, shown))
    for name in project.catalogue.calibrations:
        shown = paths.fmt(paths.CALIBRATION, cal=name)
        if (base / shown).is_file():
            lines.append(f"  calibration {name}: {shown}")
    if not lines:
        return []
    return ["vcor: what the results hold (ok: inside the model's stated range; flagged: ok but outside it, "
            "by reason; failed: not ok, by status):", *lines]
