"""Time histories of a scene's listed runs, with the ghost part after separation (thin)."""

from vcor.io import netcdf
from vcor.io.joblog import count, job_log
from vcor.materials import Catalogue
from vcor.study import datasets, scene, summary

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    h, settings = smk.params.histories, smk.params.settings
    catalogue = Catalogue(**smk.params.catalogue)
    ds = datasets.histories_dataset([tuple(r) for r in h["runs"]], h["v0"], options=settings["solver"],
                                    geometry=settings["geometry"], catalogue=catalogue)
    attrs = {"scene": smk.wildcards.scene, "histories_config": h, "solver_settings": settings,
             "materials": scene.material_params(sorted({r[0] for r in h["runs"]}), catalogue)}
    netcdf.write_dataset(ds, smk.output[0], title=f"vcor histories, scene {smk.wildcards.scene}", extra_attrs=attrs,
                         command="snakemake rule histories")
    runs = count(len(h["runs"]), "time history", "time histories")
    log.note(f"solved {runs} of scene {smk.wildcards.scene} at v0 = {h['v0']:g} m/s: "
             f"{summary.outcome_of(ds).text()}; {smk.output[0]}")
    for run, reasons in zip(ds["run"].values, ds["validity_message"].values):
        if reasons:  # the dataset's validity flags of this run, in words
            log.note(f"{run} flagged: {reasons}", timed=False)
