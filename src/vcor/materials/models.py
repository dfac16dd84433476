"""Linear viscoelastic relaxation models (uniaxial moduli, SI units: Pa, s, rad/s).

Every model provides

* ``relaxation_modulus(t)``  E(t) in Pa,
* ``relaxation_rate(t)``     dE/dt in Pa/s (``-inf`` where it is singular),
* ``complex_modulus(omega)`` E*(omega) = i omega L[E](i omega) in Pa,
* ``antiderivative(t, order)`` the first (Pa s) or second (Pa s^2) antiderivative of
  the regular part of E, in closed form; the solvers integrate kernels *exactly* over
  each time step with these (product integration), which is what makes the weakly
  singular fractional kernels (E ~ t^-1/2) work without clamping t to dt,
* ``viscosity`` the weight (Pa s) of a Dirac term eta * delta(t) in E(t) (Kelvin-Voigt
  only), ``glassy`` = E(0+) (may be ``inf``) and ``rubbery`` = E(inf).

* ``scaled(modulus, time)`` the same model with E(t) -> modulus E(t / time) (time-temperature
  superposition and calibration scale every model through this one method).

Presets (Green 2026, Eqs. 14, 23b, 24, 26) are in :mod:`vcor.materials.presets`.
"""

from __future__ import annotations

import functools
import json
import math
import numbers
from dataclasses import dataclass, field

import numpy as np
from scipy.special import erfcx, gamma

from ..checks import positive as _positive

__all__ = [
    "SLS",
    "Cerf",
    "Elastic",
    "EqOne",
    "FractionalPower",
    "KelvinVoigt",
    "Material",
    "Prony",
    "from_dict",
]

_SQRT_PI = math.sqrt(math.pi)


#: Gauss-Legendre nodes and weights on [-1, 1] for the step integrals of smooth kernels (steps i >= 1:
#: the only singularity, t = 0, is at least one step away, so 12 nodes are exact to rounding)
_GL_X, _GL_W = np.polynomial.legendre.leggauss(12)
#: int_0^dt e^{-b x} (x - dt/2) dx / dt^2 = sum_{k >= 1} c_k (-b dt)^k, c_k = k / (2 k! (k + 1)(k + 2)),
#: k = 1..15 (used for b dt <= 0.05: the truncation is below 1e-30 relative)
_MOMENT_SERIES = np.array([k / (2.0 * math.factorial(k) * (k + 1) * (k + 2)) for k in range(1, 16)])


