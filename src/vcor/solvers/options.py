"""Solver options: the one table of solver defaults and allowed values.

``SolverOptions`` is a frozen, keyword-only, validated dataclass. ``simulate``, sweeps, histories,
the convergence study, the CLI and the workflow's JSON schema all take their defaults and allowed
values from here (a test compares the schema with this table).

Options that only some methods use default to ``None`` ("not set"). Setting one that the chosen
method ignores is an error that names the option (``dt`` with ``method="ive"``, ``rtol`` with
``method="direct"``): nothing is silently dropped. After validation every option the method uses
holds its value (``None`` is replaced by the method's default), every other one is ``None``, so
``to_dict()`` is the complete, canonical description of a run's settings (it enters the shard
identity).
"""

from __future__ import annotations

import dataclasses
import difflib
import math
import numbers
from dataclasses import dataclass

from ..checks import interned, shown
from ..materials.expsums import MAX_SOE_TOL, MIN_SOE_TOL

__all__ = ["BOOLEAN_OPTIONS", "COMPILED_METHODS", "DEFAULT_METHOD", "FIXED_STEP_METHODS", "METHOD_NAMES",
           "MAX_STEPS_PER_CONTACT", "MIN_STEPS_PER_CONTACT",
           "OPTION_HELP", "OPTION_UNITS", "RTOL_MIN", "SUM_TOL", "SolverOptions", "solver_options"]

#: relative error of the exponential sum of a two-body (Eq. 1) contact modulus taken by the internal-variable
#: methods, which have no soe_tol option (below their own error; the same as soe_tol's default; where no fit
#: reaches it, vcor.materials.expsums.FIT_ACCEPT as for soe_tol)
SUM_TOL = 1e-10

#: solver methods (``vcor.solvers.simulate.METHODS`` maps each to its runner); ``paper`` is the
#: explicit baseline of the work-precision study
METHOD_NAMES = ("adaptive", "direct", "ive", "ive-numba", "paper", "soe")
#: the method everywhere a user does not choose one (simulate, the CLI, sweeps, histories,
#: calibration): the fastest that meets the default accuracy (COR and t0 within 1e-7 relative of
#: independent references) on every preset, the one that solves thin plates, and every pair of bodies
DEFAULT_METHOD = "adaptive"
#: methods marching with a fixed time step dt (they take dt, steps_per_contact, max_steps)
FIXED_STEP_METHODS = ("direct", "ive-numba", "paper", "soe")
#: the fewest fixed steps per contact-time estimate (steps_per_contact; a given dt likewise)
MIN_STEPS_PER_CONTACT = 10
#: the most (a billion steps per contact time: beyond any step budget a run can spend, O(N^2) for direct; a
#: smaller dt or a larger count would only run to its budget)
MAX_STEPS_PER_CONTACT = 10**9
#: methods whose solver is compiled by numba (the workflow compiles their kernels first, one job per
#: method; vcor.study.kernels); ``ive`` is scipy's solve_ivp and compiles nothing
COMPILED_METHODS = ("adaptive", "direct", "ive-numba", "paper", "soe")
#: options that take true or false
BOOLEAN_OPTIONS = ("volterra", "richardson")
IVE_METHODS = ("Radau", "BDF", "LSODA", "RK45", "DOP853")


def _one_of(value, allowed) -> bool:
    """``value`` is one of ``allowed``: a plain string or number (not a bool, array or other container)."""
    return isinstance(value, (str, int, float)) and not isinstance(value, bool) and value in allowed


def _spec(default, methods, help_text, allowed=None, bounds=None, method_defaults=None, unit="none"):
    """Field metadata: the value used when the option is not set (``default``; ``method_defaults``
    overrides it per method), the methods that use it, the allowed values (a tuple), a help text and
    the unit (UDUNITS; "1" for a dimensionless number, "none" for a choice or a switch)."""
    return {"default": default, "methods": tuple(methods), "help": help_text, "allowed": allowed, "bounds": bounds,
            "method_defaults": dict(method_defaults or {}), "unit": unit}


#: the smallest rtol (scipy's solve_ivp clamps smaller ones to about 100 eps)
RTOL_MIN = 1e-13

