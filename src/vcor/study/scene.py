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
(``Material.params()``: E_glassy, alpha, beta for ``sls``; E0, E1 for ``butyl-fc``; ...); the grid
and the role of each axis are :mod:`vcor.study.grid`'s. A body's ``material`` is any name of the
project's catalogue (preset, config material, fit, calibration), an inline spec or ``rigid``.
This module validates scenes and builds points; shard identity and planning are in
:mod:`vcor.study.shards`, solving in :mod:`vcor.study.runner`.
"""

from __future__ import annotations

import difflib
import itertools
import math

from ..contact.bodies import impact_inputs, scene_bodies
from ..contact.impact import GEOMETRY_AXES, make_impact
from ..materials.catalogue import Catalogue
from ..solvers.applicability import refusal
from ..solvers.options import SolverOptions
from .grid import AXIS_UNITS, MAX_AXIS_VALUES, Grid, axis_error, axis_length, axis_role, axis_values, canon, first_below
from .uncertainty import sample_material, samples_file, uncertainty_of

__all__ = [
    "AXIS_UNITS",
    "MAX_AXIS_VALUES",
    "MAX_JOBS",
    "MAX_POINTS",
    "axis_length",
    "axis_values",
    "build_point",
    "canon",
    "check_temperature_axis",
    "grid_of",
    "material_params",
    "point_count",
    "scene_axes",
    "scene_points",
    "settings_of",
    "solver_options_of",
    "validate_scene",
]

#: the most points (materials x axes) and sweep jobs a scene may plan: planning builds every point's
#: record (1e6 points take ~10 s on one core, each further job adds to Snakemake's graph); split a
#: larger study into scenes or raise shard_size
MAX_POINTS = 1_000_000
MAX_JOBS = 5_000


def grid_of(scene) -> Grid:
    """The :class:`~vcor.study.grid.Grid` of a scene's config (its ``sample`` axis with
    ``uncertainty``); ValueError naming the axis."""
    spec = uncertainty_of(scene)
    return Grid.from_scene(scene, samples=None if spec is None else spec["bootstrap"])


def scene_axes(scene) -> dict[str, list[float]]:
    """{axis: values} of the scene's grid, in config order (the bootstrap axis ``sample`` last)."""
    return grid_of(scene).values()


def point_count(scene) -> int:
    """The number of grid points of a scene (materials x axes), from the axis specs alone."""
    n = len(scene.get("materials") or [])
    for k, v in (scene.get("grid") or {}).items():
        try:
            n *= axis_length(v)
        except ValueError as exc:
            raise ValueError(axis_error(k, exc)) from None
    spec = scene.get("uncertainty")
    if isinstance(spec, dict) and isinstance(spec.get("bootstrap"), int):
        n *= max(int(spec["bootstrap"]), 1)
    return n


def scene_points(scene) -> list[dict]:
    """All grid points, in index order (:meth:`vcor.study.grid.Grid.points`)."""
    return grid_of(scene).points()


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


def _check_bodies(where, scene, grid: Grid):
    """A scene with bodies: no case geometry, no geometry axes, one body takes the swept material, and a
    method that can solve the combination."""
    if not ("sphere" in scene or "plate" in scene):
        return
    if scene.get("geometry"):
        raise ValueError(f"{where}.geometry: a scene with sphere/plate bodies takes no geometry keywords "
                         f"(they are the bodies' r, h, rho, nu), got {sorted(scene['geometry'])}")
    geo_axes = [a.name for a in grid.of_role("geometry")]
    if geo_axes:
        raise ValueError(f"{where}.grid: with sphere/plate bodies, geometry axes {geo_axes} are not available "
                         f"(grid axes: v0, T and the swept material's parameters)")
    specs = [scene.get(k) or {} for k in ("sphere", "plate")]
    if all("material" in sp for sp in specs):
        raise ValueError(f"{where}: both bodies name a material, so the scene's materials would not be used: "
                         f"omit material in the body that takes them")


