"""Shared pieces of the solvers: the Result record, status codes, and separation post-processing."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

import numpy as np

from ._records import Body, Nodes

__all__ = ["LONG_NAMES", "OUTCOME", "UNITS", "Histories", "Result", "peak", "richardson", "separation"]

UNITS = {
    "cor": "1",
    "t0": "s",
    "s_max": "m",
    "f_max": "N",
    "s_residual": "m",
    "w_h": "J",
    "w_plate": "J",
    "omega_min": "rad s-1",
    "sphere_velocity": "m s-1",
    "energy_residual": "1",
    "steps": "1",
    "wall_time": "s",
    "dt": "s",
    "soe_error": "1",
    "validity": "1",
}

LONG_NAMES = {
    "cor": "coefficient of restitution |s'(t0)|/v0",
    "t0": "separation time (contact force returns to zero)",
    "s_max": "maximum interference",
    "f_max": "maximum contact force",
    "s_residual": "residual interference at separation",
    "w_h": "hysteretic loss int_0^t0 F s' dt",
    "w_plate": "work done on the plate int_0^t0 F U' dt",
    "omega_min": "minimum frequency of relevance 2 pi / t0",
    "sphere_velocity": "sphere velocity z'(t0) at separation (negative: rebound)",
    "energy_residual": "relative energy balance residual (m v0^2/2 - m z0^2/2 - int F dz) / (m v0^2/2)",
    "steps": "time steps taken",
    "wall_time": "solver wall time",
    "dt": "time step (the largest one on a variable grid)",
    "soe_error": "relative error of the exponential sums that carried the kernel's history and the plate's "
                 "modulus, on the solve's time window (0: none used, or exact)",
    "validity": "validity flags of an ok result (vcor.solvers.validity)",
}


@dataclass(kw_only=True)
class Histories:
    """Time histories (SI). ``ghost`` marks samples after separation (t > t0).

    Examples
    --------
    >>> import vcor
    >>> h = vcor.simulate("sls", 1.0, history=True).history
    >>> f"F_max {h.F[~h.ghost].max():.1f} N", bool(h.ghost[0]), bool(h.ghost[-1])
    ('F_max 36.2 N', False, True)
    """

    t: np.ndarray
    s: np.ndarray
    sdot: np.ndarray
    F: np.ndarray
    J: np.ndarray
    zdot: np.ndarray
    U: np.ndarray

    @property
    def ghost(self) -> np.ndarray:
        return self._ghost

    def mark(self, t0: float):
        self._ghost = self.t > t0
        return self


@dataclass(kw_only=True)
class Result:
    """Outcome of one impact. Units: s, m, N, J, rad/s; cor, energy_residual and soe_error are ratios.
    ``soe_error``: the relative error of the exponential sums the method carried the kernel's history
    and the plate's modulus on (:mod:`vcor.materials.expsums`; 0 for exact sums and for the methods
    that use none; for a two-body modulus that relaxes below ``expsums.RELAXED`` of its start, beyond
    that point the error relative to the start). ``validity``: flags of an ok result outside the model's
    stated range, with ``validity_message`` (:mod:`vcor.solvers.validity`). ``wall_time`` (s): the solve;
    a process's first call of a method also loads that method's numba kernels (from numba's cache, or
    compiling them), and that time is in it: ``vcor.solvers.backend.load_kernels([method])`` loads them
    beforehand, and the ``vcor impact`` command reports the loading apart (``kernel_load_time``).

    Examples
    --------
    >>> import vcor
    >>> r = vcor.simulate("butyl-prony3", 1.0)
    >>> r.ok, f"{r.cor:.3f}", f"{r.s_max * 1e3:.3f} mm", f"{r.w_h * 1e3:.2f} mJ"
    (True, '0.287', '0.423 mm', '12.17 mJ')
    >>> d = r.with_units()
    >>> d["f_max"]["units"], round(d["f_max"]["value"], 1)
    ('N', 55.3)
    """

    cor: float = math.nan
    t0: float = math.nan
    s_max: float = math.nan
    f_max: float = math.nan
    s_residual: float = math.nan
    w_h: float = math.nan
    w_plate: float = math.nan
    omega_min: float = math.nan
    sphere_velocity: float = math.nan
    energy_residual: float = math.nan
    steps: int = 0
    wall_time: float = math.nan
    dt: float = math.nan
    soe_error: float = 0.0
    status: str = "ok"
    message: str = ""
    validity: int = 0
    validity_message: str = ""
    method: str = ""
    history: Histories | None = field(default=None, repr=False)

    @property
    def ok(self) -> bool:
        return self.status == "ok"

    def scalars(self) -> dict:
        d = asdict(self)
        d.pop("history", None)
        return d

    def with_units(self) -> dict:
        """Scalars as {name: {"value": v, "units": u}} (for JSON output)."""
        out = {}
        for k, v in self.scalars().items():
            if k in UNITS:
                out[k] = {"value": v, "units": UNITS[k]}
            else:
                out[k] = v
        return out


def peak(t, y, f=None):
    """Maximum of sampled y(t). Refined by the parabola through the largest sample and its neighbours
    (any spacing), or, when ``f`` (a callable y(t), e.g. a dense output) is given, by a bounded
    scalar search for the maximum of f between the neighbouring samples.

    Examples
    --------
    >>> import numpy as np
    >>> from vcor.solvers.common import peak
    >>> t = np.linspace(0.0, 1.0, 11)
    >>> round(peak(t, 1.0 - (t - 0.53) ** 2), 12)  # the parabola through three samples: exact here
    1.0
    """
    # the kernels and scipy.optimize are imported on use: the records and the vocabulary of this module
    # (OUTCOME, UNITS, Result) are read by jobs that solve nothing (aggregation, figures)
    from ._separation import parabola_peak

    i = int(np.argmax(y))
    if i == 0 or i == y.size - 1:
        return float(y[i])
    if f is not None:
        from scipy.optimize import minimize_scalar

        lo, hi = t[i - 1], t[i + 1]
        r = minimize_scalar(lambda x: -f(x), bounds=(lo, hi), method="bounded", options={"xatol": 1e-14 * hi})
        return float(max(-r.fun, y[i]))
    return float(parabola_peak(np.asarray(t, dtype=float), np.asarray(y, dtype=float), y.size - 1))


def separation(t, s, g, F, J, n_sep, rule, m, v0, still_plate=False, glassy=0.0):
    """Locate separation inside [t_{n-1}, t_n] and evaluate the outcome there.

    The crossing of F (rule "force"; of s when s also crossed in that step) or of s (rule "overlap")
    is found as the root of the cubic interpolant (Newton form) through the four nodes around it
    (third-order interpolation, error O(dt^4)); s, s', J are interpolated the same way, except s' of an
    elastic kernel (``F = k u``, ``u = sgn(s) |s|^(3/2)``) crossing s = 0 on a plate of constant mobility
    (``still_plate``): s'(t0) = v0 - J(t0)/m there, exactly (its ``F ~ |t - t0|^(3/2)`` is not smooth).
    ``glassy`` (N m^-1.5): the kernel's finite k(0) (no Dirac term), or 0: a root of F is then located on
    glassy u(s) + (F - glassy u) (``_separation.separation_point``).
    The interpolant equals the nodes, so the root is always bracketed in a march's separation step;
    anything else raises (no silent guess).
    Returns a dict of the scalars and ``message`` (empty).
    """
    from ._separation import locate_separation

    n = int(n_sep)
    out = np.empty(9)
    u = np.sign(s) * np.abs(s) ** 1.5  # (every march's u; the paper's explicit one keeps none)
    nodes = tuple(Nodes(*(np.ascontiguousarray(a, dtype=float) for a in (t, s, g, F, J, u))))
    if not locate_separation(nodes, n, len(t), rule == "overlap", tuple(Body(0.0, float(m), float(v0))),
                             bool(still_plate), float(glassy), out):
        # cannot happen for a march's separation step (the interpolant equals the nodes, and the
        # target was > 0 at step n - 1 and <= 0 at step n); loud rather than a silent guess
        by_overlap = rule == "overlap" or (s[n] <= 0.0 < s[n - 1])
        target = s if by_overlap else F
        raise RuntimeError(f"separation step {n}: {'s' if by_overlap else 'F'} does not change sign "
                           f"({target[n - 1]!r} -> {target[n]!r})")
    return separation_scalars(out)


#: the outcome of a separation as ``_separation.separation_point`` returns it, in this order (UNITS)
OUTCOME = ("cor", "t0", "s_residual", "w_h", "w_plate", "sphere_velocity", "energy_residual", "s_max", "f_max")


def separation_scalars(values) -> dict:
    """The Result fields from ``_separation.separation_point``'s values (a list or an array in the order
    of OUTCOME; any further values ignored), with ``omega_min`` and ``message`` (empty)."""
    out = dict(zip(OUTCOME, values.tolist() if isinstance(values, np.ndarray) else values))
    out["omega_min"] = 2 * math.pi / out["t0"]
    out["message"] = ""
    return out


def richardson(coarse: float, fine: float, order: float = 2.0) -> tuple[float, float]:
    """Richardson extrapolation from runs at dt (``coarse``) and dt/2 (``fine``) of a method of the
    given order: (extrapolated value, error estimate of the coarse value ``|coarse - extrapolated|``).

    Examples
    --------
    >>> from vcor.solvers.common import richardson
    >>> richardson(1.0, 1.75)  # second order: the error falls by 4 when dt halves
    (2.0, 1.0)
    """
    f = 2.0**order
    extrapolated = fine + (fine - coarse) / (f - 1.0)
    return extrapolated, abs(coarse - extrapolated)
