"""The Kelvin-Voigt solid, E(t) = E [1 + tau delta(t)]: an elastic spring with a Dirac (viscous) term,
the sphere model of Ramirez et al. 1999."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ..checks import positive as _positive
from .base import Material, Parameter, modulus

__all__ = ["KelvinVoigt"]


@dataclass(frozen=True)
class KelvinVoigt(Material, kind="kelvin-voigt"):
    """Kelvin-Voigt solid, E(t) = E [1 + tau delta(t)]: sigma = E (eps + tau eps').

    In the contact law this gives F = k (u + tau u'), Ramirez et al. 1999 Eq. 3 with
    their dissipative constant A = tau.

    Parameters
    ----------
    E : float
        Elastic modulus, Pa, in (0, 1e20] (:data:`~vcor.materials.base.MAX_MODULUS`).
    tau : float
        Retardation time, s, >= 0.
    """

    TITLE: ClassVar[str] = "Kelvin-Voigt, Ramirez et al. 1999 Eq. 3 (A = tau)"
    FORMULA: ClassVar[str] = "E(t) = E [1 + tau delta(t)]"
    PARAMETERS: ClassVar[tuple] = (Parameter(name="E", unit="Pa", meaning="elastic modulus"),
                                   Parameter(name="tau", unit="s", meaning="retardation time"))

    E: float
    tau: float

    def __post_init__(self):
        modulus("E", self.E)
        _positive("tau", self.tau, allow_zero=True, unit="s")

    @property
    def viscosity(self) -> float:  # type: ignore[override]
        return self.E * self.tau

    @property
    def is_elastic(self) -> bool:
        return self.tau == 0

    @property
    def is_prony(self) -> bool:
        """A Prony series with no relaxing terms plus the Dirac term: the internal-variable solvers
        take it (the viscous force is treated with the local, implicit term)."""
        return True

    def prony_terms(self):
        return float(self.E), np.zeros(0), np.zeros(0)

    def relaxation_modulus(self, t):
        """Regular part of E(t) (the Dirac term is ``viscosity``)."""
        return np.full_like(np.asarray(t, dtype=float), self.E)

    def relaxation_rate(self, t):
        return np.zeros_like(np.asarray(t, dtype=float))

    def complex_modulus(self, omega):
        return self.E * (1.0 + 1j * np.asarray(omega, dtype=float) * self.tau)

    def antiderivative(self, t, order: int = 1):
        t = np.asarray(t, dtype=float)
        if order == 1:
            return self.E * t
        if order == 2:
            return 0.5 * self.E * t**2
        raise ValueError(f"order must be 1 or 2, got {order}")

    def first_step_second_moment(self, dt):
        # a constant regular part: the zero-mean polynomial integrates to 0
        return np.zeros_like(np.asarray(dt, dtype=float))

    def params(self) -> dict:
        return {"E": self.E, "tau": self.tau}

    def _scaled(self, modulus, time):
        # E tau delta(t / a) = E (tau a) delta(t)
        return KelvinVoigt(self.E * modulus, self.tau * time)