class Material:
    """Base class: a relaxation modulus E(t) = E_reg(t) + viscosity * delta(t)."""

    kind: str = "material"
    viscosity: float = 0.0

    # -- to be provided by subclasses -------------------------------------------------
    def relaxation_modulus(self, t):  # pragma: no cover - abstract
        raise NotImplementedError

    def relaxation_rate(self, t):  # pragma: no cover - abstract
        raise NotImplementedError

    def modulus_at(self, t: float) -> float:
        """E(t) at one time t (s), Pa (subclasses may evaluate it without arrays)."""
        return float(self.relaxation_modulus(np.array([t]))[0])

    def complex_modulus(self, omega):  # pragma: no cover - abstract
        raise NotImplementedError

    def antiderivative(self, t, order: int = 1):  # pragma: no cover - abstract
        raise NotImplementedError

    def params(self) -> dict:  # pragma: no cover - abstract
        raise NotImplementedError

    def _scaled(self, modulus: float, time: float) -> Material:  # pragma: no cover - abstract
        raise NotImplementedError

    def scaled(self, modulus: float = 1.0, time: float = 1.0) -> Material:
        """The same model with every modulus times ``modulus`` and time stretched by ``time``:

        .. math:: E_{new}(t) = m \\, E(t / a)

        (``modulus`` = m, dimensionless, > 0; ``time`` = a, dimensionless, > 0). Time-temperature
        superposition uses a = a_T (a material at T relaxes a_T times slower than at T_ref); calibration
        uses both factors."""
        m = _positive("modulus", modulus, unit="(factor)")
        a = _positive("time", time, unit="(factor)")
        return self if m == 1.0 and a == 1.0 else self._scaled(m, a)

    # -- shared -----------------------------------------------------------------------
    @functools.cached_property
    def glassy(self) -> float:
        """E(0+) in Pa (``inf`` for the fractional power law); computed once per material (every impact
        asks for it)."""
        return float(self.relaxation_modulus(np.array([0.0]))[0])

    @functools.cached_property
    def rubbery(self) -> float:
        """E(t -> inf) in Pa; computed once per material."""
        return float(self.relaxation_modulus(np.array([np.inf]))[0])

    @property
    def is_prony(self) -> bool:
        return False

    @property
    def fastest_rate(self) -> float:
        """Largest relaxation rate in 1/s (0 for rate-free models)."""
        return 0.0

    @property
    def is_elastic(self) -> bool:
        """True when E(t) is constant (no relaxation, no viscosity)."""
        return False

    def sqrt_law(self) -> tuple[float, float] | None:
        """(E0 in Pa, c in Pa s^0.5) when E(t) = E0 + c t^-1/2 exactly, else None (the adaptive march
        then evaluates a plate's modulus in closed form instead of through the exponential sum)."""
        return None

    def _gauss_steps(self, dt: float, n: int, fn):
        """int over steps i = 1..n-1 of fn(t, x) dt, x = t - t_mid (12-point Gauss-Legendre)."""
        h = 0.5 * dt
        mid = dt * (np.arange(1, n, dtype=float) + 0.5)
        x = h * _GL_X
        return h * (fn(np.add.outer(mid, x), x) @ _GL_W)

    def step_integrals(self, dt: float, n: int) -> np.ndarray:
        """W_i = int_{i dt}^{(i+1) dt} E_reg(t) dt for i = 0..n-1, in Pa s.

        Step 0 from the antiderivative (it holds any singularity at t = 0); the others by
        Gauss-Legendre on the positive integrand E (no differences of growing antiderivatives,
        so no cancellation however many steps)."""
        out = np.empty(n)
        out[0] = float(self.first_step(dt)[0])
        if n > 1:
            out[1:] = self._gauss_steps(dt, n, lambda t, x: self.relaxation_modulus(t))
        return out

    def first_step(self, dt):
        """(int_0^dt E_reg(t) dt in Pa s, int_0^dt E_reg(t) (t - dt/2) dt in Pa s^2) for a step size or
        an array of them at once: the first entries of ``step_integrals`` and ``step_moments``.
        From the antiderivatives K1, K2: (K1(dt), dt/2 K1(dt) - K2(dt))."""
        dt = np.asarray(dt, dtype=float)
        k1 = self.antiderivative(dt, 1)
        return k1, 0.5 * dt * k1 - self.antiderivative(dt, 2)

    def step_moments(self, dt: float, n: int) -> np.ndarray:
        """V_i = int_{i dt}^{(i+1) dt} E_reg(t) (t - (i + 1/2) dt) dt for i = 0..n-1, in Pa s^2.

        Used by the second-order (quadratic-in-u) product integration of the direct solver.
        Step 0 from the antiderivatives, dt/2 K1(dt) - K2(dt). For i >= 1, by parts,
        V_i = 1/2 int E'(t) ((dt/2)^2 - (t - t_mid)^2) dt: the integrand has one sign, so Gauss-Legendre
        loses no digits (the difference form dt/2 (K1(b) + K1(a)) - (K2(b) - K2(a)) loses them all by
        step ~1e5)."""
        out = np.empty(n)
        out[0] = float(self.first_step(dt)[1])
        if n > 1:
            h2 = 0.25 * dt * dt
            out[1:] = 0.5 * self._gauss_steps(dt, n, lambda t, x: self.relaxation_rate(t) * (h2 - x * x))
        return out

    def storage_loss(self, omega):
        """(E', E'', tan delta) at angular frequency omega [rad/s]."""
        e = self.complex_modulus(omega)
        return e.real, e.imag, e.imag / e.real

    def to_dict(self) -> dict:
        return {"kind": self.kind, **self.params()}

    def describe(self) -> str:
        return json.dumps(self.to_dict())


