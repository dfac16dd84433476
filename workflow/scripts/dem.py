"""One dem: entry (thin: vcor.dem_export): the collision's COR, the DEM laws fitted to it, the dataset, the
COR table, the parameters file, and the LAMMPS decks and Yade script when the entry has their laws."""

import vcor
from vcor.io.joblog import count, job_log
from vcor.materials import Catalogue
from vcor.study import summary

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    name = smk.params.name
    export = vcor.dem_export(smk.params.spec, name=name, config=Catalogue(**smk.params.catalogue))
    written = export.write(".", command=f"snakemake rule {smk.rule}")
    done = summary.outcome_of(export.dataset)
    log.note(f"DEM entry {name}: solved {count(done.points, 'collision')}: {done.text()}; fitted "
             f"{count(export.dataset.sizes['model'], 'contact law')}: {written['nc']}")
    for key, what in (("deck", "the LAMMPS deck"), ("hereditary", "the LAMMPS deck of vcor's own contact law"),
                      ("yade", "the Yade script")):
        if key in written:
            log.note(f"wrote {what} {written[key]}")
