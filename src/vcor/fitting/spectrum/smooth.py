r"""Smooth relaxation spectrum fits ("smooth by construction") of complex-modulus data.

Model
-----
Relaxation times on a *fixed* logarithmic grid :math:`\tau_j` (``per_decade`` per decade, spanning
the data's :math:`1/(2\pi f_\max) .. 1/(2\pi f_\min)` widened by ``margin`` decades,
:data:`vcor.fitting.spectrum.model.MARGIN`), non-negative moduli :math:`E_j = e^{H_j}` and an
equilibrium modulus :math:`E_\infty = e^{H_0}`:

.. math::

   E(t) = E_\infty + \sum_j E_j e^{-t/\tau_j}, \qquad
   E^*(\omega) = E_\infty + \sum_j E_j \frac{i\omega\tau_j}{1 + i\omega\tau_j}.

On the uniform log grid :math:`E_j = h(\tau_j)\,\Delta\ln\tau`, so :math:`H_j` is the log-spectrum
:math:`\ln h` up to a constant.

What is minimised
-----------------
.. math::

   V_\lambda(H) = \sum_i m_i \Big[a'\Big(\frac{E'_{\rm fit}(\omega_i)}{E'_i} - 1\Big)^2
                 + a''\Big(\frac{E''_{\rm fit}(\omega_i)}{E''_i} - 1\Big)^2\Big]
                 + a_t \sum_l \Big(\frac{E_{\rm fit}(t_l)}{E(t_l)} - 1\Big)^2
                 + \lambda \sum_j (H_{j-1} - 2H_j + H_{j+1})^2

(:math:`m_i` point multiplicities, :math:`a', a'', a_t` component weights, default 1; the data rows
are :mod:`vcor.fitting.spectrum.residual`'s): relative errors of :math:`E'` and :math:`E''` (and
optionally of :math:`E(t)`), plus Tikhonov regularisation of the roughness (second differences) of the
log-spectrum.  The log-parametrisation makes the moduli positive by construction and penalises
*relative* wiggles of the spectrum equally in its large and small parts (a penalty on :math:`h` itself
lets the low-amplitude wings, which set the glassy :math:`\tan\delta`, wiggle freely); the tails beyond
the data continue as power laws (zero second difference).  As in Shanbhag's pyReSpect
(``contSpec.py``: log-spectrum, second-difference penalty, relative residuals) but with both
:math:`E'` and :math:`E''` residuals relative to themselves and :math:`\lambda` chosen by GCV
(:mod:`vcor.fitting.spectrum.lam`).

How it is solved
----------------
Levenberg-Marquardt (Gauss-Newton with adaptive damping) on :math:`(H_0, H_1..H_n)` with the
analytic Jacobian, warm-started along the scan of :math:`\lambda`.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
from scipy.linalg import cho_factor, cho_solve

from .lam import choose_lambda
from .lm import levenberg_marquardt
from .model import MARGIN, PER_DECADE, complex_modulus, fit_metrics, relaxation_modulus, tau_grid
from .residual import Design, Residual, second_differences

__all__ = ["SmoothProblem", "SpectrumFit", "component_weights", "fit_spectrum", "log_spectrum", "loss_weights"]

#: relative uncertainty of a measured modulus, the default of :func:`loss_weights`
U_MODULUS = 0.01
#: absolute uncertainty of a measured loss angle, rad (0.11 deg), the default of :func:`loss_weights`
U_PHASE = 0.002
#: the start's E_inf is this fraction of the smallest E' (below every measured E')
E_INF_START = 0.9
#: smallest start modulus relative to the largest E': keeps the start's log finite
E_FLOOR = 1e-9


@dataclass(frozen=True, kw_only=True)
class SpectrumFit:
    """A smooth-spectrum Prony fit (:func:`fit_spectrum`).

    Attributes
    ----------
    tau : ndarray
        Relaxation times, s (fixed log grid).
    E : ndarray
        Mode moduli E_j, Pa (> 0).
    E_inf : float
        Equilibrium modulus, Pa.
    h : ndarray
        Spectrum per unit ln tau, Pa: E_j / Delta ln tau.
    lam : float
        The regularisation parameter used.
    method : str
        How lam was chosen ("gcv1se", "gcv", "lcurve" or "given").
    scan : dict
        lam grid and, per lam: GCV, residual norm rho, roughness eta, effective dof, iterations.
    metrics : dict
        :func:`vcor.fitting.spectrum.model.fit_metrics` against the data fitted.
    f_range : tuple
        Data frequency range (Hz) over which the metrics and extrema are evaluated.
    time : float
        Wall time, s.
    notes : list of str
    """

    tau: np.ndarray
    E: np.ndarray
    E_inf: float
    h: np.ndarray
    lam: float
    method: str
    scan: dict
    metrics: dict
    f_range: tuple
    time: float
    notes: list = field(default_factory=list)

    @property
    def n_modes(self) -> int:
        return int(self.E.size)

    def complex_modulus(self, omega):
        """E*(omega), Pa (omega rad/s)."""
        return complex_modulus(omega, self.E_inf, self.E, self.tau)

    def relaxation_modulus(self, t):
        """E(t), Pa (t s)."""
        return relaxation_modulus(t, self.E_inf, self.E, self.tau)

    def prony_terms(self):
        """(E_inf [Pa], E [Pa], beta = 1/tau [1/s]) as vcor.materials.Prony takes them."""
        return float(self.E_inf), self.E.copy(), 1.0 / self.tau


class SmoothProblem:
    """V_lambda in theta = (ln E_inf, H_1..H_n): the data rows at a fixed design plus the roughness."""

    def __init__(self, residual: Residual, design: Design, n_modes: int, fit_E_inf: bool):
        self.residual, self.design = residual, design
        self.n = n_modes
        self.D = second_differences(n_modes)
        self.fit_E_inf = fit_E_inf

    def moduli(self, th):
        """(E_inf, E) in Pa of theta (E_inf = 0 unless fitted)."""
        return (float(np.exp(th[0])) if self.fit_E_inf else 0.0), np.exp(th[1:])

    def data_residual(self, th):
        with np.errstate(over="ignore", invalid="ignore"):     # a wild trial step: cost inf, rejected
            return self.residual.value(self.design, *self.moduli(th))

    def data_jac(self, th):
        return self.residual.spectrum_columns(self.design, *self.moduli(th))

    def penalty_matrix(self):
        """L^T L in theta coordinates (E_inf unpenalised)."""
        P = np.zeros((self.n + 1, self.n + 1))
        P[1:, 1:] = self.D.T @ self.D
        return P

    def solve(self, th, lam, max_iter=300, tol=1e-10):
        """Levenberg-Marquardt minimisation of ||r_data||^2 + lam ||D H||^2 from theta = th."""
        P = lam * self.penalty_matrix()

        def cost(t):
            r = self.data_residual(t)
            dh = self.D @ t[1:]
            with np.errstate(over="ignore", invalid="ignore"):
                return float(r @ r) + lam * float(dh @ dh), r

        def normal(t, r):
            J = self.data_jac(t)
            A = J.T @ J + P
            g = J.T @ r + P @ t
            if not self.fit_E_inf:
                A[0, :], A[:, 0], A[0, 0], g[0] = 0.0, 0.0, 1.0, 0.0
            return A, g

        return levenberg_marquardt(cost, normal, th, max_iter=max_iter, tol=tol, nu_max=1e12)

    def diagnostics(self, th, lam):
        """(rho = ||r_data||, eta = ||D H||, edf = tr A_lambda, N)."""
        r = self.data_residual(th)
        J = self.data_jac(th)
        JtJ = J.T @ J
        if not self.fit_E_inf:
            JtJ = JtJ[1:, 1:]
            P = lam * (self.D.T @ self.D)
        else:
            P = lam * self.penalty_matrix()
        M = JtJ + P + 1e-12 * np.trace(JtJ) / JtJ.shape[0] * np.eye(JtJ.shape[0])
        edf = float(np.trace(cho_solve(cho_factor(M), JtJ)))
        return float(np.linalg.norm(r)), float(np.linalg.norm(self.D @ th[1:])), edf, r.size


def log_spectrum(start: SpectrumFit, tau, E_max):
    """A fit's (ln E_inf, H) carried onto the grid ``tau`` (log-log interpolation of h), E_inf floored
    at :data:`E_FLOOR` times ``E_max`` (Pa)."""
    dl = math.log(tau[1] / tau[0])
    H = np.interp(np.log(tau), np.log(start.tau), np.log(start.h)) + math.log(dl)
    return math.log(max(start.E_inf, E_FLOOR * E_max)), H


def _start(omega, E_stor, E_loss, tau):
    """Start: h(tau) ~ (2/pi) E''(omega = 1/tau) (the first approximation of the spectrum),
    interpolated in log-log and clipped; E_inf ~ :data:`E_INF_START` min E'."""
    o = np.argsort(omega)
    lw, ll = np.log(omega[o]), np.log(E_loss[o])
    h = np.exp(np.interp(np.log(1 / tau), lw, ll)) * 2 / math.pi
    dlt = math.log(tau[1] / tau[0])
    return np.concatenate([[math.log(E_INF_START * float(np.min(E_stor)))], np.log(np.maximum(h * dlt, 1e-12))])


