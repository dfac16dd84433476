"""The Yade script of a dem: entry (thin: vcor.dem.yade)."""

import xarray as xr

from vcor.dem import yade
from vcor.io import receipts
from vcor.io.joblog import job_log

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    yade.write_script(smk.output[0], xr.load_dataset(receipts.verified(smk.input[0])))
    log.note(f"wrote the Yade script {smk.output[0]} from {smk.input[0]}")
