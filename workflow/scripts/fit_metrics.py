"""Error metrics of a scene's fitted materials beside the paper's own sets (thin)."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

from vcor.fitting import fits

with open(snakemake.output[0], "w") as fh:  # noqa: F821
    fh.write(fits.scene_metrics_table(snakemake.params.names, snakemake.params.material_dir))  # noqa: F821
