"""Computed materials (fits, calibrations, bootstrap samples): each as the workflow's rule computes and
archives it, and the material folder a study function reads them from.

:func:`fit_archive`, :func:`calibration_archive` and :func:`samples_archive` are the computations
behind :func:`vcor.fit`, :func:`vcor.calibrate` and a scene's bootstrap band; the workflow's rules run
them through those functions (``workflow/scripts/fit_material.py``, ``calibrate.py``).

:func:`ready_catalogue` gives :func:`vcor.sweep` a catalogue in which every computed material a scene
needs has its file: the project's own file (``<material_dir>/<name>.nc``, written by the workflow or by
``vcor fit`` / ``vcor calibrate``) where its receipt matches the material's identity (the same spec,
data and code), else the file computed for this call, in a temporary folder that the call removes. A
call writes nothing into the project.
"""

from __future__ import annotations

import shutil
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING

from ..io import receipts
from ..io.archived import Archive
from ..materials.catalogue import Catalogue
from . import paths
from .uncertainty import SAMPLE_JOBS, samples_file, samples_identity

if TYPE_CHECKING:
    from ..fitting.calibrate import Calibration
    from ..fitting.prony import FitResult

__all__ = ["DETERMINISTIC", "calibration_archive", "fit_archive", "needed", "ready_catalogue", "samples_archive"]

#: the history of a computed material's file: no time stamp, so that the same inputs give the same bytes
DETERMINISTIC = "(deterministic: no time stamp)"


def fit_archive(name: str, spec: dict, base_dir=".") -> tuple[Archive, FitResult, str]:
    """(archive of the fit's dataset, fitted material, its text table) of the fit ``spec`` named ``name``
    (:func:`vcor.fitting.fits.run_fit`; data files relative to ``base_dir``)."""
    from ..fitting import fits

    result, data, attrs = fits.run_fit(spec, base_dir=base_dir)
    ds = fits.result_dataset(result, data, spec)
    ds.attrs.update(attrs, material_name=name)
    row = [(name, result.material, result.metrics)]
    measured = "file" in (spec.get("data") or {})
    table = (f"# {name}: {result.material.to_dict()}\n"
             + (f"# shift function: {attrs['shift']}\n" if attrs.get("shift") else "")
             + (fits.metrics_table(row, fits.MEASURED_KEYS, fits.MEASURED_HEADER) if measured
                else fits.metrics_table(row)))
    return Archive(dataset=ds, title=f"vcor fitted material {name}", timestamp=False), result, table


def calibration_archive(name: str, spec: dict, catalogue: Catalogue) -> tuple[Archive, Calibration]:
    """(archive of the calibration's record, :class:`vcor.fitting.calibrate.Calibration`) of the
    calibration ``spec`` named ``name``; its start material by name from ``catalogue``."""
    from ..fitting import calibrate

    cal = calibrate.run_calibration(spec, catalogue=catalogue, where=f"calibrations.{name}")
    ds = calibrate.calibration_dataset(cal, spec)
    return Archive(dataset=ds, title=f"vcor calibration {name}", timestamp=False), cal


def samples_archive(name: str, spec: dict, uncertainty: dict, fit_file, base_dir=".") -> Archive:
    """Every bootstrap sample of the fit ``name`` (``spec``) for a scene's ``uncertainty``, computed in
    the workflow's parts (:data:`vcor.study.uncertainty.SAMPLE_JOBS`) and merged, as its rules do."""
    from ..fitting import resample, samples

    n, seed = uncertainty["bootstrap"], uncertainty["seed"]
    parts = []
    for part in range(SAMPLE_JOBS):
        ds = resample.samples_dataset(name, spec, n, seed=seed, base_dir=base_dir, full=str(fit_file),
                                      indices=samples.part_indices(n, part, SAMPLE_JOBS))
        archive = Archive(dataset=ds, title=f"vcor bootstrap samples of {name}", timestamp=False)
        parts.append(archive.loaded(command=f"vcor.fitting.resample {DETERMINISTIC}"))
    return Archive(dataset=samples.merge_samples(parts), title=f"vcor bootstrap samples of {name}", timestamp=False)


def needed(catalogue: Catalogue, names) -> list[str]:
    """The computed materials among ``names`` and what they are computed from (a calibration's start
    material), each after the ones it needs."""
    out: list[str] = []

    def visit(name):
        if not isinstance(name, str) or name in out or name not in catalogue.computed():
            return
        start = (catalogue.calibrations.get(name) or {}).get("material")
        visit(start)
        out.append(name)

    for name in names:
        visit(name)
    return out


def _compute(name: str, catalogue: Catalogue, path: Path, base: Path) -> None:
    command = "vcor.sweep: computed for the call"
    if name in catalogue.fits:
        archive = fit_archive(name, catalogue.fits[name], base)[0]
    else:
        archive = calibration_archive(name, catalogue.calibrations[name], catalogue)[0]
    archive.write(path, command=command, identity=catalogue.identity(name))


def _samples_into(name: str, catalogue: Catalogue, uncertainty: dict, own: Path, folder: Path) -> None:
    """The bootstrap samples file of fit ``name`` in ``folder`` (the catalogue's): copied from ``own`` where
    it matches its identity, else computed from the fit's file in ``folder``."""
    source = Path(samples_file(str(own), name, uncertainty))
    target = Path(samples_file(str(folder), name, uncertainty))
    identity = samples_identity(catalogue, name, uncertainty)
    if receipts.problem(source, identity) is None:
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(source, target)
        return
    archive = samples_archive(name, catalogue.fits[name], uncertainty, paths.material(str(folder), name),
                              catalogue.base_dir)
    archive.write(target, command=f"vcor.fitting.resample {DETERMINISTIC}", identity=identity)


def ready_catalogue(catalogue: Catalogue, names, uncertainty: dict | None, folder: Path) -> Catalogue:
    """``catalogue`` with a material folder holding the file of every computed material of ``names`` (and
    their bootstrap samples for ``uncertainty``): the project's folder when its files all match their
    identities, else ``folder`` (module docstring). Relative paths are taken from the catalogue's
    ``base_dir``."""
    base = Path(catalogue.base_dir)
    own = base / catalogue.material_dir
    todo = needed(catalogue, names)
    files = [(n, paths.material(str(own), n), catalogue.identity(n)) for n in todo]
    if uncertainty is not None:
        files += [(n, samples_file(str(own), n, uncertainty), samples_identity(catalogue, n, uncertainty))
                  for n in names if n in catalogue.fits]
    if all(receipts.problem(path, identity) is None for _, path, identity in files):
        return replace(catalogue, material_dir=str(own))
    here = replace(catalogue, material_dir=str(folder))
    for name in todo:
        source, target = Path(paths.material(str(own), name)), Path(paths.material(str(folder), name))
        if receipts.problem(source, here.identity(name)) is None:
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(source, target)
        else:
            _compute(name, here, target, base)
    if uncertainty is not None:
        for name in (n for n in names if n in catalogue.fits):
            _samples_into(name, here, uncertainty, own, folder)
    return here
