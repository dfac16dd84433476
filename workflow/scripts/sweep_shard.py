"""Solve one shard of grid points (thin: vcor.study.runner does the work)."""

from vcor.io import netcdf, receipts
from vcor.io.joblog import count, job_log, seconds
from vcor.materials import Catalogue
from vcor.solvers.backend import load_kernels
from vcor.study import runner, scene, shards, summary

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    points, settings = smk.params.points, smk.params.settings
    catalogue = Catalogue(**smk.params.catalogue)
    ready = load_kernels([settings["solver"]["method"]])
    log.note(f"numba kernels of method {settings['solver']['method']} ready (loaded or compiled) in {seconds(ready)}",
             timed=False)
    ds = runner.run_points(points, settings, catalogue)
    attrs = {"settings": settings, "materials": scene.material_params(sorted({p["material"] for p in points}),
                                                                        catalogue)}
    netcdf.write_dataset(ds, smk.output.nc, title="vcor sweep shard", extra_attrs=attrs,
                         command="snakemake rule sweep_shard", identity=smk.wildcards.shard)
    log.note(f"solved {count(len(points), 'point')} of scene {smk.wildcards.scene}: {summary.outcome_of(ds).text()}")
    receipts.atomic_text(smk.output.index, shards.index_text(points, settings))
