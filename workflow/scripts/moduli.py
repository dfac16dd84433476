"""Tabulate relaxation and dynamic moduli of a scene's materials (thin)."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

from vcor.io import netcdf
from vcor.materials import Catalogue
from vcor.study import datasets, scene

names = list(snakemake.params.materials)  # noqa: F821
catalogue = Catalogue(**snakemake.params.catalogue)  # noqa: F821
ds = datasets.moduli_dataset(names, catalogue=catalogue)
attrs = {"materials": scene.material_params(names, catalogue)}
netcdf.write_dataset(ds, snakemake.output[0], title="vcor material moduli", extra_attrs=attrs,  # noqa: F821
                 command="snakemake rule moduli")
