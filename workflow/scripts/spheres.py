"""eps(b) of viscoelastic spheres: numerics, series, Pade (thin: vcor.study.scene_datasets does the work)."""

from vcor.io.joblog import count, job_log
from vcor.study import scene_datasets, summary

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    spec = smk.params.spec
    archive = scene_datasets.spheres_archive(smk.wildcards.scene, spec)
    archive.write(smk.output[0], command="snakemake rule spheres")
    log.note(f"solved eps(b) of scene {smk.wildcards.scene} at {archive.dataset.sizes['b']} values of b with "
             f"{count(len(spec['rules']), 'separation rule')}: {summary.outcome_of(archive.dataset).text()}; "
             f"{smk.output[0]}")