def _term(name, value, unit):
    """One Prony modulus or rate: a finite number >= 0 (a negative modulus would make E(t) increase)."""
    if isinstance(value, numbers.Real) and not isinstance(value, bool) and value < 0:
        why = " (a negative term makes the relaxation modulus increase)" if "E[" in name else ""
        raise ValueError(f"{name} must be in [0, inf) {unit}{why}, got {value!r}")
    return _positive(name, value, allow_zero=True, unit=unit)


@dataclass(frozen=True)
class Prony(Material):
    """Generalised Maxwell (Prony) solid.

    .. math:: E(t) = E_\\infty + \\sum_i E_i e^{-\\beta_i t}

    Parameters
    ----------
    E_inf : float
        Rubbery (equilibrium) modulus, Pa, >= 0.
    E : sequence of float
        Term moduli, Pa, each >= 0 (negative terms would make E(t) increase).
    beta : sequence of float
        Relaxation rates, 1/s, each >= 0 (beta_i = 1/tau_i).
    """

    E_inf: float
    E: tuple = ()
    beta: tuple = ()
    kind: str = field(default="prony", init=False)

    def __post_init__(self):
        _positive("E_inf", self.E_inf, allow_zero=True, unit="Pa")
        e = tuple(_term(f"Prony E[{i}]", x, "Pa") for i, x in enumerate(np.atleast_1d(np.asarray(self.E, dtype=object))))
        b = tuple(_term(f"Prony beta[{i}]", x, "1/s")
                  for i, x in enumerate(np.atleast_1d(np.asarray(self.beta, dtype=object))))
        if len(e) != len(b):
            raise ValueError(f"Prony: E and beta must have equal length, got {len(e)} and {len(b)}")
        object.__setattr__(self, "E", e)
        object.__setattr__(self, "beta", b)
        if self.E_inf + sum(e) <= 0:
            raise ValueError("Prony: glassy modulus E_inf + sum(E) must be > 0 Pa")
        # the terms as arrays, built once (not dataclass fields: equality and hashing use E and beta)
        object.__setattr__(self, "_term_arrays", (np.asarray(e, float), np.asarray(b, float)))

    @property
    def is_prony(self) -> bool:
        return True

    @property
    def is_elastic(self) -> bool:
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

    def modulus_at(self, t: float) -> float:
        total = self.E_inf
        for e, b in zip(self.E, self.beta):
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

    def term_step_integrals(self, dt: float, n: int) -> np.ndarray:
        """Per term k (last axis): int_{i dt}^{(i+1) dt} E_k e^{-beta_k t} dt, i = 0..n-1, Pa s."""
        i = np.arange(n, dtype=float)
        e, b = self._arrays()
        bdt = b * dt
        frac = np.where(b > 0, -np.expm1(-bdt) / np.where(b > 0, b, 1.0), dt)
        return e * frac * np.exp(-np.multiply.outer(i, bdt))

    def term_step_moments(self, dt: float, n: int) -> np.ndarray:
        """Per term k (last axis): int_{step i} E_k e^{-beta_k t} (t - (i + 1/2) dt) dt, Pa s^2; with
        int_0^dt e^{-b x} (x - dt/2) dx in closed form or (small b dt) its series."""
        i = np.arange(n, dtype=float)
        e, b = self._arrays()
        x = b * dt
        safe = np.where(x > 0.05, x, 1.0)
        closed = dt**2 * ((-np.expm1(-safe)) / safe**2 - np.exp(-safe) / safe - 0.5 * (-np.expm1(-safe)) / safe)
        small = np.where(x > 0.05, 0.0, x)  # the series is used (and evaluated) only where x <= 0.05
        series = np.zeros_like(x)
        for coef in _MOMENT_SERIES[::-1]:  # Horner in -x
            series = (series + coef) * -small
        phi = np.where(x > 0.05, closed, dt**2 * series)
        return e * phi * np.exp(-np.multiply.outer(i, x))

    def prony_terms(self):
        """(E_inf, E[], beta[]) as float and arrays (for the internal-variable solver)."""
        e, b = self._arrays()
        return float(self.E_inf), e, b

    def params(self) -> dict:
        return {"E_inf": float(self.E_inf), "E": [float(x) for x in self.E], "beta": [float(x) for x in self.beta]}

    def _scaled(self, modulus, time):
        return Prony(self.E_inf * modulus, tuple(e * modulus for e in self.E), tuple(b / time for b in self.beta))


