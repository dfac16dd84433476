"""Combine a scene's shards into results/<scene>/sweep.nc (thin)."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

import xarray as xr

from vcor.io import netcdf
from vcor.materials import Catalogue
from vcor.study import aggregation

cfg = snakemake.params.scene  # noqa: F821
catalogue = Catalogue(**snakemake.params.catalogue)  # noqa: F821
shards = [xr.load_dataset(p) for p in snakemake.input.shards]  # noqa: F821
ds = aggregation.aggregate(shards, cfg, dict(snakemake.params.identities), catalogue)  # noqa: F821
attrs = aggregation.dataset_attrs(snakemake.wildcards.scene, cfg, catalogue)  # noqa: F821
netcdf.write_dataset(ds, snakemake.output[0], title=f"vcor sweep, scene {snakemake.wildcards.scene}",  # noqa: F821
                 extra_attrs=attrs, command="snakemake rule aggregate")
