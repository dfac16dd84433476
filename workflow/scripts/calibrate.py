"""Calibrate one material to measured COR (thin: vcor.fitting.calibrate); writes the record twice: the
calibration and the material file a scene reads by name."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

from vcor.fitting import calibrate
from vcor.io import netcdf
from vcor.materials import Catalogue

name = snakemake.wildcards.cal  # noqa: F821
spec = snakemake.params.spec  # noqa: F821
cal = calibrate.run_calibration(spec, catalogue=Catalogue(**snakemake.params.catalogue), where=f"calibrations.{name}")  # noqa: F821
print(cal.report(), file=sys.stderr)
ds = calibrate.calibration_dataset(cal, spec)
for path in (snakemake.output.record, snakemake.output.material):  # noqa: F821
    netcdf.write_dataset(ds, path, title=f"vcor calibration {name}", command="vcor.calibrate", timestamp=False)
