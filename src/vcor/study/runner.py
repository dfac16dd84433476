"""Running points: solve grid points into an ``xarray.Dataset`` (one shard; :mod:`vcor.study.aggregation`
combines a scene's shards), every variable with its units and long name.

A failed point never sinks its shard: it is stored with its status and message
(:mod:`vcor.status`). With ``error_estimate`` every ok point is solved again (dt/2 for fixed-step
methods: Richardson; rtol/100 for ``ive``; step_tol/16 for ``adaptive``) and the estimates
``cor_err``, ``t0_err`` get their own ``error_status`` / ``error_message``: a failing estimate run
never overwrites the point's status.
"""

from __future__ import annotations

import functools
import math
import time

import numpy as np

from .. import status as _status
from ..materials.catalogue import Catalogue
from ..solvers import validity as _validity
from ..solvers.common import LONG_NAMES, UNITS, richardson
from ..solvers.options import RTOL_MIN, SolverOptions
from ..solvers.simulate import simulate
from .grid import Axis, axis_role
from .scene import build_point

__all__ = ["ERRORS", "SCALARS", "rows_dataset", "run_points", "solve_point", "solve_rows", "solving_order"]

#: scalar outputs stored per point
SCALARS = ("cor", "t0", "s_max", "f_max", "s_residual", "w_h", "w_plate", "omega_min", "sphere_velocity",
           "energy_residual", "steps", "dt", "wall_time", "soe_error")
ERRORS = ("cor_err", "t0_err")


def solve_point(point, settings, catalogue: Catalogue, memo: dict | None = None) -> dict:
    """Scalars, status and message of one point (and the error estimates with ``error_estimate``);
    ``memo``: :func:`vcor.study.scene.build_point`'s."""
    material, v0, geometry = build_point(point, settings, catalogue, memo)
    opts = settings["solver"]
    res = simulate(material, v0, options=_solver_options(tuple(opts.items())), **geometry)
    out = {k: getattr(res, k) for k in SCALARS}
    out["status"], out["message"] = res.status, res.message
    out["validity"], out["validity_message"] = res.validity, res.validity_message
    if settings.get("error_estimate"):
        out.update(_error_estimate(res, material, v0, opts, geometry))
    return out


@functools.lru_cache(maxsize=16)
def _solver_options(items: tuple) -> SolverOptions:
    """The options of a scene's settings, validated once per process (not once per point)."""
    return SolverOptions(**dict(items))


def _error_estimate(res, material, v0, opts, geometry) -> dict:
    """Fixed step: Richardson from dt and dt/2 (order 2), |x_dt - x_extrapolated|. solve_ivp: the
    difference to a run at rtol/100 (not below RTOL_MIN: at rtol 1e-12 the run at 1e-13); adaptive: to a
    run at step_tol/16 (its error is about proportional to step_tol). The stored values stay those of the
    first run, so the estimate is an estimate of *their* error. A second run that raises is stored with
    its own status and message (``status.guarded``); the point keeps its own."""
    out = {"cor_err": math.nan, "t0_err": math.nan}
    if not res.ok:
        return {**out, "error_status": res.status, "error_message": "no estimate: the point itself is not ok"}
    if opts["method"] in ("ive", "adaptive"):
        key, div = ("rtol", 100) if opts["method"] == "ive" else ("step_tol", 16)
        finer = max(opts[key] / div, RTOL_MIN) if key == "rtol" else opts[key] / div
        fine, status, message = _status.guarded(simulate, material, v0, options={**opts, key: finer}, **geometry)
        if fine is None:
            return {**out, "error_status": status, "error_message": message}
        if fine.ok:
            out["cor_err"], out["t0_err"] = abs(res.cor - fine.cor), abs(res.t0 - fine.t0)
    else:
        halved = {**opts, "dt": res.dt / 2, "steps_per_contact": None}  # (dt and steps_per_contact: one of them)
        fine, status, message = _status.guarded(simulate, material, v0, options=halved, **geometry)
        if fine is None:
            return {**out, "error_status": status, "error_message": message}
        if fine.ok:
            out["cor_err"] = richardson(res.cor, fine.cor)[1]
            out["t0_err"] = richardson(res.t0, fine.t0)[1]
    return {**out, "error_status": fine.status, "error_message": fine.message if not fine.ok else ""}


