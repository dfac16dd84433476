"""Parameter sweeps: scene grids -> points -> content-addressed shards -> one xarray Dataset.

A *scene* (a mapping, as in ``config.yaml``) names materials, grid axes and solver settings:

    materials: [sls]                      # presets or fitted names (results/materials/<name>.nc)
    grid: {v0: {start: 1, stop: 30, step: 1}, beta: [600, 1200, 2400]}
    tie: {alpha: {to: beta, ratio: 0.25}}  # alpha = 0.25 * beta at every point
    solver: {method: direct, dt: null, steps_per_contact: 2000, volterra: false, form: a}
    geometry: {}                          # fixed geometry keywords (r, rho_a, rho_b, h, nu, case, rigid)

Grid axes are ``v0`` (m/s), any geometry keyword, or any scalar parameter of the material
(``Material.params()``: E_glassy, alpha, beta for ``sls``; E0, E1 for ``butyl-fc``; ...).

Shards are named by content: ``<settings hash>-<points hash>``. Planning reuses every existing
shard (its JSON index lists its points) computed with the same settings, and groups only the
points not yet covered into new shards, so extending a grid never recomputes finished points.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import time
import traceback
from pathlib import Path

import numpy as np

from . import materials as _materials
from .impact import GEOMETRY_DEFAULTS
from .solvers import simulate
from .solvers.common import LONG_NAMES, STATUS_CODES, UNITS

__all__ = [
    "axis_values",
    "scene_points",
    "settings_of",
    "settings_hash",
    "plan_shards",
    "run_points",
    "aggregate",
    "resolve_material",
    "validate_scene",
    "material_params",
    "dataset_attrs",
    "SCALARS",
    "AXIS_UNITS",
]

#: scalar outputs stored per point
SCALARS = ("cor", "t0", "s_max", "f_max", "s_residual", "w_h", "w_plate", "omega_min", "sphere_velocity",
           "energy_residual", "steps", "dt", "wall_time")

AXIS_UNITS = {
    "v0": ("m s-1", "impact speed"),
    "r": ("m", "sphere radius"),
    "rho_a": ("kg m-3", "sphere density"),
    "rho_b": ("kg m-3", "plate density"),
    "h": ("m", "plate half-thickness"),
    "nu": ("1", "Poisson ratio of the viscoelastic body"),
    "E_plate": ("Pa", "elastic plate modulus (case 4)"),
    "nu_plate": ("1", "plate Poisson ratio (case 4)"),
    "beta": ("s-1", "relaxation (decay) rate"),
    "alpha": ("s-1", "SLS rate alpha (rubbery/glassy = alpha/beta)"),
    "E_glassy": ("Pa", "glassy modulus"),
    "E0": ("Pa", "rubbery modulus"),
    "E1": ("Pa", "relaxing modulus"),
    "E": ("Pa", "modulus"),
    "E_inf": ("Pa", "rubbery modulus"),
    "b1": ("s-1/2", "CERF rate parameter"),
    "tau": ("s", "retardation time"),
}

SOLVER_DEFAULTS = {
    "method": "direct",
    "dt": None,
    "steps_per_contact": 2000,
    "volterra": False,
    "form": "a",
    "rule": "force",
    "rtol": 1e-10,
    "ive_method": "Radau",
}


# ----------------------------------------------------------------------------- grids
def _canon(v) -> float:
    """Canonical float (12 significant digits) so that 0.1 * 3 and 0.3 name the same point."""
    return float(f"{float(v):.12g}")


def axis_values(spec) -> list[float]:
    """Grid axis values from a list or {start, stop, step} (stop inclusive) / {start, stop, num[, log]}.

    Returns sorted unique floats; raises ValueError on NaN, infinities or an empty axis.
    """
    if isinstance(spec, dict):
        start, stop = float(spec["start"]), float(spec["stop"])
        if "step" in spec:
            step = float(spec["step"])
            if not step > 0:
                raise ValueError(f"grid step must be > 0, got {step}")
            n = int(math.floor((stop - start) / step + 1e-9)) + 1
            vals = [start + i * step for i in range(max(n, 0))]
        else:
            num = int(spec["num"])
            vals = list(np.geomspace(start, stop, num) if spec.get("log") else np.linspace(start, stop, num))
    else:
        vals = [float(v) for v in np.atleast_1d(spec)]
    vals = sorted({_canon(v) for v in vals})
    if not vals:
        raise ValueError("grid axis is empty")
    if any(not math.isfinite(v) for v in vals):
        raise ValueError(f"grid axis values must be finite numbers, got {vals}")
    return vals


def resolve_material(name: str, overrides: dict | None = None, material_dir: str | Path = "results/materials"):
    """Material by preset name or fitted file ``<material_dir>/<name>.nc``, with parameter overrides."""
    if name in _materials.PRESETS:
        mat = _materials.get(name)
    else:
        path = Path(material_dir) / f"{name}.nc"
        if not path.exists():
            raise ValueError(
                f"unknown material {name!r}: not a preset ({sorted(_materials.PRESETS)}) and no fitted file {path}"
            )
        mat = _materials.from_file(path)
    if overrides:
        d = mat.to_dict()
        for key, value in overrides.items():
            if key not in d or isinstance(d[key], list):
                scalars = [k for k, v in d.items() if k != "kind" and not isinstance(v, list)]
                raise ValueError(f"material {name!r} has no scalar parameter {key!r}; allowed: {scalars}")
            d[key] = float(value)
        mat = _materials.from_dict(d)
    return mat


def _scene_axes(scene) -> dict[str, list[float]]:
    grid = scene.get("grid") or {}
    if "v0" not in grid:
        raise ValueError("scene grid must contain 'v0' (m/s)")
    return {k: axis_values(v) for k, v in grid.items()}


def scene_points(scene) -> list[dict]:
    """All grid points (material first, then axes in config order)."""
    axes = _scene_axes(scene)
    names = list(axes)
    pts = []
    for mat in scene["materials"]:
        for combo in itertools.product(*(axes[n] for n in names)):
            pts.append({"material": mat, **dict(zip(names, combo))})
    return pts


def settings_of(scene) -> dict:
    """Everything except the grid values that determines a point's result."""
    solver = {**SOLVER_DEFAULTS, **(scene.get("solver") or {})}
    return {
        "solver": solver,
        "geometry": dict(scene.get("geometry") or {}),
        "tie": dict(scene.get("tie") or {}),
        "error_estimate": bool(scene.get("error_estimate", False)),
    }


