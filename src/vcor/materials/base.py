"""The material contract and the registry of material models (uniaxial moduli, SI units: Pa, s, rad/s).

Every model provides

* ``relaxation_modulus(t)``  E(t) in Pa,
* ``relaxation_rate(t)``     dE/dt in Pa/s (``-inf`` where it is singular),
* ``complex_modulus(omega)`` E*(omega) = i omega L[E](i omega) in Pa,
* ``antiderivative(t, order)`` the first (Pa s) or second (Pa s^2) antiderivative of
  the regular part of E, in closed form; the solvers integrate kernels *exactly* over
  each time step with these (product integration), which is what makes the weakly
  singular fractional kernels (E ~ t^-1/2) work without clamping t to dt,
* ``viscosity`` the weight (Pa s) of a Dirac term eta * delta(t) in E(t) (Kelvin-Voigt
  only), ``glassy`` = E(0+) (may be ``inf``) and ``rubbery`` = E(inf),
* ``scaled(modulus, time)`` the same model with E(t) -> modulus E(t / time) (time-temperature
  superposition and calibration scale every model through this one method).

The time functions (``relaxation_modulus``, ``relaxation_rate``, ``antiderivative``, ``modulus_at``) are
causal: E(t) = 0 before the strain step, so each gives 0 at t < 0, elementwise (an array holding some
negative times is not an error, as a :mod:`scipy.stats` density is 0 outside its support), and t = 0
gives the limit t -> 0+. A model implements them for t >= 0 only: :class:`Material` wraps every
subclass's own definitions (:func:`causal`), so no model can extrapolate its formula to t < 0.

A model registers itself by subclassing :class:`Material` with a ``kind`` class keyword,
``class Cerf(Material, kind="cerf")``, and stating its ``TITLE``, ``FORMULA`` and ``PARAMETERS``
(:class:`Parameter`: name, UDUNITS unit, meaning) in the class body. :data:`REGISTRY` maps every
kind to its :class:`Family`; material files (``from_dict``), config specs
(:mod:`vcor.materials.specs`) and the tables that list the models read it, so a new model is added
in one place.
"""

from __future__ import annotations

import functools
import json
from collections.abc import Mapping
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ..checks import number
from ..checks import positive as _positive

__all__ = ["GL_NODES", "GL_WEIGHTS", "MAX_MODULUS", "PARAMETER_SHAPES", "REGISTRY", "SECOND_MOMENT_NODES",
           "SECOND_MOMENT_PANELS", "TIME_FUNCTIONS", "Family", "Material", "Parameter", "causal", "causal_inline",
           "from_dict", "modulus", "second_moment_rule", "unregister"]

#: Gauss-Legendre nodes and weights on [-1, 1] for the step integrals of smooth kernels (steps i >= 1:
#: the only singularity, t = 0, is at least one step away, so 12 nodes are exact to rounding)
GL_NODES, GL_WEIGHTS = np.polynomial.legendre.leggauss(12)

#: the newest step's second moment (``Material.first_step_second_moment``) of a kernel without a closed
#: form: Gauss-Legendre in y = sqrt(t / dt), SECOND_MOMENT_NODES nodes on each of the panels
#: [2^-(k+1), 2^-k] of y, k = 0..SECOND_MOMENT_PANELS - 2, and [0, 2^-(SECOND_MOMENT_PANELS - 1)]: exact
#: for E(t) polynomial in sqrt(t) and 1/sqrt(t), and the panels follow a change of E(t) on any time scale
#: down to dt / 4^(SECOND_MOMENT_PANELS - 1) (the CERF law's 1/b1^2, an exponential's 1/beta: to 1e-15 of
#: the result's scale against scipy's quad, tests/materials/test_second_moment.py)
SECOND_MOMENT_NODES = 12
SECOND_MOMENT_PANELS = 20


#: the largest modulus a material takes, Pa (and the largest fractional coefficient E1, Pa s^0.5): 1e8 times the
#: stiffest solid (diamond, E ~ 1.05e12 Pa), so no measured material comes near it, while a law used at the limit
#: of its family stays inside (a CERF fit to fractional data walks E1 and b1 up together, E1/b1 fixed: the shipped
#: butyl-cerf-fit ends at E1 = 2.6e16 Pa); and far below the moduli at which the solvers' arithmetic leaves double
#: precision (the paper's impact: from 1e200 to 1e250 Pa, a diverged march or an exponential sum or contact-time
#: estimate that overflows). A larger value is refused when the material is made, naming the parameter and range.
MAX_MODULUS = 1e20


