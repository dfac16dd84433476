"""Draw a dem: entry: vcor's COR against each DEM law's, and the error (thin: vcor.plots)."""

from vcor import plots
from vcor.io import netcdf, receipts
from vcor.io.joblog import job_log

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    plots.save(plots.dem(netcdf.read_dataset(receipts.verified(smk.input[0]))), smk.output.png, smk.output.pdf)
    log.note(f"drew {smk.output.png} and {smk.output.pdf} from {smk.input[0]}")
