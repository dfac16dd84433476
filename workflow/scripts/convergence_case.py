"""One (material, v0) case of the work-precision study (thin)."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

from vcor import convergence, io  # noqa: E402

ds = convergence.study(snakemake.params.material, float(snakemake.params.v0),  # noqa: F821
                       material_dir=snakemake.params.material_dir)  # noqa: F821
io.write_dataset(ds, snakemake.output[0], title="vcor work-precision case", command="snakemake rule convergence_case",  # noqa: F821
                 extra_attrs={"material": snakemake.params.material, "v0": float(snakemake.params.v0)})  # noqa: F821
