"""Draw a calibration: data, fitted curve with its 95 % band, residuals (thin: vcor.plots)."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

import xarray as xr

from vcor import plots

fig = plots.calibration(xr.load_dataset(snakemake.input[0]))  # noqa: F821
fig.savefig(snakemake.output.png, dpi=130)  # noqa: F821
fig.savefig(snakemake.output.pdf, metadata={"CreationDate": None})  # noqa: F821
