"""Draw one figure from datasets only (thin: vcor.plots does the drawing)."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

import xarray as xr

from vcor import plots

fn, needs = plots.FIGURES[snakemake.wildcards.fig]  # noqa: F821
data = [xr.load_dataset(snakemake.input[n]) for n in needs]  # noqa: F821
fig = fn(*data, dict(snakemake.params.options))  # noqa: F821
fig.savefig(snakemake.output.png, dpi=130)  # noqa: F821
fig.savefig(snakemake.output.pdf, metadata={"CreationDate": None})  # noqa: F821
