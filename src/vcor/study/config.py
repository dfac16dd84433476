"""Config checks: everything about a workflow config that can be checked before any job runs.

The JSON schema (``workflow/schemas/config.schema.yaml``, applied by :func:`vcor.study.schema.check_schema`)
checks the shape; :func:`load_project` checks what needs vcor and returns the
:class:`~vcor.study.project.Project` the workflow plans from: the material catalogue (presets,
config materials, fits, calibrations) and the scenes, each with its grid and settings, built once.
Every error is a ``ValueError`` whose one-line message starts with the config key
(``scenes.<name>.grid.T``, ``materials.<name>.E``, ...) and says the allowed values.
"""

from __future__ import annotations

import difflib
import math
import re
from dataclasses import replace
from pathlib import Path

from ..checks import number
from ..contact.impact import RANGES, make_impact
from ..fitting.calibrate import check_spec
from ..fitting.spec import check_fit_spec, expand_fits
from ..materials.catalogue import Catalogue
from ..materials.presets import PRESETS
from ..materials.specs import canonical, from_spec
from ..plots import AXIS_OPTIONS, FIGURE_OPTIONS, NEEDS_AXIS, needs, options_of
from ..solvers.applicability import refusal
from ..solvers.options import METHOD_NAMES, solver_options
from .dem import check_dem
from .grid import Grid, canon
from .project import BUILDS, DATASETS, DEFAULTS, Project, Scene
from .scene import (
    MAX_JOBS,
    MAX_POINTS,
    check_temperature_axis,
    grid_of,
    point_count,
    settings_of,
    solver_options_of,
    validate_scene,
)
from .uncertainty import check_uncertainty

__all__ = ["NAME_PATTERN", "SCENE_NAME_PATTERN", "Project", "inline_config_materials", "load_project"]

#: names of materials, fits and calibrations
NAME_PATTERN = r"[A-Za-z0-9_.-]+"
#: names of scenes (they become rule names)
SCENE_NAME_PATTERN = r"[A-Za-z0-9_-]+"


def inline_config_materials(scene: dict, catalogue: Catalogue) -> dict:
    """The scene with each body's ``material`` that names a config material replaced by that
    material's parameters as an inline spec, so that the material's content (CSV tables included) is
    part of the scene's settings and of its shards' identity."""
    out = dict(scene)
    for key in ("sphere", "plate"):
        body = dict(scene.get(key) or {})
        name = body.get("material")
        if isinstance(name, str) and name in catalogue.specs:
            d = catalogue.material(name).to_dict()
            body["material"] = {"model": d.pop("kind"), **d}
            out[key] = body
    return out


def _check_names(block: str, names, taken: dict) -> None:
    for name in names:
        if not re.fullmatch(NAME_PATTERN, name):
            raise ValueError(f"{block}.{name}: names may use letters, digits, ., - and _")
        for other, owner in taken.items():
            if name in owner:
                raise ValueError(f"{block}.{name}: the name is taken by a {other}; choose another")


def inside_project(key: str, value, base_dir: Path) -> str:
    """``value``, a non-empty relative path that stays inside the project folder; ValueError naming
    ``key`` otherwise. Every path of a config is one: results are never written outside the project,
    and the files a result depends on are part of it (link or copy outside data into the project)."""
    if not isinstance(value, str) or not value.strip():
        raise ValueError(f"{key} must be a non-empty path inside the project folder, got {value!r}")
    path, base = Path(value), base_dir.resolve()
    if path.is_absolute() or not (base_dir / path).resolve().is_relative_to(base):
        inside = path.is_absolute() and path.resolve().is_relative_to(base)
        raise ValueError(f"{key} must be a relative path inside the project folder ({base}), got {value!r}"
                         + (f": write {str(path.resolve().relative_to(base))!r}" if inside else
                            " (link or copy the file into the project)"))
    return value


