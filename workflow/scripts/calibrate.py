"""Calibrate one material to measured COR (thin: vcor.calibrate); writes the record twice: the calibration
and the material file a scene reads by name."""

import sys

import vcor
from vcor.io.joblog import job_log
from vcor.materials import Catalogue

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    name, spec = smk.wildcards.cal, smk.params.spec
    calibrated = vcor.calibrate(spec, name=name, config=Catalogue(**smk.params.catalogue))
    print(calibrated.report(), file=sys.stderr)
    for path in (smk.output.record, smk.output.material):
        calibrated.write(path, identity=smk.params.identity)
    log.note(f"calibrated {name} to {spec['data']}: {smk.output.record}, {smk.output.material}")