_SPEC = {
    "method": _spec(DEFAULT_METHOD, METHOD_NAMES, "solver: adaptive (variable steps with error control, "
                    "exponential-sum history, Richardson-extrapolated: any kernel, O(N K)); references: direct "
                    "(full-history product integration, the paper's scheme, O(N^2)), soe (fixed step, exponential-sum "
                    "history), ive (internal variables, scipy solve_ivp; Prony kernels), ive-numba (internal "
                    "variables, fixed step; Prony kernels), paper (explicit baseline for benchmarks)", METHOD_NAMES),
    "dt": _spec(None, FIXED_STEP_METHODS, f"time step, s, at most the contact-time estimate / "
                f"{MIN_STEPS_PER_CONTACT} and at least the estimate / {MAX_STEPS_PER_CONTACT} (null: the estimate / "
                f"steps_per_contact; give one of the two)",
                bounds=("float", 0.0, math.inf, "(0, inf) s"), unit="s"),
    "steps_per_contact": _spec(2000, FIXED_STEP_METHODS, f"automatic dt = contact-time estimate / this (integer "
                               f"{MIN_STEPS_PER_CONTACT}..{MAX_STEPS_PER_CONTACT})",
                               bounds=("int", MIN_STEPS_PER_CONTACT, MAX_STEPS_PER_CONTACT,
                                       f"an integer in [{MIN_STEPS_PER_CONTACT}, {MAX_STEPS_PER_CONTACT}]"),
                               unit="1"),
    "max_steps": _spec(200_000, FIXED_STEP_METHODS + ("ive",), "step budget (integer >= 100): of the fixed-step "
                       "march (4000000 for soe and ive-numba, whose cost is linear in the steps), and of solve_ivp's "
                       "steps for ive (60000, counted as calls of its event over every horizon, a doubled horizon "
                       "restarting from t = 0: enough for a 1 mm plate); a run that reaches it "
                       "without separating ends with status step-budget",
                       bounds=("int", 100, math.inf, "an integer >= 100"),
                       method_defaults={"soe": 4_000_000, "ive-numba": 4_000_000, "ive": 60_000}, unit="1"),
    "step_tol": _spec(4e-4, ("adaptive",), "adaptive only: local error per unit step of s' (the trapezoidal "
                      "error h^2 |g''|/12, g = s') relative to the motion's scale min(v0, |s'| + s / t_c), in "
                      "(0, 0.01); the default 4e-4 keeps COR and t0 within 1e-7 of independent references on every "
                      "preset at 0.001..300 m/s with the default extrapolation (docs: solver options, accuracy "
                      "table)", bounds=("float", 0.0, 1e-2, "(0, 0.01)"), unit="1"),
    "richardson": _spec(True, ("adaptive",), "adaptive only: march again on the accepted grid with every step "
                        "divided by 2, 4 and 8 and Richardson-extrapolate the results (eliminates the h^2, h^3.5 and "
                        "h^4 error terms; 15 times the steps of the grid), or by 2 and 4 only (h^2 and h^4; 7 times) "
                        "for an exact exponential-sum kernel with every mode resolved on the grid"),
    "max_adaptive_steps": _spec(1_000_000, ("adaptive",), "adaptive only: step budget (integer >= 100); a run that "
                                "reaches it without separating ends with status step-budget",
                                bounds=("int", 100, math.inf, "an integer >= 100"), unit="1"),
    "volterra": _spec(False, ("direct", "ive"), "add the second-order Volterra term (Green Eqs. 10, 15, 16)"),
    "c2": _spec(1.0, ("direct", "ive"), "Volterra coefficient, m^-1.5 (only with volterra: true)",
                bounds=("float", -math.inf, math.inf, "a finite number, m^-1.5"), unit="m-1.5"),
    "form": _spec("a", ("direct",), "hereditary Hertz law form (Green Eq. 8): a (any kernel) or b (finite k(0))",
                  ("a", "b")),
    "rule": _spec("force", METHOD_NAMES, "separation: force (F returns to zero, the paper's) or overlap (s returns to "
                  "zero)", ("force", "overlap")),
    "rtol": _spec(1e-10, ("ive",), f"relative tolerance of solve_ivp, in [{RTOL_MIN:g}, 1) (scipy clamps smaller "
                  "ones)", bounds=("float", RTOL_MIN, 1.0, f"[{RTOL_MIN:g}, 1)"), unit="1"),
    "ive_method": _spec("Radau", ("ive",), "solve_ivp method", IVE_METHODS),
    "soe_tol": _spec(1e-10, ("soe", "adaptive"), "relative error bound of the exponential sum of the kernel's "
                     "history part (vcor.materials.expsums; a two-body modulus no sum fits that closely is "
                     f"taken within FIT_ACCEPT and its error reported), in [{MIN_SOE_TOL:g}, {MAX_SOE_TOL:g}) (a sum "
                     f"checked in double precision reaches 1e-14 at best)",
                     bounds=("float", MIN_SOE_TOL, MAX_SOE_TOL, f"[{MIN_SOE_TOL:g}, {MAX_SOE_TOL:g})"), unit="1"),
    "ghost": _spec(0.5, METHOD_NAMES, "histories only: continue the solution this fraction of t0 past separation, "
                   "in [0, 10]", bounds=("float", 0.0, 10.0, "[0, 10]"), unit="1"),
}