def _check_paths(config: dict, base_dir: Path) -> None:
    """Every file path of the config is inside the project (inside_project)."""
    for name, spec in (config.get("materials") or {}).items():
        if isinstance(spec, dict) and "file" in spec:
            inside_project(f"materials.{name}.file", spec["file"], base_dir)
    for name, spec in (config.get("fits") or {}).items():
        data = (spec or {}).get("data") if isinstance(spec, dict) else None
        for key in ("file", "shift_file"):
            if isinstance(data, dict) and key in data:
                inside_project(f"fits.{name}.data.{key}", data[key], base_dir)
    for name, spec in (config.get("calibrations") or {}).items():
        if isinstance(spec, dict) and "data" in spec:
            inside_project(f"calibrations.{name}.data", spec["data"], base_dir)
    for name, spec in (config.get("dem") or {}).items():
        for body in ("sphere", "target"):
            part = (spec or {}).get(body) if isinstance(spec, dict) else None
            if body == "target" and isinstance(part, dict):
                part = part.get("sphere")
            material = part.get("material") if isinstance(part, dict) else None
            if isinstance(material, dict) and "file" in material:
                where = f"dem.{name}.{body}" + (".sphere" if body == "target" else "") + ".material.file"
                inside_project(where, material["file"], base_dir)


def _material_dir(config: dict, base_dir: Path) -> str:
    """``material_dir``: a non-empty relative path inside the project."""
    return inside_project("material_dir", config.get("material_dir", DEFAULTS["material_dir"]), base_dir)


def _catalogue(config: dict, base_dir: Path) -> Catalogue:
    _check_paths(config, base_dir)
    specs = dict(config.get("materials") or {})
    fits = expand_fits(config.get("fits") or {}, where="fits")
    calibrations = dict(config.get("calibrations") or {})
    _check_names("fits", fits, {"preset": PRESETS})
    _check_names("materials", specs, {"preset": PRESETS, "fit": fits})
    _check_names("calibrations", calibrations, {"preset": PRESETS, "fit": fits, "config material": specs})
    for name, spec in specs.items():
        from_spec(spec, name=name, base_dir=base_dir)
    specs = {name: canonical(spec) for name, spec in specs.items()}  # 5000000 and 5.0e+6: one spec
    for name, spec in fits.items():
        check_fit_spec(spec, base_dir=base_dir, where=f"fits.{name}")
    catalogue = Catalogue(specs=specs, fits=fits, calibrations=calibrations,
                          material_dir=_material_dir(config, base_dir), base_dir=str(base_dir))
    for name, spec in calibrations.items():
        _check_start_chain(name, calibrations)
        _check_calibration(name, spec, catalogue)
    return catalogue


def _check_start_chain(name: str, calibrations: dict) -> None:
    """A calibration starts from a material that is not, through other calibrations, itself: ValueError
    naming the chain otherwise (the workflow could never build the first of them)."""
    spec = calibrations.get(name)
    chain, start = [name], spec.get("material") if isinstance(spec, dict) else None
    while isinstance(start, str) and start in calibrations and isinstance(calibrations[start], dict):
        chain.append(start)
        if start == name:
            raise ValueError(f"calibrations.{name}.material: the calibration starts from itself "
                             f"({' -> '.join(chain)}); start it from another material")
        if chain.count(start) > 1:
            return  # a loop of others: reported at their own names
        start = calibrations[start].get("material")


def _check_calibration(name: str, spec: dict, catalogue: Catalogue) -> None:
    """A calibration spec (:func:`vcor.fitting.calibrate.check_spec`: keys, data, start, free parameters) and
    its forward model, as a scene's corner points are checked: the solver options, and the start material's
    impacts at the data's lowest and highest speed with the calibration's geometry, by a method that can
    solve them. The schema has checked the geometry's and the solver's keys, types and ranges (a scene's)."""
    where = f"calibrations.{name}"
    # its start is looked up among the other materials (a calibration is not its own start)
    others = replace(catalogue, calibrations={k: v for k, v in catalogue.calibrations.items() if k != name})
    data = check_spec(spec, catalogue=others, where=where, pending=catalogue.computed())
    try:
        options = solver_options(spec.get("solver") or {})
    except ValueError as exc:
        raise ValueError(f"{where}.solver: {exc}") from None
    start = spec["material"]
    if isinstance(start, str) and start in catalogue.computed():
        return  # a fit's or calibration's file is written by its rule: its values are checked by the job
    material = (catalogue.material(start) if isinstance(start, str)
                else from_spec(start, base_dir=catalogue.base_dir, where=f"{where}.material"))
    geometry = dict(spec.get("geometry") or {})
    for v0 in (float(data.v0.min()), float(data.v0.max())):
        try:
            impact = make_impact(material, v0, geometry)
        except ValueError as exc:  # the message starts with the keyword it is about, where it is one
            word, _, rest = str(exc).partition(" ")
            key, said = (f"{where}.geometry.{word}", rest) if word in geometry else (f"{where}.geometry", str(exc))
            raise ValueError(f"{key}: {said} (the start material at v0 = {v0:g} m/s, a speed of the data)") from None
        why = refusal(impact.material, options)
        if why:
            raise ValueError(f"{where}.solver.method: {why}")