@dataclass(frozen=True, init=False)
class SLS(Prony):
    """Standard linear solid (Zener material), Green 2026 Eq. 13.

    .. math:: E(t) = E_g [\\alpha/\\beta + (1 - \\alpha/\\beta) e^{-\\beta t}],
              \\quad E^*(\\omega) = E_g (\\alpha + i\\omega)/(\\beta + i\\omega)

    Parameters
    ----------
    E_glassy : float
        Glassy modulus E_g, Pa, > 0.
    alpha, beta : float
        Rates in 1/s with 0 <= alpha <= beta; rubbery modulus E_g alpha/beta.
        beta = 0 (then alpha must be 0) is the elastic limit E(t) = E_g used by the
        paper's check against Zener.
    """

    E_glassy: float = 0.0
    alpha: float = 0.0

    def __init__(self, E_glassy: float, alpha: float, beta: float):
        eg = _positive("E_glassy", E_glassy, unit="Pa")
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
        object.__setattr__(self, "kind", "sls")
        Prony.__post_init__(self)

    def params(self) -> dict:
        return {"E_glassy": self.E_glassy, "alpha": self.alpha, "beta": self.beta[0]}

    def _scaled(self, modulus, time):
        return SLS(self.E_glassy * modulus, self.alpha / time, self.beta[0] / time)


@dataclass(frozen=True, init=False)
class Elastic(Prony):
    """Elastic solid, E(t) = E (Pa)."""

    def __init__(self, E: float):
        object.__setattr__(self, "E_inf", _positive("E", E, unit="Pa"))
        object.__setattr__(self, "E", ())
        object.__setattr__(self, "beta", ())
        object.__setattr__(self, "kind", "elastic")
        Prony.__post_init__(self)

    def params(self) -> dict:
        return {"E": self.E_inf}

    def _scaled(self, modulus, time):
        return Elastic(self.E_inf * modulus)


@dataclass(frozen=True)
class FractionalPower(Material):
    """Bagley-Torvik fractional (order 1/2) law, Green 2026 Eq. 23.

    .. math:: E(t) = E_0 + E_1 / \\sqrt{\\pi t}, \\quad E^*(\\omega) = E_0 + E_1 \\sqrt{i\\omega}

    Parameters
    ----------
    E0 : float
        Rubbery modulus, Pa, >= 0.
    E1 : float
        Fractional coefficient, Pa s^0.5, >= 0.
    """

    E0: float
    E1: float
    kind: str = field(default="fractional", init=False)

    def __post_init__(self):
        _positive("E0", self.E0, allow_zero=True, unit="Pa")
        _positive("E1", self.E1, allow_zero=True, unit="Pa s^0.5")
        if self.E0 + self.E1 <= 0:
            raise ValueError("FractionalPower: E0 + E1 must be > 0")

    @property
    def fastest_rate(self) -> float:
        return math.inf if self.E1 > 0 else 0.0

    def relaxation_modulus(self, t):
        t = np.asarray(t, dtype=float)
        with np.errstate(divide="ignore"):
            return self.E0 + self.E1 / np.sqrt(math.pi * t)

    def sqrt_law(self) -> tuple[float, float]:
        return self.E0, self.E1 / _SQRT_PI

    def modulus_at(self, t: float) -> float:
        if t <= 0:
            return math.inf if self.E1 > 0 else self.E0
        return self.E0 + self.E1 / math.sqrt(math.pi * t)

    def relaxation_rate(self, t):
        t = np.asarray(t, dtype=float)
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

    def params(self) -> dict:
        return {"E0": self.E0, "E1": self.E1}

    def _scaled(self, modulus, time):
        # E1 / sqrt(pi t / a) = (E1 sqrt(a)) / sqrt(pi t)
        return FractionalPower(self.E0 * modulus, self.E1 * modulus * math.sqrt(time))


