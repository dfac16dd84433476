"""The Mittag-Leffler relaxation of order 1/2, the 'CERF' law E(t) = E0 + E1 erfcx(b1 sqrt(t))
(Green 2026 Eqs. 24-25), with antiderivatives that stay accurate where the closed form cancels."""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ..checks import positive as _positive
from .base import Material, Parameter, causal_inline, modulus

__all__ = ["Cerf"]

_SQRT_PI = math.sqrt(math.pi)


def erfcx(x):
    """:func:`scipy.special.erfcx` (scipy loads on first use: the workflow's planning imports the
    material classes, not their numerics)."""
    return _scipy_erfcx()(x)


@functools.cache
def _scipy_erfcx():
    """scipy's erfcx ufunc, imported once (an import statement in every call costs 0.5 us, and a CERF impact makes nine:
    ``modulus_at`` in the contact-time estimate and the validity check)."""
    from scipy.special import erfcx as f

    return f


@functools.cache
def _gamma_half():
    """Gamma(n/2 + 1) for n = 0..79 (scipy's values, computed on first use)."""
    from scipy.special import gamma

    return gamma(np.arange(80) / 2 + 1)


def _erfcx_tail(x, start: int):
    """sum_{n >= start} (-x)^n / Gamma(n/2 + 1): erfcx(x) minus its first Taylor terms.

    Closed form for x >= 0.2, the (absolutely convergent) series below, where the
    closed form would cancel.
    """
    shape = np.shape(x)
    x = np.atleast_1d(np.asarray(x, dtype=float))
    head = np.zeros_like(x)
    for n in range(start):
        head = head + (-x) ** n / _gamma_half()[n]
    out = np.asarray(erfcx(x) - head)
    small = x < 0.2
    if np.any(small):
        xs = x[small]
        series = np.zeros_like(xs)
        for n in range(start, start + 30):
            series = series + (-xs) ** n / _gamma_half()[n]
        out[small] = series
    return out.reshape(shape)


@dataclass(frozen=True)
class Cerf(Material, kind="cerf"):
    """Mittag-Leffler (order 1/2) relaxation, the 'CERF' law of Green 2026 Eq. 24-25.

    .. math:: E(t) = E_0 + E_1\\,\\mathrm{erfcx}(b_1\\sqrt t), \\quad
              E^*(\\omega) = E_0 + E_1 \\sqrt{i\\omega}/(\\sqrt{i\\omega} + b_1)

    ``erfcx`` is :func:`scipy.special.erfcx` (the paper's CERF, Appendix Eq. A3).

    Parameters
    ----------
    E0 : float
        Rubbery modulus, Pa, in [0, 1e20] (:data:`~vcor.materials.base.MAX_MODULUS`).
    E1 : float
        Relaxing part, Pa, in [0, 1e20] (glassy modulus E0 + E1).
    b1 : float
        Rate parameter, s^-1/2 ... in the paper's units "1/s" with x = b1 sqrt(t);
        b1^2 is a rate in 1/s. Must be > 0.
    """

    TITLE: ClassVar[str] = "Mittag-Leffler, order 1/2 (CERF), Green 2026 Eq. 24"
    FORMULA: ClassVar[str] = "E(t) = E0 + E1 erfcx(b1 sqrt(t))"
    PARAMETERS: ClassVar[tuple] = (Parameter(name="E0", unit="Pa", meaning="rubbery modulus"),
                                   Parameter(name="E1", unit="Pa", meaning="relaxing part (glassy modulus E0 + E1)"),
                                   Parameter(name="b1", unit="s-0.5", meaning="rate parameter (b1^2 is a rate)"))

    E0: float
    E1: float
    b1: float

    def __post_init__(self):
        modulus("E0", self.E0, allow_zero=True)
        modulus("E1", self.E1, allow_zero=True)
        _positive("b1", self.b1, unit="s^-1/2")
        if self.E0 + self.E1 <= 0:
            raise ValueError("Cerf: E0 + E1 must be > 0")

    @property
    def fastest_rate(self) -> float:
        return math.inf if self.E1 > 0 else 0.0

    def relaxation_modulus(self, t):
        t = np.asarray(t, dtype=float)
        return self.E0 + self.E1 * erfcx(self.b1 * np.sqrt(t))

    def erfcx_law(self) -> tuple[float, float, float]:
        return float(self.E0), float(self.E1), float(self.b1)

    def relaxation_spectrum(self):
        """erfcx(b1 sqrt t) = b1/pi int_0^inf e^-st / (s^1/2 (s + b1^2)) ds."""
        e1, b = self.E1, self.b1
        return (lambda t: e1 * erfcx(b * np.sqrt(t))), (lambda s: e1 * b / math.pi / (np.sqrt(s) * (s + b * b)))

    @causal_inline
    def modulus_at(self, t: float) -> float:
        if t < 0:
            return 0.0
        return self.E0 + self.E1 * float(erfcx(self.b1 * math.sqrt(t)))

    def relaxation_rate(self, t):
        """dE/dt = E1 (b1 / sqrt t) (x erfcx(x) - 1/sqrt(pi)), x = b1 sqrt t.

        x erfcx(x) - 1/sqrt(pi) cancels for large x (relative error eps x^2, 25 % at x = 5e7);
        there its asymptotic series (1/sqrt(pi)) sum_{n>=1} (-1)^n (2n-1)!! / (2 x^2)^n is used.
        """
        t = np.asarray(t, dtype=float)
        x = self.b1 * np.sqrt(t)
        with np.errstate(divide="ignore", invalid="ignore"):
            h = x * erfcx(x) - 1.0 / _SQRT_PI
            big = x > 8.0
            if np.any(big):
                y = 1.0 / (2.0 * np.where(big, x, 8.0) ** 2)
                term = np.ones_like(y)
                series = np.zeros_like(y)
                for n in range(1, 30):
                    term = -term * (2 * n - 1) * y
                    series = series + term
                h = np.where(big, series / _SQRT_PI, h)
            r = self.E1 * self.b1 / np.sqrt(t) * h
        return np.where(t > 0, r, -np.inf)

    def complex_modulus(self, omega):
        w = np.sqrt(1j * np.asarray(omega, dtype=float))
        return self.E0 + self.E1 * w / (w + self.b1)

    def antiderivative(self, t, order: int = 1):
        t = np.asarray(t, dtype=float)
        b1 = np.float64(self.b1)  # b1^4 of a b1 above 1e77 is inf (the term 0), not Python's OverflowError
        x = b1 * np.sqrt(t)
        with np.errstate(over="ignore"):
            if order == 1:
                return self.E0 * t + self.E1 * _erfcx_tail(x, 2) / b1**2
            if order == 2:
                return 0.5 * self.E0 * t**2 + self.E1 * _erfcx_tail(x, 4) / b1**4
        raise ValueError(f"order must be 1 or 2, got {order}")

    @property
    def is_elastic(self) -> bool:
        return self.E1 == 0

    def params(self) -> dict:
        return {"E0": float(self.E0), "E1": float(self.E1), "b1": float(self.b1)}

    def _scaled(self, modulus, time):
        # erfcx(b1 sqrt(t / a)) = erfcx((b1 / sqrt(a)) sqrt(t))
        return Cerf(self.E0 * modulus, self.E1 * modulus, self.b1 / math.sqrt(time))