def _check_figures(name: str, scene: dict, catalogue: Catalogue, grid: Grid | None) -> None:
    """The scene builds what its figures need, and every figure option is one the figure takes, with a
    value it can draw (a material of the scene, a value on the grid axis, ...: plots.FIGURE_OPTIONS)."""
    where = f"scenes.{name}"
    figures = scene.get("figures") or {}
    need = needs(figures)
    if "sweep" in need and grid is None:
        raise ValueError(f"{where}.figures: {sorted(figures)} need a sweep: add {where}.grid")
    for dataset in DATASETS[1:]:
        if dataset in need and dataset not in scene:
            raise ValueError(f"{where}.figures: {sorted(figures)} need {where}.{dataset}")
    axes = grid.values() if grid is not None else {}
    for fig, opts in figures.items():
        key = f"{where}.figures.{fig}"
        for axis in NEEDS_AXIS.get(fig, ()):
            if axis not in axes:
                raise ValueError(f"{key} needs a sweep with a grid axis {axis}: add {where}.grid.{axis}")
        if opts is not None and not isinstance(opts, dict):
            raise ValueError(f"{key}: the figure's options, a mapping (or {{}}), got {opts!r}")
        options = options_of(fig, opts)
        taken = FIGURE_OPTIONS[fig]
        for option in (o for o, kind in taken.items() if kind == "fits" and o not in options):
            raise ValueError(f"{key}.{option}: figure {fig} needs a list of fits (of {sorted(catalogue.fits)})")
        for option, value in options.items():
            given = option in (opts or {})
            if option in taken:
                _check_option(f"{key}.{option}", taken[option], value, scene, axes, catalogue, given, options)
            elif fig in AXIS_OPTIONS and option in axes:
                _check_option(f"{key}.{option}", option, value, scene, axes, catalogue, given, options)
            else:
                allowed = sorted(taken) + ([f"a grid axis ({', '.join(a for a in axes if a != 'v0')})"]
                                           if fig in AXIS_OPTIONS else [])
                raise ValueError(f"{key}.{option}: figure {fig} takes no option {option!r}; allowed: {allowed}")


def _check_option(key, kind, value, scene, axes, catalogue, given=True, options=None):
    """One figure option's value against what it names (plots.FIGURE_OPTIONS); ``given``: the scene
    gave it (not a default of the figure's)."""
    materials = list(scene.get("materials") or [])
    if kind == "material":
        if value not in materials:
            raise ValueError(f"{key}: {value!r} is not a material of the scene; allowed: {materials}")
    elif kind == "fits":
        if not isinstance(value, list) or not value or not set(value) <= set(catalogue.fits):
            raise ValueError(f"{key} must be a list of fits (of {sorted(catalogue.fits)}), got {value!r}")
    elif kind == "runs":
        runs = [f"{m}/{method}" for m, method in (scene.get("histories") or {}).get("runs", [])]
        if not isinstance(value, list) or not set(value) <= set(runs):
            raise ValueError(f"{key} must be a list of the scene's history runs (of {runs}), got {value!r}")
    elif kind in ("number", "text", "pattern"):
        ok = (isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
              if kind == "number" else isinstance(value, str) and (kind == "text" or "{n}" in value))
        if not ok:
            what = {"number": "a finite number", "text": "a text", "pattern": "a text containing {n}"}[kind]
            raise ValueError(f"{key} must be {what}, got {value!r}")
    else:
        _check_axis_option(key, kind, value, axes, catalogue, given, options or {})