def _erfcx_tail(x, start: int):
    """sum_{n >= start} (-x)^n / Gamma(n/2 + 1): erfcx(x) minus its first Taylor terms.

    Closed form for x >= 0.2, the (absolutely convergent) series below, where the
    closed form would cancel.
    """
    shape = np.shape(x)
    x = np.atleast_1d(np.asarray(x, dtype=float))
    head = np.zeros_like(x)
    for n in range(start):
        head = head + (-x) ** n / _GAMMA_HALF[n]
    out = np.asarray(erfcx(x) - head)
    small = x < 0.2
    if np.any(small):
        xs = x[small]
        series = np.zeros_like(xs)
        for n in range(start, start + 30):
            series = series + (-xs) ** n / _GAMMA_HALF[n]
        out[small] = series
    return out.reshape(shape)


_GAMMA_HALF = gamma(np.arange(80) / 2 + 1)


@dataclass(frozen=True)
class Cerf(Material):
    """Mittag-Leffler (order 1/2) relaxation, the 'CERF' law of Green 2026 Eq. 24-25.

    .. math:: E(t) = E_0 + E_1\\,\\mathrm{erfcx}(b_1\\sqrt t), \\quad
              E^*(\\omega) = E_0 + E_1 \\sqrt{i\\omega}/(\\sqrt{i\\omega} + b_1)

    ``erfcx`` is :func:`scipy.special.erfcx` (the paper's CERF, Appendix Eq. A3).

    Parameters
    ----------
    E0 : float
        Rubbery modulus, Pa, >= 0.
    E1 : float
        Relaxing part, Pa, >= 0 (glassy modulus E0 + E1).
    b1 : float
        Rate parameter, s^-1/2 ... in the paper's units "1/s" with x = b1 sqrt(t);
        b1^2 is a rate in 1/s. Must be > 0.
    """

    E0: float
    E1: float
    b1: float
    kind: str = field(default="cerf", init=False)

    def __post_init__(self):
        _positive("E0", self.E0, allow_zero=True, unit="Pa")
        _positive("E1", self.E1, allow_zero=True, unit="Pa")
        _positive("b1", self.b1, unit="s^-1/2")
        if self.E0 + self.E1 <= 0:
            raise ValueError("Cerf: E0 + E1 must be > 0")

    @property
    def fastest_rate(self) -> float:
        return math.inf if self.E1 > 0 else 0.0

    def relaxation_modulus(self, t):
        t = np.asarray(t, dtype=float)
        return self.E0 + self.E1 * erfcx(self.b1 * np.sqrt(t))

    def modulus_at(self, t: float) -> float:
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
        x = self.b1 * np.sqrt(t)
        if order == 1:
            return self.E0 * t + self.E1 * _erfcx_tail(x, 2) / self.b1**2
        if order == 2:
            return 0.5 * self.E0 * t**2 + self.E1 * _erfcx_tail(x, 4) / self.b1**4
        raise ValueError(f"order must be 1 or 2, got {order}")

    @property
    def is_elastic(self) -> bool:
        return self.E1 == 0

    def params(self) -> dict:
        return {"E0": float(self.E0), "E1": float(self.E1), "b1": float(self.b1)}

    def _scaled(self, modulus, time):
        # erfcx(b1 sqrt(t / a)) = erfcx((b1 / sqrt(a)) sqrt(t))
        return Cerf(self.E0 * modulus, self.E1 * modulus, self.b1 / math.sqrt(time))


@dataclass(frozen=True)
class KelvinVoigt(Material):
    """Kelvin-Voigt solid, E(t) = E [1 + tau delta(t)]: sigma = E (eps + tau eps').

    In the contact law this gives F = k (u + tau u'), Ramirez et al. 1999 Eq. 3 with
    their dissipative constant A = tau.

    Parameters
    ----------
    E : float
        Elastic modulus, Pa, > 0.
    tau : float
        Retardation time, s, >= 0.
    """

    E: float
    tau: float
    kind: str = field(default="kelvin-voigt", init=False)

    def __post_init__(self):
        _positive("E", self.E, unit="Pa")
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

    def params(self) -> dict:
        return {"E": self.E, "tau": self.tau}

    def _scaled(self, modulus, time):
        # E tau delta(t / a) = E (tau a) delta(t)
        return KelvinVoigt(self.E * modulus, self.tau * time)


