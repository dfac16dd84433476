"""The numba back end: every compile flag of the solver kernels is set here.

* ``jit``: ``cache=True`` (a fresh process loads compiled kernels from ``__pycache__``, or from
  ``NUMBA_CACHE_DIR``), ``nogil=True``, ``error_model="numpy"`` (a division by zero gives inf/NaN,
  which the marches detect, instead of raising), no ``fastmath``;
* ``jit_inline``: the same, inlined into the caller at the numba IR level (the implicit step inside
  the adaptive march, where the call and its arguments were a measurable share of an impact);
* ``jit_sum``: the same plus fastmath *reassociation* only, for the two sums over many exponential
  modes of the adaptive march, which numba then vectorises (their order does not matter to the
  result beyond rounding: ``tests/solvers/test_adaptive.py::test_reassociated_sums_are_safe``).

With ``NUMBA_DISABLE_JIT=1`` the kernels run as plain Python (coverage, debugging).
"""

from __future__ import annotations

import numba

__all__ = ["FLAGS", "SUM_FLAGS", "jit", "jit_inline", "jit_sum"]

FLAGS = {"cache": True, "nogil": True, "error_model": "numpy"}
SUM_FLAGS = {**FLAGS, "fastmath": {"reassoc"}}


def jit(fn):
    """Compile ``fn`` in nopython mode with :data:`FLAGS`."""
    return numba.njit(**FLAGS)(fn)


def jit_inline(fn):
    """Compile ``fn`` to be inlined into its numba callers (numba ``inline="always"``)."""
    return numba.njit(inline="always", **FLAGS)(fn)


def jit_sum(fn):
    """Compile ``fn`` with :data:`SUM_FLAGS` (reassociated additions)."""
    return numba.njit(**SUM_FLAGS)(fn)