def _check_axis_option(key, kind, value, axes, catalogue, given, options):
    """A value (or list of values) on a grid axis; a figure's ``beta`` without a beta axis is the
    material's own, which a value the scene gives must then equal."""
    axis, listed = kind.split(" ")[0], kind.endswith(" list")
    values = value if listed else [value]
    if listed and (not isinstance(value, list) or not value):
        raise ValueError(f"{key} must be a list of values of the grid axis {axis} {axes.get(axis)}, got {value!r}")
    for v in values:
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise ValueError(f"{key}: {v!r} is not a number on the grid axis {axis}")
    if axis in axes:
        for v in values:
            if canon(v) not in axes[axis]:
                raise ValueError(f"{key}: {v!r} is not on the grid axis {axis} {axes[axis]}")
        return
    if axis != "beta":
        raise ValueError(f"{key} names values on the grid axis {axis}, which the scene has not")
    material = options.get("material")
    if not given or not isinstance(material, str) or material in catalogue.computed():
        return  # the figure's default, or a fit's beta known only after the fit
    own = catalogue.material(material).to_dict().get("beta")
    if own is None or canon(own) != canon(value):
        raise ValueError(f"{key}: {value!r} is neither on a grid axis beta (the scene has none) nor material "
                         f"{material!r}'s own beta ({own}); give the material's beta, or sweep beta")


