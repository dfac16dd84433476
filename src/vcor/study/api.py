"""The study functions: every capability of the workflow as one public function, returning what the
workflow writes (exported from :mod:`vcor`: ``vcor.sweep``, ``vcor.fit``, ``vcor.calibrate``,
``vcor.dem_export``, ``vcor.histories``, ``vcor.moduli``, ``vcor.viscoelastic_spheres``,
``vcor.convergence``).

===============================  ============================  =============================================
function                         takes (as a config has it)    returns (what the workflow writes)
===============================  ============================  =============================================
:func:`sweep`                    a scene (``scenes.<name>``)   ``results/<scene>/sweep.nc``, an xarray.Dataset
:func:`fit`                      a fit (``fits.<name>``)       :class:`Fitted`: ``<material_dir>/<name>.nc``
                                                               (and its ``.txt`` table), the material
:func:`calibrate`                a calibration                 :class:`Calibrated`: the calibration record
                                 (``calibrations.<name>``)     (``results/calibrations/<name>.nc``, also the
                                                               material file), the material
:func:`dem_export`               a DEM entry (``dem.<name>``)  :class:`DemExport`: ``results/dem/<name>.nc``,
                                                               and its tables, LAMMPS deck and Yade script
:func:`histories`                a scene with ``histories``    ``results/<scene>/histories.nc``
:func:`moduli`                   a scene (``moduli``, else     ``results/<scene>/moduli.nc``
                                 its ``materials``)
:func:`viscoelastic_spheres`     a scene with ``spheres``      ``results/<scene>/spheres.nc``
:func:`convergence`              a scene with ``convergence``  ``results/<scene>/convergence.nc`` (the
                                                               work-precision study)
===============================  ============================  =============================================

Each takes its entry as a mapping (the keys of its config section) or as the name of one in
``config``: a config file, a mapping or a :class:`~vcor.materials.Catalogue`; materials are names
(presets, and a config's materials, fits and calibrations), material objects or inline specs
``{model: ...}`` (a scene's ``materials`` and ``convergence.materials``, a body, a DEM entry's bodies, a
calibration's start; named ``<model>-<hash of the spec>``). Every argument is checked by the workflow's
own checks before any work (:mod:`vcor.study.inputs`): a refusal is a ``ValueError`` whose one line names
the key. The workflow's jobs run the same code: its scripts call
:func:`fit`, :func:`calibrate` and :func:`dem_export`, its sweep jobs the two halves of :func:`sweep`
(:mod:`vcor.study.sweep`), and its histories, moduli, spheres and work-precision jobs the builders of
:mod:`vcor.study.scene_datasets` that the functions of the same names return.

This module is part of :mod:`vcor.study`, the layer that knows a project (its config, scenes and
catalogue) and uses every layer below it (materials, solvers, fitting, DEM); the command line
(:mod:`vcor.cli_study`) sits above it.
"""

from __future__ import annotations

import contextlib
import json
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..io.archived import Archive
from ..materials.shift import ShiftFunction, at_temperature
from .computed import DETERMINISTIC, calibration_archive, fit_archive, ready_catalogue
from .inputs import resolve_entry, resolve_scene
from .pool import check_workers
from .progress import wanted
from .scene_datasets import convergence_archive, convergence_case, histories_archive, moduli_archive, spheres_archive
from .shards import identified_points
from .sweep import combine, solve_points

if TYPE_CHECKING:
    import xarray

    from ..fitting.calibrate import Calibration
    from ..fitting.prony import FitResult
    from ..materials.models import Material

__all__ = ["Calibrated", "DemExport", "Fitted", "calibrate", "convergence", "dem_export", "fit", "histories", "moduli",
           "sweep", "sweep_archive", "viscoelastic_spheres"]


