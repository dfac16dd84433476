"""List a scene's outputs with sizes and SHA-256 (what to archive); thin: vcor.io.manifest does it."""

from vcor.io.joblog import count, job_log
from vcor.io.manifest import write_manifest

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    write_manifest(f"scene {smk.wildcards.scene}", smk.input, smk.output[0])
    log.note(f"listed the sizes and SHA-256 of {count(len(smk.input), 'output')} of scene {smk.wildcards.scene} "
             f"in {smk.output[0]}")
