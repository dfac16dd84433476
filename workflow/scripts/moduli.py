"""Tabulate relaxation and dynamic moduli of a scene's materials (thin)."""

from vcor.io.joblog import count, job_log
from vcor.materials import Catalogue
from vcor.study import scene_datasets

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    names = list(smk.params.materials)
    scene_datasets.moduli_archive(names, Catalogue(**smk.params.catalogue)).write(smk.output[0],
                                                                                  command="snakemake rule moduli")
    log.note(f"tabulated the moduli of {count(len(names), 'material')} ({', '.join(names)}): {smk.output[0]}")
