"""Scenes: a config mapping -> grid points, solver settings, and one point -> (material, v0, geometry).

A *scene* (as in ``config.yaml``) names materials, grid axes and solver settings:

    materials: [sls]                      # names of vcor.materials.Catalogue (presets, config, fits)
    grid: {v0: {start: 1, stop: 30, step: 1}, beta: [600, 1200, 2400]}
    tie: {alpha: {to: beta, ratio: 0.25}}  # alpha = 0.25 * beta at every point
    solver: {method: direct, steps_per_contact: 2000}   # vcor.solvers.options.SolverOptions
    geometry: {}                          # fixed geometry keywords (r, rho_a, rho_b, h, nu, case, rigid)
    # or, instead of geometry, two bodies (vcor.contact.bodies; the one without material takes the swept one):
    sphere: {material: {model: elastic, E: 200.0e+9}, r: 0.01, rho: 7800, nu: 0.3}
    plate: {h: 0.02, rho: 1100, nu: 0.5}

Grid axes are ``v0`` (m/s), any geometry keyword, or any scalar parameter of the material
(``Material.params()``: E_glassy, alpha, beta for ``sls``; E0, E1 for ``butyl-fc``; ...).
This module validates scenes and builds points; shard identity and planning are in
:mod:`vcor.study.shards`, solving in :mod:`vcor.study.runner`.
"""

from __future__ import annotations

import itertools
import math

import numpy as np

from ..contact.bodies import impact_inputs, scene_bodies
from ..contact.impact import GEOMETRY_DEFAULTS, make_impact
from ..materials.catalogue import Catalogue
from ..solvers.options import SolverOptions
from .uncertainty import sample_material, samples_file, uncertainty_of

__all__ = [
    "AXIS_UNITS",
    "GEOMETRY_AXES",
    "MAX_AXIS_VALUES",
    "MAX_JOBS",
    "MAX_POINTS",
    "axis_length",
    "axis_values",
    "build_point",
    "canon",
    "check_temperature_axis",
    "material_params",
    "point_count",
    "scene_axes",
    "scene_points",
    "settings_of",
    "solver_options_of",
    "validate_scene",
]

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
    "T": ("degC", "temperature (materials with a shift function: E(t; T) = E(t / a_T))"),
    "sample": ("1", "bootstrap sample of the fitted materials (scenes with uncertainty)"),
}


#: geometry keywords a grid may sweep (numbers; case, rigid and plate_material are fixed per scene)
GEOMETRY_AXES = ("r", "rho_a", "rho_b", "h", "nu", "E_plate", "nu_plate")


def canon(v) -> float:
    """Canonical float (12 significant digits) so that 0.1 * 3 and 0.3 name the same point."""
    return float(f"{float(v):.12g}")


#: the most values one grid axis may have, and the most points (materials x axes) and sweep jobs a
#: scene may plan: planning builds every point's record (1e6 points take ~10 s on one core, each
#: further job adds to Snakemake's graph); split a larger study into scenes or raise shard_size
MAX_AXIS_VALUES = 100_000
MAX_POINTS = 1_000_000
MAX_JOBS = 5_000


def axis_length(spec) -> int:
    """The number of values of an axis spec before they are built (duplicates counted); ValueError
    for a spec that is not a list or {start, stop, step} / {start, stop, num[, log]}."""
    if isinstance(spec, dict):
        unknown = set(spec) - {"start", "stop", "step", "num", "log"}
        if unknown or not {"start", "stop"} <= set(spec) or ("step" in spec) == ("num" in spec):
            raise ValueError(f"an axis range is {{start, stop, step}} or {{start, stop, num[, log]}}, got {spec!r}")
        start, stop = _finite("start", spec["start"]), _finite("stop", spec["stop"])
        if "step" in spec:
            step = _finite("step", spec["step"])
            if not step > 0:
                raise ValueError(f"step must be > 0, got {step}")
            if stop < start:
                raise ValueError(f"the range is empty: stop {stop} < start {start}")
            return math.floor((stop - start) / step + 1e-9) + 1
        num = spec["num"]
        if isinstance(num, bool) or not isinstance(num, (int, np.integer)) or num < 1:
            raise ValueError(f"num must be an integer >= 1, got {num!r}")
        if spec.get("log") and not (start > 0 and stop > 0):
            raise ValueError(f"a log range needs start and stop > 0, got {start}, {stop}")
        return int(num)
    values = list(np.atleast_1d(spec)) if not isinstance(spec, (str, bytes)) else [spec]
    if not values:
        raise ValueError("the axis is empty (give at least one value)")
    for v in values:
        _finite("value", v)
    return len(values)


