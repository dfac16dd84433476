"""One material of the work-precision study, all impact speeds (thin)."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

import xarray as xr

from vcor import convergence, io

name = snakemake.params.material  # noqa: F821
v0s = [float(v) for v in snakemake.params.v0]  # noqa: F821
cases = [convergence.study(name, v, material_dir=snakemake.params.material_dir) for v in v0s]  # noqa: F821
ds = xr.concat([c.expand_dims(v0=[v]) for c, v in zip(cases, v0s)], dim="v0")
io.write_dataset(ds, snakemake.output[0], title="vcor work-precision case", command="snakemake rule convergence_case",  # noqa: F821
                 extra_attrs={"material": name})
