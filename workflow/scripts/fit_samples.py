"""One job's share of the bootstrap samples of a fit to measured data, refitted from the fit's own file
(thin: vcor.fitting.resample)."""

from vcor.fitting import resample, samples
from vcor.io import netcdf
from vcor.io.joblog import count, job_log

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    name, n, seed = smk.wildcards.material, int(smk.wildcards.n), int(smk.wildcards.seed)
    part, parts = int(smk.wildcards.part), int(smk.wildcards.parts)
    indices = samples.part_indices(n, part, parts)
    ds = resample.samples_dataset(name, smk.params.spec, n, seed=seed, base_dir=".", full=smk.input.fit,
                                  indices=indices)
    netcdf.write_dataset(ds, smk.output[0], title=f"vcor bootstrap samples of {name}", timestamp=False,
                         command="vcor.fitting.resample (deterministic: no time stamp)",
                         identity=smk.params.identity)
    log.note(f"refitted {name} to {count(indices.size, 'bootstrap sample')} of its data, {indices[0]}..{indices[-1]} "
             f"of {n} (part {part + 1} of {parts}, seed {seed}), from {smk.input.fit}: {smk.output[0]}")
    for i, notes in samples.not_converged(ds).items():
        log.note(f"sample {i}: {'; '.join(notes)} (kept in the band; the file's attribute not_converged lists it)")
