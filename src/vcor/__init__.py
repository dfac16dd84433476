"""vcor: the viscoelastic coefficient of restitution (Green 2026; Ramirez et al. 1999)."""

from . import materials
from .options import SolverOptions
from .solvers import Result, simulate

__version__ = "0.1.0"
__all__ = ["Result", "SolverOptions", "__version__", "materials", "simulate"]
