"""Solve one shard of grid points (thin: vcor.sweep does the work)."""

import json
import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

from vcor import io, sweep  # noqa: E402

points = snakemake.params.points  # noqa: F821
settings = snakemake.params.settings  # noqa: F821
ds = sweep.run_points(points, settings, snakemake.params.material_dir)  # noqa: F821
io.write_dataset(ds, snakemake.output.nc, title="vcor sweep shard", extra_attrs={"settings": settings},  # noqa: F821
                 command="snakemake rule sweep_shard")
with open(snakemake.output.index, "w") as fh:  # noqa: F821
    json.dump({"points": points, "settings": settings}, fh, indent=1)
