"""Compile (or load) every numba kernel once (thin: vcor.solvers.simulate.compile_kernels)."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

from vcor.solvers.simulate import compile_kernels

compile_kernels()
