"""One dem: entry (thin: vcor.study.dem and vcor.dem): the collision's COR, the DEM laws fitted to it,
the dataset, the COR table and the parameters file."""

from vcor.dem import export
from vcor.io import netcdf
from vcor.io.joblog import count, job_log
from vcor.materials import Catalogue
from vcor.solvers.backend import load_kernels
from vcor.study import dem, summary

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    name, spec = smk.wildcards.dem, smk.params.spec
    load_kernels([(spec.get("solver") or {}).get("method", "adaptive")])  # compiled once per machine
    collisions, fits, temps = dem.run_dem(name, spec, Catalogue(**smk.params.catalogue))
    ds = export.dem_dataset(name, collisions, fits, temps, config=spec)
    netcdf.write_dataset(ds, smk.output.nc, title=f"vcor DEM parameters, {name}", command="snakemake rule dem")
    export.table_csv(smk.output.table, collisions, temps)
    export.parameters_csv(smk.output.parameters, ds)
    done = summary.outcome_of(ds)
    log.note(f"DEM entry {name}: solved {count(done.points, 'collision')}: {done.text()}; fitted "
             f"{count(ds.sizes['model'], 'contact law')}: {smk.output.nc}")
