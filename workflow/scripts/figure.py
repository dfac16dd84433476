"""Draw all figures of a scene from its datasets (thin: vcor.plots does the drawing)."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

import xarray as xr

from vcor import plots

inp, params = snakemake.input, snakemake.params  # noqa: F821
loaded = {}  # one load per file: several figures of a scene read the same dataset


def load(path):
    if path not in loaded:
        loaded[path] = xr.load_dataset(path)
    return loaded[path]


for fig, png, pdf in zip(params.figures, snakemake.output.png, snakemake.output.pdf):  # noqa: F821
    files = {n: inp[f"{fig}_fits"] if n == "material_fit" else inp[n] for n in plots.FIGURES[fig][1]}
    data = {n: [load(p) for p in f] if isinstance(f, list)
            else load(f) for n, f in files.items()}
    plots.save(plots.draw(fig, data, params.options[fig]), png, pdf)
