"""The Bagley-Torvik fractional law of order 1/2, E(t) = E0 + E1 / sqrt(pi t) (Green 2026 Eq. 23):
weakly singular at t = 0, integrated exactly over each step."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from .base import Material, Parameter, causal_inline, modulus

__all__ = ["FractionalPower"]

_SQRT_PI = math.sqrt(math.pi)


@dataclass(frozen=True)
class FractionalPower(Material, kind="fractional"):
    """Bagley-Torvik fractional (order 1/2) law, Green 2026 Eq. 23.

    .. math:: E(t) = E_0 + E_1 / \\sqrt{\\pi t}, \\quad E^*(\\omega) = E_0 + E_1 \\sqrt{i\\omega}

    Parameters
    ----------
    E0 : float
        Rubbery modulus, Pa, in [0, 1e20] (:data:`~vcor.materials.base.MAX_MODULUS`).
    E1 : float
        Fractional coefficient, Pa s^0.5, in [0, 1e20] (the same bound).
    """

    TITLE: ClassVar[str] = "fractional, order 1/2 (Bagley-Torvik), Green 2026 Eq. 23"
    FORMULA: ClassVar[str] = "E(t) = E0 + E1 / sqrt(pi t)"
    PARAMETERS: ClassVar[tuple] = (Parameter(name="E0", unit="Pa", meaning="rubbery modulus"),
                                   Parameter(name="E1", unit="Pa s0.5", meaning="fractional coefficient"))

    E0: float
    E1: float

    def __post_init__(self):
        modulus("E0", self.E0, allow_zero=True)
        modulus("E1", self.E1, allow_zero=True, unit="Pa s^0.5")
        if self.E0 + self.E1 <= 0:
            raise ValueError("FractionalPower: E0 + E1 must be > 0")

    @property
    def fastest_rate(self) -> float:
        return math.inf if self.E1 > 0 else 0.0

    def relaxation_modulus(self, t):
        t = np.asarray(t, dtype=float)
        if self.E1 == 0:  # elastic (0 / 0 at t = 0 otherwise)
            return np.full_like(t, float(self.E0))
        with np.errstate(divide="ignore"):
            return self.E0 + self.E1 / np.sqrt(math.pi * t)

    def sqrt_law(self) -> tuple[float, float]:
        return self.E0, self.E1 / _SQRT_PI

    def relaxation_spectrum(self):
        """1/sqrt(pi t) = 1/pi int_0^inf s^-1/2 e^-st ds."""
        e1 = self.E1
        return (lambda t: e1 / np.sqrt(np.pi * t)), (lambda s: e1 / math.pi / np.sqrt(s))

    @causal_inline
    def modulus_at(self, t: float) -> float:
        if t < 0:
            return 0.0
        if t == 0:
            return math.inf if self.E1 > 0 else self.E0
        return self.E0 + self.E1 / math.sqrt(math.pi * t)

    def relaxation_rate(self, t):
        t = np.asarray(t, dtype=float)
        if self.E1 == 0:
            return np.zeros_like(t)
        with np.errstate(divide="ignore"):
            return -0.5 * self.E1 / (_SQRT_PI * t**1.5)

    def complex_modulus(self, omega):
        w = np.asarray(omega, dtype=float)
        return self.E0 + self.E1 * np.sqrt(1j * w)

    def antiderivative(self, t, order: int = 1):
        t = np.asarray(t, dtype=float)
        if order == 1:
            return self.E0 * t + 2.0 * self.E1 * np.sqrt(t / math.pi)
        if order == 2:
            return 0.5 * self.E0 * t**2 + (4.0 / 3.0) * self.E1 * t**1.5 / _SQRT_PI
        raise ValueError(f"order must be 1 or 2, got {order}")

    @property
    def is_elastic(self) -> bool:
        return self.E1 == 0

    def _sqrt_steps(self, dt, n):
        """sqrt(b) - sqrt(a) = dt / (sqrt(a) + sqrt(b)) for the steps [a, b] (no cancellation)."""
        r = np.sqrt(dt * np.arange(n + 1, dtype=float))
        return dt / (r[1:] + r[:-1])

    def step_integrals(self, dt: float, n: int) -> np.ndarray:
        # E0 dt + 2 E1/sqrt(pi) (sqrt(b) - sqrt(a)), the difference taken without cancellation
        return self.E0 * dt + 2.0 * self.E1 / _SQRT_PI * self._sqrt_steps(dt, n)

    def step_moments(self, dt: float, n: int) -> np.ndarray:
        # int_a^b (t - m) dt/sqrt(pi t) = (2/3)(b^1.5 - a^1.5) - 2 m (sqrt b - sqrt a)
        #   = (sqrt b - sqrt a) (2/3) (sqrt(a) sqrt(b) - (a + b)/2) = -(sqrt b - sqrt a)^3 / 3;
        # the E0 part integrates to zero
        return -self.E1 / (3.0 * _SQRT_PI) * self._sqrt_steps(dt, n) ** 3

    def first_step(self, dt):
        # the closed forms of step_integrals and step_moments for one step of each size
        dt = np.asarray(dt, dtype=float)
        sq = dt / np.sqrt(dt)
        return self.E0 * dt + 2.0 * self.E1 / _SQRT_PI * sq, -self.E1 / (3.0 * _SQRT_PI) * sq**3

    def first_step_second_moment(self, dt):
        # int_0^dt ((t - dt/2)^2 - dt^2/12) t^-1/2 dt = dt^2.5 (2/5 - 2/3 + 1/3) = dt^2.5 / 15; E0 gives 0
        dt = np.asarray(dt, dtype=float)
        return self.E1 / (15.0 * _SQRT_PI) * dt**2 * np.sqrt(dt)

    def params(self) -> dict:
        return {"E0": self.E0, "E1": self.E1}

    def _scaled(self, modulus, time):
        # E1 / sqrt(pi t / a) = (E1 sqrt(a)) / sqrt(pi t)
        return FractionalPower(self.E0 * modulus, self.E1 * modulus * math.sqrt(time))
