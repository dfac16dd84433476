"""The generalised Maxwell (Prony) solid: a relaxation modulus that is a finite sum of exponentials.

Its step integrals and moments are closed forms per term (no differences of growing antiderivatives);
the standard linear solid (:mod:`vcor.materials.sls`) and the elastic solid
(:mod:`vcor.materials.elastic`) are its special cases.
"""

from __future__ import annotations

import functools
import math
import numbers
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ..checks import positive as _positive
from .base import MAX_MODULUS, Material, Parameter, causal_inline, modulus

__all__ = ["MOMENT_SERIES", "SECOND_MOMENT_SERIES", "SECOND_SERIES_SWITCH", "SERIES_SWITCH", "Prony"]

#: b dt at and below which a step moment is summed from its series: the closed form subtracts terms of
#: size 1/(b dt) to leave one of size b dt, losing ~ eps / (b dt)^2 relative (4e-13 here)
SERIES_SWITCH = 0.05
#: int_0^dt e^{-b x} (x - dt/2) dx / dt^2 = sum_{k >= 1} c_k (-b dt)^k, c_k = k / (2 k! (k + 1)(k + 2)),
#: k = 1..15 (used for b dt <= SERIES_SWITCH: the truncation is below 1e-30 relative)
MOMENT_SERIES = np.array([k / (2.0 * math.factorial(k) * (k + 1) * (k + 2)) for k in range(1, 16)])
#: b dt at and below which the step's second moment is summed from its series: the closed form's terms
#: are 1/(6 b dt) in size for a result of (b dt)^2 / 360 (its loss, ~60 eps / (b dt)^3, is 7.5 eps here)
SECOND_SERIES_SWITCH = 2.0
#: int_0^dt e^{-b x} ((x - dt/2)^2 - dt^2/12) dx / dt^3 = sum_{k >= 2} s_k (-b dt)^k,
#: s_k = (1/(k+3) - 1/(k+2) + 1/(6 (k+1))) / k!, k = 2..35 (truncation below 1e-25 at the switch)
SECOND_MOMENT_SERIES = np.array([(1.0 / (k + 3) - 1.0 / (k + 2) + 1.0 / (6.0 * (k + 1))) / math.factorial(k)
                                 for k in range(2, 36)])


def _rows(first, x, n):
    """Per step i = 0..n-1 (first axis): ``first`` e^{-i x}; the first step is ``first`` itself."""
    if n == 1:
        return first[None]
    return first * np.exp(-np.multiply.outer(np.arange(n, dtype=float), x))


def _term(name, value, unit, hi):
    """One Prony modulus (``hi`` MAX_MODULUS) or rate (``hi`` inf): a finite number in [0, hi] (a negative
    modulus would make E(t) increase)."""
    if isinstance(value, numbers.Real) and not isinstance(value, bool) and value < 0:
        why = " (a negative term makes the relaxation modulus increase)" if "E[" in name else ""
        raise ValueError(f"{name} must be in [0, {hi:g}{']' if hi < math.inf else ')'} {unit}{why}, got {value!r}")
    if hi < math.inf:
        return modulus(name, value, allow_zero=True, unit=unit)
    return _positive(name, value, allow_zero=True, unit=unit)


def _terms(name, values, unit, hi=math.inf) -> tuple:
    """Prony moduli (``hi`` MAX_MODULUS) or rates as floats, each checked by :func:`_term`; floats that are all
    finite and in [0, hi] (every material a fit or a temperature shift builds) pass in one vectorised check."""
    seq = np.atleast_1d(np.asarray(values, dtype=object))
    if all(isinstance(x, float) for x in seq):
        arr = seq.astype(float)
        if np.isfinite(arr).all() and (arr >= 0).all() and (arr <= hi).all():
            return tuple(arr.tolist())
    return tuple(_term(f"{name}[{i}]", x, unit, hi) for i, x in enumerate(seq))