def solve_rows(points, settings, catalogue: Catalogue | None = None, *, ordered: bool = False) -> list[dict]:
    """One row per point (in the order of ``points``): its scalars, status and message, and its error
    estimate with ``error_estimate``; materials named in ``catalogue`` (default: presets). A failure is
    stored with its status and message, never raised. Points are solved in :func:`solving_order`
    (``ordered``: the caller has put them in it already)."""
    catalogue = catalogue or Catalogue()
    rows: list = [None] * len(points)
    memo: dict = {}
    for i in range(len(points)) if ordered else solving_order(points):
        p = points[i]
        t = time.perf_counter()
        row, name, message = _status.guarded(solve_point, p, settings, catalogue, memo)
        if row is None:
            row = {"status": name, "message": message}
        row.setdefault("wall_time", time.perf_counter() - t)
        if settings.get("error_estimate"):
            row.setdefault("error_status", row["status"])
            row.setdefault("error_message", "no estimate: the point itself is not ok")
        rows[i] = row
    return rows


def run_points(points, settings, catalogue: Catalogue | None = None):
    """The dataset of ``points`` solved (:func:`solve_rows`, :func:`rows_dataset`): one shard, in one
    process; the dataset keeps the order of ``points``."""
    return rows_dataset(points, solve_rows(points, settings, catalogue), settings)


def solving_order(points) -> list[int]:
    """Indices of ``points``, those that differ only in speed together (in their order of first
    appearance): a material's tables and kernels (vcor.solvers.adaptive.impact_tables,
    vcor.solvers.adaptive_tables.level_tables and the materials' caches, each bounded) are built once per
    material rather than once per point when the speed is an outer grid axis. The results do not depend on
    the order: every cached value is a pure function of its arguments.

    Examples
    --------
    >>> solving_order([{"v0": 1, "beta": 10}, {"v0": 1, "beta": 20}, {"v0": 2, "beta": 10}])
    [0, 2, 1]
    """
    groups: dict[tuple, list[int]] = {}
    for i, p in enumerate(points):
        key = tuple((k, v) for k, v in p.items() if k != "index" and axis_role(k) != "speed")
        groups.setdefault(key, []).append(i)
    return [i for members in groups.values() for i in members]


def rows_dataset(points, rows, settings):
    """The shard dataset of ``points`` and their rows (:func:`solve_rows`): dimension ``point``, every
    variable with its units and long name, status and validity as CF flags."""
    import xarray as xr

    n = len(points)
    estimate = bool(settings.get("error_estimate"))
    data = {k: ("point", np.array([float(r.get(k, math.nan)) for r in rows]))
            for k in SCALARS + (ERRORS if estimate else ())}
    data["status"] = ("point", _status.codes_of(r["status"] for r in rows))
    data["message"] = ("point", np.array([r.get("message", "") for r in rows], dtype=object))
    data["validity"] = ("point", np.array([r.get("validity", 0) for r in rows], dtype=np.int8))
    data["validity_message"] = ("point", np.array([r.get("validity_message", "") for r in rows], dtype=object))
    if estimate:
        data["error_status"] = ("point", _status.codes_of(r["error_status"] for r in rows))
        data["error_message"] = ("point", np.array([r["error_message"] for r in rows], dtype=object))
    coords = {"point": ("point", np.arange(n), {"units": "1", "long_name": "point of the shard"})}
    axes = [k for k in points[0] if k not in ("index", "material", "material_id")] if points else []
    coords["material"] = ("point", np.array([p["material"] for p in points], dtype=object),
                          {"long_name": "material (preset or fitted name)"})
    coords["material_id"] = ("point", np.array([p.get("material_id", "") for p in points], dtype=object),
                             {"long_name": "content identity of the material (vcor.materials.Catalogue.identity)"})
    if points and all("index" in p for p in points):
        coords["index"] = ("point", np.array([int(p["index"]) for p in points], dtype=np.int64))
    for a in axes:
        coords[a] = ("point", np.array([float(p[a]) for p in points]))
    ds = xr.Dataset(data, coords=coords)
    for a in axes:
        axis = Axis.of(a, ())
        ds[a].attrs.update(units=axis.unit, long_name=axis.long_name)
    if "index" in ds.coords:
        ds["index"].attrs.update(units="1", long_name="the point's index in its scene's grid when the shard was "
                                                      "written (vcor.study.grid)")
    for v in SCALARS + (ERRORS if estimate else ()):
        base = v.replace("_err", "")
        ds[v].attrs["units"] = UNITS.get(base, "1")
        ds[v].attrs["long_name"] = LONG_NAMES.get(v, "") or (f"error estimate of {base}" if v.endswith("_err") else v)
    ds["status"].attrs.update(_status.cf_attrs("solver status"))
    ds["message"].attrs["long_name"] = "solver message (failure reason, or a note such as a refined dt)"
    ds["validity"].attrs.update(_validity.cf_attrs())
    ds["validity_message"].attrs["long_name"] = "why an ok result is outside the model's stated range"
    if estimate:
        ds["error_status"].attrs.update(_status.cf_attrs("status of the error-estimate run (dt/2, rtol/100 or "
                                                         "step_tol/16)"))
        ds["error_message"].attrs["long_name"] = "message of the error-estimate run"
    return ds
