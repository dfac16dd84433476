"""Combine the work-precision cases and write the table of observed orders (thin)."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

import xarray as xr  # noqa: E402

from vcor import convergence, io  # noqa: E402

spec = snakemake.params.spec  # noqa: F821
mats, v0s = spec["materials"], spec["v0"]
paths = iter(snakemake.input)  # noqa: F821
cases = {(m, i): xr.load_dataset(next(paths)) for m in mats for i in range(len(v0s))}
ds = convergence.combine(cases, mats, v0s)
io.write_dataset(ds, snakemake.output.nc, title="vcor work-precision study", command="snakemake rule convergence",  # noqa: F821
                 extra_attrs={"convergence_config": spec})
with open(snakemake.output.orders, "w") as fh:  # noqa: F821
    fh.write(convergence.orders_table(ds))
