"""Two bodies' moduli combined pointwise in time, as Green 2026 Eq. 1 writes it (the contact modulus of
a viscoelastic sphere on a viscoelastic plate)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from ..checks import positive as _positive
from .base import GL_NODES, GL_WEIGHTS, Material, Parameter, causal_inline

__all__ = ["EqOne"]


@dataclass(frozen=True)
class EqOne(Material, kind="eq1"):
    """Two bodies' plane-strain moduli combined pointwise in time, as Green 2026 Eq. 1 writes it:

    .. math:: E'(t) = \\frac{E'_a(t) E'_b(t)}{E'_a(t) + E'_b(t)}, \\quad E'_i = c_i E_i(t), \\; c_i = 1/(1 - \\nu_i^2)

    This is *not* the viscoelastic series combination (compliances adding in the Laplace domain,
    :func:`vcor.contact.bodies.series_modulus`); the two agree when one body is rigid, both are elastic, or
    both are the same material (E'/2), and differ in between (the documentation, user guide "Bodies").
    E'(t) has no closed form for its step integrals or its complex modulus: steps are integrated by
    Gauss-Legendre (the base class), the antiderivatives by composite Gauss-Legendre on a grid graded
    towards t = 0; the fast solvers carry it as an exponential sum fitted on their time window
    (:mod:`vcor.materials.expfit`). Kelvin-Voigt (Dirac) bodies cannot be combined pointwise and are
    refused.

    ``names`` says what the two bodies are called where they were given (``("sphere", "plate")``,
    ``("sphere", "target.sphere")``): messages use them. It is not a parameter (not compared, not stored).
    """

    TITLE: ClassVar[str] = "two bodies' plane-strain moduli combined pointwise, Green 2026 Eq. 1"
    FORMULA: ClassVar[str] = "E'(t) = c_a E_a(t) c_b E_b(t) / (c_a E_a(t) + c_b E_b(t))"
    PARAMETERS: ClassVar[tuple] = (Parameter(name="a", unit=None, meaning="body a's material", shape="material"),
                                   Parameter(name="c_a", unit="1", meaning="plane-strain factor 1/(1 - nu_a^2)"),
                                   Parameter(name="b", unit=None, meaning="body b's material", shape="material"),
                                   Parameter(name="c_b", unit="1", meaning="plane-strain factor 1/(1 - nu_b^2)"))
    #: made from two bodies, never named by a config spec
    CONFIGURABLE: ClassVar[bool] = False

    a: Material
    c_a: float
    b: Material
    c_b: float
    names: tuple = field(default=("body a", "body b"), compare=False, repr=False)

    def __post_init__(self):
        for name, m in zip(self.names, (self.a, self.b)):
            if not isinstance(m, Material) or m.viscosity > 0 or isinstance(m, EqOne):
                raise ValueError(f"EqOne: {name} must be a material without a Dirac (Kelvin-Voigt) term, "
                                 f"got {m!r}")
        _positive("c_a", self.c_a, unit="(1/(1 - nu^2))")
        _positive("c_b", self.c_b, unit="(1/(1 - nu^2))")

    @property
    def fastest_rate(self) -> float:
        return max(self.a.fastest_rate, self.b.fastest_rate)

    def summed_rates(self, order: int) -> list:
        """The sums of up to ``order`` of the two bodies' Prony rates (1/s): the spectrum of E' when
        both are Prony-type, the first candidates of its exponential-sum fit
        (:func:`vcor.materials.expfit.summed_rates`)."""
        from .expfit import summed_rates

        rates = [b for m in (self.a, self.b) if m.is_prony for b in m.prony_terms()[2]]
        return summed_rates(rates, order)

    def describe_bodies(self) -> str:
        """The two bodies as given, e.g. "sphere (elastic) and plate (sls)"."""
        return f"{self.names[0]} ({self.a.kind}) and {self.names[1]} ({self.b.kind})"

    def _parts(self, t):
        t = np.asarray(t, dtype=float)
        return self.c_a * self.a.relaxation_modulus(t), self.c_b * self.b.relaxation_modulus(t), t

    def relaxation_modulus(self, t):
        A, B, _ = self._parts(t)
        with np.errstate(invalid="ignore", divide="ignore"):
            out = A * B / (A + B)
        return np.where(np.isinf(A), B, np.where(np.isinf(B), A, out))

    @causal_inline
    def modulus_at(self, t: float) -> float:
        """E'(t) at one time t (s), Pa, from the bodies' own scalar evaluations (the contact-time
        estimate asks for it at every impact); 0 at t < 0, where both bodies' moduli are."""
        a, b = self.c_a * self.a.modulus_at(t), self.c_b * self.b.modulus_at(t)
        if math.isinf(a) or math.isinf(b):
            return b if math.isinf(a) else a
        total = a + b
        return a * b / total if total > 0.0 else 0.0

    def relaxation_rate(self, t):
        A, B, t = self._parts(t)
        dA, dB = self.c_a * self.a.relaxation_rate(t), self.c_b * self.b.relaxation_rate(t)
        with np.errstate(invalid="ignore", divide="ignore"):
            return (dA * B * B + dB * A * A) / (A + B) ** 2

    def complex_modulus(self, omega):
        raise ValueError("the pointwise Eq. 1 combination (EqOne) has no closed-form complex modulus")

    def antiderivative(self, t, order: int = 1):
        if order not in (1, 2):
            raise ValueError(f"order must be 1 or 2, got {order}")
        t = np.asarray(t, dtype=float)
        flat = t.ravel()
        pos = flat[flat > 0]
        if pos.size == 0:
            return np.zeros_like(t)
        # breakpoints: every requested t, and 16 per decade from min(t) * 1e-12 to max(t) (the fractional
        # body's sqrt(t) behaviour at t = 0; exponentials are smooth in log t)
        lo_t, hi_t = pos.min() * 1e-12, pos.max()
        grid = np.geomspace(lo_t, hi_t, int(16 * math.log10(hi_t / lo_t)) + 2)
        edges = np.unique(np.concatenate(([0.0], grid, pos)))
        lo, hi = edges[:-1], edges[1:]
        mid, half = 0.5 * (lo + hi), 0.5 * (hi - lo)
        nodes = mid[:, None] + half[:, None] * GL_NODES[None, :]
        e = self.relaxation_modulus(nodes)
        k1 = np.concatenate(([0.0], np.cumsum(half * (e @ GL_WEIGHTS))))
        if order == 2:  # K2(t) = t K1(t) - int_0^t tau E(tau) d tau
            m1 = np.concatenate(([0.0], np.cumsum(half * ((e * nodes) @ GL_WEIGHTS))))
            k1 = edges * k1 - m1
        out = np.interp(flat, edges, k1)
        out[flat <= 0] = 0.0
        return out.reshape(t.shape)

    def params(self) -> dict:
        return {"a": self.a.to_dict(), "c_a": self.c_a, "b": self.b.to_dict(), "c_b": self.c_b}

    def _scaled(self, modulus, time):
        return EqOne(self.a.scaled(modulus, time), self.c_a, self.b.scaled(modulus, time), self.c_b, self.names)
