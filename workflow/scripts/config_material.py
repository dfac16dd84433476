"""Write a material of the config's materials block to MATERIAL_DIR (thin: vcor.material_specs)."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

from vcor.material_specs import write_material

write_material(snakemake.wildcards.name, snakemake.params.spec, snakemake.output[0])  # noqa: F821
