"""Impact solvers: ``direct`` (numba, any kernel), ``ive`` (scipy solve_ivp) and ``ive-numba``."""

from .common import STATUS_CODES, Histories, Result
from .simulate import METHODS, default_dt, simulate

__all__ = ["simulate", "Result", "Histories", "STATUS_CODES", "METHODS", "default_dt"]
