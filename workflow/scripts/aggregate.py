"""Combine a scene's shards into results/<scene>/sweep.nc (thin: vcor.study.sweep.combine, as vcor.sweep does)."""

from pathlib import Path

from vcor.io import netcdf, receipts
from vcor.io.joblog import count, job_log
from vcor.materials import Catalogue
from vcor.study import summary, sweep
from vcor.study.grid import Grid

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    name, catalogue = smk.wildcards.scene, Catalogue(**smk.params.catalogue)
    # every shard is checked against its receipt (its bytes and its id) before it is used
    shards = [netcdf.read_dataset(receipts.verified(p, Path(p).stem)) for p in smk.input.shards]
    # row i of shard k is grid point rows[k][i]: the plan's join, not a lookup of values read back
    archive = sweep.combine(name, smk.params.scene, Grid.from_dict(smk.params.grid), shards, smk.params.rows,
                            catalogue)
    archive.write(smk.output[0], command="snakemake rule aggregate")
    done = summary.outcome_of(archive.dataset)
    log.note(f"combined {count(len(shards), 'shard')} of scene {name} into {smk.output[0]}: "
             f"{count(done.points, 'point')}, {done.text()}")
