"""Calibrate one material to measured COR (thin: vcor.fitting.calibrate); writes the record twice: the
calibration and the material file a scene reads by name."""

import sys

from vcor.fitting import calibrate
from vcor.io import netcdf
from vcor.io.joblog import job_log
from vcor.materials import Catalogue

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    name, spec = smk.wildcards.cal, smk.params.spec
    cal = calibrate.run_calibration(spec, catalogue=Catalogue(**smk.params.catalogue), where=f"calibrations.{name}")
    print(cal.report(), file=sys.stderr)
    ds = calibrate.calibration_dataset(cal, spec)
    for path in (smk.output.record, smk.output.material):
        netcdf.write_dataset(ds, path, title=f"vcor calibration {name}", command="vcor.fitting.calibrate",
                             timestamp=False, identity=smk.params.identity)
    log.note(f"calibrated {name} to {spec['data']}: {smk.output.record}, {smk.output.material}")
