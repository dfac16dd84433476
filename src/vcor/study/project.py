"""One typed model of a project, built once from its config (:func:`vcor.study.config.load_project`).

A :class:`Project` holds the material catalogue (presets, config materials, fits, calibrations:
every material reference of the config resolves through it), the scenes, the DEM entries and the
defaults; a :class:`Scene` holds its config, its grid (:class:`vcor.study.grid.Grid`: typed axes
and indexed points) and its solver settings. The workflow plans from this model, and every output
path comes from :mod:`vcor.study.paths`.

What a config builds (the workflow's default target):

* every scene's datasets, figures, tables and manifest, and the files of the materials it uses;
* every calibration (its record, figure and material file);
* a fit when a scene, a DEM entry or a calibration uses it (nothing is computed that no output
  needs, except that a fit family is fitted whole: :meth:`Project.fit_groups`), and every fit of a
  config that has no scenes, DEM entries or calibrations (a config of fits asks for them);
* every DEM entry's dataset, COR table, parameters file, LAMMPS deck, Yade script, figure and manifest.

The ``materials:`` block defines materials for the others to use; it builds nothing by itself.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..dem.laws import HEREDITARY
from ..fitting.spec import fit_families
from ..materials.catalogue import Catalogue
from ..plots import needs
from . import paths
from .cost import JOB_SECONDS
from .dem import entry_models
from .grid import Grid
from .uncertainty import samples_file, uncertainty_of

__all__ = ["BUILDS", "DATASETS", "DEFAULTS", "Project", "Scene"]

#: defaults of the config's top-level keys (the schema states the same; tests/study/test_config_model.py)
#: job_seconds: estimated solver work per sweep job (vcor.study.cost.JOB_SECONDS); shard_size: at most so
#: many points per sweep job (None: no cap, jobs sized by work alone)
DEFAULTS = {"job_seconds": JOB_SECONDS, "shard_size": None, "material_dir": "results/materials"}
#: datasets a scene may build (besides its sweep), each from a config block of the same name
DATASETS = ("moduli", "histories", "spheres", "convergence")
#: the top-level sections that name something to build
BUILDS = ("scenes", "fits", "calibrations", "dem")


@dataclass(frozen=True, kw_only=True)
class Scene:
    """One checked scene: ``config`` as configured (config materials of bodies inlined), ``grid``
    (None without a sweep), ``settings`` (:func:`vcor.study.scene.settings_of`, plus the identities of
    computed body materials), the estimated work per sweep job ``job_seconds`` (s) and the cap on its
    points ``shard_size`` (None: none); :mod:`vcor.study.cost`."""

    name: str
    config: dict
    grid: Grid | None
    settings: dict
    job_seconds: float = DEFAULTS["job_seconds"]
    shard_size: int | None = DEFAULTS["shard_size"]

    @property
    def materials(self) -> list[str]:
        return list(self.config.get("materials") or [])

    @property
    def figures(self) -> dict:
        return dict(self.config.get("figures") or {})

    @property
    def uncertainty(self) -> dict | None:
        return uncertainty_of(self.config)

    def datasets(self) -> list[str]:
        """The datasets the scene builds: ``sweep`` with a grid, each one its figures need, and each one
        its config names (``histories:``, ``moduli:``, ``spheres:``, ``convergence:``: asked for, so built
        with no figure too)."""
        need = needs(self.figures) | (set(DATASETS) & set(self.config))
        return (["sweep"] if self.grid is not None else []) + [n for n in DATASETS if n in need]

    def used_materials(self) -> list[str]:
        """Names of the catalogue the scene uses (swept, tabulated, convergence and body materials)."""
        cfg = self.config
        return sorted(set(self.materials) | set(cfg.get("moduli", []))
                      | set(cfg.get("convergence", {}).get("materials", [])) | set(self.body_materials()))

    def moduli_materials(self) -> list[str]:
        """The materials whose moduli the scene tabulates: its ``moduli`` list, else its swept materials."""
        return list(self.config.get("moduli", self.materials))

    def isothermal(self) -> bool:
        """True when the scene has no temperature axis: its materials are taken at their reference
        temperature (:meth:`Project.scene_catalogue`)."""
        return self.grid is None or "T" not in self.grid.names

    def body_materials(self) -> list[str]:
        """Names of the catalogue the scene's sphere and plate name (not ``rigid``, not inline specs)."""
        bodies = [(self.config.get(k) or {}).get("material") for k in ("sphere", "plate")]
        return sorted({b for b in bodies if isinstance(b, str) and b != "rigid"})


