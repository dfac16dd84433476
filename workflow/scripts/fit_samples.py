"""Bootstrap samples of one fit to measured data (thin: vcor.fitting.resample)."""

from vcor.fitting import resample
from vcor.io import netcdf
from vcor.io.joblog import count, job_log

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    name, n, seed = smk.wildcards.material, int(smk.wildcards.n), int(smk.wildcards.seed)
    ds = resample.samples_dataset(name, smk.params.spec, n, seed=seed, base_dir=".")
    netcdf.write_dataset(ds, smk.output[0], title=f"vcor bootstrap samples of {name}", timestamp=False,
                         command="vcor.fitting.resample (deterministic: no time stamp)",
                         identity=smk.params.identity)
    log.note(f"refitted {name} to {count(n, 'bootstrap sample')} of its data (seed {seed}): {smk.output[0]}")
