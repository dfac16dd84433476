"""Impact solvers: one front end, :func:`simulate`, and a table of methods (``METHODS``).

``adaptive`` (the default) is the product-integration scheme on a variable grid with an
exponential-sum history and Richardson extrapolation; the others are references chosen by name:
``direct`` (full history, O(N^2), the paper's scheme), ``soe`` (fixed step, exponential-sum
history), ``ive`` (internal variables, scipy ``solve_ivp``; Prony kernels), ``ive-numba`` (internal
variables, fixed step; Prony kernels) and ``paper`` (an explicit baseline for benchmarks).

Names are loaded on first use (PEP 562): importing :mod:`vcor.solvers.options` alone does not
import numba. The function is :func:`vcor.simulate`; ``vcor.solvers.simulate`` is always the front-end
module (a package attribute of the same name as a submodule would be replaced by the submodule as
soon as it is imported).
"""

from importlib import import_module

__all__ = ["METHODS", "Histories", "Result", "SolverOptions"]

_NAMES = {"METHODS": "simulate", "Histories": "common", "Result": "common", "SolverOptions": "options"}


def __getattr__(name):
    if name in _NAMES:
        value = getattr(import_module(f"vcor.solvers.{_NAMES[name]}"), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'vcor.solvers' has no attribute {name!r}")