# --------------------------------------------------------------------------------------
@dataclass(frozen=True)
class EqOne(Material):
    """Two bodies' plane-strain moduli combined pointwise in time, as Green 2026 Eq. 1 writes it:

    .. math:: E'(t) = \\frac{E'_a(t) E'_b(t)}{E'_a(t) + E'_b(t)}, \\quad E'_i = c_i E_i(t), \\; c_i = 1/(1 - \\nu_i^2)

    This is *not* the viscoelastic series combination (compliances adding in the Laplace domain,
    :func:`vcor.contact.bodies.series_modulus`); the two agree when one body is rigid, both are elastic, or
    both are the same material (E'/2), and differ in between (the documentation, user guide "Bodies"). E'(t) has no closed
    form for its step integrals or its complex modulus: steps are integrated by Gauss-Legendre (the
    base class), the antiderivatives by composite Gauss-Legendre on a grid graded towards t = 0. Kelvin-
    Voigt (Dirac) bodies cannot be combined pointwise and are refused.
    """

    a: Material
    c_a: float
    b: Material
    c_b: float
    kind: str = field(default="eq1", init=False)

    def __post_init__(self):
        for name, m in (("a", self.a), ("b", self.b)):
            if not isinstance(m, Material) or m.viscosity > 0 or isinstance(m, EqOne):
                raise ValueError(f"EqOne: body {name} must be a material without a Dirac (Kelvin-Voigt) term, "
                                 f"got {m!r}")
        _positive("c_a", self.c_a, unit="(1/(1 - nu^2))")
        _positive("c_b", self.c_b, unit="(1/(1 - nu^2))")

    @property
    def fastest_rate(self) -> float:
        return max(self.a.fastest_rate, self.b.fastest_rate)

    def _parts(self, t):
        t = np.asarray(t, dtype=float)
        return self.c_a * self.a.relaxation_modulus(t), self.c_b * self.b.relaxation_modulus(t), t

    def relaxation_modulus(self, t):
        A, B, _ = self._parts(t)
        with np.errstate(invalid="ignore", divide="ignore"):
            out = A * B / (A + B)
        return np.where(np.isinf(A), B, np.where(np.isinf(B), A, out))

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
        nodes = mid[:, None] + half[:, None] * _GL_X[None, :]
        e = self.relaxation_modulus(nodes)
        k1 = np.concatenate(([0.0], np.cumsum(half * (e @ _GL_W))))
        if order == 2:  # K2(t) = t K1(t) - int_0^t tau E(tau) d tau
            m1 = np.concatenate(([0.0], np.cumsum(half * ((e * nodes) @ _GL_W))))
            k1 = edges * k1 - m1
        out = np.interp(flat, edges, k1)
        out[flat <= 0] = 0.0
        return out.reshape(t.shape)

    def params(self) -> dict:
        return {"a": self.a.to_dict(), "c_a": self.c_a, "b": self.b.to_dict(), "c_b": self.c_b}

    def _scaled(self, modulus, time):
        return EqOne(self.a.scaled(modulus, time), self.c_a, self.b.scaled(modulus, time), self.c_b)


_KINDS = {
    "prony": Prony,
    "sls": SLS,
    "elastic": Elastic,
    "fractional": FractionalPower,
    "cerf": Cerf,
    "kelvin-voigt": KelvinVoigt,
    "eq1": EqOne,
}



def from_dict(d: dict) -> Material:
    """Material from ``Material.to_dict()`` output."""
    d = dict(d)
    kind = d.pop("kind", None)
    if kind not in _KINDS:
        raise ValueError(f"unknown material kind {kind!r}; allowed: {sorted(_KINDS)}")
    if kind == "eq1":
        d["a"], d["b"] = from_dict(d["a"]), from_dict(d["b"])
    return _KINDS[kind](**d)
