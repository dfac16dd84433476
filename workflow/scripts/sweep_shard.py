"""Solve one shard of grid points (thin: vcor.study.sweep.solve_points, as vcor.sweep solves a scene)."""

from vcor.io import netcdf, receipts
from vcor.io.joblog import count, job_log, seconds
from vcor.materials import Catalogue
from vcor.solvers.backend import load_kernels
from vcor.study import shards, summary, sweep

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    points, settings = smk.params.points, smk.params.settings
    catalogue = Catalogue(**smk.params.catalogue)
    shards.check_current(points, catalogue, smk.wildcards.shard)
    ready = load_kernels([settings["solver"]["method"]])
    log.note(f"numba kernels of method {settings['solver']['method']} ready (loaded or compiled) in {seconds(ready)}",
             timed=False)
    ds = sweep.solve_points(points, settings, catalogue)
    netcdf.write_dataset(ds, smk.output.nc, title=sweep.SHARD_TITLE, command="snakemake rule sweep_shard",
                         identity=smk.wildcards.shard)
    log.note(f"solved {count(len(points), 'point')} of scene {smk.wildcards.scene}: {summary.outcome_of(ds).text()}")
    receipts.atomic_text(smk.output.index, shards.index_text(points, settings))