def _finite(what, v) -> float:
    if isinstance(v, (bool, str, bytes)) or v is None:
        raise ValueError(f"{what} must be a finite number, got {v!r}")
    try:
        x = float(v)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"{what} must be a finite number, got {v!r}") from None
    if not math.isfinite(x):
        raise ValueError(f"{what} must be a finite number, got {x!r}")
    return x


def axis_values(spec) -> list[float]:
    """Grid axis values from a list or {start, stop, step} (stop inclusive) / {start, stop, num[, log]}.

    Returns sorted unique floats; raises ValueError on NaN, infinities, an empty axis or one longer
    than MAX_AXIS_VALUES.
    """
    n = axis_length(spec)
    if n > MAX_AXIS_VALUES:
        raise ValueError(f"{n} values, more than the {MAX_AXIS_VALUES} one axis may have")
    if isinstance(spec, dict):
        start, stop = float(spec["start"]), float(spec["stop"])
        if "step" in spec:
            vals = [start + i * float(spec["step"]) for i in range(n)]
        else:
            vals = list(np.geomspace(start, stop, n) if spec.get("log") else np.linspace(start, stop, n))
    else:
        vals = [float(v) for v in np.atleast_1d(spec)]
    vals = sorted({canon(v) for v in vals})
    if any(not math.isfinite(v) for v in vals):
        raise ValueError(f"values must be finite numbers, got {vals}")
    return vals


def scene_axes(scene) -> dict[str, list[float]]:
    """{axis: values} of the scene's grid, in config order; ValueError naming the axis."""
    grid = scene.get("grid") or {}
    if "v0" not in grid:
        raise ValueError("the grid must contain 'v0' (m/s)")
    out = {}
    for k, v in grid.items():
        try:
            out[k] = axis_values(v)
        except ValueError as exc:
            raise ValueError(f"{k}: {exc}") from None
    spec = uncertainty_of(scene)
    if spec is not None:  # the bootstrap axis (vcor.study.uncertainty)
        out["sample"] = [float(k) for k in range(spec["bootstrap"])]
    return out


def point_count(scene) -> int:
    """The number of grid points of a scene (materials x axes), from the axis specs alone."""
    n = len(scene.get("materials") or [])
    for k, v in (scene.get("grid") or {}).items():
        try:
            n *= axis_length(v)
        except ValueError as exc:
            raise ValueError(f"{k}: {exc}") from None
    spec = scene.get("uncertainty")
    if isinstance(spec, dict) and isinstance(spec.get("bootstrap"), int):
        n *= max(int(spec["bootstrap"]), 1)
    return n


def scene_points(scene) -> list[dict]:
    """All grid points (material first, then axes in config order)."""
    axes = scene_axes(scene)
    names = list(axes)
    pts = []
    for mat in scene["materials"]:
        for combo in itertools.product(*(axes[n] for n in names)):
            pts.append({"material": mat, **dict(zip(names, combo))})
    return pts


def solver_options_of(scene) -> SolverOptions:
    """The scene's validated solver options (``scene['solver']``; unset ones take their defaults)."""
    return SolverOptions(**(scene.get("solver") or {}))


