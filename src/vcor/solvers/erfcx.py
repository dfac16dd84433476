"""erfcx(x) = exp(x^2) erfc(x) and its slope for the march (the CERF law's plate mobility, evaluated at
every node of every grid).

Below SWITCH: a piecewise polynomial, one per interval of width WIDTH, of degree DEGREE in
tau = 2 (x - centre) / WIDTH in [-1, 1]: the interpolant at DEGREE + 1 Chebyshev nodes, in powers of tau
(evaluated by Estrin's scheme). Its relative error against scipy.special.erfcx is below 3e-15 on
[0, SWITCH) (``tests/solvers/test_erfcx.py``); libm's exp(x^2) erfc(x) is slower, and its exp
carries the rounding of x^2 (relative x^2 eps, 7e-14 at the switch). The node values are
exp(x^2) erfc(x) with x^2 split exactly into two doubles (Veltkamp/Dekker), so that only libm's own
rounding enters. Above SWITCH: the asymptotic series 1 / (x sqrt(pi)) sum_n (-1)^n (2n - 1)!! / (2 x^2)^n,
TERMS terms (truncation below 1e-17 at the switch).

The table is built at import from the standard library's erfc (no scipy: a Prony-only run does not load
scipy.special); numba takes it into the compiled march as a constant, so that numba's disk cache, keyed
on the march's own module, does not see a change of this table: after editing this module, clear the
cache (``vcor.solvers.backend.cache_folder``).
"""

from __future__ import annotations

import math

import numpy as np

from ._jit import jit_inline

__all__ = ["DEGREE", "SWITCH", "TABLE", "TERMS", "WIDTH", "erfcx_slope", "erfcx_table"]

SWITCH = 25.0
WIDTH = 0.25
DEGREE = 10
TERMS = 8
_TWO_OVER_SQRT_PI = 2.0 / math.sqrt(math.pi)
_SQRT_PI = math.sqrt(math.pi)
_SPLIT = 134217729.0  # 2^27 + 1 (Veltkamp)


def _erfcx_at(x: float) -> float:
    """exp(x^2) erfc(x) with x^2 = hi + lo exactly (Dekker's product), exp(hi + lo) = exp(hi) (1 + lo)."""
    c = _SPLIT * x
    xh = c - (c - x)
    xl = x - xh
    hi = x * x
    lo = ((xh * xh - hi) + 2.0 * xh * xl) + xl * xl
    return math.exp(hi) * (1.0 + lo) * math.erfc(x)


def erfcx_table(width: float = WIDTH, degree: int = DEGREE, switch: float = SWITCH) -> np.ndarray:
    """Coefficients (interval, power of tau) of the piecewise interpolant of erfcx (module docstring): row i
    on [i width, (i + 1) width], tau = 2 (x - (i + 1/2) width) / width, lowest power first. ``switch`` must
    be a whole number of intervals."""
    if not (isinstance(width, float | int) and 0.0 < width <= 1.0):
        raise ValueError(f"width must be in (0, 1], got {width!r}")
    if not (isinstance(degree, int) and 1 <= degree <= 20):
        raise ValueError(f"degree must be an integer in [1, 20], got {degree!r}")
    n = round(switch / width) if isinstance(switch, float | int) and switch > 0 else 0
    if not (n >= 1 and n * width == switch):
        raise ValueError(f"switch must be a positive whole multiple of width = {width!r}, got {switch!r}")
    nodes = np.cos(np.pi * (np.arange(degree + 1) + 0.5) / (degree + 1))  # Chebyshev nodes in [-1, 1]
    centres = (np.arange(n) + 0.5) * width
    values = np.array([[_erfcx_at(float(c + 0.5 * width * t)) for t in nodes] for c in centres])
    # values -> Chebyshev coefficients (the interpolation matrix is the same on every interval) -> powers
    to_cheb = np.linalg.inv(np.polynomial.chebyshev.chebvander(nodes, degree))
    to_power = np.zeros((degree + 1, degree + 1))
    for k in range(degree + 1):  # column k: T_k in powers of tau
        power = np.polynomial.chebyshev.cheb2poly(np.eye(degree + 1)[k])
        to_power[: power.size, k] = power
    # in two products: their product as one matrix would mix T_10's large power coefficients (512) into
    # every row's rounding (1e-13 instead of 3e-15)
    return np.ascontiguousarray((values @ to_cheb.T) @ to_power.T)


TABLE = erfcx_table()
assert DEGREE == 10  # erfcx_slope's Estrin scheme is written out for degree 10
_SCALE = 2.0 / WIDTH


@jit_inline
def erfcx_slope(x):
    """(erfcx(x), erfcx'(x)) for x >= 0 (NaN for x < 0, which the march never passes),
    erfcx'(x) = 2 x erfcx(x) - 2 / sqrt(pi). Above the switch the slope
    is 2 / sqrt(pi) times the series' terms after the first (about -1 / (sqrt(pi) x^2)): subtracting the two
    O(1) numbers there would leave rounding, relative 2 x^2 eps, and nothing at all from x ~ 1e8 on (the
    CERF law of a fitted material with b1 ~ 1e10 1/s reaches x ~ 1e8 within the contact)."""
    if 0.0 <= x < SWITCH:  # (NaN: the series, NaN out)
        i = int(x * (0.5 * _SCALE))
        tau = x * _SCALE - (2.0 * i + 1.0)
        # Estrin's scheme (four dependent multiply-adds, not Horner's ten: the march waits on this chain)
        t2 = tau * tau
        t4 = t2 * t2
        q0 = (TABLE[i, 0] + TABLE[i, 1] * tau) + (TABLE[i, 2] + TABLE[i, 3] * tau) * t2
        q1 = (TABLE[i, 4] + TABLE[i, 5] * tau) + (TABLE[i, 6] + TABLE[i, 7] * tau) * t2
        q2 = (TABLE[i, 8] + TABLE[i, 9] * tau) + TABLE[i, 10] * t2
        ex = q0 + (q1 + q2 * t4) * t4
        return ex, 2.0 * x * ex - _TWO_OVER_SQRT_PI
    if x < 0.0:
        return math.nan, math.nan
    inv = 1.0 / (2.0 * x * x)
    term = 1.0
    tail = 0.0
    for n in range(1, TERMS):
        term *= -(2.0 * n - 1.0) * inv
        tail += term
    return (1.0 + tail) / (x * _SQRT_PI), _TWO_OVER_SQRT_PI * tail