def modulus(name: str, value, *, allow_zero: bool = False, unit: str = "Pa") -> float:
    """A modulus parameter: a finite number in (0, MAX_MODULUS] (with ``allow_zero``, [0, MAX_MODULUS]), else
    ValueError naming ``name`` and that range (:func:`vcor.checks.number`)."""
    return number(name, value, 0.0, MAX_MODULUS, lo_open=not allow_zero, hi_open=False, unit=unit)


#: what a parameter's value is: one number, one number per Prony term, or a material (``to_dict`` form)
PARAMETER_SHAPES = ("scalar", "terms", "material")


@functools.cache
def second_moment_rule():
    """The quadrature rule in y = sqrt(t / dt) on [0, 1] of :meth:`Material.first_step_second_moment`.

    Gauss-Legendre with SECOND_MOMENT_NODES nodes on each of SECOND_MOMENT_PANELS panels that halve
    towards y = 0 (see SECOND_MOMENT_NODES). In y a t^-1/2 or sqrt(t) behaviour of a kernel at t = 0 is
    smooth, so the rule also serves other weighted integrals over the newest step of such a kernel
    (int_0^dt E(t) p(t) dt with p a polynomial: substitute t = dt y^2, dt_t = 2 dt y dy). Cached.

    Returns
    -------
    y : ndarray
        The nodes, dimensionless, in (0, 1) (t = dt y^2 in s for a step of dt s).
    w : ndarray
        Their weights, dimensionless: sum_i w_i f(y_i) approximates int_0^1 f(y) dy.
    """
    x, w = np.polynomial.legendre.leggauss(SECOND_MOMENT_NODES)
    edges = np.concatenate(([0.0], 2.0 ** -np.arange(SECOND_MOMENT_PANELS - 1, -1, -1.0)))
    lo, hi = edges[:-1, None], edges[1:, None]
    return (0.5 * (lo + hi) + 0.5 * (hi - lo) * x).ravel(), (0.5 * (hi - lo) * w).ravel()


@dataclass(frozen=True, kw_only=True)
class Parameter:
    """One parameter of a material model.

    Parameters
    ----------
    name : str
        The name the constructor, ``params()``, material files and config specs use.
    unit : str or None
        UDUNITS string ("Pa", "s-1", "Pa s0.5", "1" for a dimensionless factor); None for a parameter
        that is itself a material.
    meaning : str
        What it is, in a few words.
    shape : str
        One of :data:`PARAMETER_SHAPES`.
    """

    name: str
    unit: str | None
    meaning: str
    shape: str = "scalar"

    def __post_init__(self):
        if self.shape not in PARAMETER_SHAPES:
            raise ValueError(f"parameter {self.name!r}: shape must be one of {list(PARAMETER_SHAPES)}, "
                             f"got {self.shape!r}")
        if (self.unit is None) != (self.shape == "material"):
            raise ValueError(f"parameter {self.name!r}: a unit (UDUNITS string) is required unless the "
                             f"parameter is a material, got unit {self.unit!r} with shape {self.shape!r}")


@dataclass(frozen=True, kw_only=True)
class Family:
    """A registered material model: its ``kind`` (the name in config specs and material files), its
    class, a one-line ``title``, its relaxation modulus as text (``formula``), its ``parameters`` and
    whether a config spec may name it (``configurable``; the two-body combination may not)."""

    kind: str
    cls: type
    title: str
    formula: str
    parameters: tuple
    configurable: bool

    @property
    def names(self) -> tuple:
        """Parameter names in the order the formula names them."""
        return tuple(p.name for p in self.parameters)

    @property
    def scalars(self) -> tuple:
        """Names of the scalar parameters (those a grid axis or a calibration may vary)."""
        return tuple(p.name for p in self.parameters if p.shape == "scalar")

    def unit(self, name: str) -> str | None:
        """UDUNITS unit of parameter ``name``; ValueError naming the allowed ones otherwise."""
        for p in self.parameters:
            if p.name == name:
                return p.unit
        raise ValueError(f"a {self.kind} material has no parameter {name!r}; allowed: {list(self.names)}")


class _Registry(Mapping):
    """Read-only view of a dict kind -> :class:`Family`, shown as kind -> class name."""

    def __init__(self, families: dict):
        self._families = families

    def __getitem__(self, kind):
        return self._families[kind]

    def __iter__(self):
        return iter(self._families)

    def __len__(self):
        return len(self._families)

    def __repr__(self):
        return "{" + ", ".join(f"{k!r}: {f.cls.__name__}" for k, f in self._families.items()) + "}"


_REGISTRY: dict = {}
#: kind -> :class:`Family` of every registered material model (read-only view)
REGISTRY = _Registry(_REGISTRY)