def _check_body_materials(where, scene, catalogue):
    """A body's material name is one of the catalogue's (or ``rigid``)."""
    for kind in ("sphere", "plate"):
        value = (scene.get(kind) or {}).get("material")
        if isinstance(value, str) and value != "rigid":
            catalogue.check(value, f"{where}.{kind}.material")


def _check_axis_names(where, scene, grid: Grid, catalogue):
    """Every grid axis of role material (and every tie target) is a scalar parameter of every material
    of the scene."""
    params = {m: catalogue.scalar_parameters(m) for m in scene["materials"] if _known(catalogue, m)}
    shared = sorted(set.intersection(*map(set, params.values()))) if params else []
    fixed = ["T", "v0"] + ([] if "sphere" in scene or "plate" in scene else list(GEOMETRY_AXES))
    keys = [(a.name, "grid") for a in grid.of_role("material")] + [(t, "tie") for t in scene.get("tie") or {}]
    for key, block in keys:
        lacking = sorted(m for m, names in params.items() if key not in names)
        if lacking:
            allowed = (sorted(fixed) if block == "grid" else []) + shared
            close = difflib.get_close_matches(key, allowed, n=1)
            raise ValueError(f"{where}.{block}.{key}: materials {lacking} have no parameter {key!r}; "
                             f"allowed {'grid axes' if block == 'grid' else 'tie targets'}: {allowed}"
                             + (f"; did you mean {close[0]!r}?" if close else ""))


def _known(catalogue, name) -> bool:
    try:
        catalogue.source(name)
    except ValueError:
        return False
    return True


def _check_ties(where, scene, grid: Grid):
    for target, spec in (scene.get("tie") or {}).items():
        if spec["to"] not in grid.names:
            raise ValueError(f"{where}.tie.{target}: 'to' must name a grid axis ({grid.names}), got {spec['to']!r}")
        if target in grid.names:
            raise ValueError(f"{where}.tie.{target}: {target} is also a grid axis; tie it or sweep it, not both")


def _point_refusal(where, scene, point, text) -> str:
    """The refusal ``text`` of a grid point, after the key path of the value it names (its first word, or
    its second after a model's label: ``SLS alpha must be ...``): the grid axis, with the value's index
    when the axis is a list (``scenes.s.grid.E_glassy[1]``), or the tie that sets it; else the scene."""
    names = [w.split("[", 1)[0] for w in text.split(" ", 2)[:2]]
    ties = scene.get("tie") or {}
    for name in names:
        if name in ties:
            return f"{where}.tie.{name}: point {point}: {text}"
        if name != "material" and name in point:
            given = (scene.get("grid") or {}).get(name)
            index = next((i for i, v in enumerate(given) if isinstance(v, (int, float)) and not isinstance(v, bool)
                          and math.isclose(v, point[name], rel_tol=1e-12)), None) if isinstance(given, list) else None
            return f"{where}.grid.{name}{'' if index is None else f'[{index}]'}: point {point}: {text}"
    return f"{where}: point {point}: {text}"


def _check_corners(where, scene, grid: Grid, catalogue):
    """Build the material and geometry of the grid's corner points, so that bad values fail now, and
    refuse a solver method that cannot solve a material's kernel (:func:`vcor.solvers.applicability.refusal`)."""
    settings = settings_of(scene)
    options = solver_options_of(scene)
    bodies = [(scene.get(k) or {}).get("material") for k in ("sphere", "plate")]
    if any(isinstance(b, str) and b in catalogue.computed() for b in bodies):
        return  # a body's fit or calibration: its file is written by its rule, its values checked by the job
    for mat in grid.materials:
        if mat in catalogue.computed():
            continue
        corners = itertools.product(*[(a.values[0], a.values[-1]) for a in grid.axes])
        for combo in corners:
            point = {"material": mat, **dict(zip(grid.names, combo))}
            try:
                material, v0, geometry = build_point(point, settings, catalogue)
                impact = make_impact(material, v0, geometry)
            except ValueError as exc:
                raise ValueError(_point_refusal(where, scene, point, str(exc))) from None
            why = refusal(impact.material, options)
            if why:  # the same at every point of this material: the scene is refused, not each point
                raise ValueError(f"{where}.solver.method: material {mat!r}: {why}")