@dataclass(frozen=True, kw_only=True)
class Project:
    """A checked config (module docstring)."""

    catalogue: Catalogue
    scenes: dict = field(default_factory=dict)
    dem: dict = field(default_factory=dict)
    job_seconds: float = DEFAULTS["job_seconds"]
    shard_size: int | None = DEFAULTS["shard_size"]
    config: dict = field(repr=False, default_factory=dict)

    @property
    def material_dir(self) -> str:
        return self.catalogue.material_dir

    @property
    def fitted_to_data(self) -> frozenset:
        """Names of the fits to measured data (DMA sets): tens of Prony modes, a larger solve cost
        (:mod:`vcor.study.cost`)."""
        return frozenset(n for n, spec in self.catalogue.fits.items() if "data" in spec)

    # -- scenes -----------------------------------------------------------------------------------
    def scene_catalogue(self, scene: str) -> Catalogue:
        """The catalogue a scene's jobs are given: the project's, without the shift functions of config
        materials when the scene has no temperature axis (:meth:`Catalogue.without_shifts`)."""
        return self.catalogue.without_shifts() if self.scenes[scene].isothermal() else self.catalogue

    def scene_targets(self, scene: str) -> list[str]:
        """Every output of a scene (its datasets, figures, tables, the files of the materials it uses that
        are not presets), paths relative to the project: the workflow's default target requires them
        all, so a lost one is computed again."""
        sc = self.scenes[scene]
        out = [paths.fmt(paths.DATASET, scene=scene, dataset=n) for n in sc.datasets()]
        out += [paths.material(self.material_dir, m) for m in sc.used_materials()
                if m in self.catalogue.specs or m in self.catalogue.computed()]
        out += [path for path, _ in self.samples_of(scene)]
        for fig in sc.figures:
            out += [paths.fmt(paths.FIGURE, scene=scene, fig=fig, ext=e) for e in ("png", "pdf")]
        if "convergence" in sc.config:
            out.append(paths.fmt(paths.ORDERS, scene=scene))
        if set(sc.materials) & set(self.catalogue.fits):
            out.append(paths.fmt(paths.FIT_METRICS, scene=scene))
        return out

    def material_files_of(self, scene: str, names=None) -> list[str]:
        """The computed material files (fits, calibrations) a scene's jobs read; presets and config
        materials are built from their definitions. ``names``: of those materials only (a shard's,
        :func:`vcor.study.shards.shard_materials`)."""
        computed = self.catalogue.computed()
        used = self.scenes[scene].used_materials() if names is None else names
        return ([paths.material(self.material_dir, m) for m in used if m in computed]
                + [path for path, m in self.samples_of(scene) if names is None or m in names])

    def samples_of(self, scene: str) -> list[tuple[str, str]]:
        """(samples file, fit name) of every material of an uncertainty scene (vcor.study.uncertainty)."""
        sc = self.scenes[scene]
        spec = sc.uncertainty
        if spec is None:
            return []
        return [(samples_file(self.material_dir, m, spec), m) for m in sc.materials]

    # -- fits, calibrations, DEM entries ------------------------------------------------------------
    def fit_targets(self) -> list[str]:
        """Every fit's material file and parameter table."""
        return [p for m in self.catalogue.fits
                for p in (paths.material(self.material_dir, m), paths.material_table(self.material_dir, m))]

    def built_fits(self) -> list[str]:
        """The fits the project builds (module docstring): those a scene, DEM entry or calibration uses,
        or every fit when the config builds nothing else."""
        fits = self.catalogue.fits
        if not (self.scenes or self.dem or self.catalogue.calibrations):
            return list(fits)
        used = {m for sc in self.scenes.values() for m in sc.used_materials()}
        used |= {m for name in self.dem for m in self.dem_materials(name)}
        used |= {spec.get("material") for spec in self.catalogue.calibrations.values()
                 if isinstance(spec.get("material"), str)}  # a name, or an inline spec
        return [m for m in fits if m in used]

    def fit_groups(self) -> dict[str, list[str]]:
        """{family name: members}: every member of a fit family (a name with ``{n}``, two or more
        members) of which the project builds at least one, fitted in one job. The family is one config
        entry and is fitted as a whole, whichever members the scenes use: the job and its outputs do
        not change when a scene starts or stops using a member, so finished work that reads the other
        members stays finished. It costs one process start (about half a second) for the family; a
        family fits synthetic data only (measured data take ``n_terms: auto``), a fraction of a second
        per member."""
        built = set(self.built_fits())
        return {family: members for family, members in fit_families(self.config.get("fits")).items()
                if len(members) >= 2 and built & set(members)}

    def calibration_targets(self) -> list[str]:
        """Every calibration's record, figure and material file."""
        out = []
        for c in self.catalogue.calibrations:
            out += [paths.fmt(paths.CALIBRATION, cal=c)]
            out += [paths.fmt(paths.CALIBRATION_FIGURE, cal=c, ext=e) for e in ("png", "pdf")]
            out += [paths.material(self.material_dir, c)]
        return out

    def dem_files(self, name: str) -> dict[str, str]:
        """The files of a ``dem:`` entry that its collisions' job writes: ``nc`` (the dataset), ``table``
        (the COR table), ``parameters``, ``deck`` (the LAMMPS deck ``in.pair`` or ``in.wall``, when the
        entry fits a LAMMPS law), ``hereditary`` (the deck ``in.hereditary``, when the entry has vcor's own
        law, :func:`vcor.study.dem.entry_models`) and ``yade`` (the Yade script, when it fits Yade's)."""
        spec = self.dem[name]
        target = spec.get("target", "rigid")
        models = entry_models(spec, self.catalogue)
        kind = "pair" if isinstance(target, dict) and "sphere" in target else "wall"
        out = {key: paths.fmt(p, dem=name) for key, p in
               (("nc", paths.DEM), ("table", paths.DEM_TABLE), ("parameters", paths.DEM_PARAMETERS))}
        if {"lammps-viscoelastic", "lammps-coeff-restitution"} & set(models):
            out["deck"] = paths.fmt(paths.DEM_DECK, dem=name, kind=kind)
        if HEREDITARY in models:
            out["hereditary"] = paths.fmt(paths.DEM_DECK, dem=name, kind="hereditary")
        if "yade-mindlin" in models:
            out["yade"] = paths.fmt(paths.DEM_YADE, dem=name)
        return out

    def dem_targets(self, name: str) -> list[str]:
        """The outputs of a ``dem:`` entry: its dataset, COR table, parameters file, figure, the LAMMPS
        decks (:meth:`dem_files`) and the Yade script when it fits Yade's (not its manifest, which lists
        these)."""
        files = self.dem_files(name)
        out = [files["nc"], files["table"], files["parameters"]]
        out += [paths.fmt(paths.DEM_FIGURE, dem=name, ext=e) for e in ("png", "pdf")]
        return out + [files[k] for k in ("deck", "hereditary", "yade") if k in files]

    def dem_materials(self, name: str) -> list[str]:
        """Names of the catalogue a ``dem:`` entry's bodies use (the sphere's, a target body's)."""
        spec = self.dem[name]
        target = spec.get("target", "rigid")
        bodies = [spec["sphere"]] + (list(target.values()) if isinstance(target, dict) else [])
        return [b["material"] for b in bodies
                if isinstance(b, dict) and isinstance(b.get("material"), str) and b["material"] != "rigid"]

    def dem_catalogue(self, name: str) -> Catalogue:
        """The catalogue a ``dem:`` entry's job is given: as :meth:`scene_catalogue`, without the shift
        functions of config materials when the entry has no temperatures ``T``."""
        return self.catalogue if "T" in self.dem[name] else self.catalogue.without_shifts()

    def dem_material_files(self, name: str) -> list[str]:
        """The computed material files (fits, calibrations) a ``dem:`` entry's job reads."""
        computed = self.catalogue.computed()
        return [paths.material(self.material_dir, m) for m in self.dem_materials(name) if m in computed]

    def all_targets(self) -> list[str]:
        """What ``snakemake`` builds without a target (module docstring)."""
        out = []
        for scene in self.scenes:
            out += self.scene_targets(scene) + [paths.fmt(paths.MANIFEST, scene=scene)]
        for name in self.dem:
            out += self.dem_targets(name) + [paths.fmt(paths.DEM_MANIFEST, dem=name)]
        if not (self.scenes or self.dem or self.catalogue.calibrations):
            out += self.fit_targets()
        out += self.calibration_targets()
        return list(dict.fromkeys(out))
