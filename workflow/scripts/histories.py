"""Time histories of a scene's listed runs, with the ghost part after separation (thin)."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

from vcor import datasets, io, sweep  # noqa: E402

scene = snakemake.params.scene  # noqa: F821
h = scene["histories"]
settings = sweep.settings_of(scene)
ds = datasets.histories_dataset([tuple(r) for r in h["runs"]], h["v0"], solver=settings["solver"],
                                geometry=settings["geometry"], ghost=h.get("ghost", 0.5),
                                material_dir=snakemake.params.material_dir)  # noqa: F821
attrs = sweep.dataset_attrs(snakemake.wildcards.scene, scene, snakemake.params.material_dir)  # noqa: F821
io.write_dataset(ds, snakemake.output[0], title=f"vcor histories, scene {snakemake.wildcards.scene}",  # noqa: F821
                 extra_attrs=attrs, command="snakemake rule histories")
