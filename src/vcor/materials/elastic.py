"""The elastic solid, E(t) = E: a Prony series without terms (the limit every viscoelastic model
reaches without relaxation)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from .base import Parameter, modulus
from .prony import Prony

__all__ = ["Elastic"]


@dataclass(frozen=True, init=False)
class Elastic(Prony, kind="elastic"):
    """Elastic solid, E(t) = E (Pa, in (0, 1e20]: :data:`~vcor.materials.base.MAX_MODULUS`)."""

    TITLE: ClassVar[str] = "elastic"
    FORMULA: ClassVar[str] = "E(t) = E"
    PARAMETERS: ClassVar[tuple] = (Parameter(name="E", unit="Pa", meaning="elastic modulus"),)

    def __init__(self, E: float):
        object.__setattr__(self, "E_inf", modulus("E", E))
        object.__setattr__(self, "E", ())
        object.__setattr__(self, "beta", ())
        Prony.__post_init__(self)

    def params(self) -> dict:
        return {"E": self.E_inf}

    def _scaled(self, modulus, time):
        return Elastic(self.E_inf * modulus)
