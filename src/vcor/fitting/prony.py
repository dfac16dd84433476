"""Fits of CERF and Prony relaxation models to relaxation and/or complex-modulus data.

Design (and why it differs from the usual Prony tools): every residual is *relative*
(E_fit/E - 1 in time, ``|E*_fit|/|E*| - 1`` and tan(delta)_fit/tan(delta) - 1 in frequency), all
coefficients are positive by construction (fitted in log space), nothing is pinned to a data
point, and the relaxation rates start log-spaced over the data's range and are then refined
together with the moduli by ``scipy.optimize.least_squares`` (trust-region, bounded). The start
for the moduli is a non-negative linear least-squares solution (``scipy.optimize.nnls``) at the
log-spaced rates. Everything is deterministic (no random starts).

The Bagley-Torvik Butyl B252 data are the fractional law (Green Eq. 23) evaluated on the paper's
band f = 1e2..1e5 Hz (omega = 2 pi f); the time window is the one that band maps to with
t = 1/omega (not 1/f): t = 1/(2 pi 1e5) .. 1/(2 pi 1e2) = 1.59 us .. 1.59 ms.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.optimize import least_squares, nnls

from ..materials import models as _materials
from ..materials.presets import get as _preset

__all__ = ["FitData", "FitResult", "bagley_torvik_data", "fit", "fit_cerf", "fit_prony", "metrics"]


def _axis_and_values(axis_name, unit, axis, values_name, values, dtype):
    """Validated (axis, values): 1-D, equal length >= 3, axis finite, > 0 and strictly increasing."""
    x = np.asarray(axis, float)
    v = np.asarray(values, dtype)
    if x.shape != v.shape or x.ndim != 1 or x.size < 3:
        raise ValueError(f"{axis_name} and {values_name} must be 1-D arrays of equal length >= 3")
    if not (np.all(np.isfinite(x)) and np.all(x > 0) and np.all(np.diff(x) > 0)):
        raise ValueError(f"{axis_name} must be finite, > 0 {unit} and strictly increasing")
    return x, v


@dataclass(frozen=True, kw_only=True)
class FitData:
    """Relaxation data E(t) (Pa at s) and/or complex-modulus data E*(omega) (Pa at rad/s)."""

    t: np.ndarray | None = None
    E_t: np.ndarray | None = None
    omega: np.ndarray | None = None
    E_star: np.ndarray | None = None
    name: str = "data"
    #: measured data: noise may make E' or E(t) locally non-monotone (not an error then)
    measured: bool = False
    #: superposed measured data: the temperature (deg C) of the set each frequency point came from
    T_point: np.ndarray | None = None

    def __post_init__(self):
        has_t = self.t is not None or self.E_t is not None
        has_w = self.omega is not None or self.E_star is not None
        if not (has_t or has_w):
            raise ValueError("FitData needs relaxation data (t, E_t) and/or frequency data (omega, E_star)")
        if has_t:
            t, e = _axis_and_values("t", "s", self.t, "E_t", self.E_t, float)
            if not (np.all(np.isfinite(e)) and np.all(e > 0)):
                raise ValueError("E_t must be finite and > 0 Pa")
            if not self.measured and np.any(np.diff(e) > 1e-12 * e[:-1]):
                i = int(np.argmax(np.diff(e) > 1e-12 * e[:-1]))
                raise ValueError(
                    f"E_t is not a relaxation modulus: it increases between t = {t[i]:.4g} s and {t[i + 1]:.4g} s"
                )
            object.__setattr__(self, "t", t)
            object.__setattr__(self, "E_t", e)
        if has_w:
            w, es = _axis_and_values("omega", "rad/s", self.omega, "E_star", self.E_star, complex)
            if not np.all(np.isfinite(es)):
                raise ValueError("E_star must be finite")
            for part, values in (("storage", es.real), ("loss", es.imag)):
                if np.any(values <= 0):
                    i = int(np.argmax(values <= 0))
                    raise ValueError(f"E_star {part} modulus must be > 0 Pa (the fit's tan delta residual is "
                                     f"relative), got {float(values[i])!r} Pa at omega = {w[i]:.6g} rad/s")
            if not self.measured and np.any(np.diff(es.real) < -1e-12 * es.real[:-1]):
                raise ValueError("E_star is not a viscoelastic solid's: the storage modulus decreases with omega")
            object.__setattr__(self, "omega", w)
            object.__setattr__(self, "E_star", es)

    @property
    def has_time(self):
        return self.t is not None

    @property
    def has_freq(self):
        return self.omega is not None


def bagley_torvik_data(n_freq: int = 61, n_time: int = 61, f_min=1e2, f_max=1e5) -> FitData:
    """The fractional law of Green Eq. 23 sampled on the paper's band (log-spaced)."""
    mat = _preset("butyl-fc")
    w = 2 * math.pi * np.geomspace(f_min, f_max, n_freq)
    t = np.geomspace(1.0 / w[-1], 1.0 / w[0], n_time)
    return FitData(t=t, E_t=mat.relaxation_modulus(t), omega=w, E_star=mat.complex_modulus(w),
                   name=f"Bagley-Torvik Butyl B252 (Eq. 23), f = {f_min:g}..{f_max:g} Hz, t = 1/omega")