def _hash(obj, n=12) -> str:
    return hashlib.sha1(json.dumps(obj, sort_keys=True, default=float).encode()).hexdigest()[:n]


def settings_hash(scene) -> str:
    return _hash(settings_of(scene), 10)


def point_key(p: dict) -> str:
    return json.dumps(p, sort_keys=True)


def plan_shards(scene, shard_dir: str | Path, shard_size: int) -> dict[str, list[dict]]:
    """{shard id: points}. Existing shards with the same settings are reused as they are."""
    h = settings_hash(scene)
    todo = {point_key(p): p for p in scene_points(scene)}
    order = ["material"] + list(scene.get("grid") or {})
    plan: dict[str, list[dict]] = {}
    for idx in sorted(Path(shard_dir).glob(f"{h}-*.json")):
        try:
            pts = json.loads(idx.read_text())["points"]
            # same key order as scene_points, so Snakemake sees unchanged params
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
        plan[f"{h}-{_hash([point_key(p) for p in chunk])}"] = chunk
    return plan


def validate_scene(name: str, scene: dict, material_dir="results/materials", fitted=()) -> None:
    """Checks that need vcor (the JSON schema checks the shape): axes, ties, materials, values.

    Builds the material and geometry of the grid's corner points so that bad values fail now,
    naming the key, before any job runs. Fitted materials (listed in ``fitted``) are checked by
    name only, since their files may not exist yet.
    """
    where = f"scenes.{name}"
    try:
        axes = _scene_axes(scene)
    except (ValueError, KeyError, TypeError) as exc:
        raise ValueError(f"{where}.grid: {exc}") from None
    if axes["v0"][0] <= 0:
        raise ValueError(f"{where}.grid.v0: impact speeds must be > 0 m/s, got {axes['v0'][0]}")
    tie = scene.get("tie") or {}
    for target, spec in tie.items():
        if spec["to"] not in axes:
            raise ValueError(f"{where}.tie.{target}: 'to' must name a grid axis, got {spec['to']!r}")
    for mat in scene["materials"]:
        if mat not in _materials.PRESETS and mat not in fitted:
            raise ValueError(
                f"{where}.materials: unknown material {mat!r}; presets {sorted(_materials.PRESETS)}, "
                f"fitted {sorted(fitted)}"
            )
        if mat in fitted:
            continue
        corners = itertools.product(*[(v[0], v[-1]) for v in axes.values()])
        for combo in corners:
            point = {"material": mat, **dict(zip(axes, combo))}
            try:
                _build(point, settings_of(scene), material_dir, check_only=True)
            except ValueError as exc:
                raise ValueError(f"{where}: point {point}: {exc}") from None