def sweep(scene: dict | str, *, config: Any = None, workers: int | None = None,
          progress: bool | None = None, name: str | None = None) -> xarray.Dataset:
    """Solve a scene's grid: the dataset the workflow archives as ``results/<scene>/sweep.nc``.

    Parameters
    ----------
    scene : dict or str
        A scene as under ``scenes.<name>`` of a config (``materials``, ``grid``, ``tie``, ``solver``,
        ``geometry`` or ``sphere``/``plate``, ``error_estimate``, ``uncertainty``; the user guide's Scenes
        page), or the name of a scene of ``config``. Materials are names or material objects; grid values
        lists (NumPy arrays too) or ranges ``{start, stop, step}`` / ``{start, stop, num, log}``.
    config : str, path, dict or Catalogue, optional
        Where names are looked up: a config file (relative paths in it from its project folder:
        :func:`vcor.study.inputs.project_folder`), a config mapping or a :class:`~vcor.materials.Catalogue`;
        None: presets only.
    workers : int, optional
        Processes that solve (default: the cores available); the result does not depend on it.
    progress : bool, optional
        A progress bar (points done, ok / flagged / failed, time left) once the work has lasted two seconds
        (a shorter solve shows none): None on a terminal or in Jupyter, True also elsewhere (a log, a
        pipe), False never.
    name : str, optional
        The name of a scene given as a mapping, in the dataset's ``scene`` attribute and title (default:
        the name of the config's scene that equals it, else ``sweep``), as ``scenes.<name>`` would give it.

    Returns
    -------
    xarray.Dataset
        Dimensions ``material`` and the grid's axes; one variable per result field with ``units`` and
        ``long_name``, ``status`` and ``validity`` as CF flags, the global attributes that make it enough
        to re-run its scene. It equals the workflow's ``sweep.nc`` but for the points' ``wall_time`` and
        the ``history`` attribute (it is that file's content: the same writer's encoding, read back in memory,
        :class:`vcor.io.archived.Archive`).

    Raises
    ------
    ValueError
        Bad input, before any work, in one line naming the key (``scene.grid.bta: unknown ...``).
    KeyboardInterrupt
        On Ctrl-C, within a second, with every worker process stopped.

    Examples
    --------
    >>> import vcor
    >>> ds = vcor.sweep({"materials": ["sls"], "grid": {"v0": [1, 10]}}, workers=1, progress=False)
    >>> [round(float(c), 3) for c in ds["cor"].sel(material="sls")], ds["cor"].attrs["units"]
    ([0.388, 0.432], '1')
    """
    return sweep_archive(scene, config=config, workers=workers, progress=progress, name=name).loaded(
        command="vcor.sweep")


def sweep_archive(scene: dict | str, *, config: Any = None, workers: int | None = None,
                  progress: bool | None = None, name: str | None = None) -> Archive:
    """:func:`sweep`'s dataset before it is archived (:class:`vcor.io.archived.Archive`): what ``vcor sweep``
    writes to its ``--out`` file."""
    processes = check_workers(workers)
    show = wanted(progress)
    study = resolve_scene(scene, config, name)
    sc, project = study.scene, study.project
    with _ready(project.scene_catalogue(study.name), sc.used_materials(), sc.uncertainty) as catalogue:
        points = identified_points(sc.config, {m: catalogue.identity(m) for m in sc.materials}, sc.grid)
        shard = solve_points(points, sc.settings, catalogue, workers=processes, progress=show,
                             from_data=project.fitted_to_data)
        return combine(study.name, sc.config, sc.grid, [shard], [[p["index"] for p in points]], catalogue)


@dataclass(frozen=True, kw_only=True)
class Fitted:
    """A fitted material: its ``name``, the ``material`` (at the data's reference temperature), its shift
    function ``shift`` (:class:`vcor.materials.shift.ShiftFunction`; a fit to multi-temperature DMA data
    has one, the material file's attribute ``shift``; otherwise None), its ``dataset`` (the file
    ``<material_dir>/<name>.nc``: parameters, residual curves, metrics), its text ``table`` and the fit's
    ``result`` (:class:`vcor.fitting.prony.FitResult`: metrics, settings, fit time). :meth:`at` gives the
    material at another temperature, as a sweep's temperature axis does."""

    name: str
    material: Material
    shift: ShiftFunction | None
    result: FitResult = field(repr=False)
    dataset: xarray.Dataset = field(repr=False)
    table: str = field(repr=False)
    archive: Archive = field(repr=False)

    def at(self, T: float) -> Material:
        """The material at temperature ``T`` (deg C), time-shifted by ``shift`` (log a_T at T), as a sweep
        over ``T`` takes it; ValueError when the fit has no shift function or T is outside its range."""
        return at_temperature(self.material, self.shift, T, self.name)

    def write(self, path, *, table=None, identity: str | None = None) -> Path:
        """Write the material file to ``path`` (and the table to ``table``) as the workflow does; a material
        file a config names (``<material_dir>/<name>.nc``) is then used by the sweeps of that config."""
        from ..io.receipts import atomic_text

        if table is not None:
            atomic_text(table, self.table)
        return self.archive.write(path, command=f"vcor.fitting.fits {DETERMINISTIC}", identity=identity)


