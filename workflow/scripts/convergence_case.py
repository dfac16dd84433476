"""One material of the work-precision study, all impact speeds (thin)."""

from vcor.io.joblog import count, job_log
from vcor.materials import Catalogue
from vcor.study import convergence, scene_datasets, summary

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    name, v0s = smk.params.material, [float(v) for v in smk.params.v0]
    archive = scene_datasets.convergence_case(name, v0s, Catalogue(**smk.params.catalogue))
    archive.write(smk.output[0], command="snakemake rule convergence_case")
    done = summary.outcome_of(convergence.ladder_runs(archive.dataset))
    speeds = ", ".join(f"{v:g}" for v in v0s)
    log.note(f"work-precision ladder of {name} at v0 = {speeds} m/s: {count(done.points, 'run')}: {done.text()}; "
             f"{smk.output[0]}")
