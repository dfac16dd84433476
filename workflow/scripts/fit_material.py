"""Fit materials to their data and write each one's <name>.nc and text table (thin: vcor.fit; deterministic
bytes). One material (rule fit_material) or the members of a fit family (rules fit_family_*)."""

import vcor
from vcor.io.joblog import brief, job_log, seconds

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    params = smk.params
    ncs, tables = ([f] if isinstance(f, str) else list(f) for f in (smk.output.nc, smk.output.table))
    for name, spec, identity, nc, table_file in zip(params.names, params.specs, params.identities, ncs, tables,
                                                    strict=True):
        fitted = vcor.fit(spec, name=name)
        log.note(f"fitted {name} in {seconds(fitted.result.fit_time)}: {brief(fitted.result.settings)}", timed=False)
        fitted.write(nc, table=table_file, identity=identity)
        log.note(f"wrote {nc}, {table_file}")