def _register(cls, kind) -> None:
    if not isinstance(kind, str) or not kind:
        raise ValueError(f"{cls.__name__}: kind must be a non-empty string, got {kind!r}")
    if kind in _REGISTRY:
        raise ValueError(f"material kind {kind!r} is already registered by {_REGISTRY[kind].cls.__name__}; "
                         f"taken: {sorted(_REGISTRY)}")
    params = cls.__dict__.get("PARAMETERS")
    if not params or not all(isinstance(p, Parameter) for p in params):
        raise ValueError(f"{cls.__name__} ({kind}): PARAMETERS must be a non-empty tuple of Parameter")
    if not cls.__dict__.get("TITLE") or not cls.__dict__.get("FORMULA"):
        raise ValueError(f"{cls.__name__} ({kind}): TITLE and FORMULA must be given in the class body")
    cls.kind = kind
    _REGISTRY[kind] = Family(kind=kind, cls=cls, title=cls.TITLE, formula=cls.FORMULA, parameters=tuple(params),
                             configurable=bool(cls.CONFIGURABLE))


#: the elementwise time functions of a model, each 0 at t < 0 (a subclass's own definition is wrapped by
#: :func:`causal`); ``modulus_at`` (one time) is wrapped alike
TIME_FUNCTIONS = ("relaxation_modulus", "relaxation_rate", "antiderivative")


def causal(fn):
    """``fn``, a model's E(t), dE/dt or antiderivative (elementwise in its first argument ``t``, s), evaluated
    only where t >= 0, and 0 where t < 0: the relaxation modulus is causal (0 before the strain step), and so
    are its rate and its antiderivatives from 0. A NaN time is passed to ``fn`` as it is; the result has the
    shape of ``t`` (a numpy scalar for a scalar). A function wrapped already is returned as it is."""
    if getattr(fn, "causal", False):
        return fn

    @functools.wraps(fn)
    def evaluate(self, t, *args, **kwargs):
        t = np.asarray(t, dtype=float)
        before = t < 0
        if not before.any():
            return fn(self, t, *args, **kwargs)
        out = np.zeros(t.shape)
        after = ~before
        out[after] = fn(self, t[after], *args, **kwargs)  # (also when empty: the arguments are checked)
        return out[()]

    evaluate.causal = True
    return evaluate


def causal_inline(fn):
    """Mark a model's ``modulus_at`` that gives 0 at t < 0 itself (a comparison in its body): :class:`Material`
    leaves it unwrapped, so that it costs no second call (the contact-time estimate asks for it eight times
    per impact, the march's tables more). The built-in models' are so; an added model's is wrapped."""
    fn.causal = True
    return fn


def _causal_at(fn):
    """``fn``, a model's ``modulus_at(t)`` (one time, s), with 0 at t < 0 (:func:`causal`)."""
    if getattr(fn, "causal", False):
        return fn

    @functools.wraps(fn)
    def evaluate(self, t):
        return 0.0 if t < 0 else fn(self, t)

    evaluate.causal = True
    return evaluate


def unregister(kind: str) -> None:
    """Remove a registered kind (a model defined for a while, as in a test); ValueError if unknown."""
    if kind not in _REGISTRY:
        raise ValueError(f"unknown material kind {kind!r}; registered: {sorted(_REGISTRY)}")
    del _REGISTRY[kind]


def from_dict(d: dict) -> Material:
    """Material from ``Material.to_dict()`` output (any registered kind)."""
    d = dict(d)
    kind = d.pop("kind", None)
    if kind not in _REGISTRY:
        raise ValueError(f"unknown material kind {kind!r}; allowed: {sorted(_REGISTRY)}")
    family = _REGISTRY[kind]
    for p in family.parameters:
        if p.shape == "material":
            d[p.name] = from_dict(d[p.name])
    return family.cls(**d)


