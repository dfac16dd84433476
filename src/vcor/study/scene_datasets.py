"""A scene's datasets other than its sweep, as the workflow archives them: time histories, material
moduli, the viscoelastic spheres' eps(b) and the work-precision study.

Each builder returns a :class:`vcor.io.archived.Archive` (the dataset, its title and its global
attributes). A workflow job writes it to its file (``results/<scene>/<dataset>.nc``); the study
functions (:mod:`vcor.study.api`: ``vcor.histories``, ``vcor.moduli``, ``vcor.viscoelastic_spheres``,
``vcor.convergence``) return it read back in memory. One builder per dataset, so both give the same
numbers and attributes.
"""

from __future__ import annotations

from ..io.archived import Archive
from ..materials.catalogue import Catalogue
from . import convergence, datasets, scene

__all__ = ["convergence_archive", "convergence_case", "histories_archive", "moduli_archive",
           "spheres_archive"]

#: the title of one material's work-precision case (a workflow job's file, combined by convergence_archive)
CASE_TITLE = "vcor work-precision case"


def histories_archive(name: str, histories: dict, settings: dict, catalogue: Catalogue) -> Archive:
    """``results/<name>/histories.nc``: the time histories of a scene's ``histories`` block ({v0 (m/s),
    runs: [[material, method], ...]}) with the scene's solver and geometry ``settings``. The methods'
    kernels are loaded first, so that each run's ``wall_time`` is its solve alone."""
    from ..solvers.backend import load_kernels  # on use: the moduli and combining jobs load no solver

    load_kernels(sorted({run[1] for run in histories["runs"]}))
    ds = datasets.histories_dataset([tuple(r) for r in histories["runs"]], histories["v0"],
                                    options=settings["solver"], geometry=settings["geometry"], catalogue=catalogue)
    attrs = {"scene": name, "histories_config": histories, "solver_settings": settings,
             "materials": scene.material_params(sorted({r[0] for r in histories["runs"]}), catalogue)}
    return Archive(dataset=ds, title=f"vcor histories, scene {name}", extra_attrs=attrs)


def moduli_archive(names, catalogue: Catalogue) -> Archive:
    """``results/<scene>/moduli.nc``: E(t) and E*(omega) of the materials ``names``."""
    names = list(names)
    return Archive(dataset=datasets.moduli_dataset(names, catalogue=catalogue), title="vcor material moduli",
                   extra_attrs={"materials": scene.material_params(names, catalogue)})


def spheres_archive(name: str, spec: dict) -> Archive:
    """``results/<name>/spheres.nc``: eps(b) of viscoelastic spheres (numerics, series, Pade approximants)
    for a scene's ``spheres`` block."""
    ds = datasets.spheres_dataset(scene.axis_values(spec["b"]), rules=spec["rules"], tau_ratios=spec["tau_ratio"],
                                  steps_per_contact=spec["steps_per_contact"], ice=spec.get("ice"))
    return Archive(dataset=ds, title=f"vcor viscoelastic spheres, scene {name}", extra_attrs={"spheres_config": spec})


def convergence_case(material: str, v0s, catalogue: Catalogue) -> Archive:
    """One material's work-precision ladders at the impact speeds ``v0s`` (m/s): a workflow job's file.
    Every method's kernels are loaded first: the wall times are the measurement."""
    import xarray as xr

    from ..solvers import METHODS
    from ..solvers.backend import load_kernels  # on use: the combining job loads no solver

    load_kernels(METHODS)

    v0s = [float(v) for v in v0s]
    cases = [convergence.study(material, v, catalogue=catalogue) for v in v0s]
    ds = xr.concat([c.expand_dims(v0=[v]) for c, v in zip(cases, v0s)], dim="v0")
    ds["v0"].attrs.update(convergence.V0_ATTRS)
    return Archive(dataset=ds, title=CASE_TITLE, extra_attrs={"material": material})


def convergence_archive(spec: dict, per_material) -> Archive:
    """``results/<scene>/convergence.nc``: the cases ``per_material`` (one dataset per material of a scene's
    ``convergence`` block ``spec``, in its order, dims (v0, solver, level)) combined."""
    mats = spec["materials"]
    cases = {(m, i): ds.isel(v0=i, drop=True) for m, ds in zip(mats, per_material) for i in range(ds.sizes["v0"])}
    return Archive(dataset=convergence.combine(cases, mats, spec["v0"]), title="vcor work-precision study",
                   extra_attrs={"convergence_config": spec})
