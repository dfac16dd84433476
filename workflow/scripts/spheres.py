"""eps(b) of viscoelastic spheres: numerics, series, Pade (thin: vcor.datasets does the work)."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

from vcor.io import netcdf
from vcor.study import datasets, scene

spec = snakemake.params.spec  # noqa: F821
ds = datasets.spheres_dataset(scene.axis_values(spec["b"]), rules=spec["rules"], tau_ratios=spec["tau_ratio"],
                              steps_per_contact=spec["steps_per_contact"], ice=spec.get("ice"))
netcdf.write_dataset(ds, snakemake.output[0], title=f"vcor viscoelastic spheres, scene {snakemake.wildcards.scene}",  # noqa: F821
                 extra_attrs={"spheres_config": spec}, command="snakemake rule spheres")
