"""Running points: solve grid points into an ``xarray.Dataset`` (one shard), and aggregate shards
into a scene's dataset with dims (material, *grid axes).

A failed point never sinks its shard: it is stored with its status and message
(:mod:`vcor.status`). With ``error_estimate`` every ok point is solved again (dt/2 for fixed-step
methods: Richardson; rtol/100 for ``ive``; step_tol/16 for ``adaptive``) and the estimates ``cor_err``, ``t0_err`` get their own
``error_status`` / ``error_message``: a failing estimate run never overwrites the point's status.

The aggregate refuses to combine shards computed by different code (their ``code_fingerprint``
attributes differ from each other or from the running code) or with different material
parameters than the current ones: an archive never mixes old and new results.
"""

from __future__ import annotations

import json
import math
import time

import numpy as np

from . import status as _status
from .provenance import code_fingerprint
from .scene import (
    AXIS_UNITS,
    build_point,
    canon,
    material_params,
    scene_axes,
    settings_of,
)
from .shards import identified_points, point_key
from .solvers import simulate
from .solvers.common import LONG_NAMES, UNITS, richardson

__all__ = ["SCALARS", "aggregate", "dataset_attrs", "run_points", "solve_point"]

#: scalar outputs stored per point
SCALARS = ("cor", "t0", "s_max", "f_max", "s_residual", "w_h", "w_plate", "omega_min", "sphere_velocity",
           "energy_residual", "steps", "dt", "wall_time")
ERRORS = ("cor_err", "t0_err")


def solve_point(point, settings, material_dir) -> dict:
    """Scalars, status and message of one point (and the error estimates with ``error_estimate``)."""
    material, v0, geometry = build_point(point, settings, material_dir)
    opts = settings["solver"]
    res = simulate(material, v0, options=opts, **geometry)
    out = {k: getattr(res, k) for k in SCALARS}
    out["status"], out["message"] = res.status, res.message
    if settings.get("error_estimate"):
        out.update(_error_estimate(res, material, v0, opts, geometry))
    return out


def _error_estimate(res, material, v0, opts, geometry) -> dict:
    """Fixed step: Richardson from dt and dt/2 (order 2), |x_dt - x_extrapolated|. solve_ivp: the
    difference to a run at rtol/100; adaptive: to a run at step_tol/16 (its error is about
    proportional to step_tol). The stored values stay those of the first run, so the
    estimate is an estimate of *their* error."""
    out = {"cor_err": math.nan, "t0_err": math.nan}
    if not res.ok:
        return {**out, "error_status": res.status, "error_message": "no estimate: the point itself is not ok"}
    if opts["method"] in ("ive", "adaptive"):
        key, div = ("rtol", 100) if opts["method"] == "ive" else ("step_tol", 16)
        fine = simulate(material, v0, options={**opts, key: opts[key] / div}, **geometry)
        if fine.ok:
            out["cor_err"], out["t0_err"] = abs(res.cor - fine.cor), abs(res.t0 - fine.t0)
    else:
        fine = simulate(material, v0, options={**opts, "dt": res.dt / 2}, **geometry)
        if fine.ok:
            out["cor_err"] = richardson(res.cor, fine.cor)[1]
            out["t0_err"] = richardson(res.t0, fine.t0)[1]
    return {**out, "error_status": fine.status, "error_message": fine.message if not fine.ok else ""}


def run_points(points, settings, material_dir="results/materials"):
    """Solve each point; a failure is stored with its status and message, never raised."""
    rows = []
    for p in points:
        t = time.perf_counter()
        row, name, message = _status.guarded(solve_point, p, settings, material_dir)
        if row is None:
            row = {"status": name, "message": message}
        row.setdefault("wall_time", time.perf_counter() - t)
        if settings.get("error_estimate"):
            row.setdefault("error_status", row["status"])
            row.setdefault("error_message", "no estimate: the point itself is not ok")
        rows.append(row)
    return _rows_to_dataset(points, rows, settings)


