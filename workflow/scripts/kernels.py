"""Compile, or load from numba's cache, the kernels of one solver method (thin: vcor.solvers.backend)."""

from pathlib import Path

from vcor.io.joblog import job_log
from vcor.solvers.backend import cache_folder, load_kernels

smk = snakemake  # noqa: F821
with job_log(smk) as log:
    method = smk.wildcards.method
    load_kernels([method])
    Path(smk.output[0]).write_text(f"numba kernels of method {method} in {cache_folder()}\n")
    log.note(f"numba kernels of method {method} ready (compiled, or loaded from {cache_folder()})")