def _build(point, settings, material_dir, check_only=False):
    """(material, v0, geometry) of one point."""
    geometry = dict(settings["geometry"])
    overrides = {}
    v0 = None
    for key, value in point.items():
        if key == "material":
            continue
        if key == "v0":
            v0 = float(value)
        elif key in GEOMETRY_DEFAULTS:
            geometry[key] = value
        else:
            overrides[key] = value
    for target, spec in settings["tie"].items():
        overrides[target] = float(spec["ratio"]) * float(point[spec["to"]])
    mat = resolve_material(point["material"], overrides, material_dir)
    if check_only:
        from .solvers.simulate import make_impact

        make_impact(mat, v0, geometry)
    return mat, v0, geometry


def _solve(point, settings, material_dir):
    mat, v0, geometry = _build(point, settings, material_dir)
    s = settings["solver"]
    kw = dict(method=s["method"], dt=s["dt"], volterra=s["volterra"], form=s["form"], rule=s["rule"],
              rtol=s["rtol"], ive_method=s["ive_method"], steps_per_contact=int(s["steps_per_contact"]))
    res = simulate(mat, v0, **kw, **geometry)
    out = {k: getattr(res, k) for k in SCALARS}
    out["status"], out["message"] = res.status, res.message
    if settings.get("error_estimate"):
        # Fixed step: Richardson from dt and dt/2 (order 2), err ~ |x_dt - x_dt/2| * 4/3. solve_ivp:
        # the difference to a run at rtol/100. The stored values stay those of the first run, so the
        # estimate is an estimate of *their* error.
        out["cor_err"] = out["t0_err"] = math.nan
        if res.ok:
            if s["method"] == "ive":
                fine = simulate(mat, v0, **{**kw, "rtol": s["rtol"] / 100}, **geometry)
                factor = 1.0
            else:
                fine = simulate(mat, v0, **{**kw, "dt": res.dt / 2}, **geometry)
                factor = 4.0 / 3.0
            if fine.ok:
                out["cor_err"] = abs(res.cor - fine.cor) * factor
                out["t0_err"] = abs(res.t0 - fine.t0) * factor
            else:
                out["status"] = fine.status
                out["message"] = "error estimate run: " + fine.message
    return out


def run_points(points, settings, material_dir="results/materials"):
    """Solve each point; a failure is stored with its status and message, never raised."""
    rows = []
    for p in points:
        t = time.perf_counter()
        try:
            row = _solve(p, settings, material_dir)
        except ValueError as exc:
            row = {"status": "invalid-input", "message": str(exc)}
        except Exception as exc:  # noqa: BLE001 - a failed point must not sink its shard
            row = {"status": "failed", "message": f"{type(exc).__name__}: {exc} | {traceback.format_exc(limit=2)}"}
        row.setdefault("wall_time", time.perf_counter() - t)
        rows.append(row)
    return _rows_to_dataset(points, rows, settings)


