"""Config checks: everything about a workflow config that can be checked before any job runs.

The JSON schema (``workflow/schemas/config.schema.yaml``, applied by ``snakemake.utils.validate``)
checks the shape; :func:`load_project` checks what needs vcor and returns the :class:`Project` the
workflow plans from: the material catalogue (presets, config materials, fits, calibrations) and the
scenes, each with its datasets, figures and targets. Every error is a ``ValueError`` whose message
starts with the config key (``scenes.<name>.grid.T``, ``materials.<name>.E``, ...) and says the
allowed values.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path

from ..fitting.calibrate import check_spec
from ..fitting.fits import check_fit_spec, expand_fits
from ..materials.catalogue import Catalogue
from ..materials.presets import PRESETS
from ..materials.specs import from_spec
from ..plots import AXIS_OPTIONS, FIGURE_OPTIONS, NEEDS_AXIS, needs, options_of
from ..solvers.options import METHOD_NAMES
from .dem import check_dem
from .scene import (
    MAX_JOBS,
    MAX_POINTS,
    canon,
    check_temperature_axis,
    point_count,
    scene_axes,
    validate_scene,
)
from .uncertainty import check_uncertainty, samples_file, uncertainty_of

__all__ = ["NAME_PATTERN", "SCENE_NAME_PATTERN", "Project", "inline_config_materials", "load_project"]

#: names of materials, fits and calibrations
NAME_PATTERN = r"[A-Za-z0-9_.-]+"
#: names of scenes (they become rule names)
SCENE_NAME_PATTERN = r"[A-Za-z0-9_-]+"
#: datasets a scene may build (besides its sweep), each from a config block of the same name
DATASETS = ("moduli", "histories", "spheres", "convergence")


@dataclass(frozen=True)
class Project:
    """A checked config: ``catalogue`` (every material name), ``scenes`` (name -> scene, config
    materials of bodies inlined), ``shard_size`` (points per sweep job unless a scene says otherwise)."""

    catalogue: Catalogue
    scenes: dict
    shard_size: int
    config: dict = field(repr=False, default_factory=dict)
    dem: dict = field(default_factory=dict)

    def dem_targets(self, name: str) -> list[str]:
        """The outputs of a ``dem:`` entry: its dataset, COR table, LAMMPS deck and figure."""
        target = self.dem[name].get("target", "rigid")
        deck = "in.pair" if isinstance(target, dict) and "sphere" in target else "in.wall"
        return [f"results/dem/{name}.nc", f"results/dem/{name}/table.csv", f"results/dem/{name}/lammps/{deck}",
                f"results/dem/{name}.png", f"results/dem/{name}.pdf"]

    def dem_material_files(self, name: str) -> list[str]:
        """The computed material file a ``dem:`` entry's job reads (a fit or calibration), if any."""
        value = self.dem[name]["sphere"].get("material")
        computed = self.catalogue.computed()
        return [f"{self.catalogue.material_dir}/{value}.nc"] if isinstance(value, str) and value in computed else []

    def shard_size_of(self, scene: str) -> int:
        return int(self.scenes[scene].get("shard_size", self.shard_size))

    def datasets_of(self, scene: str) -> list[str]:
        """The datasets the scene builds: ``sweep`` with a grid, and each one its figures need."""
        cfg = self.scenes[scene]
        need = needs(cfg.get("figures", {}))
        return (["sweep"] if "grid" in cfg else []) + [n for n in DATASETS if n in need]

    def scene_targets(self, scene: str) -> list[str]:
        """Every output of a scene (its datasets, figures, tables, the files of the materials it uses that
        are not presets), paths relative to the project: the workflow's default target requires them
        all, so a lost one is computed again."""
        cfg = self.scenes[scene]
        out = [f"results/{scene}/{n}.nc" for n in self.datasets_of(scene)]
        out += [f"{self.catalogue.material_dir}/{m}.nc" for m in self._used(scene)
                if m in self.catalogue.specs or m in self.catalogue.computed()]
        out += [path for path, _ in self.samples_of(scene)]
        for fig in cfg.get("figures", {}):
            out += [f"results/{scene}/figures/{fig}.png", f"results/{scene}/figures/{fig}.pdf"]
        if "convergence" in cfg:
            out.append(f"results/{scene}/orders.txt")
        if set(cfg.get("materials", [])) & set(self.catalogue.fits):
            out.append(f"results/{scene}/fit_metrics.txt")
        return out

    def _used(self, scene: str) -> list[str]:
        cfg = self.scenes[scene]
        return sorted(set(cfg.get("materials", [])) | set(cfg.get("moduli", []))
                      | set(cfg.get("convergence", {}).get("materials", [])))

    def material_files_of(self, scene: str) -> list[str]:
        """The computed material files (fits, calibrations) a scene's jobs read; presets and config
        materials are built from their definitions."""
        computed = self.catalogue.computed()
        return ([f"{self.catalogue.material_dir}/{m}.nc" for m in self._used(scene) if m in computed]
                + [path for path, _ in self.samples_of(scene)])

    def samples_of(self, scene: str) -> list[tuple[str, str]]:
        """(samples file, fit name) of every material of an uncertainty scene (vcor.study.uncertainty)."""
        spec = uncertainty_of(self.scenes[scene])
        if spec is None:
            return []
        return [(samples_file(self.catalogue.material_dir, m, spec), m) for m in self.scenes[scene]["materials"]]


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
    path = Path(value)
    if path.is_absolute() or not (base_dir / path).resolve().is_relative_to(base_dir.resolve()):
        raise ValueError(f"{key} must be a relative path inside the project folder ({base_dir.resolve()}), "
                         f"got {value!r}")
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
    return inside_project("material_dir", config.get("material_dir", "results/materials"), base_dir)


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
    for name, spec in fits.items():
        check_fit_spec(spec, base_dir=base_dir, where=f"fits.{name}")
    catalogue = Catalogue(specs=specs, fits=fits, calibrations=calibrations,
                          material_dir=_material_dir(config, base_dir), base_dir=str(base_dir))
    for name, spec in calibrations.items():
        check_spec(spec, catalogue=catalogue, where=f"calibrations.{name}", pending=catalogue.computed())
    return catalogue


