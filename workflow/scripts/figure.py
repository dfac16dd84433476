"""Draw one figure from datasets only (thin: vcor.plots does the drawing)."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

import xarray as xr

from vcor import plots

fn, needs = plots.FIGURES[snakemake.wildcards.fig]  # noqa: F821
# a need is one file, or a list of files (master_curve: one fit per column)
files = [snakemake.input[n] for n in needs]  # noqa: F821
data = [xr.load_dataset(f) if isinstance(f, str) else [xr.load_dataset(x) for x in f] for f in files]
fig = fn(*data, dict(snakemake.params.options))  # noqa: F821
fig.savefig(snakemake.output.png, dpi=130)  # noqa: F821
fig.savefig(snakemake.output.pdf, metadata={"CreationDate": None})  # noqa: F821
