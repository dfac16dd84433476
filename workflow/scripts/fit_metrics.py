"""Error metrics of a scene's fitted materials beside the paper's own sets (thin)."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

from vcor import fit, scene

data = fit.bagley_torvik_data()
rows = []
for name in ["butyl-cerf", "butyl-prony3", *snakemake.params.names]:  # noqa: F821
    mat = scene.resolve_material(name, material_dir=snakemake.params.material_dir)  # noqa: F821
    rows.append((name, mat, fit.metrics(mat, data)))
with open(snakemake.output[0], "w") as fh:  # noqa: F821
    fh.write(fit.metrics_table(rows))
