"""List a dem: entry's outputs with sizes and SHA-256 (thin: vcor.io.manifest)."""

from vcor.io.joblog import count, job_log
from vcor.io.manifest import write_manifest

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    write_manifest(f"DEM entry {smk.wildcards.dem}", smk.input, smk.output[0])
    log.note(f"listed the sizes and SHA-256 of {count(len(smk.input), 'output')} of DEM entry {smk.wildcards.dem} "
             f"in {smk.output[0]}")
