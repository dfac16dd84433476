"""Shard identity and planning: which grid points a sweep job solves, and what names its file.

A shard file is named ``<settings hash>-<points hash>``:

* the settings hash covers everything common to a scene's points that determines their numbers:
  the complete solver options, fixed geometry, ties, the error-estimate switch, and the
  fingerprint of the computing code (:func:`vcor.provenance.code_fingerprint`);
* every point carries ``material_id``, the identity of its material's content: the resolved
  parameters of a preset (not its name), or for a fitted material the fit's identity
  (:func:`vcor.fit.fit_identity`: its spec, its data and the code that fits; the fit is
  deterministic, so this determines the parameters before the file exists). The points hash
  covers the points with their ``material_id``.

So changed code, a changed preset or fit, or changed settings give new shard names: the workflow
recomputes exactly those shards and ``snakemake -n`` lists them. Planning reuses every finished
shard whose settings hash matches and that holds still-wanted points, and groups only the points
not yet covered into new shards, so extending a grid never recomputes finished points.
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

from .provenance import code_fingerprint
from .scene import resolve_material, scene_points, settings_of

__all__ = [
    "SHARD_PATTERN",
    "content_hash",
    "identified_points",
    "material_identity",
    "plan_shards",
    "point_key",
    "settings_hash",
    "shard_settings",
]

#: the wildcard pattern of shard ids
SHARD_PATTERN = "[0-9a-f]{10}-[0-9a-f]{12}"


def content_hash(obj, n: int = 12) -> str:
    """First ``n`` hex digits of the SHA-1 of ``obj`` as canonical JSON."""
    return hashlib.sha1(json.dumps(obj, sort_keys=True, default=float).encode()).hexdigest()[:n]


def material_identity(name: str, *, fits: dict | None = None, material_dir="results/materials",
                      materials: dict | None = None, base_dir=".", calibrations: dict | None = None) -> str:
    """Identity of a material's content (see the module docstring); ``materials``: the config's
    material specs (identity = the built material's parameters, so a CSV table's values count);
    ``calibrations``: calibrated materials (identity = spec, data file, start material, code)."""
    fits = fits or {}
    if calibrations and name in calibrations:
        from .calibrate import calibration_identity

        spec = calibrations[name]
        start = spec.get("material")
        start_id = (material_identity(start, fits=fits, material_dir=material_dir, materials=materials,
                                      base_dir=base_dir) if isinstance(start, str) else None)
        return content_hash({"calibration": calibration_identity(spec, base_dir, start_id)})
    if name in fits:
        from .fit import fit_identity

        return content_hash({"fit": fit_identity(fits[name])})
    if materials and name in materials:
        from .material_specs import from_spec, shift_function

        spec = materials[name]
        shift = shift_function(spec, name)
        return content_hash({"material": from_spec(spec, name=name, base_dir=base_dir).to_dict(),
                             "shift": shift.to_dict() if shift else None})
    return content_hash({"material": resolve_material(name, material_dir=material_dir).to_dict()})


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


def plan_shards(scene, shard_dir: str | Path, shard_size: int, identities: dict) -> dict[str, list[dict]]:
    """{shard id: points}. Existing shards with the same settings hash are reused as they are."""
    h = settings_hash(scene)
    wanted = identified_points(scene, identities)
    todo = {point_key(p): p for p in wanted}
    order = list(wanted[0]) if wanted else []
    plan: dict[str, list[dict]] = {}
    for idx in sorted(Path(shard_dir).glob(f"{h}-*.json")):
        try:
            pts = json.loads(idx.read_text())["points"]
            # same key order as the scene's points, so Snakemake sees unchanged params
            pts = [{k: p[k] for k in order if k in p} | {k: p[k] for k in sorted(p) if k not in order} for p in pts]
        except (OSError, ValueError, KeyError):
            continue
        if not idx.with_suffix(".nc").exists():
            continue
        keys = [point_key(p) for p in pts]
        if any(k in todo for k in keys):
            plan[idx.stem] = pts
            for k in keys:
                todo.pop(k, None)
    rest = list(todo.values())
    for i in range(0, len(rest), shard_size):
        chunk = rest[i : i + shard_size]
        plan[f"{h}-{content_hash([point_key(p) for p in chunk])}"] = chunk
    return plan
