"""Shard identity and planning: which grid points a sweep job solves, and what names its file.

A shard file is named ``<settings hash>-<points hash>``:

* the settings hash covers everything common to a scene's points that determines their numbers:
  the complete solver options, fixed geometry, ties, the error-estimate switch, and the
  fingerprint of the computing code (:func:`vcor.provenance.code_fingerprint`);
* every point carries ``material_id``, the identity of its material's content
  (:meth:`vcor.materials.Catalogue.identity`: a preset's or config material's parameters, a fit's or
  calibration's spec, data and code). The points hash covers the points with their ``material_id``.

So changed code, a changed preset or fit, or changed settings give new shard names: the workflow
recomputes exactly those shards and ``snakemake -n`` lists them. Planning reuses every finished
shard whose settings hash matches, that holds still-wanted points and none of a changed or removed
material, and groups only the points not yet covered into new shards, so extending a grid never
recomputes finished points; a changed material recomputes its points and those that shared their
shards. A job is given only the materials its points and the scene's sphere and plate name
(:func:`shard_materials`): editing one material re-runs no job without its points.

A point's name (:func:`vcor.study.grid.point_key`) leaves out its grid index, which moves when a grid
is extended; every shard still records the index of each point when it was written (its ``index``
coordinate), and the plan gives, for each shard, the index of each of its points in the current grid
(:attr:`Shard.rows`), which the aggregate joins by. A shard whose index file has no point indices (an
older vcor's) is recomputed, never misread.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

from ..io import receipts
from ..materials.catalogue import content_hash
from ..provenance import code_fingerprint
from .cost import point_cost, split_by_work
from .grid import Grid, point_key
from .scene import grid_of, settings_of

__all__ = [
    "SHARD_PATTERN",
    "Shard",
    "check_current",
    "identified_points",
    "index_text",
    "plan_shards",
    "point_key",
    "settings_hash",
    "shard_materials",
    "shard_settings",
]

#: the wildcard pattern of shard ids
SHARD_PATTERN = "[0-9a-f]{10}-[0-9a-f]{12}"


@dataclass(frozen=True, kw_only=True)
class Shard:
    """One sweep job: ``points`` as the job solves and records them (a reused shard: as its index file
    holds them, with the grid index they had when it was written), and ``rows``, the index of each
    of those points in the current grid (-1: no longer on the grid), which the aggregate joins by."""

    id: str
    points: list
    rows: list


def shard_settings(scene) -> dict:
    """The scene's settings plus the code fingerprint: what the settings hash covers."""
    return {**settings_of(scene), "code": code_fingerprint()}


def settings_hash(scene, settings: dict | None = None) -> str:
    """The hash of the scene's settings (``settings``: already built, e.g. with body identities)."""
    return content_hash({**(settings or settings_of(scene)), "code": code_fingerprint()}, 10)


def identified_points(scene, identities: dict, grid: Grid | None = None) -> list[dict]:
    """The scene's points (index order), each with the ``material_id`` of its material (``identities``:
    name -> id)."""
    grid = grid or grid_of(scene)
    return [{**p, "material_id": identities[p["material"]]} for p in grid.points()]


def shard_materials(points, bodies) -> list[str]:
    """The materials a shard's job is given: those its points name and the scene's ``bodies`` (the
    materials its sphere and plate name), so that a changed material re-runs no shard without its points
    (their jobs' params and inputs do not name it)."""
    return sorted({p["material"] for p in points} | set(bodies))


def check_current(points, catalogue, shard: str) -> None:
    """ValueError, before any work, when a point's ``material_id`` is not the identity its material has
    in ``catalogue``: solving it would store numbers under the identity of another definition
    (:func:`plan_shards` reuses no such shard; this guards the job itself)."""
    seen = {}
    for p in points:
        name = p["material"]
        if name not in seen:
            try:
                seen[name] = catalogue.identity(name)
            except ValueError:
                seen[name] = None
        if seen[name] != p["material_id"]:
            now = f"identity {seen[name]}" if seen[name] else "no such material"
            raise ValueError(f"shard {shard}: its points of material {name!r} were planned for identity "
                             f"{p['material_id']}, and the config now gives {now}: they cannot be solved again; "
                             f"move the shard's .nc and .json files aside to plan its points anew")


def _lookup(point: dict) -> tuple:
    """A point's identity for matching planned and finished points: its items without the index (the
    same identity as :func:`point_key`, whose JSON text names new shards, at a fraction of the cost)."""
    return tuple(sorted((k, v) for k, v in point.items() if k != "index"))


