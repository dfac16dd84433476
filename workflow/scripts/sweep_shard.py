"""Solve one shard of grid points (thin: vcor.runner does the work)."""

import json
import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

from vcor.io import netcdf
from vcor.materials import Catalogue
from vcor.study import runner, scene

points = snakemake.params.points  # noqa: F821
settings = snakemake.params.settings  # noqa: F821
catalogue = Catalogue(**snakemake.params.catalogue)  # noqa: F821
ds = runner.run_points(points, settings, catalogue)
attrs = {"settings": settings, "materials": scene.material_params(sorted({p["material"] for p in points}), catalogue)}
netcdf.write_dataset(ds, snakemake.output.nc, title="vcor sweep shard", extra_attrs=attrs,  # noqa: F821
                 command="snakemake rule sweep_shard")
with open(snakemake.output.index, "w") as fh:  # noqa: F821
    json.dump({"points": points, "settings": settings}, fh, indent=1)
