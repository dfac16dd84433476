"""The numba back end seen from outside: every solver kernel and what numba compiled for it.

Benchmarks and tests use :func:`compiled_signatures` to check that no kernel is compiled twice (a
literal argument in a call from another kernel, e.g. a constant 0 or True, makes numba compile a
second copy, ~1 s of compile per process for the adaptive march).
"""

from __future__ import annotations

import numba

from . import _adaptive_kernels, _fixed_kernels, _separation, _step

__all__ = ["KERNEL_MODULES", "compiled_signatures"]

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
