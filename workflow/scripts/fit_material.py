"""Fit one material to its data and write <name>.nc and a text table (thin; deterministic bytes)."""

from vcor.fitting import fits
from vcor.io import netcdf, receipts
from vcor.io.joblog import brief, job_log, seconds

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    name, spec = smk.wildcards.material, smk.params.spec
    result, data, attrs = fits.run_fit(spec)
    log.note(f"fitted {name} in {seconds(result.fit_time)}: {brief(result.settings)}", timed=False)
    ds = fits.result_dataset(result, data, spec)
    ds.attrs.update(attrs, material_name=name)
    netcdf.write_dataset(ds, smk.output.nc, title=f"vcor fitted material {name}", timestamp=False,
                         command="vcor.fitting.fits (deterministic: no time stamp)", identity=smk.params.identity)
    table = f"# {name}: {result.material.to_dict()}\n" + fits.metrics_table([(name, result.material, result.metrics)])
    receipts.atomic_text(smk.output.table, table)
    log.note(f"wrote {smk.output.nc}, {smk.output.table}")
