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

The compiled kernels are cached in :func:`cache_folder`, a folder named by a hash of every kernel source
(:data:`KERNEL_SOURCES`) inside ``NUMBA_CACHE_DIR`` (or ``__pycache__`` beside the modules). numba checks a
cached kernel against its own file only, not against the kernels it calls from other files: after an
update of ``_separation.py`` alone, ``adaptive_grids`` (``_adaptive_kernels.py``) would load its old
compiled code, with the old separation in it, and give the old numbers. A changed kernel source names a
new folder, so every kernel is compiled again.
"""

from __future__ import annotations

import functools
import hashlib
import os
from pathlib import Path

import numba

__all__ = ["FLAGS", "KERNEL_SOURCES", "SUM_FLAGS", "cache_folder", "jit", "jit_inline", "jit_sum", "kernel_stamp"]

FLAGS = {"cache": True, "nogil": True, "error_model": "numpy"}
SUM_FLAGS = {**FLAGS, "fastmath": {"reassoc"}}
#: the files (in this folder) whose code the numba kernels hold: the kernels and everything they call
KERNEL_SOURCES = ("_jit.py", "_records.py", "_step.py", "_separation.py", "_adaptive_kernels.py", "_fixed_kernels.py",
                  "erfcx.py")


@functools.lru_cache(maxsize=1)
def kernel_stamp() -> str:
    """12 hex digits of the SHA-256 of :data:`KERNEL_SOURCES` (module docstring)."""
    h = hashlib.sha256()
    for name in KERNEL_SOURCES:
        h.update((Path(__file__).parent / name).read_bytes())
    return h.hexdigest()[:12]


def cache_folder() -> Path:
    """Where numba caches vcor's kernels: ``vcor-kernels-<kernel_stamp>`` in ``NUMBA_CACHE_DIR`` when it is
    set, else in ``__pycache__`` beside the kernel modules (module docstring)."""
    base = os.environ.get("NUMBA_CACHE_DIR") or Path(__file__).parent / "__pycache__"
    return Path(base) / f"vcor-kernels-{kernel_stamp()}"


def _njit(fn, **options):
    """numba.njit(**options)(fn) with its cache in :func:`cache_folder` (numba chooses a kernel's cache
    folder when it is decorated, from ``numba.config.CACHE_DIR``, which is restored after: other numba
    code in the process keeps its own)."""
    saved = numba.config.CACHE_DIR
    numba.config.CACHE_DIR = str(cache_folder())
    try:
        return numba.njit(**options)(fn)
    finally:
        numba.config.CACHE_DIR = saved


def jit(fn):
    """Compile ``fn`` in nopython mode with :data:`FLAGS`."""
    return _njit(fn, **FLAGS)


def jit_inline(fn):
    """Compile ``fn`` to be inlined into its numba callers (numba ``inline="always"``)."""
    return _njit(fn, inline="always", **FLAGS)


def jit_sum(fn):
    """Compile ``fn`` with :data:`SUM_FLAGS` (reassociated additions)."""
    return _njit(fn, **SUM_FLAGS)
