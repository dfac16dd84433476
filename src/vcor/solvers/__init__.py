"""Impact solvers: ``direct`` (numba, any kernel), ``ive`` (scipy solve_ivp) and ``ive-numba``."""

from ..options import SolverOptions
from ..status import STATUS_CODES
from .common import Histories, Result
from .simulate import METHODS, default_dt, simulate

__all__ = ["METHODS", "STATUS_CODES", "Histories", "Result", "SolverOptions", "default_dt", "simulate"]