def validate_scene(name: str, scene: dict, catalogue: Catalogue | None = None, grid: Grid | None = None) -> Grid:
    """Checks that need vcor (the JSON schema checks the shape): solver options, axes, ties,
    materials, values; returns the scene's grid (``grid``, when the caller built it already).

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
    if grid is None:
        try:
            grid = grid_of(scene)
        except (ValueError, KeyError, TypeError) as exc:
            raise ValueError(f"{where}.grid.{exc}" if "v0" in (scene.get("grid") or {})
                             else f"{where}.grid: {exc}") from None
    v0 = grid.axis("v0").values
    if v0[0] <= 0:
        at = first_below(scene["grid"]["v0"], 0.0)
        raise ValueError(f"{where}.grid.v0{at}: impact speeds must be > 0 m/s, got {v0[0]}")
    _check_bodies(where, scene, grid)
    _check_body_materials(where, scene, catalogue)
    _check_axis_names(where, scene, grid, catalogue)
    _check_ties(where, scene, grid)
    for mat in grid.materials:
        catalogue.check(mat, f"{where}.materials")
    _check_corners(where, scene, grid, catalogue)
    return grid


def check_temperature_axis(name: str, scene: dict, catalogue: Catalogue, grid: Grid) -> None:
    """A grid axis T (deg C) needs every material of the scene to have a shift function (a config
    material with ``shift:``, valid at the axis' ends, or a fit to raw multi-temperature data: a table
    valid on its sets' temperatures, :func:`_check_table_range`; a fitted WLF or Arrhenius function is known
    only after the fit, and a T outside its range is then that point's invalid-input status); ValueError
    naming the key otherwise."""
    if "T" not in grid.names:
        return
    temps = grid.axis("T").values
    for mat in grid.materials:
        fitted = catalogue.source(mat) == "fit"
        data = (catalogue.fits[mat].get("data") or {}) if fitted else {}
        if "file" in data and ("shift_file" in data or _raw_sets(catalogue, data["file"])):
            _check_table_range(f"scenes.{name}.grid.T", mat, data, catalogue, (temps[0], temps[-1]))
            continue
        shift = None if fitted else catalogue.shift(mat)
        if shift is None:
            what = (f"fit {mat!r} has no shift function (its data {data['file']} is a master curve, without T and Set "
                    f"columns)" if "file" in data else
                    f"fit {mat!r} has no shift function (a fit to built-in data has none)" if fitted else
                    f"material {mat!r} has no shift function")
            raise ValueError(f"scenes.{name}.grid.T: {what}; a temperature axis needs materials.<name>.shift in the "
                             f"config, or a fit to raw sets at two or more temperatures")
        for T in (temps[0], temps[-1]):
            try:
                shift.log_aT(T)
            except ValueError as exc:
                raise ValueError(f"scenes.{name}.grid.T: material {mat!r}: {exc}") from None


def _check_table_range(where: str, mat: str, data: dict, catalogue: Catalogue, ends) -> None:
    """A fit to raw sets whose shift function is a table (``shift_model: table``, the default) is valid on its
    sets' temperatures (the means of their T columns) +- TABLE_TOLERANCE, known from the data file before the
    fit: ValueError naming ``where`` for an end of the axis (``ends``, deg C) outside. A fitted WLF or
    Arrhenius function's range follows from its fitted constants: a T outside it is that point's
    invalid-input status. An unreadable file is left to the fit's own check."""
    from pathlib import Path

    from ..fitting.dma.data import read_table
    from ..fitting.dma.sets import split_sets
    from ..fitting.spec import SHIFT_MODELS
    from ..materials.shift import TABLE_TOLERANCE

    if data.get("shift_model", SHIFT_MODELS[0]) != "table":
        return
    try:
        temps = [s.T for s in split_sets(read_table(Path(catalogue.base_dir) / data["file"]))]
    except (OSError, ValueError):
        return
    lo, hi = min(temps) - TABLE_TOLERANCE, max(temps) + TABLE_TOLERANCE
    for T in ends:
        if not lo <= T <= hi:
            raise ValueError(f"{where}: fit {mat!r}: temperature T must be in [{lo:g}, {hi:g}] deg C, its data's "
                             f"sets' range (shift_model table is not extrapolated; wlf or arrhenius is), got {T:g}")


def _raw_sets(catalogue: Catalogue, file: str) -> bool:
    """Does a fit's data file hold raw sets (T and Set columns: a shift function follows from the fit)? True
    also where the file cannot be read: the fit's own check names that."""
    from pathlib import Path

    from ..fitting.dma.data import read_table

    try:
        return read_table(Path(catalogue.base_dir) / file).is_raw
    except (OSError, ValueError):
        return True


def _body_materials(bodies: dict, catalogue: Catalogue) -> dict:
    """The bodies with each material that names a catalogue entry (a fit, a calibration; config
    materials arrive inlined) replaced by the material itself."""
    out = {}
    for kind, spec in bodies.items():
        name = spec.get("material")
        if isinstance(name, str) and name != "rigid" and catalogue.source(name) != "preset":
            spec = {**spec, "material": catalogue.material(name)}
        out[kind] = spec
    return out


def build_point(point, settings, catalogue: Catalogue | None = None, memo: dict | None = None):
    """(material, v0, geometry) of one point. Each key is used by its axis role
    (:func:`vcor.study.grid.axis_role`): the speed, a geometry keyword, a material parameter, the
    temperature (deg C, through the material's shift function) or the bootstrap sample; ties set a
    material parameter from an axis. ``memo`` (a dict the caller keeps, one entry): the last point's
    material, reused by a point that differs from it only in speed or geometry (the same immutable
    object, with the values it has computed and cached: a grid's speeds cost what a loop over them does)."""
    catalogue = catalogue or Catalogue()
    geometry = dict(settings["geometry"])
    v0 = None
    for key, value in point.items():
        if key in ("index", "material", "material_id"):
            continue
        role = axis_role(key)
        if role == "speed":
            v0 = float(value)
        elif role == "geometry":
            geometry[key] = value
    key = tuple((k, v) for k, v in point.items() if k not in ("index", "material_id")
                and (k == "material" or axis_role(k) not in ("speed", "geometry")))
    if memo is not None and memo.get("key") == key:
        material, bodies = memo["value"]
    else:
        material, bodies = _point_material(point, settings, catalogue)
        if memo is not None:
            memo.update(key=key, value=(material, bodies))
    return material, v0, (geometry if bodies is None else dict(bodies))


def _point_material(point, settings, catalogue: Catalogue):
    """(material, geometry of the bodies or None) of a point (:func:`build_point`)."""
    overrides = {k: v for k, v in point.items() if k not in ("index", "material", "material_id")
                 and axis_role(k) == "material"}
    for target, spec in settings["tie"].items():
        overrides[target] = float(spec["ratio"]) * float(point[spec["to"]])
    T = float(point["T"]) if "T" in point else None
    if "sample" in point:
        path = samples_file(catalogue.material_dir, point["material"], settings["uncertainty"])
        material = sample_material(path, int(point["sample"]), overrides, T, point["material"])
    else:
        material = catalogue.at(point["material"], overrides, T)
    if "bodies" in settings:
        return impact_inputs(*scene_bodies(_body_materials(settings["bodies"], catalogue), material))
    return material, None


def material_params(names, catalogue: Catalogue | None = None) -> dict:
    """{name: what the catalogue records of it} for provenance (source, parameters, shift, spec, identity)."""
    catalogue = catalogue or Catalogue()
    return {n: catalogue.describe(n) for n in names}