class Material:
    """Base class: a relaxation modulus E(t) = E_reg(t) + viscosity * delta(t).

    A subclass given the class keyword ``kind`` is registered (module docstring); its class body
    states ``TITLE``, ``FORMULA`` and ``PARAMETERS``, and ``CONFIGURABLE = False`` when a config spec
    may not name it.

    E(t) is causal: the time functions give 0 at t < 0, elementwise, and the limit t -> 0+ at t = 0. A
    subclass implements them for t >= 0; its own definitions of :data:`TIME_FUNCTIONS` and ``modulus_at``
    are wrapped when the class is made (:func:`causal`), so every model, built in or added, agrees."""

    kind: ClassVar[str] = "material"
    TITLE: ClassVar[str] = ""
    FORMULA: ClassVar[str] = ""
    PARAMETERS: ClassVar[tuple] = ()
    CONFIGURABLE: ClassVar[bool] = True
    viscosity: float = 0.0

    def __init_subclass__(cls, kind: str | None = None, **kwargs):
        super().__init_subclass__(**kwargs)
        for name in TIME_FUNCTIONS:
            if name in cls.__dict__:
                setattr(cls, name, causal(cls.__dict__[name]))
        if "modulus_at" in cls.__dict__:
            cls.modulus_at = _causal_at(cls.__dict__["modulus_at"])
        if kind is not None:
            _register(cls, kind)

    # -- to be provided by subclasses -------------------------------------------------
    def relaxation_modulus(self, t):  # pragma: no cover - abstract
        """The relaxation modulus E(t): its regular part (a Dirac term is :attr:`viscosity`).

        Parameters
        ----------
        t : float or array_like
            Time since the strain step, s. Any real time: E(t) is causal, so t < 0 gives 0, elementwise
            (an array holding some negative times is not an error); t = 0 gives E(0+) (``inf`` for the
            fractional law).

        Returns
        -------
        numpy.ndarray or numpy.float64
            E(t) in Pa, of the shape of ``t``.
        """
        raise NotImplementedError

    def relaxation_rate(self, t):  # pragma: no cover - abstract
        """dE/dt of the regular part for t > 0 (the jump E(0+) at t = 0 is not included).

        Parameters
        ----------
        t : float or array_like
            Time, s: t < 0 gives 0 (E is causal), t = 0 the limit t -> 0+ (``-inf`` where it is singular).

        Returns
        -------
        numpy.ndarray or numpy.float64
            dE/dt in Pa/s, of the shape of ``t``.
        """
        raise NotImplementedError

    def modulus_at(self, t: float) -> float:
        """E(t) at one time t (s), Pa: 0 for t < 0, as :meth:`relaxation_modulus` (subclasses may evaluate
        it without arrays)."""
        return float(self.relaxation_modulus(np.array([t]))[0])

    def complex_modulus(self, omega):  # pragma: no cover - abstract
        raise NotImplementedError

    def antiderivative(self, t, order: int = 1):  # pragma: no cover - abstract
        """The antiderivative from 0 of the regular part of E: K1(t) = int_0^t E, K2(t) = int_0^t K1.

        Parameters
        ----------
        t : float or array_like
            Time, s: t < 0 gives 0 (E is causal: it vanishes before 0).
        order : int
            1 (Pa s) or 2 (Pa s^2); ValueError otherwise.

        Returns
        -------
        numpy.ndarray or numpy.float64
            K1(t) or K2(t), of the shape of ``t``.
        """
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

    def erfcx_law(self) -> tuple[float, float, float] | None:
        """(E0 in Pa, E1 in Pa, b1 in s^-0.5) when E(t) = E0 + E1 erfcx(b1 sqrt(t)) exactly (the CERF law),
        else None (the adaptive march then evaluates a plate's modulus in closed form)."""
        return None

    def relaxation_spectrum(self) -> tuple | None:
        """(transient(t) in Pa, rho(s) in Pa s) when the transient E(t) - E(inf) is completely monotone,
        transient(t) = int_0^inf rho(s) e^{-s t} ds, with t in s and s in 1/s; None otherwise. The
        exponential sums (:mod:`vcor.materials.expsums`) are built from it; Prony-type models are
        their own sums and return None."""
        return None

    def _gauss_steps(self, dt: float, n: int, fn):
        """int over steps i = 1..n-1 of fn(t, x) dt, x = t - t_mid (12-point Gauss-Legendre)."""
        h = 0.5 * dt
        mid = dt * (np.arange(1, n, dtype=float) + 0.5)
        x = h * GL_NODES
        return h * (fn(np.add.outer(mid, x), x) @ GL_WEIGHTS)

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

    def first_step_second_moment(self, dt):
        """int_0^dt E_reg(t) ((t - dt/2)^2 - dt^2/12) dt in Pa s^3, for a step size or an array of them: the
        weight of the curvature of u' over the newest step in the adaptive method's product integration
        (the polynomial has zero mean on the step, so a constant modulus gives 0). Here by Gauss-Legendre
        in y = sqrt(t / dt) (see SECOND_MOMENT_NODES), where a t^-1/2 or sqrt(t) behaviour at t = 0 is
        smooth; models with a closed form override it."""
        dt = np.asarray(dt, dtype=float)
        y, w = second_moment_rule()
        # t = dt y^2, dt_t = 2 dt y dy; (t - dt/2)^2 - dt^2/12 = dt^2 ((y^2 - 1/2)^2 - 1/12)
        poly = 2.0 * y * ((y * y - 0.5) ** 2 - 1.0 / 12.0) * w
        e = self.relaxation_modulus(np.multiply.outer(dt, y * y))
        return dt**3 * (e @ poly)

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
