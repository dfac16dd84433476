"""Combine the work-precision cases and write the table of observed orders (thin)."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

import xarray as xr

from vcor.io import netcdf
from vcor.study import convergence

spec = snakemake.params.spec  # noqa: F821
mats = spec["materials"]
per_material = [xr.load_dataset(p) for p in snakemake.input]  # noqa: F821
cases = {(m, i): ds.isel(v0=i, drop=True) for m, ds in zip(mats, per_material) for i in range(ds.sizes["v0"])}
ds = convergence.combine(cases, mats, spec["v0"])
netcdf.write_dataset(ds, snakemake.output.nc, title="vcor work-precision study", command="snakemake rule convergence",  # noqa: F821
                 extra_attrs={"convergence_config": spec})
with open(snakemake.output.orders, "w") as fh:  # noqa: F821
    fh.write(convergence.orders_table(ds))