def fit(fit: dict | str, *, config: Any = None, name: str | None = None) -> Fitted:
    """Fit a material to its data: the built-in Bagley-Torvik data, or measured DMA data.

    Parameters
    ----------
    fit : dict or str
        A fit as under ``fits.<name>`` of a config (``{model: prony | cerf, n_terms, tol, ...}`` or
        ``{model: prony, data: {file, T_ref, ...}}``; the user guide's Materials and DMA pages), or the name
        of one in ``config`` (a member of a fit family too, e.g. ``butyl-prony-n3``).
    config : str, path, dict or Catalogue, optional
        The config the name is looked up in. A data file's path is relative to the config's project folder
        (:func:`vcor.study.inputs.project_folder`; for a mapping, or no config, the current directory) and
        inside it, as every path of a workflow project is (the files a result depends on belong to the
        project): link or copy outside data there.
    name : str, optional
        The material's name when ``fit`` is a mapping (default ``fit``).

    Returns
    -------
    Fitted
        The material and the dataset of ``<material_dir>/<name>.nc`` (the workflow's writer's encoding, read
        back in memory).

    Examples
    --------
    >>> import vcor
    >>> f = vcor.fit({"model": "prony", "n_terms": 3}, name="my-prony")
    >>> f.material.kind, len(f.material.E), f.dataset.attrs["material_name"]
    ('prony', 3, 'my-prony')
    """
    study = resolve_entry("fits", fit, name, config, "fit")
    spec = study.project.catalogue.fits[study.name]
    archive, result, table = fit_archive(study.name, spec, study.base_dir)
    dataset = archive.loaded(command=f"vcor.fitting.fits {DETERMINISTIC}")
    text = dataset.attrs.get("shift")
    return Fitted(name=study.name, material=result.material, shift=ShiftFunction.from_spec(json.loads(text)) if text
                  else None, result=result, table=table, archive=archive, dataset=dataset)


@dataclass(frozen=True, kw_only=True)
class Calibrated:
    """A calibration: its ``name``, the :class:`~vcor.fitting.calibrate.Calibration` (estimates, errors,
    correlations), the calibrated ``material`` and the ``dataset`` the workflow writes (the calibration
    record, which is also the material's file)."""

    name: str
    calibration: Calibration = field(repr=False)
    material: Material
    dataset: xarray.Dataset = field(repr=False)
    archive: Archive = field(repr=False)

    def report(self) -> str:
        """The estimates as a plain-text table."""
        return self.calibration.report()

    def write(self, path, *, identity: str | None = None) -> Path:
        """Write the record to ``path`` as the workflow does (its record and its material file)."""
        return self.archive.write(path, command="vcor.fitting.calibrate", identity=identity)


def calibrate(calibration: dict | str, *, config: Any = None, name: str | None = None) -> Calibrated:
    """Calibrate a material's parameters to measured COR against impact speed.

    Parameters
    ----------
    calibration : dict or str
        A calibration as under ``calibrations.<name>`` of a config (``data``: a CSV file ``v0,cor[,cor_std]``,
        ``material``: a name or a spec, ``free``: the parameters with their bounds, optional ``geometry`` and
        ``solver``; the user guide's Calibration page), or the name of one in ``config``.
    config : str, path, dict or Catalogue, optional
        Where the data file (relative to its project folder, for a mapping or no config the current
        directory, and inside it: as :func:`fit`) and a named start material are found; a start material
        that is a fit is fitted for the call unless the config's material folder holds its file.
    name : str, optional
        The calibrated material's name when ``calibration`` is a mapping (default ``calibration``).

    Returns
    -------
    Calibrated
        The calibration and the dataset of ``results/calibrations/<name>.nc``.
    """
    study = resolve_entry("calibrations", calibration, name, config, "calibration")
    catalogue = study.project.catalogue
    spec = catalogue.calibrations[study.name]
    start = spec.get("material")
    with _ready(catalogue, [start] if isinstance(start, str) else []) as ready:
        archive, cal = calibration_archive(study.name, spec, ready)
    return Calibrated(name=study.name, calibration=cal, material=cal.material, archive=archive,
                      dataset=archive.loaded(command="vcor.fitting.calibrate"))


