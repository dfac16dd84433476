"""Write a material of the config's materials block to MATERIAL_DIR (thin: vcor.materials.files)."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

from vcor.io.netcdf import write_dataset
from vcor.materials.files import material_dataset

name = snakemake.wildcards.name  # noqa: F821
ds, attrs = material_dataset(name, snakemake.params.spec)  # noqa: F821
write_dataset(ds, snakemake.output[0], title=f"vcor material {name} (config materials block)", extra_attrs=attrs,  # noqa: F821
              command="vcor.materials.files.material_dataset (deterministic: no time stamp)", timestamp=False)
