"""Draw all figures of a scene from its datasets (thin: vcor.plots does the drawing)."""

from vcor import plots
from vcor.io import netcdf, receipts
from vcor.io.joblog import count, job_log

smk = snakemake  # noqa: F821
loaded = {}  # one load per file: several figures of a scene read the same dataset


def load(path):
    if path not in loaded:
        loaded[path] = netcdf.read_dataset(receipts.verified(path))
    return loaded[path]


with job_log(smk) as log:
    inp, params = smk.input, smk.params
    for fig, png, pdf in zip(params.figures, smk.output.png, smk.output.pdf):
        lists = {"material_fit": f"{fig}_fits", "material_samples": f"{fig}_samples"}
        files = {n: list(getattr(inp, lists[n], [])) if n in lists else inp[n] for n in plots.FIGURES[fig][1]}
        data = {n: [load(p) for p in f] if isinstance(f, list) else load(f) for n, f in files.items()}
        plots.save(plots.draw(fig, data, params.options[fig]), png, pdf)
    log.note(f"drew {count(len(params.figures), 'figure')} of scene {params.scene} ({', '.join(params.figures)}; "
             f"png and pdf) from {', '.join(sorted(loaded))}")
