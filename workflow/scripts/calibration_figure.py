"""Draw a calibration: data, fitted curve with its 95 % band, residuals (thin: vcor.plots)."""

from vcor import plots
from vcor.io import netcdf, receipts
from vcor.io.joblog import job_log

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    cal = netcdf.read_dataset(receipts.verified(smk.input[0]))
    plots.save(plots.calibration(cal), smk.output.png, smk.output.pdf)
    log.note(f"drew {smk.output.png} and {smk.output.pdf} from {smk.input[0]}")
