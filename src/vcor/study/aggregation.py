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
from .scene import AXIS_UNITS, canon, material_params, scene_axes, settings_of
from .shards import identified_points, point_key
from .uncertainty import reduce_samples, uncertainty_of

__all__ = ["aggregate", "dataset_attrs"]


def dataset_attrs(scene_name, scene, catalogue: Catalogue | None = None) -> dict:
    """Global attributes that make a dataset enough to re-run its scene."""
    return {
        "scene": scene_name,
        "scene_config": scene,
        "solver_settings": settings_of(scene),
        "materials": material_params(scene["materials"], catalogue),
        "geometry_defaults": dict(GEOMETRY_DEFAULTS),
    }


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


def aggregate(shards, scene, identities: dict, catalogue: Catalogue | None = None):
    """Combine shard datasets into one Dataset with dims ``(material, *grid axes)``."""
    import xarray as xr

    catalogue = catalogue or Catalogue()
    _check_provenance(shards, scene, catalogue)
    axes = scene_axes(scene)
    mats = list(scene["materials"])
    names = list(axes)
    shape = (len(mats),) + tuple(len(axes[a]) for a in names)
    # position of every requested point in the output arrays
    pos_of = {}
    for p in identified_points(scene, identities):
        pos_of[point_key(p)] = (mats.index(p["material"]),) + tuple(axes[a].index(p[a]) for a in names)
    first = shards[0]
    text_vars = ("message", "error_message", "validity_message")
    int_vars = ("status", "error_status", "validity")
    var_names = [v for v in first.data_vars if v not in text_vars + int_vars]
    out = {v: np.full(shape, np.nan) for v in var_names}
    ints = {v: np.zeros(shape, dtype=np.int8) for v in int_vars if v in first}
    texts = {v: np.empty(shape, dtype=object) for v in text_vars if v in first}
    filled = np.zeros(shape, dtype=bool)
    for ds in shards:
        cols = {v: ds[v].values for v in list(var_names) + list(ints) + list(texts)}
        mat_col, id_col = ds["material"].values, ds["material_id"].values
        ax_cols = {a: ds[a].values for a in names}
        for i in range(ds.sizes["point"]):
            p = {"material": str(mat_col[i]), "material_id": str(id_col[i])}
            for a in names:
                p[a] = canon(ax_cols[a][i])
            pos = pos_of.get(point_key(p))
            if pos is None:
                continue  # a reused shard may hold points no longer in the grid
            for v, col in cols.items():
                (out.get(v) if v in out else ints.get(v) if v in ints else texts[v])[pos] = col[i]
            filled[pos] = True
    if not filled.all():
        raise ValueError(f"{int((~filled).sum())} grid points missing from the shards")
    dims = ("material",) + tuple(names)
    data = {v: (dims, arr) for v, arr in {**out, **ints}.items()}
    data.update({v: (dims, arr.astype(str)) for v, arr in texts.items()})
    coords = {"material": np.array(mats, dtype=str), **{a: np.array(axes[a]) for a in names}}
    ds = xr.Dataset(data, coords=coords)
    for v in ds.data_vars:
        ds[v].attrs.update(first[v].attrs)  # units, long names, status flags: as the shards have them
    for a in names:
        u, ln = AXIS_UNITS.get(a, ("1", a))
        ds[a].attrs.update(units=u, long_name=ln)
    ds["material"].attrs["long_name"] = "material (preset or fitted name)"
    spec = uncertainty_of(scene)
    return ds if spec is None else reduce_samples(ds, spec["level"])
