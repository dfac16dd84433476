"""List a dem: entry's outputs with sizes and SHA-256 (thin: vcor.io.manifest)."""

from vcor.io.joblog import job_log
from vcor.io.manifest import write_manifest

smk = snakemake  # noqa: F821
with job_log(smk):
    write_manifest(f"DEM entry {smk.wildcards.dem}", smk.input, smk.output[0])
