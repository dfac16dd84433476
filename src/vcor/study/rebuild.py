"""A sweep's scene rebuilt from its dataset alone: an archived ``sweep.nc`` is enough to re-run it.

A sweep dataset records (global attributes, JSON) its scene as configured (``scene_config``, grid
axes in their config order) and every material as the catalogue described it (``materials``:
source, parameters, shift function, spec, identity; :meth:`vcor.materials.Catalogue.describe`).
:func:`scene_from_dataset` turns these back into a scene and a catalogue in which every material
that is not a preset is a config material with the recorded parameters and shift function, so a
fit's or calibration's file is not needed. Re-running the rebuilt scene with the same code gives
the dataset's numbers bit for bit (``tests/workflow/test_provenance.py``).
"""

from __future__ import annotations

import json

from ..materials.catalogue import Catalogue
from ..materials.presets import PRESETS, get
from .project import Scene
from .scene import grid_of, settings_of

__all__ = ["scene_from_dataset"]


def _attr(ds, key):
    if key not in ds.attrs:
        raise ValueError(f"the dataset has no attribute {key!r}: it is not a vcor sweep (written by the aggregate "
                         f"rule), or older than the attributes that rebuild a scene")
    value = ds.attrs[key]
    return json.loads(value) if isinstance(value, str) else value


def scene_from_dataset(ds) -> tuple[Scene, Catalogue]:
    """(:class:`~vcor.study.project.Scene`, catalogue) of a sweep dataset (module docstring).
    ValueError when the dataset lacks the attributes, or a preset's recorded parameters differ from
    the running code's preset (the preset changed since: the scene cannot be rebuilt under its name)."""
    scene = _attr(ds, "scene_config")
    described = _attr(ds, "materials")
    specs = {}
    for name, record in described.items():
        params = dict(record["material"])
        kind = params.pop("kind")
        if record["source"] == "preset":
            if name not in PRESETS or get(name).to_dict() != record["material"]:
                raise ValueError(f"material {name!r}: the dataset used the preset {record['material']}, the running "
                                 f"code's preset is {get(name).to_dict() if name in PRESETS else 'missing'}")
            continue
        spec = {"model": kind, **params}
        if record.get("shift"):
            spec["shift"] = dict(record["shift"])
        specs[name] = spec
    name = str(ds.attrs.get("scene", "rebuilt"))
    rebuilt = Scene(name=name, config=scene, grid=grid_of(scene), settings=settings_of(scene))
    return rebuilt, Catalogue(specs=specs)
