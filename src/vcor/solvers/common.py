"""Shared pieces of the solvers: the Result record, status codes, and separation post-processing."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from ..status import STATUS_CODES

__all__ = ["LONG_NAMES", "STATUS_CODES", "UNITS", "Histories", "Result", "peak", "richardson", "separation"]

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
    "energy_residual": "relative energy balance residual (see README)",
    "steps": "time steps taken",
    "wall_time": "solver wall time",
    "dt": "time step",
}


@dataclass
class Histories:
    """Time histories (SI). ``ghost`` marks samples after separation (t > t0)."""

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


@dataclass
class Result:
    """Outcome of one impact. Units: s, m, N, J, rad/s; cor and energy_residual are ratios."""

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
    status: str = "ok"
    message: str = ""
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


class _Cubic:
    """The interpolating polynomial through (tn, yn) (any number of nodes, here four) in Newton form:
    divided differences once, then each evaluation costs a few multiplications (the separation's
    root search evaluates it ~10 times)."""

    __slots__ = ("c", "tn")

    def __init__(self, tn, yn):
        self.tn = [float(x) for x in tn]
        c = [float(y) for y in yn]
        n = len(c)
        for j in range(1, n):
            for i in range(n - 1, j - 1, -1):
                c[i] = (c[i] - c[i - 1]) / (self.tn[i] - self.tn[i - j])
        self.c = c

    def __call__(self, t):
        c, tn = self.c, self.tn
        total = c[-1]
        for i in range(len(c) - 2, -1, -1):
            total = total * (t - tn[i]) + c[i]
        return total


def peak(t, y, f=None):
    """Maximum of sampled y(t). Refined by the parabola through the largest sample and its neighbours
    (any spacing), or, when ``f`` (a callable y(t), e.g. a dense output) is given, by a bounded
    scalar search for the maximum of f between the neighbouring samples."""
    i = int(np.argmax(y))
    if i == 0 or i == y.size - 1:
        return float(y[i])
    if f is not None:
        lo, hi = t[i - 1], t[i + 1]
        r = minimize_scalar(lambda x: -f(x), bounds=(lo, hi), method="bounded", options={"xatol": 1e-14 * hi})
        return float(max(-r.fun, y[i]))
    # the parabola through the three samples (any spacing), Newton form around t[i - 1]
    h1, h2 = t[i] - t[i - 1], t[i + 1] - t[i]
    d1 = (y[i] - y[i - 1]) / h1
    curv = ((y[i + 1] - y[i]) / h2 - d1) / (h1 + h2)
    if curv >= 0.0:
        return float(y[i])
    x = 0.5 * (t[i - 1] + t[i]) - 0.5 * d1 / curv
    return float(y[i - 1] + d1 * (x - t[i - 1]) + curv * (x - t[i - 1]) * (x - t[i]))


def separation(t, s, g, F, J, n_sep, rule, m, v0):
    """Locate separation inside [t_{n-1}, t_n] and evaluate the outcome there.

    The crossing of F (rule "force"; of s when s also crossed in that step) or of s (rule "overlap")
    is found as the root of the cubic
    interpolant (Newton form) through the four nodes around it (third-order interpolation, error
    O(dt^4)); s, s', J are interpolated the same way. The interpolant equals the nodes, so the
    root is always bracketed in a march's separation step; anything else raises (no silent guess).
    Returns a dict of the scalars and ``message`` (empty).
    """
    n = int(n_sep)
    lo = max(0, min(n - 2, len(t) - 4))
    idx = slice(lo, lo + 4)
    tn = t[idx]
    # F = 0 and s = 0 in the same step (elastic-like separation): F ~ s^{3/2} is not smooth at its
    # root, s is, so the root of s locates the same instant far more accurately. (If s crossed in an
    # earlier step, its root is not in this one: F's is used.)
    by_overlap = rule == "overlap" or (s[n] <= 0.0 < s[n - 1])
    target = s if by_overlap else F
    f = _Cubic(tn, target[idx])
    a, b = t[n - 1], t[n]
    fa, fb = f(a), f(b)
    message = ""
    if not (fa > 0 >= fb):
        # cannot happen for a march's separation step (the interpolant equals the nodes, and the
        # target was > 0 at step n - 1 and <= 0 at step n); loud rather than a silent guess
        raise RuntimeError(f"separation step {n}: {'s' if by_overlap else 'F'} does not change sign "
                           f"({fa!r} -> {fb!r})")
    # Brent's method on the cubic interpolant, bracketed by fa > 0 >= fb
    t0 = b if fb == 0.0 else brentq(f, a, b, xtol=1e-15 * max(b, 1e-300), rtol=4 * np.finfo(float).eps, maxiter=200)
    s0 = _Cubic(tn, s[idx])(t0)
    g0 = _Cubic(tn, g[idx])(t0)
    J0 = _Cubic(tn, J[idx])(t0)
    F0 = 0.0 if rule == "force" else _Cubic(tn, F[idx])(t0)
    z0 = v0 - J0 / m
    # quadrature: trapezoid on nodes 0..n-1 plus the partial interval [t_{n-1}, t0]
    zd = v0 - J / m
    fg = F[:n] * g[:n]
    fz = F[:n] * zd[:n]
    half = 0.5 * np.diff(t[:n])  # trapezoid on any grid
    w_h = float(half @ (fg[1:] + fg[:-1])) + 0.5 * (t0 - a) * (fg[-1] + F0 * g0)
    w_z = float(half @ (fz[1:] + fz[:-1])) + 0.5 * (t0 - a) * (fz[-1] + F0 * z0)
    e_in = 0.5 * m * v0 * v0
    energy_residual = (e_in - 0.5 * m * z0 * z0 - w_z) / e_in
    return {
        "t0": float(t0),
        "cor": float(abs(g0) / v0),
        "s_residual": float(s0),
        "w_h": float(w_h),
        "w_plate": float(w_z - w_h),
        "omega_min": float(2 * math.pi / t0),
        "sphere_velocity": float(z0),
        "energy_residual": float(energy_residual),
        "s_max": peak(t[: n + 1], s[: n + 1]),
        "f_max": peak(t[: n + 1], F[: n + 1]),
        "message": message,
    }


def richardson(coarse: float, fine: float, order: float = 2.0) -> tuple[float, float]:
    """Richardson extrapolation from runs at dt (``coarse``) and dt/2 (``fine``) of a method of the
    given order: (extrapolated value, error estimate of the coarse value |coarse - extrapolated|)."""
    f = 2.0**order
    extrapolated = fine + (fine - coarse) / (f - 1.0)
    return extrapolated, abs(coarse - extrapolated)
