"""Combine the work-precision cases and write the table of observed orders (thin)."""

from vcor.io import netcdf, receipts
from vcor.io.joblog import count, job_log
from vcor.study import convergence, scene_datasets

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    spec = smk.params.spec
    per_material = [netcdf.read_dataset(receipts.verified(p)) for p in smk.input]
    archive = scene_datasets.convergence_archive(spec, per_material)
    archive.write(smk.output.nc, command="snakemake rule convergence")
    receipts.atomic_text(smk.output.orders, convergence.orders_table(archive.dataset))
    log.note(f"combined the work-precision study of {count(len(spec['materials']), 'material')} at "
             f"{count(len(spec['v0']), 'impact speed')}: {smk.output.nc}; observed orders: {smk.output.orders}")