def settings_of(scene) -> dict:
    """Everything except the grid values and the materials that determines a point's result
    (solver options complete and canonical, as ``SolverOptions.to_dict()``)."""
    out = {
        "solver": solver_options_of(scene).to_dict(),
        "geometry": dict(scene.get("geometry") or {}),
        "tie": dict(scene.get("tie") or {}),
        "error_estimate": bool(scene.get("error_estimate", False)),
    }
    if "sphere" in scene or "plate" in scene:
        out["bodies"] = {k: dict(scene.get(k) or {}) for k in ("sphere", "plate")}
    spec = uncertainty_of(scene)
    if spec is not None:
        out["uncertainty"] = spec
    return out


def _check_bodies(where, scene, axes):
    """A scene with bodies: no case geometry, no geometry axes, one body takes the swept material, and a
    method that can solve the combination."""
    if not ("sphere" in scene or "plate" in scene):
        return
    if scene.get("geometry"):
        raise ValueError(f"{where}.geometry: a scene with sphere/plate bodies takes no geometry keywords "
                         f"(they are the bodies' r, h, rho, nu), got {sorted(scene['geometry'])}")
    geo_axes = sorted(set(axes) & set(GEOMETRY_AXES))
    if geo_axes:
        raise ValueError(f"{where}.grid: with sphere/plate bodies, geometry axes {geo_axes} are not available "
                         f"(grid axes: v0, T and the swept material's parameters)")
    specs = [scene.get(k) or {} for k in ("sphere", "plate")]
    if all("material" in sp for sp in specs):
        raise ValueError(f"{where}: both bodies name a material, so the scene's materials would not be used: "
                         f"omit material in the body that takes them")


def _check_axis_names(where, scene, axes, catalogue):
    """Every grid axis is v0, T, a geometry keyword (not with bodies) or a scalar parameter of every
    material of the scene; every tie target is a scalar parameter of every material."""
    fixed = {"v0", "T", "sample"} | (set() if "sphere" in scene or "plate" in scene else set(GEOMETRY_AXES))
    params = {m: catalogue.scalar_parameters(m) for m in scene["materials"] if _known(catalogue, m)}
    shared = sorted(set.intersection(*map(set, params.values()))) if params else []
    for key, block in [(a, "grid") for a in axes if a not in fixed] + [(t, "tie") for t in scene.get("tie") or {}]:
        lacking = sorted(m for m, names in params.items() if key not in names)
        if lacking:
            allowed = (sorted(fixed) if block == "grid" else []) + shared
            raise ValueError(f"{where}.{block}.{key}: materials {lacking} have no parameter {key!r}; "
                             f"allowed {'grid axes' if block == 'grid' else 'tie targets'}: {allowed}")


def _known(catalogue, name) -> bool:
    try:
        catalogue.source(name)
    except ValueError:
        return False
    return True


def validate_scene(name: str, scene: dict, catalogue: Catalogue | None = None) -> None:
    """Checks that need vcor (the JSON schema checks the shape): solver options, axes, ties,
    materials, values.

    Builds the material and geometry of the grid's corner points so that bad values fail now,
    naming the key, before any job runs. Computed materials (fits, calibrations: their files may not
    exist yet) are checked by name only.
    """
    catalogue = catalogue or Catalogue()
    where = f"scenes.{name}"
    try:
        solver_options_of(scene)
    except ValueError as exc:
        raise ValueError(f"{where}.solver: {exc}") from None
    try:
        axes = scene_axes(scene)
    except (ValueError, KeyError, TypeError) as exc:
        raise ValueError(f"{where}.grid.{exc}" if "grid" in scene and "v0" in scene["grid"]
                         else f"{where}.grid: {exc}") from None
    if axes["v0"][0] <= 0:
        raise ValueError(f"{where}.grid.v0: impact speeds must be > 0 m/s, got {axes['v0'][0]}")
    _check_bodies(where, scene, axes)
    _check_axis_names(where, scene, axes, catalogue)
    tie = scene.get("tie") or {}
    for target, spec in tie.items():
        if spec["to"] not in axes:
            raise ValueError(f"{where}.tie.{target}: 'to' must name a grid axis, got {spec['to']!r}")
        if target in axes:
            raise ValueError(f"{where}.tie.{target}: {target} is also a grid axis; tie it or sweep it, not both")
    settings = settings_of(scene)
    for mat in scene["materials"]:
        catalogue.check(mat, f"{where}.materials")
        if mat in catalogue.computed():
            continue
        corners = itertools.product(*[(v[0], v[-1]) for v in axes.values()])
        for combo in corners:
            point = {"material": mat, **dict(zip(axes, combo))}
            try:
                material, v0, geometry = build_point(point, settings, catalogue)
                make_impact(material, v0, geometry)
            except ValueError as exc:
                raise ValueError(f"{where}: point {point}: {exc}") from None
            method = settings["solver"]["method"]
            if _needs_direct(material, geometry) and method not in ("direct", "paper"):
                raise ValueError(f"{where}.solver.method: {method!r} cannot solve two deformable bodies combined "
                                 f"by Eq. 1 (contact modulus {material.kind!r}, a viscoelastic body on a "
                                 f"deformable one): set solver: {{method: direct}}")


