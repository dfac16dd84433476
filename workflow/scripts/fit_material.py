"""Fit one material to its data and write <name>.nc and a text table (thin; deterministic bytes)."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

from vcor.fitting import fits
from vcor.io import netcdf

spec = snakemake.params.spec  # noqa: F821
result, data, attrs = fits.run_fit(spec)
print(f"fit {snakemake.wildcards.material}: {result.fit_time:.3f} s, {result.settings}", file=sys.stderr)  # noqa: F821
ds = fits.result_dataset(result, data, spec)
ds.attrs.update(attrs, material_name=snakemake.wildcards.material)  # noqa: F821
netcdf.write_dataset(ds, snakemake.output.nc, title=f"vcor fitted material {snakemake.wildcards.material}",  # noqa: F821
                 command="vcor.fit (deterministic: no time stamp)", timestamp=False)
with open(snakemake.output.table, "w") as fh:  # noqa: F821
    fh.write(f"# {snakemake.wildcards.material}: {result.material.to_dict()}\n")  # noqa: F821
    fh.write(fits.metrics_table([(snakemake.wildcards.material, result.material, result.metrics)]))  # noqa: F821
