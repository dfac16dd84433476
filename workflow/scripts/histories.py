"""Time histories of a scene's listed runs, with the ghost part after separation (thin)."""

from vcor.io.joblog import count, job_log
from vcor.materials import Catalogue
from vcor.study import scene_datasets, summary

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    h = smk.params.histories
    archive = scene_datasets.histories_archive(smk.wildcards.scene, h, smk.params.settings,
                                               Catalogue(**smk.params.catalogue))
    archive.write(smk.output[0], command="snakemake rule histories")
    ds = archive.dataset
    runs = count(len(h["runs"]), "time history", "time histories")
    log.note(f"solved {runs} of scene {smk.wildcards.scene} at v0 = {h['v0']:g} m/s: "
             f"{summary.outcome_of(ds).text()}; {smk.output[0]}")
    for run, reasons in zip(ds["run"].values, ds["validity_message"].values):
        if reasons:  # the dataset's validity flags of this run, in words
            log.note(f"{run} flagged: {reasons}", timed=False)
