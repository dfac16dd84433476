"""Every bootstrap sample of a fit in one file: the jobs' parts merged (thin: vcor.fitting.samples)."""

from vcor.fitting import samples
from vcor.io import netcdf
from vcor.io.joblog import count, job_log

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    name = smk.wildcards.material
    ds = samples.merge_samples([netcdf.read_dataset(path) for path in smk.input])
    netcdf.write_dataset(ds, smk.output[0], title=f"vcor bootstrap samples of {name}", timestamp=False,
                         command="vcor.fitting.resample (deterministic: no time stamp)",
                         identity=smk.params.identity)
    log.note(f"merged {count(len(smk.input), 'part')} into {count(ds.sizes['sample'], 'bootstrap sample')} of "
             f"{name}: {smk.output[0]}")