def _rows_to_dataset(points, rows, settings):
    import xarray as xr

    n = len(points)
    estimate = bool(settings.get("error_estimate"))
    data = {k: ("point", np.array([float(r.get(k, math.nan)) for r in rows])) for k in SCALARS + (ERRORS if estimate else ())}
    data["status"] = ("point", _status.codes_of(r["status"] for r in rows))
    data["message"] = ("point", np.array([r.get("message", "") for r in rows], dtype=object))
    if estimate:
        data["error_status"] = ("point", _status.codes_of(r["error_status"] for r in rows))
        data["error_message"] = ("point", np.array([r["error_message"] for r in rows], dtype=object))
    coords = {"point": np.arange(n)}
    axes = [k for k in points[0] if k not in ("material", "material_id")] if points else []
    coords["material"] = ("point", np.array([p["material"] for p in points], dtype=object))
    coords["material_id"] = ("point", np.array([p.get("material_id", "") for p in points], dtype=object))
    for a in axes:
        coords[a] = ("point", np.array([float(p[a]) for p in points]))
    return xr.Dataset(data, coords=coords)


def dataset_attrs(scene_name, scene, material_dir="results/materials") -> dict:
    """Global attributes that make a dataset enough to re-run its scene."""
    from .impact import GEOMETRY_DEFAULTS

    return {
        "scene": scene_name,
        "scene_config": scene,
        "solver_settings": settings_of(scene),
        "materials": material_params(scene["materials"], material_dir),
        "geometry_defaults": dict(GEOMETRY_DEFAULTS),
    }


def _check_provenance(shards, scene, material_dir):
    """Refuse shards of other code or other material parameters (see the module docstring)."""
    current = code_fingerprint()
    prints = {ds.attrs.get("code_fingerprint", "missing") for ds in shards}
    if prints != {current}:
        raise ValueError(f"shards were computed by different code (fingerprints {sorted(prints)}, running "
                         f"code {current}): refusing to combine them; recompute the stale shards")
    params = material_params(scene["materials"], material_dir)
    for ds in shards:
        used = json.loads(ds.attrs.get("materials", "{}"))
        for name, p in used.items():
            if name in params and p != params[name]:
                raise ValueError(f"a shard used material {name!r} with parameters {p}, the current ones are "
                                 f"{params[name]}: refusing to combine them; recompute the stale shards")


def aggregate(shards, scene, identities: dict, material_dir="results/materials"):
    """Combine shard datasets into one Dataset with dims (material, *grid axes)."""
    import xarray as xr

    _check_provenance(shards, scene, material_dir)
    axes = scene_axes(scene)
    mats = list(scene["materials"])
    names = list(axes)
    shape = (len(mats),) + tuple(len(axes[a]) for a in names)
    # position of every requested point in the output arrays
    pos_of = {}
    for p in identified_points(scene, identities):
        pos_of[point_key(p)] = (mats.index(p["material"]),) + tuple(axes[a].index(p[a]) for a in names)
    first = shards[0]
    text_vars = ("message", "error_message")
    int_vars = ("status", "error_status")
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
    for v in var_names:
        base = v.replace("_err", "")
        ds[v].attrs["units"] = UNITS.get(base, "1")
        ds[v].attrs["long_name"] = LONG_NAMES.get(v, "") or (f"Richardson error estimate of {base}" if v.endswith("_err") else v)
    for a in names:
        u, ln = AXIS_UNITS.get(a, ("1", a))
        ds[a].attrs.update(units=u, long_name=ln)
    ds["material"].attrs["long_name"] = "material (preset or fitted name)"
    ds["status"].attrs.update(_status.cf_attrs("solver status"))
    ds["message"].attrs["long_name"] = "solver message (failure reason, or a note such as a refined dt)"
    if "error_status" in ds:
        ds["error_status"].attrs.update(_status.cf_attrs("status of the error-estimate run (dt/2 or rtol/100)"))
        ds["error_message"].attrs["long_name"] = "message of the error-estimate run"
    return ds
