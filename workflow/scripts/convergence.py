"""Combine the work-precision cases and write the table of observed orders (thin)."""

from vcor.io import netcdf, receipts
from vcor.io.joblog import count, job_log
from vcor.study import convergence

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    spec = smk.params.spec
    mats = spec["materials"]
    per_material = [netcdf.read_dataset(receipts.verified(p)) for p in smk.input]
    cases = {(m, i): ds.isel(v0=i, drop=True) for m, ds in zip(mats, per_material) for i in range(ds.sizes["v0"])}
    ds = convergence.combine(cases, mats, spec["v0"])
    netcdf.write_dataset(ds, smk.output.nc, title="vcor work-precision study", command="snakemake rule convergence",
                         extra_attrs={"convergence_config": spec})
    receipts.atomic_text(smk.output.orders, convergence.orders_table(ds))
    log.note(f"combined the work-precision study of {count(len(mats), 'material')} at "
             f"{count(len(spec['v0']), 'impact speed')}: {smk.output.nc}; observed orders: {smk.output.orders}")
