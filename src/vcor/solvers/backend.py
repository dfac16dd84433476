"""The numba back end seen from outside: every solver kernel, what numba compiled for it, and
loading the kernels a job needs once per machine.

Benchmarks and tests use :func:`compiled_signatures` to check that no kernel is compiled twice (a
literal argument in a call from another kernel, e.g. a constant 0 or True, makes numba compile a
second copy, ~1 s of compile per process for the adaptive march).

Compiled kernels are cached on disk (numba's ``cache=True``, in a folder per version of the kernel sources
inside ``NUMBA_CACHE_DIR`` when set, otherwise inside ``__pycache__`` beside the modules: ``_jit``). With an
empty cache, parallel workflow jobs would each compile the same kernels (~7 s for the adaptive method, ~11 s
for every method). :func:`load_kernels` runs one small impact per method a job uses while holding an exclusive
lock on that method's file in the cache folder: the first job compiles a method's kernels and writes the
cache, the others wait and then load them (~0.3 s); two jobs compile two different methods at the same time.
(A kernel that two methods share may then be compiled twice; numba writes its cache files atomically.) The
workflow also compiles each method in a job of its own (rule ``kernels``) before the jobs that use it, so that
waiting for a compile leaves no core idle while jobs without kernels (fits) could run.
"""

from __future__ import annotations

import contextlib
import fcntl
import time
from pathlib import Path

import numba

from . import _adaptive_kernels, _fixed_kernels, _jit, _separation, _step, erfcx

__all__ = ["KERNEL_MODULES", "KERNEL_SOURCES", "cache_folder", "compiled_signatures", "load_kernels", "lock_name"]

#: the modules that hold numba kernels
KERNEL_MODULES = (_step, _fixed_kernels, _adaptive_kernels, _separation, erfcx)
#: the files whose hash names the kernels' cache folder (:func:`cache_folder`)
KERNEL_SOURCES = _jit.KERNEL_SOURCES


def compiled_signatures() -> dict[str, list]:
    """{"module.kernel": [type signatures compiled so far in this process]} for every numba kernel."""
    out = {}
    for module in KERNEL_MODULES:
        for name, value in vars(module).items():
            if isinstance(value, numba.core.registry.CPUDispatcher) and value.__module__ == module.__name__:
                out[f"{module.__name__.rsplit('.', 1)[1]}.{name}"] = list(value.signatures)
    return out


def cache_folder() -> Path:
    """Where numba caches vcor's kernels (``_jit.cache_folder``: a folder per version of the kernel sources in
    ``NUMBA_CACHE_DIR`` when set, else in ``__pycache__`` beside the kernel modules)."""
    return _jit.cache_folder()


def lock_name(method: str) -> str:
    """The name of the lock file of ``method``'s kernels in the numba cache folder."""
    return f"vcor-compile-{method}.lock"


@contextlib.contextmanager
def _compile_lock(method: str):
    """An exclusive lock on ``method``'s lock file in the cache folder, for the block (module docstring)."""
    folder = cache_folder()
    folder.mkdir(parents=True, exist_ok=True)
    with open(folder / lock_name(method), "a") as fh:
        fcntl.flock(fh, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(fh, fcntl.LOCK_UN)


def load_kernels(methods) -> float:
    """Compile or load (from numba's cache) the kernels of each solver method in ``methods`` (names of
    :data:`vcor.solvers.METHODS`), each under its machine-wide lock (module docstring); the seconds it
    took (compile: seconds; load: under one)."""
    from .simulate import simulate

    start = time.perf_counter()
    for method in dict.fromkeys(methods):
        with _compile_lock(method):
            simulate("sls", 1.0, options={"method": method})
    return time.perf_counter() - start