def _set_aside_others(folder: Path, name: str, written) -> None:
    """Move aside, as ``<file>.stale`` and saying so on standard error, the decks and the Yade script of
    entry ``name`` under ``folder`` that are not among ``written`` (the files of the entry as configured):
    written for another configuration of it (a sphere target that is a wall now, a law it no longer
    fits), they would sit among its files and run another collision."""
    import sys

    from . import paths

    ours = {Path(p).resolve() for p in written}
    kinds = [paths.fmt(paths.DEM_DECK, dem=name, kind=k) for k in ("pair", "wall", "hereditary")]
    for path in (folder / p for p in (*kinds, paths.fmt(paths.DEM_YADE, dem=name))):
        if path.is_file() and path.resolve() not in ours:
            path.replace(path.with_name(path.name + ".stale"))
            sys.stderr.write(f"vcor: {path} is not a file of entry {name} as configured (written for another "
                             f"configuration of it): moved aside as {path.name}.stale\n")


@dataclass(frozen=True, kw_only=True)
class DemExport:
    """A DEM entry's export: its ``name``, the ``dataset`` (``results/dem/<name>.nc``: the COR against
    speed, every DEM law's fitted parameter with its error and range) and ``files``, the workflow's files
    of the entry (key -> path relative to the project: ``table``, ``parameters``, ``deck``, ``hereditary``, ``yade``),
    which :meth:`write` writes."""

    name: str
    dataset: xarray.Dataset = field(repr=False)
    files: dict
    archive: Archive = field(repr=False)
    collisions: list = field(repr=False)
    temperatures: list | None = field(repr=False, default=None)

    def write(self, folder=".", *, command: str = "vcor.dem_export") -> dict[str, Path]:
        """Write the dataset, the COR table, the parameters file and (where the entry fits their laws) the
        LAMMPS deck and the Yade script under ``folder`` as the workflow lays them out; {key: path}."""
        from ..dem import export, hereditary, lammps, yade
        from ..io.netcdf import read_dataset

        out = {key: Path(folder) / path for key, path in self.files.items()}
        _set_aside_others(Path(folder), self.name, out.values())
        self.archive.write(out["nc"], command=command)
        export.table_csv(out["table"], self.collisions, self.temperatures)
        export.parameters_csv(out["parameters"], self.archive.dataset)
        written = read_dataset(out["nc"])  # the deck and the script say what the archived dataset says
        if "deck" in out:
            lammps.write_deck(out["deck"], written)
        if "hereditary" in out:
            hereditary.write_deck(out["hereditary"], written)
        if "yade" in out:
            yade.write_script(out["yade"], written)
        return out


def dem_export(dem: dict | str, *, config: Any = None, name: str | None = None) -> DemExport:
    """A collision's COR against speed and the DEM contact laws fitted to it (LAMMPS, MercuryDPM, Yade).

    Parameters
    ----------
    dem : dict or str
        An entry as under ``dem.<name>`` of a config (``sphere``, ``target``, ``v0``, optional ``T``,
        ``models``, ``solver``; the user guide's DEM page), or the name of one in ``config``.
    config : str, path, dict or Catalogue, optional
        Where the bodies' material names are looked up.
    name : str, optional
        The entry's name when ``dem`` is a mapping (default ``dem``).

    Returns
    -------
    DemExport
        The dataset of ``results/dem/<name>.nc``; :meth:`DemExport.write` writes it with the entry's tables,
        LAMMPS deck and Yade script.
    """
    from ..dem.export import dem_dataset
    from ..solvers.backend import load_kernels
    from .dem import run_dem, solver_method

    study = resolve_entry("dem", dem, name, config, "dem")
    project, spec = study.project, study.project.dem[study.name]
    load_kernels([solver_method(spec)])
    with _ready(project.dem_catalogue(study.name), project.dem_materials(study.name)) as ready:
        collisions, fits, temps = run_dem(study.name, spec, ready)
    ds = dem_dataset(study.name, collisions, fits, temps, config=spec)
    archive = Archive(dataset=ds, title=f"vcor DEM parameters, {study.name}")
    return DemExport(name=study.name, dataset=archive.loaded(command="vcor.dem_export"), archive=archive,
                     files=project.dem_files(study.name), collisions=collisions, temperatures=temps)


@contextlib.contextmanager
def _ready(catalogue, names, uncertainty: dict | None = None):
    """:func:`~vcor.study.computed.ready_catalogue` for ``names`` (and ``uncertainty``'s bootstrap samples),
    with a temporary material folder that holds the computed materials the project's folder lacks, for the
    duration of the block."""
    with tempfile.TemporaryDirectory(prefix="vcor-materials-") as folder:
        yield ready_catalogue(catalogue, list(names), uncertainty, Path(folder))


