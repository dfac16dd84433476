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
shard whose settings hash matches and that holds still-wanted points, and groups only the points
not yet covered into new shards, so extending a grid never recomputes finished points.
"""

from __future__ import annotations

import json
from pathlib import Path

from ..io import receipts
from ..materials.catalogue import content_hash
from ..provenance import code_fingerprint
from .scene import scene_points, settings_of

__all__ = [
    "SHARD_PATTERN",
    "identified_points",
    "plan_shards",
    "point_key",
    "settings_hash",
    "shard_settings",
]

#: the wildcard pattern of shard ids
SHARD_PATTERN = "[0-9a-f]{10}-[0-9a-f]{12}"


def shard_settings(scene) -> dict:
    """The scene's settings plus the code fingerprint: what the settings hash covers."""
    return {**settings_of(scene), "code": code_fingerprint()}


def settings_hash(scene) -> str:
    return content_hash(shard_settings(scene), 10)


def identified_points(scene, identities: dict) -> list[dict]:
    """The scene's points, each with the ``material_id`` of its material (``identities``: name -> id)."""
    return [{**p, "material_id": identities[p["material"]]} for p in scene_points(scene)]


def point_key(p: dict) -> str:
    return json.dumps(p, sort_keys=True)


def plan_shards(scene, shard_dir: str | Path, shard_size: int, identities: dict, on_invalid=None) -> dict[str, list[dict]]:
    """{shard id: points}. Existing shards with the same settings hash are reused as they are, if they
    are what their writer wrote (:func:`vcor.io.receipts.problem`, the shard id as identity); a shard
    that is not is passed to ``on_invalid(path, reason)`` (the workflow moves it aside) and its points
    are planned again."""
    h = settings_hash(scene)
    wanted = identified_points(scene, identities)
    todo = {point_key(p): p for p in wanted}
    order = list(wanted[0]) if wanted else []
    plan: dict[str, list[dict]] = {}
    for idx in sorted(Path(shard_dir).glob(f"{h}-*.json")):
        nc = idx.with_suffix(".nc")
        try:
            pts = json.loads(idx.read_text())["points"]
            # same key order as the scene's points, so Snakemake sees unchanged params
            pts = [{k: p[k] for k in order if k in p} | {k: p[k] for k in sorted(p) if k not in order} for p in pts]
        except (OSError, ValueError, KeyError, TypeError):
            if nc.exists() and on_invalid is not None:
                on_invalid(nc, f"its index {idx.name} cannot be read")
            continue
        if not nc.exists():
            continue
        keys = [point_key(p) for p in pts]
        if not any(k in todo for k in keys):
            continue
        reason = receipts.problem(nc, idx.stem)
        if reason is not None:
            if on_invalid is not None:
                on_invalid(nc, reason)
            continue
        plan[idx.stem] = pts
        for k in keys:
            todo.pop(k, None)
    rest = list(todo.values())
    for i in range(0, len(rest), shard_size):
        chunk = rest[i : i + shard_size]
        plan[f"{h}-{content_hash([point_key(p) for p in chunk])}"] = chunk
    return plan
