"""The standard linear solid (Zener material): a one-term Prony series named by its glassy modulus and
two rates (Green 2026 Eqs. 13-14)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from ..checks import positive as _positive
from .base import Parameter, modulus
from .prony import Prony

__all__ = ["SLS"]


@dataclass(frozen=True, init=False)
class SLS(Prony, kind="sls"):
    """Standard linear solid (Zener material), Green 2026 Eq. 13.

    .. math:: E(t) = E_g [\\alpha/\\beta + (1 - \\alpha/\\beta) e^{-\\beta t}],
              \\quad E^*(\\omega) = E_g (\\alpha + i\\omega)/(\\beta + i\\omega)

    Parameters
    ----------
    E_glassy : float
        Glassy modulus E_g, Pa, in (0, 1e20] (:data:`~vcor.materials.base.MAX_MODULUS`).
    alpha, beta : float
        Rates in 1/s with 0 <= alpha <= beta; rubbery modulus E_g alpha/beta.
        beta = 0 (then alpha must be 0) is the elastic limit E(t) = E_g used by the
        paper's check against Zener.
    """

    TITLE: ClassVar[str] = "standard linear solid (Zener), Green 2026 Eq. 13"
    FORMULA: ClassVar[str] = "E(t) = E_glassy [alpha/beta + (1 - alpha/beta) exp(-beta t)]"
    PARAMETERS: ClassVar[tuple] = (Parameter(name="E_glassy", unit="Pa", meaning="glassy modulus E(0)"),
                                   Parameter(name="alpha", unit="s-1",
                                             meaning="rate with rubbery modulus E_glassy alpha/beta"),
                                   Parameter(name="beta", unit="s-1", meaning="relaxation rate"))

    E_glassy: float = 0.0
    alpha: float = 0.0

    def __init__(self, E_glassy: float, alpha: float, beta: float):
        eg = modulus("E_glassy", E_glassy)
        a = _positive("alpha", alpha, allow_zero=True, unit="1/s")
        b = _positive("beta", beta, allow_zero=True, unit="1/s")
        if a > b:
            raise ValueError(
                f"SLS alpha must be in [0, beta] = [0, {b}] 1/s (alpha > beta makes the "
                f"relaxation modulus increase), got {a}"
            )
        ratio = a / b if b > 0 else 0.0
        object.__setattr__(self, "E_glassy", eg)
        object.__setattr__(self, "alpha", a)
        object.__setattr__(self, "E_inf", eg * ratio)
        object.__setattr__(self, "E", (eg * (1.0 - ratio),))
        object.__setattr__(self, "beta", (b,))
        Prony.__post_init__(self)

    def params(self) -> dict:
        return {"E_glassy": self.E_glassy, "alpha": self.alpha, "beta": self.beta[0]}

    def _scaled(self, modulus, time):
        return SLS(self.E_glassy * modulus, self.alpha / time, self.beta[0] / time)