def metrics(material, data: FitData) -> dict:
    """Max and RMS relative errors of E(t) over the window, and of ``|E*|``, tan(delta), E' (storage) and E''
    (loss) over the band."""
    out = {}
    if data.has_time:
        r = material.relaxation_modulus(data.t) / data.E_t - 1
        out["E_t_max"], out["E_t_rms"] = float(np.max(np.abs(r))), float(np.sqrt(np.mean(r**2)))
    if data.has_freq:
        e = material.complex_modulus(data.omega)
        r = np.abs(e) / np.abs(data.E_star) - 1
        out["abs_E_star_max"], out["abs_E_star_rms"] = float(np.max(np.abs(r))), float(np.sqrt(np.mean(r**2)))
        tan_d = data.E_star.imag / data.E_star.real
        r = (e.imag / e.real) / tan_d - 1
        out["tan_delta_max"], out["tan_delta_rms"] = float(np.max(np.abs(r))), float(np.sqrt(np.mean(r**2)))
        for part, fit_part, data_part in (("storage", e.real, data.E_star.real), ("loss", e.imag, data.E_star.imag)):
            r = fit_part / data_part - 1
            out[f"{part}_max"], out[f"{part}_rms"] = float(np.max(np.abs(r))), float(np.sqrt(np.mean(r**2)))
    return out


def _residuals(material, data, domain):
    parts = []
    if domain in ("time", "both") and data.has_time:
        parts.append(material.relaxation_modulus(data.t) / data.E_t - 1)
    if domain in ("frequency", "both") and data.has_freq:
        e = material.complex_modulus(data.omega)
        parts.append(np.abs(e) / np.abs(data.E_star) - 1)
        parts.append((e.imag / e.real) / (data.E_star.imag / data.E_star.real) - 1)
    if not parts:
        raise ValueError(f"domain {domain!r} has no data (time: {data.has_time}, frequency: {data.has_freq})")
    return np.concatenate(parts)


@dataclass(frozen=True, kw_only=True)
class FitResult:
    """A fitted material, its metrics (:func:`metrics`), the fit's settings, the number of terms, the wall
    time (s) and, for an automatic N, the (N, worst error) pairs tried."""

    material: _materials.Material
    metrics: dict
    settings: dict
    n_terms: int | None = None
    fit_time: float = 0.0
    tried: list = field(default_factory=list)  # (N, max error) for automatic N

    @property
    def max_error(self) -> float:
        """The worst of E(t), ``|E*|`` and tan delta errors (the automatic N's criterion; E' and E'' are
        reported, not used: ``|E*|`` and tan delta carry the same information)."""
        keys = [k for k in ("E_t_max", "abs_E_star_max", "tan_delta_max") if k in self.metrics]
        return max(self.metrics[k] for k in keys) if keys else math.nan