def _rows_to_dataset(points, rows, settings):
    import xarray as xr

    n = len(points)
    data = {}
    names = list(SCALARS) + (["cor_err", "t0_err"] if settings.get("error_estimate") else [])
    for k in names:
        data[k] = ("point", np.array([float(r.get(k, math.nan)) for r in rows]))
    data["status"] = ("point", np.array([STATUS_CODES[r["status"]] for r in rows], dtype=np.int8))
    data["message"] = ("point", np.array([r.get("message", "") for r in rows], dtype=object))
    coords = {"point": np.arange(n)}
    axes = [k for k in points[0] if k != "material"] if points else []
    coords["material"] = ("point", np.array([p["material"] for p in points], dtype=object))
    for a in axes:
        coords[a] = ("point", np.array([float(p[a]) for p in points]))
    return xr.Dataset(data, coords=coords)


def material_params(names, material_dir="results/materials") -> dict:
    """{name: Material.to_dict()} for provenance (fitted materials included)."""
    return {n: resolve_material(n, material_dir=material_dir).to_dict() for n in names}


def dataset_attrs(scene_name, scene, material_dir="results/materials") -> dict:
    """Global attributes that make a dataset enough to re-run its scene."""
    return {
        "scene": scene_name,
        "scene_config": scene,
        "solver_settings": settings_of(scene),
        "materials": material_params(scene["materials"], material_dir),
        "geometry_defaults": {k: v for k, v in GEOMETRY_DEFAULTS.items()},
    }


def aggregate(shards, scene):
    """Combine shard datasets into one Dataset with dims (material, *grid axes)."""
    import xarray as xr

    axes = _scene_axes(scene)
    mats = list(scene["materials"])
    names = list(axes)
    shape = (len(mats),) + tuple(len(axes[a]) for a in names)
    # position of every requested point in the output arrays
    pos_of = {}
    for p in scene_points(scene):
        pos = (mats.index(p["material"]),) + tuple(axes[a].index(p[a]) for a in names)
        pos_of[point_key(p)] = pos
    first = shards[0]
    var_names = [v for v in first.data_vars if v not in ("status", "message")]
    out = {v: np.full(shape, np.nan) for v in var_names}
    status = np.zeros(shape, dtype=np.int8)
    message = np.empty(shape, dtype=object)
    filled = np.zeros(shape, dtype=bool)
    for ds in shards:
        cols = {v: ds[v].values for v in var_names}
        st, ms = ds["status"].values, ds["message"].values
        mat_col = ds["material"].values
        ax_cols = {a: ds[a].values for a in names}
        for i in range(ds.sizes["point"]):
            p = {"material": str(mat_col[i])}
            for a in names:
                p[a] = _canon(ax_cols[a][i])
            pos = pos_of.get(point_key(p))
            if pos is None:
                continue  # a reused shard may hold points no longer in the grid
            for v in var_names:
                out[v][pos] = cols[v][i]
            status[pos], message[pos] = st[i], ms[i]
            filled[pos] = True
    if not filled.all():
        raise ValueError(f"{int((~filled).sum())} grid points missing from the shards")
    dims = ("material",) + tuple(names)
    data = {v: (dims, out[v]) for v in var_names}
    data["status"] = (dims, status)
    data["message"] = (dims, message.astype(str))
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
    codes = sorted(STATUS_CODES.items(), key=lambda kv: kv[1])
    ds["status"].attrs.update(
        long_name="solver status", units="1",
        flag_values=np.array([c for _, c in codes], dtype=np.int8),
        flag_meanings=" ".join(k.replace("-", "_") for k, _ in codes),
    )
    ds["message"].attrs["long_name"] = "solver message (failure reason, or a note such as a refined dt)"
    return ds