#: option name -> help text (the CLI and the schema descriptions use it)
OPTION_HELP = {k: v["help"] for k, v in _SPEC.items()}
#: option name -> unit ("1": dimensionless, "none": a choice or a switch)
OPTION_UNITS = {k: v["unit"] for k, v in _SPEC.items()}


def _number(name, value, *, integer=False):
    kind = "an integer" if integer else "a number"
    try:
        as_float = float(value) if isinstance(value, numbers.Real) and not isinstance(value, bool) else None
    except OverflowError:
        raise ValueError(f"solver option {name} must be {kind} within the floating-point range, got "
                         f"{shown(value)}") from None
    if as_float is None or (integer and not (math.isfinite(as_float) and as_float.is_integer())):
        raise ValueError(f"solver option {name} must be {kind}, got {shown(value)}")
    return int(value) if integer else as_float


@dataclass(frozen=True, kw_only=True)
class SolverOptions:
    """Validated solver options (see the module docstring). Units: s, m^-1.5.

    Examples
    --------
    Options a method uses take its defaults; the others stay ``None``:

    >>> from vcor import SolverOptions
    >>> opts = SolverOptions(method="direct")
    >>> opts.steps_per_contact, opts.max_steps, opts.form, opts.step_tol
    (2000, 200000, 'a', None)

    An option the method does not use is refused, naming it:

    >>> SolverOptions(method="direct", rtol=1e-8)
    Traceback (most recent call last):
    ...
    ValueError: solver option rtol is not used by method 'direct' (it needs method ive); remove it
    >>> opts.replace(method="adaptive").step_tol
    0.0004
    """

    method: str = _SPEC["method"]["default"]
    dt: float | None = None
    steps_per_contact: int | None = None
    max_steps: int | None = None
    volterra: bool = _SPEC["volterra"]["default"]
    c2: float | None = None
    form: str | None = None
    rule: str = _SPEC["rule"]["default"]
    rtol: float | None = None
    ive_method: str | None = None
    soe_tol: float | None = None
    step_tol: float | None = None
    richardson: bool | None = None
    max_adaptive_steps: int | None = None
    ghost: float = _SPEC["ghost"]["default"]

    def __post_init__(self):
        if not _one_of(self.method, METHOD_NAMES):
            raise ValueError(f"solver option method must be one of {METHOD_NAMES}, got {self.method!r}")
        values = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}
        # 1. types and ranges of what was set
        for name, value in values.items():
            spec = _SPEC[name]
            if value is None:
                continue
            if spec["allowed"] is not None:
                if not _one_of(value, spec["allowed"]):
                    raise ValueError(f"solver option {name} must be one of {spec['allowed']}, got {value!r}")
            elif name in BOOLEAN_OPTIONS:
                if not isinstance(value, bool):
                    raise ValueError(f"solver option {name} must be true or false, got {value!r}")
            else:
                kind, lo, hi, text = spec["bounds"]
                v = _number(name, value, integer=kind == "int")
                # the interval text says which ends are closed: "[lo, hi)" ...; integers are closed
                lo_closed = kind == "int" or text.startswith("[")
                hi_closed = kind == "int" or text.endswith("]")
                inside = (lo <= v if lo_closed else lo < v) and (v <= hi if hi_closed else v < hi)
                if not (math.isfinite(v) and inside):
                    raise ValueError(f"solver option {name} must be {text if kind == 'int' else 'in ' + text}, "
                                     f"got {value!r}")
                values[name] = v
        if values["dt"] is not None and values["steps_per_contact"] is not None:
            raise ValueError(f"solver options dt = {values['dt']!r} s and steps_per_contact = "
                             f"{values['steps_per_contact']!r} both set the time step: give one of them")
        # 2. options the method ignores are errors, not silently dropped
        method = values["method"]
        for name, value in values.items():
            spec = _SPEC[name]
            unused = method not in spec["methods"] or (name == "c2" and not values["volterra"])
            is_set = value is not None and not (name == "volterra" and value is False)
            if unused and is_set:
                users = "volterra: true" if (name == "c2" and method in spec["methods"]) else \
                    f"method {' or '.join(spec['methods'])}"
                raise ValueError(f"solver option {name} is not used by method {method!r}"
                                 + (" without volterra" if name == "c2" else "") + f" (it needs {users}); remove it")
        if method == "paper" and values["volterra"]:
            raise ValueError("solver option volterra is not available with method 'paper' (benchmark baseline)")
        # 3. fill the method's defaults; everything it does not use stays None
        for name, value in values.items():
            spec = _SPEC[name]
            used = (method in spec["methods"] and not (name == "c2" and not values["volterra"])
                    and not (name == "steps_per_contact" and values["dt"] is not None))  # (dt sets the step)
            if used and value is None:
                values[name] = spec["method_defaults"].get(method, spec["default"])
        for name, value in values.items():
            object.__setattr__(self, name, value)

    def to_dict(self) -> dict:
        """All options, the unused ones as None (canonical: equal runs give equal dicts)."""
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}

    def replace(self, **changes) -> SolverOptions:
        """A copy with ``changes``; options the new method does not use are dropped first."""
        d = self.to_dict()
        if changes.get("dt") is not None:
            d["steps_per_contact"] = None  # (one of them sets the step)
        if changes.get("steps_per_contact") is not None:
            d["dt"] = None
        d.update(changes)
        method = d["method"]
        for name in list(d):
            if name not in changes and method not in _SPEC[name]["methods"]:
                d[name] = None
        if not d["volterra"] and "c2" not in changes:
            d["c2"] = None
        return SolverOptions(**d)

    @staticmethod
    def names() -> tuple[str, ...]:
        return tuple(_SPEC)

    @staticmethod
    def default_of(name: str, method: str | None = None):
        """The value an option takes when it is not set and ``method`` (default: the usual one) uses it.

        Examples
        --------
        >>> from vcor import SolverOptions
        >>> SolverOptions.default_of("max_steps"), SolverOptions.default_of("max_steps", "soe")
        (200000, 4000000)
        """
        return _SPEC[name]["method_defaults"].get(method, _SPEC[name]["default"])

    @staticmethod
    def allowed_of(name: str):
        """Allowed values (a tuple) or None for numeric/boolean options."""
        return _SPEC[name]["allowed"]

    @staticmethod
    def methods_of(name: str) -> tuple[str, ...]:
        return _SPEC[name]["methods"]


def solver_options(options=None, **kwargs) -> SolverOptions:
    """``options`` (a SolverOptions or a dict) or keyword arguments -> SolverOptions; not both.

    Examples
    --------
    >>> from vcor.solvers.options import solver_options
    >>> solver_options({"method": "ive"}).rtol
    1e-10
    >>> solver_options(method="soe").max_steps
    4000000
    """
    if options is None:
        return _validated(**kwargs)
    if kwargs:
        raise ValueError(f"give solver options either as options= or as keywords, not both ({sorted(kwargs)})")
    if isinstance(options, SolverOptions):
        return options
    if isinstance(options, dict):
        unknown = sorted(set(options) - set(_SPEC), key=str)
        if unknown:
            close = difflib.get_close_matches(str(unknown[0]), list(_SPEC), n=1, cutoff=0.6)
            hint = f"; did you mean {close[0]!r}?" if close else ""
            raise ValueError(f"unknown solver option(s) {unknown}; allowed: {sorted(_SPEC)}{hint}")
        return _validated(**options)
    raise ValueError(f"options must be a SolverOptions or a dict, got {type(options).__name__}")


#: SolverOptions(**kw), validated once per distinct option set (the dataclass is frozen)
_validated = interned(SolverOptions)