class _Matcher:
    """Finds the current grid index of a finished shard's points. A point recorded with index i that
    equals the grid's point i (the grid has not moved) is matched at once; any other point by its
    identity (:func:`_lookup`, built on first need). ``todo``: the grid indices not yet covered."""

    def __init__(self, wanted: list[dict]):
        self.wanted = wanted
        self.todo = set(range(len(wanted)))
        self._by_key = None

    def row(self, point: dict) -> int:
        i = point.get("index")
        if isinstance(i, int) and 0 <= i < len(self.wanted) and self.wanted[i] == point:
            return i
        if self._by_key is None:
            self._by_key = {_lookup(p): p["index"] for p in self.wanted}
        return self._by_key.get(_lookup(point), -1)

    def rows(self, points: list[dict]) -> list[int]:
        """The grid index of each of ``points`` (-1: no longer on the grid)."""
        return [self.row(p) for p in points]


def _in_order(point: dict, order: list) -> dict:
    """``point`` with the keys of ``order`` first, in that order, then the others sorted."""
    return {k: point[k] for k in order if k in point} | {k: point[k] for k in sorted(point) if k not in order}


def index_text(points, settings) -> str:
    """The text of a shard's index file (``{"points": [...], "settings": {...}}``, read back by
    :func:`plan_shards`): JSON with one point per line, each by json's C encoder (an indented dump
    goes through json's Python encoder: 0.4 s for 1e5 points, against 0.2 s)."""
    encode = json.JSONEncoder().encode
    return ('{"points": [\n' + ",\n".join(map(encode, points)) + '\n],\n"settings": '
            + json.dumps(settings, indent=1) + "}\n")


def _read_index(idx: Path, order: list) -> list[dict]:
    """The points of a shard's index file, keys in the grid's order (so that Snakemake sees unchanged
    params); ValueError when it cannot be read or was written before shards carried their index."""
    try:
        pts = json.loads(idx.read_text())["points"]
        pts = [p if list(p) == order else _in_order(p, order) for p in pts]
    except (OSError, ValueError, KeyError, TypeError):
        raise ValueError(f"its index {idx.name} cannot be read") from None
    if any("index" not in p for p in pts):
        raise ValueError(f"its index {idx.name} has no point indices (written by an older vcor)")
    return pts


def plan_shards(scene, shard_dir: str | Path, shard_size: int | None, identities: dict, on_invalid=None, *,
                grid: Grid | None = None, settings: dict | None = None, job_seconds: float | None = None,
                from_data: frozenset | set = frozenset()) -> dict[str, Shard]:
    """{shard id: :class:`Shard`}. Existing shards with the same settings hash are reused as they are,
    if they are what their writer wrote (:func:`vcor.io.receipts.problem`, the shard id as identity)
    and hold still-wanted points; a shard that is not is passed to ``on_invalid(path, reason)`` (the
    workflow moves it aside) and its points are planned again. A shard is reused only when every one
    of its points names a material of the scene with its current identity: one that holds points of a
    changed or removed material stays on disk unused, and its other points are planned again (its job
    could not solve the old points again, and solving them with the new definition would store
    numbers under the identity of another). The points not covered are cut into jobs of about
    ``job_seconds`` of estimated work each (:func:`vcor.study.cost.split_by_work`;
    ``from_data``: the materials fitted to measured data), at most ``shard_size`` points each (None: no
    cap). ``grid`` and ``settings``: the scene's, when the caller built them already."""
    settings = settings or settings_of(scene)
    h = settings_hash(scene, settings)
    wanted = identified_points(scene, identities, grid)
    matcher = _Matcher(wanted)
    order = list(wanted[0]) if wanted else []
    plan: dict[str, Shard] = {}
    for idx in sorted(Path(shard_dir).glob(f"{h}-*.json")):
        nc = idx.with_suffix(".nc")
        if not nc.exists():
            continue
        try:
            pts = _read_index(idx, order)
        except ValueError as exc:
            if on_invalid is not None:
                on_invalid(nc, str(exc))
            continue
        rows = matcher.rows(pts)
        if not any(r in matcher.todo for r in rows) or any(identities.get(p["material"]) != p.get("material_id")
                                                            for p in pts):
            continue
        reason = receipts.problem(nc, idx.stem)
        if reason is not None:
            if on_invalid is not None:
                on_invalid(nc, reason)
            continue
        plan[idx.stem] = Shard(id=idx.stem, points=pts, rows=rows)
        matcher.todo.difference_update(rows)
    todo = {i: wanted[i] for i in sorted(matcher.todo)}
    cost = point_cost(settings, from_data)
    for chunk in split_by_work(list(todo.values()), cost, job_seconds, shard_size):
        sid = f"{h}-{content_hash([point_key(p) for p in chunk])}"
        plan[sid] = Shard(id=sid, points=chunk, rows=[p["index"] for p in chunk])
    # in the order of their ids: the aggregate's inputs and rows do not depend on which shards were
    # found and which planned (a healed archive re-runs nothing more)
    return dict(sorted(plan.items()))
