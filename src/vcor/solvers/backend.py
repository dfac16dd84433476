"""The numba back end seen from outside: every solver kernel, what numba compiled for it, and
loading the kernels a job needs once per machine.

Benchmarks and tests use :func:`compiled_signatures` to check that no kernel is compiled twice (a
literal argument in a call from another kernel, e.g. a constant 0 or True, makes numba compile a
second copy, ~1 s of compile per process for the adaptive march).

Compiled kernels are cached on disk (numba's ``cache=True``: ``NUMBA_CACHE_DIR`` when set, otherwise
``__pycache__`` beside the modules). With an empty cache, parallel workflow jobs would each compile
the same kernels (~6 s for the adaptive method, ~15 s for every method). :func:`load_kernels` runs
one small impact per method a job uses while holding an exclusive lock on a file in that cache
folder: the first job compiles and writes the cache, the others wait and then load it (~0.6 s).
"""

from __future__ import annotations

import contextlib
import fcntl
import os
import time
from pathlib import Path

import numba

from . import _adaptive_kernels, _fixed_kernels, _separation, _step

__all__ = ["KERNEL_MODULES", "LOCK_NAME", "cache_folder", "compiled_signatures", "load_kernels"]

#: the lock file's name in the numba cache folder
LOCK_NAME = "vcor-compile.lock"

#: the modules that hold numba kernels
KERNEL_MODULES = (_step, _fixed_kernels, _adaptive_kernels, _separation)


def compiled_signatures() -> dict[str, list]:
    """{"module.kernel": [type signatures compiled so far in this process]} for every numba kernel."""
    out = {}
    for module in KERNEL_MODULES:
        for name, value in vars(module).items():
            if isinstance(value, numba.core.registry.CPUDispatcher) and value.__module__ == module.__name__:
                out[f"{module.__name__.rsplit('.', 1)[1]}.{name}"] = list(value.signatures)
    return out


def cache_folder() -> Path:
    """Where numba caches vcor's kernels: ``NUMBA_CACHE_DIR`` when set, else ``__pycache__`` beside the
    kernel modules."""
    env = os.environ.get("NUMBA_CACHE_DIR")
    return Path(env) if env else Path(_step.__file__).parent / "__pycache__"


@contextlib.contextmanager
def _compile_lock():
    """An exclusive lock on :data:`LOCK_NAME` in the cache folder, for the block (module docstring)."""
    folder = cache_folder()
    folder.mkdir(parents=True, exist_ok=True)
    with open(folder / LOCK_NAME, "a") as fh:
        fcntl.flock(fh, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(fh, fcntl.LOCK_UN)


def load_kernels(methods) -> float:
    """Compile or load (from numba's cache) the kernels of each solver method in ``methods`` (names of
    :data:`vcor.solvers.METHODS`) under the machine-wide lock of the module docstring; the seconds it
    took (compile: seconds; load: under one)."""
    from .simulate import simulate

    start = time.perf_counter()
    with _compile_lock():
        for method in dict.fromkeys(methods):
            simulate("sls", 1.0, options={"method": method})
    return time.perf_counter() - start