def loss_weights(E_stor, E_loss, u_modulus=U_MODULUS, u_phase=U_PHASE):
    r"""Weights :math:`a''_i` of the relative E'' residuals from a measurement-uncertainty model.

    A modulus measured with relative standard uncertainty :math:`u_E` and a phase angle with absolute
    uncertainty :math:`u_\varphi` (rad) give E' a relative uncertainty :math:`u_E` and
    E'' = E' tan(delta) a relative uncertainty
    :math:`u''_i = \sqrt{u_E^2 + (u_\varphi/\tan\delta_i)^2}`; relative to the E' residuals the
    E'' residuals then weigh :math:`a''_i = u_E^2 / u''^2_i`.  Where the material is nearly elastic
    (glassy, tan delta ~ 0.01-0.04) a small phase error is a large relative E'' error, and the
    weight falls accordingly.

    Parameters
    ----------
    E_stor, E_loss : array_like
        Pa (only their ratio enters).
    u_modulus : float
        Relative standard uncertainty of a modulus (default 1 %).
    u_phase : float
        Absolute standard uncertainty of the loss angle, rad (default 0.002 rad = 0.11 deg).

    Returns
    -------
    ndarray
        :math:`a''_i` in (0, 1].
    """
    tan = np.asarray(E_loss, float) / np.asarray(E_stor, float)
    return u_modulus**2 / (u_modulus**2 + (u_phase / tan) ** 2)


