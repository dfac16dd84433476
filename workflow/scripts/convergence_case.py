"""One material of the work-precision study, all impact speeds (thin)."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

import xarray as xr

from vcor.io import netcdf
from vcor.materials import Catalogue
from vcor.study import convergence

name = snakemake.params.material  # noqa: F821
v0s = [float(v) for v in snakemake.params.v0]  # noqa: F821
catalogue = Catalogue(**snakemake.params.catalogue)  # noqa: F821
cases = [convergence.study(name, v, catalogue=catalogue) for v in v0s]
ds = xr.concat([c.expand_dims(v0=[v]) for c, v in zip(cases, v0s)], dim="v0")
netcdf.write_dataset(ds, snakemake.output[0], title="vcor work-precision case", command="snakemake rule convergence_case",  # noqa: F821
                 extra_attrs={"material": name})