def histories(scene: dict | str, *, config: Any = None, name: str | None = None) -> xarray.Dataset:
    """Time histories of a scene's ``histories`` runs: the dataset ``results/<scene>/histories.nc``.

    Parameters
    ----------
    scene : dict or str
        A scene as under ``scenes.<name>`` of a config, or the name of a scene of ``config``.
    config : str, path, dict or Catalogue, optional
        Where material names are looked up (as :func:`sweep`); None: presets only.
    name : str, optional
        The name of a scene given as a mapping (default ``sweep``, as :func:`sweep`), in the dataset's
        attributes and title.

    Returns
    -------
    xarray.Dataset
        Dimensions ``run`` (``material/method``) and ``sample``: t, s, s', F, J, z', U with units, the ghost
        part after separation marked, each run's outcome, status and validity, and the solver settings.

    Examples
    --------
    >>> import vcor
    >>> ds = vcor.histories({"materials": ["sls"], "histories": {"v0": 1.0, "runs": [["sls", "adaptive"]]}})
    >>> str(ds["run"].values[0]), ds["F"].attrs["units"]
    ('sls/adaptive', 'N')
    """
    study = resolve_scene(scene, config, name, "histories")
    sc = study.project.scenes[study.name]
    spec = sc.config["histories"]
    with _ready(study.project.scene_catalogue(study.name), sorted({run[0] for run in spec["runs"]})) as ready:
        archive = histories_archive(study.name, spec, sc.settings, ready)
    return archive.loaded(command="vcor.histories")


def moduli(scene: dict | str, *, config: Any = None, name: str | None = None) -> xarray.Dataset:
    """Relaxation modulus E(t) and complex modulus E*(omega) of a scene's materials (its ``moduli`` list,
    else its ``materials``): the dataset ``results/<scene>/moduli.nc``.

    Parameters
    ----------
    scene, config, name
        As :func:`histories` (a scene, which has ``materials``, or its name in ``config``; where names are
        looked up; the name of a scene given as a mapping).

    Returns
    -------
    xarray.Dataset
        E(t) on a log time grid and storage, loss modulus and tan delta on a log frequency grid, per
        material, in Pa, s and rad/s.
    """
    study = resolve_scene(scene, config, name, "moduli")
    names = study.project.scenes[study.name].moduli_materials()
    with _ready(study.project.scene_catalogue(study.name), names) as ready:
        archive = moduli_archive(names, ready)
    return archive.loaded(command="vcor.moduli")


def viscoelastic_spheres(scene: dict | str, *, config: Any = None, name: str | None = None) -> xarray.Dataset:
    """The COR eps(b) of viscoelastic spheres (Ramirez et al. 1999) for a scene's ``spheres`` block:
    numerics, series and Pade approximants, the hereditary variant and the ice fit; the dataset
    ``results/<scene>/spheres.nc``.

    Parameters
    ----------
    scene, config, name
        As :func:`histories` (a scene with a ``spheres`` block, or its name in ``config``; where names are looked
        up; the name of a scene given as a mapping).

    Returns
    -------
    xarray.Dataset
        eps against the dimensionless damping b per separation rule and method.
    """
    study = resolve_scene(scene, config, name, "spheres")
    return spheres_archive(study.name, study.project.scenes[study.name].config["spheres"]).loaded(
        command="vcor.viscoelastic_spheres")


def convergence(scene: dict | str, *, config: Any = None, name: str | None = None) -> xarray.Dataset:
    """The work-precision study of a scene's ``convergence`` block: every solver on a ladder of steps or
    tolerances per material and impact speed, its COR and t0 error against an independent reference and
    its wall time; the dataset ``results/<scene>/convergence.nc``
    (:func:`vcor.study.convergence.orders_table` gives its table of observed orders). The materials are
    solved one after another in this process: the wall times are the measurement, and solves running
    beside each other would disturb them.

    Parameters
    ----------
    scene, config, name
        As :func:`histories` (a scene with a ``convergence`` block, or its name in ``config``; where names are looked
        up; the name of a scene given as a mapping).

    Returns
    -------
    xarray.Dataset
        Dimensions (material, v0, solver, level): cor, t0, wall_time (s), the ladder's parameter, steps,
        err_cor, err_t0 (s), status and message, and the references.
    """
    study = resolve_scene(scene, config, name, "convergence")
    spec = study.project.scenes[study.name].config["convergence"]
    with _ready(study.project.scene_catalogue(study.name), spec["materials"]) as ready:
        cases = [convergence_case(m, spec["v0"], ready).loaded(command="vcor.convergence") for m in spec["materials"]]
    return convergence_archive(spec, cases).loaded(command="vcor.convergence")
