"""Config checks: everything about a workflow config that can be checked before any job runs.

The JSON schema (``workflow/schemas/config.schema.yaml``, applied by ``snakemake.utils.validate``)
checks the shape; :func:`load_project` checks what needs vcor and returns the :class:`Project` the
workflow plans from: the material catalogue (presets, config materials, fits, calibrations) and the
scenes, each with its datasets, figures and targets. Every error is a ``ValueError`` whose message
starts with the config key (``scenes.<name>.grid.T``, ``materials.<name>.E``, ...) and says the
allowed values.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

from ..fitting.calibrate import check_spec
from ..fitting.fits import expand_fits
from ..materials.catalogue import Catalogue
from ..materials.presets import PRESETS
from ..materials.specs import from_spec
from ..plots import FIGURES, NEEDS_AXIS, needs
from ..solvers.options import METHOD_NAMES
from .scene import check_temperature_axis, validate_scene

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

    def shard_size_of(self, scene: str) -> int:
        return int(self.scenes[scene].get("shard_size", self.shard_size))

    def datasets_of(self, scene: str) -> list[str]:
        """The datasets the scene builds: ``sweep`` with a grid, and each one its figures need."""
        cfg = self.scenes[scene]
        need = needs(cfg.get("figures", {}))
        return (["sweep"] if "grid" in cfg else []) + [n for n in DATASETS if n in need]

    def scene_targets(self, scene: str) -> list[str]:
        """Every output of a scene (its datasets, figures, tables, the files of the config materials it
        uses), paths relative to the project."""
        cfg = self.scenes[scene]
        out = [f"results/{scene}/{n}.nc" for n in self.datasets_of(scene)]
        out += [f"{self.catalogue.material_dir}/{m}.nc" for m in self._used(scene) if m in self.catalogue.specs]
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
        return [f"{self.catalogue.material_dir}/{m}.nc" for m in self._used(scene) if m in computed]


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


def _material_dir(config: dict, base_dir: Path) -> str:
    """``material_dir``: a non-empty relative path inside the project (results are never written
    outside it)."""
    value = config.get("material_dir", "results/materials")
    if not isinstance(value, str) or not value.strip():
        raise ValueError(f"material_dir must be a non-empty path inside the project folder, got {value!r}")
    path = Path(value)
    inside = (base_dir / path).resolve()
    if path.is_absolute() or not inside.is_relative_to(base_dir.resolve()):
        raise ValueError(f"material_dir must be a relative path inside the project folder ({base_dir.resolve()}), "
                         f"got {value!r}")
    return value


def _catalogue(config: dict, base_dir: Path) -> Catalogue:
    specs = dict(config.get("materials") or {})
    fits = expand_fits(config.get("fits") or {}, where="fits")
    calibrations = dict(config.get("calibrations") or {})
    _check_names("fits", fits, {"preset": PRESETS})
    _check_names("materials", specs, {"preset": PRESETS, "fit": fits})
    _check_names("calibrations", calibrations, {"preset": PRESETS, "fit": fits, "config material": specs})
    for name, spec in specs.items():
        from_spec(spec, name=name, base_dir=base_dir)
    catalogue = Catalogue(specs=specs, fits=fits, calibrations=calibrations,
                          material_dir=_material_dir(config, base_dir), base_dir=str(base_dir))
    for name, spec in calibrations.items():
        check_spec(spec, catalogue=catalogue, where=f"calibrations.{name}", pending=catalogue.computed())
    return catalogue


def _check_figures(name: str, scene: dict, catalogue: Catalogue) -> None:
    where = f"scenes.{name}"
    figures = scene.get("figures", {})
    need = needs(figures)
    if "sweep" in need and "grid" not in scene:
        raise ValueError(f"{where}.figures: {sorted(figures)} need a sweep: add {where}.grid")
    for dataset in DATASETS[1:]:
        if dataset in need and dataset not in scene:
            raise ValueError(f"{where}.figures: {sorted(figures)} need {where}.{dataset}")
    for fig, opts in figures.items():
        axis = NEEDS_AXIS.get(fig)
        if axis and axis not in scene.get("grid", {}):
            raise ValueError(f"{where}.figures.{fig} needs a sweep with a grid axis {axis}: add {where}.grid.{axis}")
        fits = (opts or {}).get("materials")
        if "material_fit" in FIGURES[fig][1] and (
                not isinstance(fits, list) or not fits or not set(fits) <= set(catalogue.fits)):
            raise ValueError(f"{where}.figures.{fig}.materials must be a list of fits (of {sorted(catalogue.fits)}), "
                             f"got {fits!r}")


def _check_scene(name: str, scene: dict, catalogue: Catalogue) -> None:
    where = f"scenes.{name}"
    if not re.fullmatch(SCENE_NAME_PATTERN, name):
        raise ValueError(f"{where}: scene names may use letters, digits, - and _")
    if "grid" in scene:
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
    scenes = {}
    for name, scene in (config.get("scenes") or {}).items():
        scenes[name] = inline_config_materials(scene, catalogue)
        _check_scene(name, scenes[name], catalogue)
    return Project(catalogue=catalogue, scenes=scenes, shard_size=int(config.get("shard_size", 1000)), config=config)