def _check_size(where: str, scene: dict, shard_size: int | None) -> None:
    """The grid's points (and, with a cap of ``shard_size`` points per job, the least number of sweep
    jobs) against MAX_POINTS and MAX_JOBS, counted before any point is built."""
    try:
        n = point_count(scene)
    except ValueError as exc:
        raise ValueError(f"{where}.grid.{exc}") from None
    jobs = 1 if shard_size is None else -(-n // shard_size)
    if n > MAX_POINTS or jobs > MAX_JOBS:
        def count(k: int) -> str:  # a range with a step of 1e-300 holds a 300-digit number of points
            return str(k) if k < 10**12 else f"{float(k):.3g}"

        split = ("in one sweep job (no shard_size)" if shard_size is None
                 else f"in {count(jobs)} sweep jobs (shard_size {shard_size})")
        raise ValueError(f"{where}.grid: {count(n)} points {split}; a scene may "
                         f"have at most {MAX_POINTS} points and {MAX_JOBS} jobs: split the study into scenes, "
                         f"or raise shard_size")


def _body_identities(scene: dict, catalogue: Catalogue) -> dict:
    """{name: content identity} of the computed materials (fits, calibrations) the scene's bodies name:
    part of the settings, so a refitted body material recomputes the sweep."""
    names = [(scene.get(k) or {}).get("material") for k in ("sphere", "plate")]
    return {n: catalogue.identity(n) for n in names if isinstance(n, str) and n in catalogue.computed()}


def _build_scene(name: str, config: dict, catalogue: Catalogue, sizing: dict) -> Scene:
    """The checked :class:`Scene` of one config entry; its grid is built here, once."""
    where = f"scenes.{name}"
    if not re.fullmatch(SCENE_NAME_PATTERN, name):
        raise ValueError(f"{where}: scene names may use letters, digits, - and _")
    scene = inline_config_materials(config, catalogue)
    size = scene.get("shard_size", sizing["shard_size"])
    size = None if size is None else int(size)
    job_seconds = float(scene.get("job_seconds", sizing["job_seconds"]))
    check_uncertainty(where, scene, catalogue)
    grid = None
    if "grid" in scene:
        _check_size(where, scene, size)
        try:
            grid = grid_of(scene)
        except ValueError as exc:
            raise ValueError(f"{where}.grid.{exc}") from None
        check_temperature_axis(name, scene, catalogue, grid)  # before the corner points (which would shift)
        validate_scene(name, scene, catalogue, grid)
    _check_figures(name, scene, catalogue, grid)
    for mat in scene.get("convergence", {}).get("materials", []):
        catalogue.check(mat, f"{where}.convergence.materials")
    bodies = [k for k in ("geometry", "sphere", "plate") if "convergence" in scene and k in scene]
    if bodies:  # the study's references and ladders are those of one impact geometry, the default one
        raise ValueError(f"{where}.{bodies[0]}: the work-precision study (convergence) solves the default geometry "
                         f"(vcor.contact.impact.GEOMETRY_DEFAULTS) and takes no {bodies[0]}; put the convergence "
                         f"block in a scene without geometry, sphere or plate")
    for i, v0 in enumerate(scene.get("convergence", {}).get("v0", [])):
        try:  # the impact's own range check (vcor.contact.impact.RANGES), before any material is read
            number("v0", v0, *RANGES["v0"], lo_open=False, hi_open=False, unit="m/s")
        except ValueError as exc:
            raise ValueError(f"{where}.convergence.v0[{i}]: {exc}") from None
    for mat in scene.get("moduli", []):
        catalogue.check(mat, f"{where}.moduli")
    for mat, method in scene.get("histories", {}).get("runs", []):
        if method not in METHOD_NAMES or method == "paper":
            raise ValueError(f"{where}.histories.runs: unknown method {method!r}; allowed: "
                             f"{[m for m in METHOD_NAMES if m != 'paper']}")
        if mat not in scene.get("materials", []):
            close = difflib.get_close_matches(str(mat), [str(m) for m in scene.get("materials", [])], n=1, cutoff=0.6)
            raise ValueError(f"{where}.histories.runs: {mat!r} is not in {where}.materials "
                             f"{scene.get('materials', [])}" + (f"; did you mean {close[0]!r}?" if close else ""))
        if mat in catalogue.computed():
            continue  # a fit's or calibration's file is written by its rule: its values are checked by the job
        material = catalogue.material(mat)
        why = refusal(material, solver_options_of(scene).replace(method=method))  # the options the job runs
        if why:
            raise ValueError(f"{where}.histories.runs: [{mat}, {method}]: {why}")
        try:
            make_impact(material, scene["histories"]["v0"], settings_of(scene)["geometry"])
        except ValueError as exc:  # the speed, or the scene's geometry: the message names the parameter
            raise ValueError(f"{where}.histories (v0 = {scene['histories']['v0']} m/s, the scene's geometry): "
                             f"{exc}") from None
    settings = settings_of(scene)
    bodies = _body_identities(scene, catalogue)
    if bodies:
        settings["body_materials"] = bodies
    return Scene(name=name, config=scene, grid=grid, settings=settings, shard_size=size,
                 job_seconds=job_seconds)


def _check_builds_something(config: dict) -> None:
    if not any(config.get(k) for k in BUILDS):
        given = sorted(k for k in config if config.get(k) not in (None, {}, []) and config[k] != DEFAULTS.get(k))
        raise ValueError(f"the config names nothing to build (sections given: {given or 'none'}): add scenes, "
                         f"fits, calibrations or dem entries (materials: only defines materials for them)")


def load_project(config: dict, base_dir=".", *, require_targets: bool = True) -> Project:
    """The checked :class:`~vcor.study.project.Project` of a config (already validated against the
    schema); ValueError naming the key for anything wrong (module docstring). ``require_targets``: a
    config that names nothing to build is refused (the workflow's rule; the command line reads a
    config's materials alone)."""
    config = config or {}
    base = Path(base_dir)
    if require_targets:
        _check_builds_something(config)
    catalogue = _catalogue(config, base)
    sizing = {k: config.get(k, DEFAULTS[k]) for k in ("shard_size", "job_seconds")}
    scenes = {name: _build_scene(name, scene, catalogue, sizing)
              for name, scene in (config.get("scenes") or {}).items()}
    dem = dict(config.get("dem") or {})
    for name, spec in dem.items():
        if not re.fullmatch(SCENE_NAME_PATTERN, name):
            raise ValueError(f"dem.{name}: names may use letters, digits, - and _")
        check_dem(name, spec, catalogue)
    return Project(catalogue=catalogue, scenes=scenes, shard_size=sizing["shard_size"],
                   job_seconds=float(sizing["job_seconds"]), config=config, dem=dem)