def _check_figures(name: str, scene: dict, catalogue: Catalogue) -> None:
    """The scene builds what its figures need, and every figure option is one the figure takes, with a
    value it can draw (a material of the scene, a value on the grid axis, ...: plots.FIGURE_OPTIONS)."""
    where = f"scenes.{name}"
    figures = scene.get("figures") or {}
    need = needs(figures)
    if "sweep" in need and "grid" not in scene:
        raise ValueError(f"{where}.figures: {sorted(figures)} need a sweep: add {where}.grid")
    for dataset in DATASETS[1:]:
        if dataset in need and dataset not in scene:
            raise ValueError(f"{where}.figures: {sorted(figures)} need {where}.{dataset}")
    axes = scene_axes(scene) if "grid" in scene else {}
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
            if option in taken:
                _check_option(f"{key}.{option}", taken[option], value, scene, axes, catalogue)
            elif fig in AXIS_OPTIONS and option in axes:
                _check_option(f"{key}.{option}", option, value, scene, axes, catalogue)
            else:
                allowed = sorted(taken) + ([f"a grid axis ({', '.join(a for a in axes if a != 'v0')})"]
                                           if fig in AXIS_OPTIONS else [])
                raise ValueError(f"{key}.{option}: figure {fig} takes no option {option!r}; allowed: {allowed}")


def _check_option(key, kind, value, scene, axes, catalogue):
    """One figure option's value against what it names (plots.FIGURE_OPTIONS)."""
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
    else:  # a value (or list of values) on a grid axis
        axis, listed = kind.split(" ")[0], kind.endswith(" list")
        if axis not in axes:
            if axis == "beta":  # drawn at the material's own beta when the grid has no beta axis
                return
            raise ValueError(f"{key} names values on the grid axis {axis}, which the scene has not")
        values = value if listed else [value]
        if listed and (not isinstance(value, list) or not value):
            raise ValueError(f"{key} must be a list of values of the grid axis {axis} {axes[axis]}, got {value!r}")
        for v in values:
            if isinstance(v, bool) or not isinstance(v, (int, float)) or canon(v) not in axes[axis]:
                raise ValueError(f"{key}: {v!r} is not on the grid axis {axis} {axes[axis]}")


def _check_size(where: str, scene: dict, shard_size: int) -> None:
    """The grid's points and sweep jobs against MAX_POINTS and MAX_JOBS, counted before any point is
    built."""
    try:
        n = point_count(scene)
    except ValueError as exc:
        raise ValueError(f"{where}.grid.{exc}") from None
    jobs = -(-n // shard_size)
    if n > MAX_POINTS or jobs > MAX_JOBS:
        raise ValueError(f"{where}.grid: {n} points in {jobs} sweep jobs (shard_size {shard_size}); a scene may "
                         f"have at most {MAX_POINTS} points and {MAX_JOBS} jobs: split the study into scenes, "
                         f"or raise shard_size")


def _check_scene(name: str, scene: dict, catalogue: Catalogue, shard_size: int) -> None:
    where = f"scenes.{name}"
    if not re.fullmatch(SCENE_NAME_PATTERN, name):
        raise ValueError(f"{where}: scene names may use letters, digits, - and _")
    check_uncertainty(where, scene, catalogue)
    if "grid" in scene:
        _check_size(where, scene, int(scene.get("shard_size", shard_size)))
        check_temperature_axis(name, scene, catalogue)  # before the corner points (which would shift)
        validate_scene(name, scene, catalogue)
    _check_figures(name, scene, catalogue)
    for mat in scene.get("convergence", {}).get("materials", []):
        catalogue.check(mat, f"{where}.convergence.materials")
    for mat in scene.get("moduli", []):
        catalogue.check(mat, f"{where}.moduli")
    for mat, method in scene.get("histories", {}).get("runs", []):
        if method not in METHOD_NAMES or method == "paper":
            raise ValueError(f"{where}.histories.runs: unknown method {method!r}; allowed: "
                             f"{[m for m in METHOD_NAMES if m != 'paper']}")
        if mat not in scene.get("materials", []):
            raise ValueError(f"{where}.histories.runs: {mat!r} is not in {where}.materials")


def load_project(config: dict, base_dir=".") -> Project:
    """The checked :class:`Project` of a config (already validated against the schema); ValueError
    naming the key for anything wrong (module docstring)."""
    base = Path(base_dir)
    catalogue = _catalogue(config, base)
    shard_size = int(config.get("shard_size", 1000))
    scenes = {}
    for name, scene in (config.get("scenes") or {}).items():
        scenes[name] = inline_config_materials(scene, catalogue)
        _check_scene(name, scenes[name], catalogue, shard_size)
    dem = dict(config.get("dem") or {})
    for name, spec in dem.items():
        if not re.fullmatch(SCENE_NAME_PATTERN, name):
            raise ValueError(f"dem.{name}: names may use letters, digits, - and _")
        check_dem(name, spec, catalogue)
    return Project(catalogue=catalogue, scenes=scenes, shard_size=shard_size, config=config, dem=dem)
