"""One dem: entry (thin: vcor.study.dem and vcor.dem): the collision's COR, the DEM laws fitted to it,
the dataset, the COR table, the parameters file, and the LAMMPS deck and Yade script when the entry
fits their laws."""

from vcor.dem import export, lammps, yade
from vcor.io import netcdf
from vcor.io.joblog import count, job_log
from vcor.materials import Catalogue
from vcor.solvers.backend import load_kernels
from vcor.study import dem, summary

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    name, spec, out = smk.params.name, smk.params.spec, dict(smk.output.items())
    load_kernels([dem.solver_method(spec)])  # compiled once per machine
    collisions, fits, temps = dem.run_dem(name, spec, Catalogue(**smk.params.catalogue))
    ds = export.dem_dataset(name, collisions, fits, temps, config=spec)
    netcdf.write_dataset(ds, out["nc"], title=f"vcor DEM parameters, {name}", command=f"snakemake rule {smk.rule}")
    export.table_csv(out["table"], collisions, temps)
    export.parameters_csv(out["parameters"], ds)
    done = summary.outcome_of(ds)
    log.note(f"DEM entry {name}: solved {count(done.points, 'collision')}: {done.text()}; fitted "
             f"{count(ds.sizes['model'], 'contact law')}: {out['nc']}")
    written = netcdf.read_dataset(out["nc"])  # the deck and the script say what the archived dataset says
    if "deck" in out:
        lammps.write_deck(out["deck"], written)
        log.note(f"wrote the LAMMPS deck {out['deck']}")
    if "yade" in out:
        yade.write_script(out["yade"], written)
        log.note(f"wrote the Yade script {out['yade']}")
