"""Tabulate relaxation and dynamic moduli of a scene's materials (thin)."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

from vcor import datasets, io, scene

names = list(snakemake.params.materials)  # noqa: F821
ds = datasets.moduli_dataset(names, material_dir=snakemake.params.material_dir)  # noqa: F821
attrs = {"materials": scene.material_params(names, snakemake.params.material_dir)}  # noqa: F821
io.write_dataset(ds, snakemake.output[0], title="vcor material moduli", extra_attrs=attrs,  # noqa: F821
                 command="snakemake rule moduli")
