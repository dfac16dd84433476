"""Aggregation: a scene's shards (``vcor.study.runner.run_points``) combined into one dataset with dims
``(material, *grid axes)``, and the global attributes that make it enough to re-run its scene.

The aggregate refuses to combine shards computed by different code (their ``code_fingerprint``
attributes differ from each other or from the running code) or with different material
parameters than the current ones: an archive never mixes old and new results. Units, long names
and status flags of the variables are those the shards carry. A scene with ``uncertainty`` is
reduced over its bootstrap samples (:func:`vcor.study.uncertainty.reduce_samples`). (A module of its own, without the
solvers: the workflow's aggregate jobs then do not import numba.)
"""

from __future__ import annotations

import json

import numpy as np

from ..contact.impact import GEOMETRY_DEFAULTS
from ..materials.catalogue import Catalogue
from ..provenance import code_fingerprint
from .grid import Grid
from .scene import material_params, settings_of
from .uncertainty import reduce_samples, uncertainty_of

__all__ = ["aggregate", "dataset_attrs"]

#: variables stored as text and as small integers (status flags); every other variable is a float
TEXT_VARS = ("message", "error_message", "validity_message")
INT_VARS = ("status", "error_status", "validity")


def dataset_attrs(scene_name, scene, catalogue: Catalogue | None = None) -> dict:
    """Global attributes that make a dataset enough to re-run its scene."""
    settings = settings_of(scene)
    attrs = {
        "scene": scene_name,
        "scene_config": scene,
        "solver_settings": settings,
        "materials": material_params(scene["materials"], catalogue),
        "geometry_defaults": dict(GEOMETRY_DEFAULTS),
    }
    if "bodies" not in settings:  # (a scene of bodies: its sphere and plate blocks give the geometry)
        varied = set(scene.get("grid") or {}) | set(settings["tie"])  # the points' coordinates give these
        shared = {**GEOMETRY_DEFAULTS, **settings["geometry"]}
        attrs["geometry"] = {k: v for k, v in shared.items() if k not in varied}
    return attrs


def _check_provenance(shards, scene, catalogue):
    """Refuse shards of other code or other material parameters (see the module docstring)."""
    current = code_fingerprint()
    prints = {ds.attrs.get("code_fingerprint", "missing") for ds in shards}
    if prints != {current}:
        raise ValueError(f"shards were computed by different code (fingerprints {sorted(prints)}, running "
                         f"code {current}): refusing to combine them; recompute the stale shards")
    params = material_params(scene["materials"], catalogue)
    for ds in shards:
        used = json.loads(ds.attrs.get("materials", "{}"))
        for name, p in used.items():
            if name in params and p != params[name]:
                raise ValueError(f"a shard used material {name!r} with parameters {p}, the current ones are "
                                 f"{params[name]}: refusing to combine them; recompute the stale shards")


def _check_rows(k, ds, rows, grid: Grid):
    """The shard's points are the grid's points at ``rows`` (material and every axis value, exactly):
    a plan that does not fit its shard is an error, never a misread."""
    if len(rows) != ds.sizes["point"]:
        raise ValueError(f"shard {k}: {ds.sizes['point']} points, the plan gives {len(rows)} grid indices")
    keep = np.flatnonzero(np.asarray(rows) >= 0)
    pos = np.unravel_index(np.asarray(rows, dtype=np.int64)[keep], grid.shape)
    mats = np.asarray(grid.materials, dtype=object)[pos[0]]
    if not np.array_equal(ds["material"].values[keep].astype(str), mats.astype(str)):
        raise ValueError(f"shard {k}: its materials differ from the grid's at the planned indices")
    for axis, p in zip(grid.axes, pos[1:]):
        if axis.name not in ds.coords or not np.array_equal(ds[axis.name].values[keep], np.asarray(axis.values)[p]):
            raise ValueError(f"shard {k}: its values of axis {axis.name!r} differ from the grid's at the planned "
                             f"indices")
    return keep, pos


def aggregate(shards, rows, grid: Grid, scene: dict, catalogue: Catalogue | None = None):
    """Combine shard datasets into one Dataset with dims ``(material, *grid axes)``: row ``i`` of shard
    ``k`` is grid point ``rows[k][i]`` (-1: not on the grid any more; :attr:`vcor.study.shards.Shard.rows`)."""
    import xarray as xr

    catalogue = catalogue or Catalogue()
    _check_provenance(shards, scene, catalogue)
    first = shards[0]
    names = [v for v in first.data_vars if v not in TEXT_VARS + INT_VARS]
    out = {v: np.full(grid.shape, np.nan) for v in names}
    out.update({v: np.zeros(grid.shape, dtype=np.int8) for v in INT_VARS if v in first})
    out.update({v: np.full(grid.shape, "", dtype=object) for v in TEXT_VARS if v in first})
    filled = np.zeros(grid.shape, dtype=bool)
    for k, (ds, r) in enumerate(zip(shards, rows)):
        keep, pos = _check_rows(k, ds, r, grid)
        for v, arr in out.items():
            arr[pos] = ds[v].values[keep]
        filled[pos] = True
    if not filled.all():
        raise ValueError(f"{int((~filled).sum())} grid points missing from the shards")
    dims = ("material", *grid.names)
    data = {v: (dims, arr.astype(str) if v in TEXT_VARS else arr) for v, arr in out.items()}
    coords = {"material": np.array(grid.materials, dtype=str), **{a.name: np.array(a.values) for a in grid.axes}}
    ds = xr.Dataset(data, coords=coords)
    for v in ds.data_vars:
        ds[v].attrs.update(first[v].attrs)  # units, long names, status flags: as the shards have them
    for a in grid.axes:
        ds[a.name].attrs.update(units=a.unit, long_name=a.long_name)
    ds["material"].attrs["long_name"] = "material (preset or fitted name)"
    spec = uncertainty_of(scene)
    return ds if spec is None else reduce_samples(ds, spec["level"])
