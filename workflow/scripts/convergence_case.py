"""One material of the work-precision study, all impact speeds (thin)."""

import xarray as xr

from vcor.io import netcdf
from vcor.io.joblog import count, job_log
from vcor.materials import Catalogue
from vcor.solvers import METHODS
from vcor.solvers.backend import load_kernels
from vcor.study import convergence, summary

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    name, v0s = smk.params.material, [float(v) for v in smk.params.v0]
    catalogue = Catalogue(**smk.params.catalogue)
    load_kernels(METHODS)  # compiled once per machine (vcor.solvers.backend)
    cases = [convergence.study(name, v, catalogue=catalogue) for v in v0s]
    ds = xr.concat([c.expand_dims(v0=[v]) for c, v in zip(cases, v0s)], dim="v0")
    ds["v0"].attrs.update(convergence.V0_ATTRS)
    netcdf.write_dataset(ds, smk.output[0], title="vcor work-precision case", extra_attrs={"material": name},
                         command="snakemake rule convergence_case")
    done = summary.outcome_of(convergence.ladder_runs(ds))
    speeds = ", ".join(f"{v:g}" for v in v0s)
    log.note(f"work-precision ladder of {name} at v0 = {speeds} m/s: {count(done.points, 'run')}: {done.text()}; "
             f"{smk.output[0]}")