@dataclass(frozen=True)
class Prony(Material, kind="prony"):
    """Generalised Maxwell (Prony) solid.

    .. math:: E(t) = E_\\infty + \\sum_i E_i e^{-\\beta_i t}

    Parameters
    ----------
    E_inf : float
        Rubbery (equilibrium) modulus, Pa, in [0, 1e20] (:data:`~vcor.materials.base.MAX_MODULUS`).
    E : sequence of float
        Term moduli, Pa, each in [0, 1e20] (negative terms would make E(t) increase).
    beta : sequence of float
        Relaxation rates, 1/s, each >= 0 (beta_i = 1/tau_i).
    """

    TITLE: ClassVar[str] = "generalised Maxwell (Prony series)"
    FORMULA: ClassVar[str] = "E(t) = E_inf + sum_i E_i exp(-beta_i t)"
    PARAMETERS: ClassVar[tuple] = (Parameter(name="E_inf", unit="Pa", meaning="rubbery (equilibrium) modulus"),
                                   Parameter(name="E", unit="Pa", meaning="term moduli", shape="terms"),
                                   Parameter(name="beta", unit="s-1", meaning="relaxation rates (1/tau)",
                                             shape="terms"))

    E_inf: float
    E: tuple = ()
    beta: tuple = ()

    def __post_init__(self):
        modulus("E_inf", self.E_inf, allow_zero=True)
        e = _terms("Prony E", self.E, "Pa", MAX_MODULUS)
        b = _terms("Prony beta", self.beta, "1/s")
        if len(e) != len(b):
            raise ValueError(f"Prony: E and beta must have equal length, got {len(e)} and {len(b)}")
        object.__setattr__(self, "E", e)
        object.__setattr__(self, "beta", b)
        if self.E_inf + sum(e) <= 0:
            raise ValueError("Prony: glassy modulus E_inf + sum(E) must be > 0 Pa")
        # the terms as arrays, built once (not dataclass fields: equality and hashing use E and beta)
        object.__setattr__(self, "_term_arrays", (np.asarray(e, float), np.asarray(b, float)))
        object.__setattr__(self, "_term_pairs", tuple(zip(e, b)))  # for modulus_at, called per impact

    @property
    def is_prony(self) -> bool:
        return True

    @functools.cached_property
    def is_elastic(self) -> bool:  # (cached: the adaptive method asks per impact, and the terms never change)
        return all(e == 0 or b == 0 for e, b in zip(self.E, self.beta))

    @property
    def fastest_rate(self) -> float:
        return max(self.beta, default=0.0)

    def _arrays(self):
        return self._term_arrays

    def relaxation_modulus(self, t):
        t = np.asarray(t, dtype=float)
        e, b = self._arrays()
        with np.errstate(invalid="ignore"):
            terms = e * np.exp(-np.multiply.outer(t, b))
        if b.size and np.isinf(t).any():
            terms = np.where(np.isnan(terms), 0.0, terms)  # 0 * exp(-inf * 0) at t = inf, b = 0
            terms = np.where(np.multiply.outer(np.isinf(t), b == 0), e, terms)
        return self.E_inf + terms.sum(axis=-1)

    @causal_inline
    def modulus_at(self, t: float) -> float:
        if t < 0:
            return 0.0
        total = self.E_inf
        for e, b in self._term_pairs:
            total += e * math.exp(-b * t)
        return total

    def relaxation_rate(self, t):
        t = np.asarray(t, dtype=float)
        e, b = self._arrays()
        return -(e * b * np.exp(-np.multiply.outer(t, b))).sum(axis=-1)

    def complex_modulus(self, omega):
        w = 1j * np.asarray(omega, dtype=float)
        e, b = self._arrays()
        wc = w[..., None]
        return self.E_inf + (e * wc / (wc + b)).sum(axis=-1)

    def antiderivative(self, t, order: int = 1):
        t = np.asarray(t, dtype=float)
        e, b = self._arrays()
        bt = np.multiply.outer(t, b)
        safe_b = np.where(b > 0, b, 1.0)
        if order == 1:
            # int_0^t e^{-b s} ds = -expm1(-b t)/b  (-> t as b -> 0)
            part = np.where(b > 0, -np.expm1(-bt) / safe_b, t[..., None])
            return self.E_inf * t + (e * part).sum(axis=-1)
        if order == 2:
            # int_0^t (1 - e^{-b s})/b ds = (b t + expm1(-b t)) / b^2  (-> t^2/2)
            part = np.where(b > 0, (bt + np.expm1(-bt)) / safe_b**2, 0.5 * t[..., None] ** 2)
            return 0.5 * self.E_inf * t**2 + (e * part).sum(axis=-1)
        raise ValueError(f"order must be 1 or 2, got {order}")

    def step_integrals(self, dt: float, n: int) -> np.ndarray:
        # Closed form without differences of growing antiderivatives (no cancellation).
        return self.E_inf * dt + self.term_step_integrals(dt, n).sum(axis=-1)

    def step_moments(self, dt: float, n: int) -> np.ndarray:
        # E_inf gives 0.
        return self.term_step_moments(dt, n).sum(axis=-1)

    def first_step(self, dt):
        # per term, closed forms (the antiderivative difference of the base class cancels for small steps)
        dt = np.asarray(dt, dtype=float)
        col = dt[..., None]
        return (self.E_inf * dt + self.term_step_integrals(col, 1)[0].sum(axis=-1),
                self.term_step_moments(col, 1)[0].sum(axis=-1))

    def first_step_second_moment(self, dt):
        # per term, dt^3 phi(b dt) with phi(x) = int_0^1 e^{-x y} ((y - 1/2)^2 - 1/12) dy =
        # 1/(6x) - 1/x^2 + 2/x^3 - e^{-x} (1/(6x) + 1/x^2 + 2/x^3), or its series (SECOND_SERIES_SWITCH);
        # E_inf gives 0
        dt = np.asarray(dt, dtype=float)
        e, b = self._arrays()
        x = np.multiply.outer(dt, b)
        safe = np.where(x > SECOND_SERIES_SWITCH, x, 1.0)
        inv = 1.0 / safe
        phi = inv / 6.0 - inv**2 + 2.0 * inv**3 - np.exp(-safe) * (inv / 6.0 + inv**2 + 2.0 * inv**3)
        small = ~(x > SECOND_SERIES_SWITCH)
        if small.any():
            minus_x = -x[small]
            series = np.zeros_like(minus_x)
            for coef in SECOND_MOMENT_SERIES[::-1]:  # Horner in -x, from the x^2 term
                series = series * minus_x + coef
            phi[small] = series * minus_x**2
        return dt**3 * (phi @ e)

    def term_step_integrals(self, dt: float, n: int) -> np.ndarray:
        """Per term k (last axis): int_{i dt}^{(i+1) dt} E_k e^{-beta_k t} dt, i = 0..n-1, Pa s."""
        e, b = self._arrays()
        bdt = b * dt
        frac = np.where(b > 0, -np.expm1(-bdt) / np.where(b > 0, b, 1.0), dt)
        return _rows(e * frac, bdt, n)

    def term_step_moments(self, dt: float, n: int) -> np.ndarray:
        """Per term k (last axis): int_{step i} E_k e^{-beta_k t} (t - (i + 1/2) dt) dt, Pa s^2; with
        int_0^dt e^{-b x} (x - dt/2) dx in closed form or (small b dt) its series."""
        e, b = self._arrays()
        x = b * dt
        safe = np.where(x > SERIES_SWITCH, x, 1.0)
        dt2 = dt**2 * np.ones_like(x)  # the shape of x (dt may be a column of steps)
        decayed = -np.expm1(-safe)
        phi = dt2 * (decayed / safe**2 - np.exp(-safe) / safe - 0.5 * decayed / safe)
        small = ~(x > SERIES_SWITCH)  # the series there (NaN included: it stays NaN)
        if small.any():
            minus_x = -x[small]
            series = np.zeros_like(minus_x)
            for coef in MOMENT_SERIES[::-1]:  # Horner in -x
                series += coef
                series *= minus_x
            phi[small] = dt2[small] * series
        return _rows(e * phi, x, n)

    def prony_terms(self):
        """(E_inf, E[], beta[]) as float and arrays (for the internal-variable solver)."""
        e, b = self._arrays()
        return float(self.E_inf), e, b

    def params(self) -> dict:
        return {"E_inf": float(self.E_inf), "E": [float(x) for x in self.E], "beta": [float(x) for x in self.beta]}

    def _scaled(self, modulus, time):
        return Prony(self.E_inf * modulus, tuple(e * modulus for e in self.E), tuple(b / time for b in self.beta))
