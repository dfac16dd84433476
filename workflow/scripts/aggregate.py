"""Combine a scene's shards into results/<scene>/sweep.nc (thin: vcor.study.aggregation)."""

from pathlib import Path

from vcor.io import netcdf, receipts
from vcor.io.joblog import count, job_log
from vcor.materials import Catalogue
from vcor.study import aggregation, summary
from vcor.study.grid import Grid

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    cfg, catalogue = smk.params.scene, Catalogue(**smk.params.catalogue)
    # every shard is checked against its receipt (its bytes and its id) before it is used
    shards = [netcdf.read_dataset(receipts.verified(p, Path(p).stem)) for p in smk.input.shards]
    # row i of shard k is grid point rows[k][i]: the plan's join, not a lookup of values read back
    ds = aggregation.aggregate(shards, smk.params.rows, Grid.from_dict(smk.params.grid), cfg, catalogue)
    attrs = aggregation.dataset_attrs(smk.wildcards.scene, cfg, catalogue)
    netcdf.write_dataset(ds, smk.output[0], title=f"vcor sweep, scene {smk.wildcards.scene}", extra_attrs=attrs,
                         command="snakemake rule aggregate")
    done = summary.outcome_of(ds)
    log.note(f"combined {count(len(shards), 'shard')} of scene {smk.wildcards.scene} into {smk.output[0]}: "
             f"{count(done.points, 'point')}, {done.text()}")
