"""Tabulate relaxation and dynamic moduli of a scene's materials (thin)."""

from vcor.io import netcdf
from vcor.io.joblog import count, job_log
from vcor.materials import Catalogue
from vcor.study import datasets, scene

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    names, catalogue = list(smk.params.materials), Catalogue(**smk.params.catalogue)
    ds = datasets.moduli_dataset(names, catalogue=catalogue)
    netcdf.write_dataset(ds, smk.output[0], title="vcor material moduli", command="snakemake rule moduli",
                         extra_attrs={"materials": scene.material_params(names, catalogue)})
    log.note(f"tabulated the moduli of {count(len(names), 'material')} ({', '.join(names)}): {smk.output[0]}")