def _rate_range(data):
    lo, hi = [], []
    if data.has_time:
        lo.append(1.0 / data.t[-1])
        hi.append(1.0 / data.t[0])
    if data.has_freq:
        lo.append(data.omega[0])
        hi.append(data.omega[-1])
    return min(lo), max(hi)


def _nnls_moduli(data, b, domain):
    """Non-negative moduli (E_inf, E_k) at fixed rates b, minimising the linear relative residuals
    E_fit(t)/E(t) - 1 and (E*_fit - E*)/|E*|. Returns (coefficients, residual norm)."""
    rows, rhs = [], []
    if domain in ("time", "both") and data.has_time:
        rows.append(np.column_stack([np.ones_like(data.t), np.exp(-np.multiply.outer(data.t, b))]) / data.E_t[:, None])
        rhs.append(np.ones_like(data.t))
    if domain in ("frequency", "both") and data.has_freq:
        iw = 1j * data.omega[:, None]
        A = np.column_stack([np.ones_like(data.omega), (iw / (iw + b))]) / np.abs(data.E_star)[:, None]
        target = data.E_star / np.abs(data.E_star)
        rows += [A.real, A.imag]
        rhs += [target.real, target.imag]
    return nnls(np.vstack(rows), np.concatenate(rhs), maxiter=50 * (b.size + 1))


#: start: rates geometric over the data's rate range widened by e^c at both ends, best c of these
_SPANS = (0.0, 0.5, 1.0, 1.5, 2.0, 3.0)


def _prony_start(data, n, domain):
    """Geometric rates (the fractional law is scale-free) and NNLS moduli; best of a few spans."""
    b_lo, b_hi = _rate_range(data)
    best = None
    for c in _SPANS:
        lo, hi = math.log(b_lo) - c, math.log(b_hi) + c
        b = np.exp(np.linspace(lo, hi, n)) if n > 1 else np.array([math.sqrt(b_lo * b_hi)])
        coef, rnorm = _nnls_moduli(data, b, domain)
        if best is None or rnorm < best[0]:
            best = (rnorm, coef, b)
    _, coef, b = best
    scale = float(np.median(np.abs(data.E_star))) if data.has_freq else float(np.median(data.E_t))
    coef = np.maximum(coef, 1e-8 * scale)  # strictly positive for the log parametrisation
    return coef[0], coef[1:], b


def fit_prony(data: FitData, n_terms: int | None = None, *, tol: float = 0.01, n_max: int = 16,
              domain: str = "both") -> FitResult:
    """Prony series with ``n_terms`` terms, or (None) the smallest N whose worst metric <= tol."""
    if n_terms is not None and not (isinstance(n_terms, (int, np.integer)) and 1 <= n_terms <= 64):
        raise ValueError(f"n_terms must be an integer in [1, 64] or None, got {n_terms!r}")
    if not (0 < tol < 1):
        raise ValueError(f"tol must be in (0, 1), got {tol!r}")
    t_start = time.perf_counter()
    if n_terms is None:
        tried = []
        best = None
        for n in range(1, n_max + 1):
            res = _fit_prony_n(data, n, domain)
            tried.append((n, res.max_error))
            best = res
            if res.max_error <= tol:
                break
        best.settings.update(n_terms="auto", tol=tol, n_max=n_max)
        if best.max_error > tol:
            best.settings["warning"] = f"no N <= {n_max} met tol = {tol}"
        return replace(best, tried=tried, fit_time=time.perf_counter() - t_start)
    res = _fit_prony_n(data, int(n_terms), domain)
    return replace(res, fit_time=time.perf_counter() - t_start)


#: evaluation budget of the nonlinear polish (keeps every fit well under a second)
_NFEV_PER_PARAM = 40


