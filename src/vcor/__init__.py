"""vcor: the viscoelastic coefficient of restitution (Green 2026; Ramirez et al. 1999).

Names are loaded on first use (PEP 562), so that a process that only draws figures or fits a
material does not import the numba solvers (workflow jobs start faster).
"""

from importlib import import_module

__version__ = "0.1.0"
__all__ = ["Result", "SolverOptions", "__version__", "materials", "simulate"]

_NAMES = {"Result": "vcor.solvers", "simulate": "vcor.solvers", "SolverOptions": "vcor.options"}
_MODULES = ("checks", "cli", "convergence", "datasets", "fit", "impact", "io", "materials", "options", "plots",
            "provenance", "runner", "scene", "shards", "soe", "solvers", "spheres", "status")


def __getattr__(name):
    if name in _NAMES:
        value = getattr(import_module(_NAMES[name]), name)
        globals()[name] = value  # loaded once: later look-ups do not come here (~1 us per vcor.simulate call)
        return value
    if name in _MODULES:
        return import_module(f"vcor.{name}")
    raise AttributeError(f"module 'vcor' has no attribute {name!r}")
