"""Fit materials to their data and write each one's <name>.nc and text table (thin; deterministic bytes).
One material (rule fit_material) or the members of a fit family (rules fit_family_*)."""

from vcor.fitting import fits
from vcor.io import netcdf, receipts
from vcor.io.joblog import brief, job_log, seconds

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    params = smk.params
    ncs, tables = ([f] if isinstance(f, str) else list(f) for f in (smk.output.nc, smk.output.table))
    for name, spec, identity, nc, table_file in zip(params.names, params.specs, params.identities, ncs, tables,
                                                    strict=True):
        result, data, attrs = fits.run_fit(spec)
        log.note(f"fitted {name} in {seconds(result.fit_time)}: {brief(result.settings)}", timed=False)
        ds = fits.result_dataset(result, data, spec)
        ds.attrs.update(attrs, material_name=name)
        netcdf.write_dataset(ds, nc, title=f"vcor fitted material {name}", timestamp=False,
                             command="vcor.fitting.fits (deterministic: no time stamp)", identity=identity)
        metrics = fits.metrics_table([(name, result.material, result.metrics)])
        table = f"# {name}: {result.material.to_dict()}\n" + metrics
        receipts.atomic_text(table_file, table)
        log.note(f"wrote {nc}, {table_file}")