def component_weights(weights, E_stor, E_loss):
    """(a', a'', a_t) as arrays/scalars from a ``components`` argument: a tuple of weights (missing ones
    1) or "uncertainty" (:func:`loss_weights`)."""
    if isinstance(weights, str):
        if weights != "uncertainty":
            raise ValueError(f"components must be 'uncertainty' or a tuple of weights, got {weights!r}")
        return 1.0, loss_weights(E_stor, E_loss), 1.0
    c = tuple(weights) + (1.0,) * (3 - len(weights))
    return tuple(np.asarray(x, float) if np.ndim(x) else float(x) for x in c[:3])


def _checked(f, E_stor, E_loss, relaxation):
    """The data as float arrays (f, E', E'', t, E(t)); ValueError naming what is wrong."""
    f = np.asarray(f, float)
    es, el = np.asarray(E_stor, float), np.asarray(E_loss, float)
    if not (f.shape == es.shape == el.shape and f.ndim == 1 and f.size >= 3):
        raise ValueError("f, E_stor and E_loss must be 1-D arrays of equal length >= 3")
    if not (np.all(f > 0) and np.all(es > 0) and np.all(el > 0) and np.all(np.isfinite(f))):
        raise ValueError("f, E_stor and E_loss must be finite and > 0 (relative residuals)")
    t, E_relax = (None, None) if relaxation is None else relaxation
    if (t is None) != (E_relax is None):
        raise ValueError("give both t and E_relax, or neither")
    if t is not None:
        t, E_relax = np.asarray(t, float), np.asarray(E_relax, float)
        if not (np.all(t > 0) and np.all(E_relax > 0)):
            raise ValueError("t and E_relax must be > 0")
    return f, es, el, t, E_relax


