"""Time histories of a scene's listed runs, with the ghost part after separation (thin)."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

from vcor.io import netcdf
from vcor.materials import Catalogue
from vcor.study import datasets, scene

h = snakemake.params.histories  # noqa: F821
settings = snakemake.params.settings  # noqa: F821
catalogue = Catalogue(**snakemake.params.catalogue)  # noqa: F821
ds = datasets.histories_dataset([tuple(r) for r in h["runs"]], h["v0"], options=settings["solver"],
                                geometry=settings["geometry"], catalogue=catalogue)
attrs = {
    "scene": snakemake.wildcards.scene,  # noqa: F821
    "histories_config": h,
    "solver_settings": settings,
    "materials": scene.material_params(sorted({r[0] for r in h["runs"]}), catalogue),
}
netcdf.write_dataset(ds, snakemake.output[0], title=f"vcor histories, scene {snakemake.wildcards.scene}",  # noqa: F821
                 extra_attrs=attrs, command="snakemake rule histories")