def _fit_prony_n(data, n, domain):
    e_inf, e, b = _prony_start(data, n, domain)
    x0 = np.log(np.concatenate([[e_inf], e, b]))
    b_lo, b_hi = _rate_range(data)
    e_scale = np.log(float(np.max(np.abs(data.E_star))) if data.has_freq else float(np.max(data.E_t)))
    lo = np.concatenate([[e_scale - 40] * (n + 1), [math.log(b_lo) - 7] * n])
    hi = np.concatenate([[e_scale + 10] * (n + 1), [math.log(b_hi) + 7] * n])
    x0 = np.clip(x0, lo + 1e-9, hi - 1e-9)

    def make(x):
        ex = np.exp(x)
        order = np.argsort(ex[n + 1:])
        return _materials.Prony(float(ex[0]), tuple(ex[1 : n + 1][order]), tuple(ex[n + 1:][order]))

    sol = least_squares(lambda x: _residuals(make(x), data, domain), x0, bounds=(lo, hi), method="trf",
                        x_scale="jac", xtol=1e-10, ftol=1e-10, gtol=1e-10, max_nfev=_NFEV_PER_PARAM * (2 * n + 1))
    mat = make(sol.x)
    start = make(x0)
    if max(metrics(start, data).values()) < max(metrics(mat, data).values()):
        mat = start  # the polish may stop in a worse corner; never return worse than the start
    return FitResult(material=mat, metrics=metrics(mat, data), n_terms=n,
                     settings={"model": "prony", "n_terms": n, "domain": domain, "nfev": int(sol.nfev)})


#: residual (per point, relative) of a trial point the material refuses: large against any misfit of a fit
_REFUSED = 10.0


def fit_cerf(data: FitData, *, domain: str = "both", start=(0.442e6, 0.6765e9, 700.0)) -> FitResult:
    """CERF law E0 + E1 erfcx(b1 sqrt t), started from the paper's Eq. 24 set."""
    t_start = time.perf_counter()
    x0 = np.log(np.asarray(start, float))

    def make(x):
        e0, e1, b1 = np.exp(x)
        return _materials.Cerf(float(e0), float(e1), float(b1))

    # On the pure fractional law the optimum is the limit b1 -> inf with E1/b1 fixed (the CERF family
    # contains the power law as a limit); the evaluation cap stops that walk once the residual is tiny, and a
    # trial point beyond a parameter's range (E1 above vcor.materials.base.MAX_MODULUS) is refused: a large
    # residual, so that the walk stops there.
    size = _residuals(make(x0), data, domain).size

    def residual(x):
        try:
            mat = make(x)
        except ValueError:
            return np.full(size, _REFUSED)
        return _residuals(mat, data, domain)

    sol = least_squares(residual, x0, method="trf", x_scale="jac", xtol=1e-10, ftol=1e-10, gtol=1e-10, max_nfev=300)
    mat = make(sol.x)
    settings = {"model": "cerf", "domain": domain, "nfev": int(sol.nfev), "optimizer_status": int(sol.status),
                "start": list(start)}
    return FitResult(material=mat, metrics=metrics(mat, data), settings=settings,
                     fit_time=time.perf_counter() - t_start)


def fit(spec: dict, data: FitData | None = None) -> FitResult:
    """Fit from a config spec: {model: prony|cerf, n_terms: int|'auto', tol, n_max, domain}."""
    data = data or bagley_torvik_data()
    model = spec.get("model")
    domain = spec.get("domain", "both")
    if domain not in ("time", "frequency", "both"):
        raise ValueError(f"domain must be time, frequency or both, got {domain!r}")
    if (domain == "time" and not data.has_time) or (domain == "frequency" and not data.has_freq):
        raise ValueError(f"domain {domain!r} has no data (time: {data.has_time}, frequency: {data.has_freq})")
    if model == "prony":
        n = spec.get("n_terms", "auto")
        return fit_prony(data, None if n == "auto" else int(n), tol=float(spec.get("tol", 0.01)),
                         n_max=int(spec.get("n_max", 16)), domain=domain)
    if model == "cerf":
        return fit_cerf(data, domain=domain)
    raise ValueError(f"fit model must be 'prony' or 'cerf', got {model!r}")