def check_temperature_axis(name: str, scene: dict, catalogue: Catalogue) -> None:
    """A grid axis T (deg C) needs every material of the scene to have a shift function (a config
    material with ``shift:``, valid at the axis' ends, or a fit to raw multi-temperature data, whose
    shift function is known only after the fit: a T outside its range is then that point's
    invalid-input status); ValueError naming the key otherwise."""
    grid = scene.get("grid") or {}
    if "T" not in grid:
        return
    temps = axis_values(grid["T"])
    for mat in scene["materials"]:
        if catalogue.source(mat) == "fit" and "file" in (catalogue.fits[mat].get("data") or {}):
            continue
        shift = catalogue.shift(mat)
        if shift is None:
            raise ValueError(f"scenes.{name}.grid.T: material {mat!r} has no shift function (a temperature axis "
                             f"needs materials.{mat}.shift in the config, or a fit to multi-temperature data)")
        for T in (temps[0], temps[-1]):
            try:
                shift.log_aT(T)
            except ValueError as exc:
                raise ValueError(f"scenes.{name}.grid.T: material {mat!r}: {exc}") from None


def build_point(point, settings, catalogue: Catalogue | None = None):
    """(material, v0, geometry) of one point: grid axes are v0, geometry keywords or material
    parameters (and T, deg C, through the material's shift function); ties set a material parameter
    from an axis."""
    catalogue = catalogue or Catalogue()
    geometry = dict(settings["geometry"])
    overrides = {}
    v0 = None
    for key, value in point.items():
        if key in ("material", "material_id", "T", "sample"):
            continue
        if key == "v0":
            v0 = float(value)
        elif key in GEOMETRY_DEFAULTS:
            geometry[key] = value
        else:
            overrides[key] = value
    for target, spec in settings["tie"].items():
        overrides[target] = float(spec["ratio"]) * float(point[spec["to"]])
    T = float(point["T"]) if "T" in point else None
    if "sample" in point:
        path = samples_file(catalogue.material_dir, point["material"], settings["uncertainty"])
        material = sample_material(path, int(point["sample"]), overrides, T, point["material"])
    else:
        material = catalogue.at(point["material"], overrides, T)
    if "bodies" in settings:
        material, geometry = impact_inputs(*scene_bodies(settings["bodies"], material))
    return material, v0, geometry


def _needs_direct(material, geometry) -> bool:
    """A contact modulus only ``direct`` solves: Eq. 1's pointwise combination, or a viscoelastic plate
    whose modulus differs from the contact modulus."""
    plate = geometry.get("plate_material")
    return material.kind == "eq1" or (plate is not None and not plate.is_elastic)


def material_params(names, catalogue: Catalogue | None = None) -> dict:
    """{name: what the catalogue records of it} for provenance (source, parameters, shift, spec, identity)."""
    catalogue = catalogue or Catalogue()
    return {n: catalogue.describe(n) for n in names}
