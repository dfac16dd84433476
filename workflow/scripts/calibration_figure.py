"""Draw a calibration: data, fitted curve with its 95 % band, residuals (thin: vcor.plots)."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

import xarray as xr

from vcor import plots

plots.save(plots.calibration(xr.load_dataset(snakemake.input[0])), snakemake.output.png, snakemake.output.pdf)  # noqa: F821