def fit_spectrum(f, E_stor, E_loss, *, weight=None, relaxation=None, per_decade=PER_DECADE, margin=MARGIN, lam="gcv1se",
                 components=(1.0, 1.0, 1.0), fit_E_inf=True, start=None, phase=None) -> SpectrumFit:
    r"""Smooth-spectrum Prony fit of E', E'' (and optionally E(t)) data (module docstring).

    Parameters
    ----------
    f : array_like
        Frequencies, Hz (e.g. reduced frequencies of a master curve); any order, duplicates allowed.
    E_stor, E_loss : array_like
        Storage and loss moduli, Pa, > 0.
    weight : array_like, optional
        Point multiplicities m_i (bootstrap); default 1.
    relaxation : (t, E_relax), optional
        Relaxation data (s, Pa), fitted jointly (relative residuals).
    per_decade : float
        Relaxation times per decade of the fixed grid.
    margin : float or (float, float)
        Decades added beyond the data's 1/(2 pi f) range: on both sides, or (below the lowest frequency,
        above the highest); default :data:`vcor.fitting.spectrum.model.MARGIN`.
    lam : "gcv1se", "gcv", "lcurve" or float
        How the regularisation parameter is chosen (:mod:`vcor.fitting.spectrum.lam`), or its value.
    components : "uncertainty" or tuple
        Weights a', a'', a_t of the E', E'' and E(t) residuals (scalars or per-point arrays);
        "uncertainty": a' = a_t = 1 and a''_i from :func:`loss_weights` (its default uncertainties).
    fit_E_inf : bool
        Fit an equilibrium modulus (else E_inf = 0).
    start : SpectrumFit, optional
        Warm start: its log-spectrum interpolated onto the new grid (a lam scan still runs; with a
        given lam the continuation from large lam is skipped).
    phase : array_like, optional
        The instrument's phase error at every point, rad (e.g. :math:`2\pi f\,\Delta t` of a time lag
        :math:`\Delta t` between the force and displacement signals, f the *measured* frequency): the
        data are compared with the model as measured, :math:`E^*(\omega)\,e^{i\,\mathrm{phase}}`; the
        fitted spectrum is the material's.

    Returns
    -------
    SpectrumFit
    """
    t0 = time.perf_counter()
    f, es, el, t, E_relax = _checked(f, E_stor, E_loss, relaxation)
    w = np.ones(f.size) if weight is None else np.asarray(weight, float)
    f_lo, f_hi = float(f[w > 0].min()), float(f[w > 0].max())
    if t is not None:
        f_lo, f_hi = min(f_lo, 1 / (2 * math.pi * t.max())), max(f_hi, 1 / (2 * math.pi * t.min()))
    tau = tau_grid(f_lo, f_hi, per_decade, margin)
    omega = 2 * math.pi * f
    comp = component_weights(components, es, el)
    ph = None if phase is None else np.broadcast_to(np.asarray(phase, float), f.shape)
    residual = Residual(es, el, w, comp, None if t is None else (t, E_relax))
    problem = SmoothProblem(residual, Design(np.multiply.outer(omega, tau), ph, t, tau), tau.size, fit_E_inf)
    th = _start(omega, es, el, tau)
    if start is not None:
        th[0], th[1:] = log_spectrum(start, tau, float(np.max(es)))
    if not fit_E_inf:
        th[0] = 0.0          # unused: E_inf = 0
    lam_used, th, scan, method, notes = choose_lambda(problem, th, lam, warm=start is not None)
    E_inf, E = (math.exp(th[0]) if fit_E_inf else 0.0), np.exp(th[1:])
    met = fit_metrics(E_inf, E, tau, f, es, el, w, phase=ph)
    if t is not None:
        r = relaxation_modulus(t, E_inf, E, tau) / E_relax - 1
        met["E_relax_rms"], met["E_relax_max"] = float(np.sqrt(np.mean(r**2))), float(np.max(np.abs(r)))
    return SpectrumFit(tau=tau, E=E, E_inf=E_inf, h=E / math.log(tau[1] / tau[0]), lam=lam_used, method=method,
                       scan=scan, metrics=met, f_range=(f_lo, f_hi), time=time.perf_counter() - t0, notes=notes)
