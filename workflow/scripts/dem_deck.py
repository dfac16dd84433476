"""The LAMMPS deck of a dem: entry (thin: vcor.dem.lammps)."""

import xarray as xr

from vcor.dem import lammps
from vcor.io import receipts
from vcor.io.joblog import job_log

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    lammps.write_deck(smk.output[0], xr.load_dataset(receipts.verified(smk.input[0])))
    log.note(f"wrote the LAMMPS deck {smk.output[0]} from {smk.input[0]}")
