r"""Smooth relaxation spectrum fits ("smooth by construction") of complex-modulus data.

Model
-----
Relaxation times on a *fixed* logarithmic grid :math:`\tau_j` (``per_decade`` per decade, spanning
the data's :math:`1/(2\pi f_\max) .. 1/(2\pi f_\min)` widened by ``margin`` decades, :data:`MARGIN`),
non-negative moduli :math:`E_j = e^{H_j}` and an equilibrium modulus :math:`E_\infty = e^{H_0}`:

.. math::

   E(t) = E_\infty + \sum_j E_j e^{-t/\tau_j}, \qquad
   E^*(\omega) = E_\infty + \sum_j E_j \frac{i\omega\tau_j}{1 + i\omega\tau_j},

so :math:`E' = E_\infty + \sum_j E_j \frac{\omega^2\tau_j^2}{1+\omega^2\tau_j^2}`,
:math:`E'' = \sum_j E_j \frac{\omega\tau_j}{1+\omega^2\tau_j^2}`.  On the uniform log grid
:math:`E_j = h(\tau_j)\,\Delta\ln\tau`, so :math:`H_j` is the log-spectrum :math:`\ln h` up to a constant.

What is minimised
-----------------
.. math::

   V_\lambda(H) = \sum_i m_i \Big[a'\Big(\frac{E'_{\rm fit}(\omega_i)}{E'_i} - 1\Big)^2
                 + a''\Big(\frac{E''_{\rm fit}(\omega_i)}{E''_i} - 1\Big)^2\Big]
                 + a_t \sum_l \Big(\frac{E_{\rm fit}(t_l)}{E(t_l)} - 1\Big)^2
                 + \lambda \sum_j (H_{j-1} - 2H_j + H_{j+1})^2

(:math:`m_i` point multiplicities, :math:`a', a'', a_t` component weights, default 1): relative errors
of :math:`E'` and :math:`E''` (and optionally of :math:`E(t)`), plus Tikhonov regularisation of the
roughness (second differences) of the log-spectrum.  The log-parametrisation makes the moduli
positive by construction and penalises *relative* wiggles of the spectrum equally in its large and
small parts (a penalty on :math:`h` itself lets the low-amplitude wings, which set the glassy
:math:`\tan\delta`, wiggle freely); the tails beyond the data continue as power laws (zero second
difference).  As in Shanbhag's pyReSpect (``contSpec.py``: log-spectrum, second-difference
penalty, relative residuals) but with both :math:`E'` and :math:`E''` residuals relative to
themselves and :math:`\lambda` chosen by GCV.

How it is solved
----------------
Levenberg-Marquardt (Gauss-Newton with adaptive damping) on :math:`(H_0, H_1..H_n)` with the
analytic Jacobian; a scan of :math:`\lambda` from large to small values, each solve warm-started
from the previous one (pyReSpect does the same), so every solve starts near its solution.

How :math:`\lambda` is chosen
-----------------------------
Generalised cross-validation on the linearisation at each solution:

.. math:: \mathrm{GCV}(\lambda) = \frac{N\,\lVert r_\mathrm{data}\rVert^2}{(N - \gamma\,\mathrm{tr}\,A_\lambda)^2},
          \qquad A_\lambda = J (J^\top J + \lambda L^\top L)^{-1} J^\top,

:math:`N` the number of data residuals, :math:`J` the Jacobian of the data residuals, :math:`L` the
second-difference matrix, :math:`\gamma` = :data:`GCV_GAMMA` (1: plain GCV; Kim & Gu 2004 and mgcv
suggest 1.4 against undersmoothing, which the one-standard-error rule below already guards against).  Default ``lam="gcv1se"``: the
*largest* :math:`\lambda` whose GCV is within one standard error of the minimum,
:math:`\mathrm{GCV} \le \mathrm{GCV}_\min (1 + \sqrt{2/(N - \mathrm{tr}A)})` (GCV estimates the
residual variance, whose relative standard deviation is :math:`\sqrt{2/\mathrm{dof}}`), found by
bisection in :math:`\log\lambda`: the GCV minimum is flat, and non-superposing sets make the
residuals correlated, so the minimiser itself moves by decades under small changes of the data and
undersmooths; the one-standard-error rule (Hastie, Tibshirani & Friedman, sec. 7.10) picks the
smoothest fit the data cannot tell from the best.  ``lam="gcv"``: the minimiser (refined by a
parabola in :math:`\log\lambda`); ``"lcurve"``: the point of largest curvature of
:math:`(\log\lVert r\rVert, \log\lVert LH\rVert)`; a number fixes :math:`\lambda`.

Shifts together with the spectrum
---------------------------------
:func:`fit_with_shifts` minimises the same objective over the spectrum *and* the shift factors of
raw isothermal sets (the master curve is then the Prony model itself, so the superposed E' and E''
must be those of one linear viscoelastic material, Kramers-Kronig consistent); it refines the
start-free shifts of :func:`vcor.fitting.superpose.global_shifts`.

Fewer modes
-----------
:func:`reduce_modes` merges the fine grid into fewer modes (strength-preserving, then an NNLS
re-fit to the smooth curve) and reports what that changes in E', E'' and tan delta.

Units: frequencies Hz (angular frequency :math:`\omega = 2\pi f`), times s, moduli Pa.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
from scipy.linalg import cho_factor, cho_solve
from scipy.optimize import nnls

from .superpose import anchor_matrix

__all__ = ["GCV_GAMMA", "LAM_GRID", "MARGIN", "MAX_LAG_PHASE", "PER_DECADE", "JointFit", "ReducedModes", "SpectrumFit", "complex_modulus", "count_extrema", "fit_metrics",
           "fit_spectrum", "fit_with_shifts", "leverage", "loss_weights", "reduce_modes", "relaxation_modulus", "shift_derivative", "tau_grid"]

#: candidates of the regularisation parameter lambda, scanned from large to small
LAM_GRID = np.logspace(5, -5, 21)
#: relaxation times per decade of the fixed grid: twice the merged series' two modes per decade
#: (vcor.fitting.dmafit.MODES_PER_DECADE), so that every merged mode is a block of two fine ones (with 5
#: per decade the blocks alternate 3, 2, 3, ..., the merged modes are unevenly spaced and their tan delta
#: ripples more; the merging table of benchmarks/bench_dma.py gives the change the merge makes)
PER_DECADE = 4.0
#: decades (below the data's lowest frequency, above its highest) that the relaxation-time grid reaches
#: beyond the data. Within a margin the log-spectrum continues the data's trend as a power law (zero second
#: difference); beyond it the series ends and tan delta falls to zero. An impact (contact 10 us .. 1 ms:
#: f = 1/(2 t0) = 0.5 .. 50 kHz) at the coldest set's temperature lies up to 2.7 decades above a DMA's usual
#: top frequency of 100 Hz, so the high side reaches 3 decades (with less, the COR there follows the end of
#: the grid, not the data's trend); impacts at the hottest set lie above its lowest frequency, and on the low
#: side a long power-law continuation would invent flow (tan delta >> 1) where the data end on a plateau.
MARGIN = (1.5, 3.0)
#: GCV inflation gamma of the effective degrees of freedom, (N - gamma tr A)^2 (module docstring)
GCV_GAMMA = 1.0
#: iteration budget of each joint solve (projected Levenberg-Marquardt)
MAX_ITER = 500


def _margins(margin, extra=0.0):
    """(low-frequency, high-frequency) margin in decades from a number (both sides) or a pair, plus ``extra``."""
    lo, hi = (margin, margin) if np.ndim(margin) == 0 else margin
    return float(lo) + extra, float(hi) + extra


def tau_grid(f_min, f_max, per_decade=PER_DECADE, margin=MARGIN):
    """Fixed log grid of relaxation times, s: from 1/(2 pi f_max) / 10^m_hi to 1/(2 pi f_min) * 10^m_lo,
    ``per_decade`` points per decade (rounded to fit the span); ``margin``: decades m_lo = m_hi, or
    (m_lo, m_hi) below the lowest and above the highest frequency."""
    if not (0 < f_min < f_max):
        raise ValueError(f"need 0 < f_min < f_max (Hz), got {f_min!r}, {f_max!r}")
    m_lo, m_hi = _margins(margin)
    lo = math.log10(1.0 / (2 * math.pi * f_max)) - m_hi
    hi = math.log10(1.0 / (2 * math.pi * f_min)) + m_lo
    n = round((hi - lo) * per_decade) + 1
    return np.logspace(lo, hi, max(n, 3))


def complex_modulus(omega, E_inf, E, tau):
    r"""Prony complex modulus :math:`E^*(\omega) = E_\infty + \sum_j E_j\, i\omega\tau_j/(1+i\omega\tau_j)`
    (omega rad/s, moduli Pa, tau s)."""
    iwt = 1j * np.multiply.outer(np.asarray(omega, float), np.asarray(tau, float))
    return E_inf + (iwt / (1 + iwt)) @ np.asarray(E, float)


def shift_derivative(wt, E):
    r"""(dE'/ds, dE''/ds) of a Prony model at kernel arguments ``wt`` (:math:`\omega\tau`, points x modes)
    for a shift :math:`s = \log_{10} a_T` of the frequency, :math:`\ln 10\;\omega\,\partial E^*/\partial\omega`
    (Pa; moduli ``E`` in Pa)."""
    q = 1 + wt**2
    return math.log(10) * ((2 * wt**2 / q**2) @ E), math.log(10) * ((wt * (1 - wt**2) / q**2) @ E)


def relaxation_modulus(t, E_inf, E, tau):
    r""":math:`E(t) = E_\infty + \sum_j E_j e^{-t/\tau_j}` (t s, moduli Pa)."""
    return E_inf + np.exp(-np.divide.outer(np.asarray(t, float), np.asarray(tau, float))) @ np.asarray(E, float)


def count_extrema(y, rtol=1e-10):
    """Number of strict local extrema of a sampled curve: sign changes of its first difference,
    differences below ``rtol`` times the curve's scale counted as zero (flat steps are skipped)."""
    y = np.asarray(y, float)
    dy = np.diff(y)
    dy = dy[np.abs(dy) > rtol * np.max(np.abs(y))]
    return int(np.sum(np.sign(dy[1:]) != np.sign(dy[:-1])))


def fit_metrics(E_inf, E, tau, f, E_stor, E_loss, weight=None, n_dense=2000, phase=None):
    """Relative errors of E', E'' and tan delta (rms and max, multiplicity-weighted) of a Prony
    model against data, and the number of local extrema of its tan delta on ``n_dense`` log-spaced
    frequencies over the data's range [min f, max f] (Hz). ``phase`` (rad, per point): the model is
    compared as measured, E* e^{i phase} (an instrument's phase error, :func:`fit_spectrum`); the extrema
    are the material's own."""
    w = np.ones(np.size(f)) if weight is None else np.asarray(weight, float)
    e = complex_modulus(2 * np.pi * np.asarray(f), E_inf, E, tau)
    if phase is not None:
        e = e * np.exp(1j * np.asarray(phase, float))
    out = {}
    for name, fit, data in (("E_stor", e.real, E_stor), ("E_loss", e.imag, E_loss),
                            ("tan_delta", e.imag / e.real, np.asarray(E_loss) / np.asarray(E_stor))):
        r = fit / data - 1
        out[f"{name}_rms"] = float(np.sqrt(np.average(r**2, weights=w)))
        out[f"{name}_max"] = float(np.max(np.abs(r[w > 0])))
    fd = np.geomspace(np.min(f), np.max(f), n_dense)
    ed = complex_modulus(2 * np.pi * fd, E_inf, E, tau)
    out["tan_delta_extrema"] = count_extrema(ed.imag / ed.real)
    return out


@dataclass
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
        :func:`fit_metrics` against the data fitted.
    f_range : tuple
        Data frequency range (Hz) over which the metrics and extrema are evaluated.
    time : float
        Wall time, s.
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


def _d2(n):
    D = np.zeros((n - 2, n))
    i = np.arange(n - 2)
    D[i, i], D[i, i + 1], D[i, i + 2] = 1.0, -2.0, 1.0
    return D


def _lm(cost, normal, x0, *, lo=None, hi=None, max_iter=300, tol=1e-10, nu_max=1e14):
    r"""Levenberg-Marquardt (projected onto the box lo <= x <= hi when given) for min cost(x).

    ``cost(x)`` returns (c, r): the cost and what ``normal`` needs of x; ``normal(x, r)`` returns the
    Gauss-Newton matrix A and the gradient g (half of it) at x.  Each step solves
    :math:`(A + \nu\,\mathrm{diag}\,A)\,\Delta x = -g` (clipped to the box, variables held at a
    bound by the gradient left there: an active set) and is accepted when the cost does not rise;
    :math:`\nu` falls 3x after a success and rises 10x after a failure, and above ``nu_max`` the
    solve gives up.  Converged when the decrease a full Gauss-Newton step predicts,
    :math:`g^\top A^{-1} g`, is below ``tol`` times the cost (or below 1e-24): in a flat valley a
    heavily damped step lowers the cost by little although the minimum is far, so neither a small
    decrease nor a small step is taken for convergence.  Returns (x, iterations, converged).
    """
    x = np.asarray(x0, float).copy()
    if lo is not None:
        x = np.clip(x, lo, hi)
    c, r = cost(x)
    nu = 1e-3
    for it in range(1, max_iter + 1):
        A, g = normal(x, r)
        if lo is not None:
            act = ((x <= lo + 1e-12) & (g > 0)) | ((x >= hi - 1e-12) & (g < 0))
            if act.any():
                A[act, :], A[:, act], g[act] = 0.0, 0.0, 0.0
                A[act, act] = 1.0
        dA = np.diag(A).copy()
        dA[dA <= 0] = 1.0
        try:
            predicted = float(g @ cho_solve(cho_factor(A + 1e-12 * np.diag(dA)), g))
        except np.linalg.LinAlgError:
            predicted = math.inf
        if predicted <= tol * c + 1e-24:
            return x, it - 1, True
        while True:
            try:
                step = -cho_solve(cho_factor(A + nu * np.diag(dA)), g)
            except np.linalg.LinAlgError:
                nu *= 10
                continue
            xn = x + step if lo is None else np.clip(x + step, lo, hi)
            cn, rn = cost(xn)
            if np.isfinite(cn) and cn <= c:
                break
            nu *= 10
            if nu > nu_max:
                return x, it, False
        x, r, c = xn, rn, cn
        nu = max(nu / 3, 1e-12)
    return x, max_iter, False


class _Problem:
    """Residuals and Jacobian of V_lambda in the parameters theta = (ln E_inf, H_1..H_n)."""

    def __init__(self, omega, E_stor, E_loss, weight, t, E_relax, tau, comp, fit_E_inf, phase=None):
        wt = np.multiply.outer(omega, tau)
        ks, kl = wt**2 / (1 + wt**2), wt / (1 + wt**2)
        # the model as measured: E* rotated by the instrument's phase error, E*_m = E* e^{i phase}
        cp, sp = (np.ones(omega.size), np.zeros(omega.size)) if phase is None else (np.cos(phase), np.sin(phase))
        self.Ks, self.Kl = cp[:, None] * ks - sp[:, None] * kl, sp[:, None] * ks + cp[:, None] * kl
        self.ks0, self.kl0 = cp, sp                       # coefficients of E_inf in E'_m and E''_m
        sw = np.sqrt(weight)
        self.rows_s, self.rows_l = sw * np.sqrt(comp[0]), sw * np.sqrt(comp[1])
        self.cs = self.rows_s / E_stor                    # row scale of the E' residuals
        self.cl = self.rows_l / E_loss
        self.has_t = t is not None
        if self.has_t:
            self.Kt = np.exp(-np.divide.outer(t, tau))
            self.rows_t = np.broadcast_to(np.sqrt(comp[2]), t.shape).astype(float)
            self.ct = self.rows_t / E_relax
        self.n = tau.size
        self.D = _d2(self.n)
        self.fit_E_inf = fit_E_inf

    def data_residual(self, th):
        with np.errstate(over="ignore", invalid="ignore"):     # a wild trial step: cost inf, rejected
            Einf = float(np.exp(th[0])) if self.fit_E_inf else 0.0
            E = np.exp(th[1:])
            return self._residual(Einf, E)

    def _residual(self, Einf, E):
        r = [self.cs * (Einf * self.ks0 + self.Ks @ E) - self.rows_s, self.cl * (Einf * self.kl0 + self.Kl @ E) - self.rows_l]
        if self.has_t:
            r.append(self.ct * (Einf + self.Kt @ E) - self.rows_t)
        return np.concatenate(r)

    def data_jac(self, th):
        Einf = float(np.exp(th[0])) if self.fit_E_inf else 0.0
        E = np.exp(th[1:])
        blocks = [np.column_stack([self.cs * Einf * self.ks0, (self.cs[:, None] * self.Ks) * E]),
                  np.column_stack([self.cl * Einf * self.kl0, (self.cl[:, None] * self.Kl) * E])]
        if self.has_t:
            blocks.append(np.column_stack([self.ct * Einf, (self.ct[:, None] * self.Kt) * E]))
        return np.vstack(blocks)

    def penalty_matrix(self):
        """L^T L in theta coordinates (E_inf unpenalised)."""
        P = np.zeros((self.n + 1, self.n + 1))
        P[1:, 1:] = self.D.T @ self.D
        return P

    def solve(self, th, lam, max_iter=300, tol=1e-10):
        """Levenberg-Marquardt minimisation of ||r_data||^2 + lam ||D H||^2 from theta = th (:func:`_lm`)."""
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

        return _lm(cost, normal, th, max_iter=max_iter, tol=tol, nu_max=1e12)

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


def _start(omega, E_stor, E_loss, tau):
    """Start: h(tau) ~ (2/pi) E''(omega = 1/tau) (the first approximation of the spectrum),
    interpolated in log-log and clipped; E_inf ~ 0.9 min E'."""
    o = np.argsort(omega)
    lw, ll = np.log(omega[o]), np.log(E_loss[o])
    h = np.exp(np.interp(np.log(1 / tau), lw, ll)) * 2 / math.pi
    dlt = math.log(tau[1] / tau[0])
    return np.concatenate([[math.log(0.9 * float(np.min(E_stor)))], np.log(np.maximum(h * dlt, 1e-12))])


def loss_weights(E_stor, E_loss, u_modulus=0.01, u_phase=0.002):
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


def _components(components, es, el):
    """(a', a'', a_t) as arrays/scalars from the ``components`` argument."""
    if isinstance(components, str):
        if components != "uncertainty":
            raise ValueError(f"components must be 'uncertainty' or a tuple of weights, got {components!r}")
        return 1.0, loss_weights(es, el), 1.0
    c = tuple(components) + (1.0,) * (3 - len(components))
    return tuple(np.asarray(x, float) if np.ndim(x) else float(x) for x in c[:3])


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
        above the highest); default :data:`MARGIN`.
    lam : "gcv1se", "gcv", "lcurve" or float
        How the regularisation parameter is chosen (module docstring), or its value.
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
    f = np.asarray(f, float)
    es, el = np.asarray(E_stor, float), np.asarray(E_loss, float)
    if not (f.shape == es.shape == el.shape and f.ndim == 1 and f.size >= 3):
        raise ValueError("f, E_stor and E_loss must be 1-D arrays of equal length >= 3")
    if not (np.all(f > 0) and np.all(es > 0) and np.all(el > 0) and np.all(np.isfinite(f))):
        raise ValueError("f, E_stor and E_loss must be finite and > 0 (relative residuals)")
    w = np.ones(f.size) if weight is None else np.asarray(weight, float)
    t, E_relax = (None, None) if relaxation is None else relaxation
    if (t is None) != (E_relax is None):
        raise ValueError("give both t and E_relax, or neither")
    if t is not None:
        t, E_relax = np.asarray(t, float), np.asarray(E_relax, float)
        if not (np.all(t > 0) and np.all(E_relax > 0)):
            raise ValueError("t and E_relax must be > 0")
    f_lo, f_hi = float(f[w > 0].min()), float(f[w > 0].max())
    if t is not None:
        f_lo, f_hi = min(f_lo, 1 / (2 * math.pi * t.max())), max(f_hi, 1 / (2 * math.pi * t.min()))
    tau = tau_grid(f_lo, f_hi, per_decade, margin)
    omega = 2 * math.pi * f
    comp = _components(components, es, el)
    ph = None if phase is None else np.broadcast_to(np.asarray(phase, float), f.shape)
    pr = _Problem(omega, es, el, w, t, E_relax, tau, comp, fit_E_inf, ph)
    th = _start(omega, es, el, tau)
    if start is not None:
        dl = math.log(tau[1] / tau[0])
        th[1:] = np.interp(np.log(tau), np.log(start.tau), np.log(start.h)) + math.log(dl)
        th[0] = math.log(max(start.E_inf, 1e-9 * float(np.max(es))))
    if not fit_E_inf:
        th[0] = 0.0          # unused: E_inf = 0
    grid = LAM_GRID
    notes = []
    if isinstance(lam, str):
        if lam not in ("gcv", "gcv1se", "lcurve"):
            raise ValueError(f"lam must be 'gcv1se', 'gcv', 'lcurve' or a number, got {lam!r}")
        sols, rows = [], []
        for lm in grid:
            th, it, ok = pr.solve(th, lm)
            rho, eta, edf, N = pr.diagnostics(th, lm)
            gcv = N * rho**2 / max(N - GCV_GAMMA * edf, 1.0) ** 2
            rows.append((lm, gcv, rho, eta, edf, it, ok))
            sols.append(th.copy())
        L, G, RHO, ETA = (np.array([r[i] for r in rows]) for i in range(4))
        EDF = np.array([r[4] for r in rows])
        N = pr.data_residual(th).size
        if lam in ("gcv", "gcv1se"):
            i = int(np.argmin(G))
        else:
            x, y = np.log(RHO), np.log(np.maximum(ETA, 1e-300))
            s = np.log(L)
            dx, dy = np.gradient(x, s), np.gradient(y, s)
            ddx, ddy = np.gradient(dx, s), np.gradient(dy, s)
            kappa = (dx * ddy - dy * ddx) / np.maximum((dx**2 + dy**2) ** 1.5, 1e-300)
            i = int(np.argmax(np.abs(kappa[1:-1]))) + 1
        if i in (0, L.size - 1):
            notes.append(f"{lam} chose the edge of lam_grid ({L[i]:.3g}); widen the grid")
        lam_used, th = float(L[i]), sols[i]
        if lam == "gcv" and 0 < i < L.size - 1:
            # parabola through (log lam, log GCV) at i-1, i, i+1
            xs, ys = np.log(L[i - 1:i + 2]), np.log(G[i - 1:i + 2])
            a, b, _ = np.polyfit(xs, ys, 2)
            if a > 0:
                lam_ref = float(np.exp(np.clip(-b / (2 * a), xs.min(), xs.max())))
                th_ref, _, ok = pr.solve(th, lam_ref)
                if ok:
                    lam_used, th = lam_ref, th_ref
        elif lam == "gcv1se":
            # the smoothest lam whose GCV is within one standard error of the minimum:
            # GCV estimates sigma^2 with relative sd sqrt(2 / (N - edf))
            thr = G[i] * (1 + math.sqrt(2.0 / max(N - EDF[i], 1.0)))
            j = int(np.flatnonzero(G <= thr)[0])          # grid descends: first = largest lam
            lam_used, th = float(L[j]), sols[j]
            if j > 0:
                # bisect log lam on the threshold crossing between L[j-1] (above) and L[j] (below)
                a_, b_, th_b = math.log(L[j - 1]), math.log(L[j]), sols[j]
                for _ in range(5):
                    mid = 0.5 * (a_ + b_)
                    th_m, _, _ = pr.solve(th_b, math.exp(mid))
                    rho, _, edf, n_ = pr.diagnostics(th_m, math.exp(mid))
                    if n_ * rho**2 / max(n_ - GCV_GAMMA * edf, 1.0) ** 2 <= thr:
                        b_, th_b = mid, th_m
                    else:
                        a_ = mid
                lam_used, th = math.exp(b_), th_b
        scan = {"lam": L, "gcv": G, "rho": RHO, "eta": ETA, "edf": np.array([r[4] for r in rows]),
                "iterations": np.array([r[5] for r in rows]), "converged": np.array([r[6] for r in rows])}
        method = lam
    else:
        lam_used = float(lam)
        if start is None:
            for lm in grid[grid > lam_used]:      # continuation down to the given lam
                th, _, _ = pr.solve(th, lm)
        th, it, ok = pr.solve(th, lam_used)
        if not ok:
            notes.append("the solve at the given lam did not converge")
        scan = {}
        method = "given"
    E_inf = math.exp(th[0]) if fit_E_inf else 0.0
    E = np.exp(th[1:])
    met = fit_metrics(E_inf, E, tau, f, es, el, w, phase=ph)
    if t is not None:
        r = relaxation_modulus(t, E_inf, E, tau) / E_relax - 1
        met["E_relax_rms"], met["E_relax_max"] = float(np.sqrt(np.mean(r**2))), float(np.max(np.abs(r)))
    return SpectrumFit(tau, E, E_inf, E / math.log(tau[1] / tau[0]), lam_used, method, scan, met, (f_lo, f_hi),
                       time.perf_counter() - t0, notes)


def leverage(fit: SpectrumFit, f, E_stor, E_loss, *, weight=None, components=(1.0, 1.0, 1.0), lag=None,
             shift_index=None, curvature=False):
    r"""Leverages of data points in a spectrum fit: the diagonal of the linearised hat matrix
    :math:`A_\lambda = J (J^\top J + \lambda L^\top L)^{-1} J^\top` at the fit's solution (module
    docstring), for the E' and the E'' residual of every point; in [0, 1).

    A point of leverage :math:`h` pulls the fit towards itself: its fitted residual is about
    :math:`(1 - h)` times its error, so residuals alone understate the scatter where few points
    decide the fit (the ends of the data). Scale-free (the row weights cancel).

    The parameters are those of the spectrum, and with ``shift_index`` the shift of every set that was
    fitted too (:func:`fit_with_shifts`: a shift is one more parameter that each of its set's points
    informs, so a set's residuals shrink by more than the spectrum alone explains), and with ``lag``
    the instrument's time lag, fitted or held.

    With ``curvature`` (the spectrum's own parameters only) the residuals' curvature
    :math:`\sum_i r_i \nabla^2 r_i` joins the Gauss-Newton matrix,
    :math:`J (J^\top J + \mathrm{diag}(J^\top r) + \lambda L^\top L)^{-1} J^\top` (exact for
    moduli :math:`e^{H_j}`: each residual's second derivative in :math:`H_j` equals its first): the
    linear response of the fitted value to its own data value, which a refit follows within a few per
    cent where the Gauss-Newton value is up to 18 % off (``tests/test_resample.py``); it is not bounded
    by 1 where the fit is barely determined, so the bootstrap's residual correction takes the
    Gauss-Newton value, the one that correction is defined with.

    Parameters
    ----------
    fit : SpectrumFit
    f : array_like
        Frequencies of the points, Hz (reduced, as fitted).
    E_stor, E_loss : array_like
        The data, Pa.
    weight : array_like, optional
        Point multiplicities, as in the fit (default 1).
    components : tuple
        Weights a', a'' of the E' and E'' residuals, as in the fit.
    lag : (array_like, float, bool), optional
        (measured frequency of every point [Hz], the instrument's time lag [s], whether it was fitted):
        the model is compared as measured (:func:`fit_spectrum`, ``phase``); a fitted lag is a parameter.
    shift_index : array_like of int, optional
        For every point the index (0, 1, ...) of its set's shift among the fitted shifts, -1 where the
        shift was held (the reference set, given shifts).
    curvature : bool
        Include the residuals' curvature (above).

    Returns
    -------
    (h_stor, h_loss) : tuple of ndarray
        In [0, 1) (Gauss-Newton); the exact response with ``curvature``.
    """
    f = np.asarray(f, float)
    es, el = np.asarray(E_stor, float), np.asarray(E_loss, float)
    n = f.size
    fit_E_inf = fit.E_inf > 0
    w = np.ones(n) if weight is None else np.asarray(weight, float)
    f_meas, dt, lag_fitted = (None, 0.0, False) if lag is None else (np.asarray(lag[0], float), float(lag[1]), lag[2])
    ph = None if lag is None else 2 * math.pi * f_meas * dt
    if curvature and (shift_index is not None or lag_fitted):
        raise ValueError("curvature is exact for the spectrum's own parameters only: give no shift_index or fitted lag")
    pr = _Problem(2 * math.pi * f, es, el, w, None, None, fit.tau, _components(components, es, el), fit_E_inf, ph)
    th = np.concatenate([[math.log(fit.E_inf) if fit_E_inf else 0.0], np.log(fit.E)])
    cols = [pr.data_jac(th)]
    cp, sn = (np.ones(n), np.zeros(n)) if ph is None else (np.cos(ph), np.sin(ph))
    if shift_index is not None:
        k = np.asarray(shift_index, int)
        d1, d2 = shift_derivative(np.multiply.outer(2 * math.pi * f, fit.tau), fit.E)
        Js = np.zeros((2 * n, max(int(k.max()) + 1, 0)))
        rows = np.flatnonzero(k >= 0)
        Js[rows, k[rows]] = (pr.cs * (cp * d1 - sn * d2))[rows]
        Js[n + rows, k[rows]] = (pr.cl * (sn * d1 + cp * d2))[rows]
        cols.append(Js)
    if lag_fitted:
        e = fit.complex_modulus(2 * math.pi * f) * np.exp(1j * ph)  # as measured
        g = f_meas / f_meas.max()                                  # d phase / d (phase at the top frequency)
        cols.append(np.concatenate([pr.cs * (-g * e.imag), pr.cl * (g * e.real)])[:, None])
    J = np.hstack(cols)
    A = J.T @ J
    A[:fit.tau.size + 1, :fit.tau.size + 1] += fit.lam * pr.penalty_matrix()
    if curvature:
        # sum_i r_i d2r_i: for moduli e^theta diagonal and equal to J^T r (d2 r_i / d theta_j^2 = d r_i / d theta_j)
        A += np.diag(J.T @ pr.data_residual(th))
    if not fit_E_inf:
        J, A = J[:, 1:], A[1:, 1:]
    A += 1e-12 * np.trace(A) / A.shape[0] * np.eye(A.shape[0])
    h = np.einsum("ij,ji->i", J, np.linalg.solve(A, J.T))
    if not curvature:
        h = np.clip(h, 0.0, 1.0 - 1e-9)
    return h[:n], h[n:]


@dataclass
class ReducedModes:
    """A Prony series with fewer modes than a :class:`SpectrumFit`, and what the reduction changed.

    Attributes
    ----------
    tau, E, E_inf : ndarray, ndarray, float
        Relaxation times (s), moduli (Pa), equilibrium modulus (Pa).
    change : dict
        Relative change against the smooth fit over its data range (dense grid): ``E_stor_max``,
        ``E_stor_rms``, ``E_loss_max``, ``E_loss_rms``, ``tan_delta_max``, ``tan_delta_rms``;
        and ``tan_delta_extrema`` of the reduced model on the same 2000-point grid as the fit's.
    """

    tau: np.ndarray
    E: np.ndarray
    E_inf: float
    change: dict

    @property
    def n_modes(self) -> int:
        return int(self.E.size)

    def prony_terms(self):
        """(E_inf [Pa], E [Pa], beta = 1/tau [1/s])."""
        return float(self.E_inf), self.E.copy(), 1.0 / self.tau


def reduce_modes(fit: SpectrumFit, per_decade=1.0, *, refit=True, n_dense_per_decade=20) -> ReducedModes:
    r"""Merge the fine grid's modes into about ``per_decade`` modes per decade.

    The fine grid is split into round(span * per_decade) + 1 consecutive blocks (span: decades of the
    grid), each merged into one mode, keeping the block's strength and its
    strength-weighted mean log time: :math:`E = \sum_{j\in b} E_j`,
    :math:`\ln\tau = \sum_{j\in b} E_j \ln\tau_j / E`.  With ``refit`` the merged moduli (and
    :math:`E_\infty`) are then re-fitted by non-negative least squares to the smooth fit's
    :math:`E'` and :math:`E''` (relative residuals) on a dense grid over the data range widened by
    the fit's margin, which removes most of the ripple a coarse discrete spectrum adds; modes whose
    refitted modulus is 0 are dropped.

    Parameters
    ----------
    fit : SpectrumFit
    per_decade : float
        Target modes per decade (e.g. 1, 1.5, 2).
    refit : bool
        NNLS re-fit of the merged moduli (keeps the merged times).
    n_dense_per_decade : int
        Density of the comparison grid.

    Returns
    -------
    ReducedModes
    """
    decades = float(np.log10(fit.tau[-1] / fit.tau[0]))       # a float: numpy < 2 rounds float64 to float64
    n_blocks = min(fit.tau.size, max(1, round(decades * per_decade) + 1))
    blocks = np.array_split(np.arange(fit.tau.size), n_blocks)
    E = np.array([fit.E[b].sum() for b in blocks])
    tau = np.array([math.exp(float(np.sum(fit.E[b] * np.log(fit.tau[b])) / fit.E[b].sum())) for b in blocks])
    E_inf = fit.E_inf
    f_lo, f_hi = fit.f_range
    span = math.log10(f_hi / f_lo)
    f_dense = np.geomspace(f_lo, f_hi, max(int(span * n_dense_per_decade), 50))
    w_dense = 2 * math.pi * f_dense
    ref = fit.complex_modulus(w_dense)
    if refit:
        # fit on the data range widened by the fit's margins so the end modes stay physical
        m_lo = max(math.log10(fit.tau[-1] * 2 * math.pi * f_lo), 0.0)
        m_hi = max(math.log10(1.0 / (fit.tau[0] * 2 * math.pi * f_hi)), 0.0)
        f_fit = np.geomspace(f_lo / 10**m_lo, f_hi * 10**m_hi, max(int((span + m_lo + m_hi) * n_dense_per_decade), 50))
        wf = 2 * math.pi * f_fit
        target = fit.complex_modulus(wf)
        wt = np.multiply.outer(wf, tau)
        A = np.vstack([np.column_stack([np.ones(wf.size), wt**2 / (1 + wt**2)]) / target.real[:, None],
                       np.column_stack([np.zeros(wf.size), wt / (1 + wt**2)]) / target.imag[:, None]])
        x, _ = nnls(A, np.ones(2 * wf.size), maxiter=50 * (tau.size + 1))
        E_inf, E = float(x[0]), x[1:]
        keep = E > 0
        tau, E = tau[keep], E[keep]
    red = complex_modulus(w_dense, E_inf, E, tau)
    change = {}
    for name, a, b in (("E_stor", red.real, ref.real), ("E_loss", red.imag, ref.imag),
                       ("tan_delta", red.imag / red.real, ref.imag / ref.real)):
        r = a / b - 1
        change[f"{name}_max"], change[f"{name}_rms"] = float(np.max(np.abs(r))), float(np.sqrt(np.mean(r**2)))
    fd = np.geomspace(f_lo, f_hi, 2000)
    e2 = complex_modulus(2 * math.pi * fd, E_inf, E, tau)
    change["tan_delta_extrema"] = count_extrema(e2.imag / e2.real)
    return ReducedModes(tau, E, E_inf, change)


@dataclass
class JointFit:
    """Shift factors refined together with the spectrum (:func:`fit_with_shifts`).

    Attributes
    ----------
    T : ndarray
        Set temperatures, deg C (ascending).
    log_aT : ndarray
        Refined log10 a_T, 0 at T_ref (the given ones when the shifts are held).
    log_aT_std : ndarray
        Linearised standard errors, decades (Gauss-Newton covariance of the joint problem; 0 when held).
    at_bound : list of int
        Steps k (between sets k and k+1) that ended at the minimum-overlap bound.
    components : tuple
        The E', E'' weights used.
    lam_joint : float
        lambda of the joint solve.
    spectrum : SpectrumFit
        The final smooth fit (lam by GCV) of the master curve at the refined shifts (and lag).
    objective : float
        Final value of the joint objective (data + lam_joint roughness).
    nfev : int
    time : float
        s.
    cov : ndarray
        Covariance of log_aT, decades^2.
    lag, lag_std : float
        The instrument's time lag between force and displacement (s; 0 when not fitted) and its
        linearised standard error (s).
    lag_fitted, free_shifts : bool
        Whether the lag and the shifts were fitted (not held).
    held_set : int
        With free shifts, the set held at 0 during the solve (nearest T_ref): every other set's shift is
        a parameter of the fit; -1 when all shifts are held.
    """

    T: np.ndarray
    log_aT: np.ndarray
    log_aT_std: np.ndarray
    at_bound: list
    components: tuple
    lam_joint: float
    spectrum: SpectrumFit
    objective: float
    nfev: int
    time: float
    cov: np.ndarray
    notes: list = field(default_factory=list)
    lag: float = 0.0
    lag_std: float = 0.0
    lag_fitted: bool = False
    free_shifts: bool = True
    held_set: int = -1

    @property
    def smoothing(self) -> dict:
        """lambda of the joint solve and of the final spectrum (to hold fixed in a bootstrap)."""
        return {"lam_joint": float(self.lam_joint), "lam": float(self.spectrum.lam)}


#: largest instrument phase error (rad) at the highest measured frequency that :func:`fit_with_shifts`
#: may fit (17 deg; a lag that large says the data need an instrument correction, not a fit)
MAX_LAG_PHASE = 0.3


def fit_with_shifts(sets, T_ref, log_aT_start, *, components=(1.0, 0.01), per_decade=PER_DECADE, margin=MARGIN,
                    min_overlap=0.5, lam=None, final_lam="gcv1se", start_spectrum=None, lag=False,
                    free_shifts=True) -> JointFit:
    r"""Refine shift factors (and an instrument lag) together with the spectrum: the master curve is
    the Prony model itself.

    Minimises over the steps :math:`d_k = s_{k+1} - s_k` (bounded so that adjacent sets overlap by
    ``min_overlap`` decades), :math:`\ln E_\infty`, the log-spectrum :math:`H` and, with ``lag``, a
    time lag :math:`\Delta t` of the instrument

    .. math:: \sum_{k,i} m_{ki}\Big[a'\Big(\frac{\mathrm{Re}\,M_{ki}}{E'_{ki}} - 1\Big)^2
              + a''\Big(\frac{\mathrm{Im}\,M_{ki}}{E''_{ki}} - 1\Big)^2\Big]
              + \lambda \lVert D_2 H \rVert^2, \qquad
              M_{ki} = E^*_{\rm fit}(2\pi f_{ki}10^{s_k})\, e^{\,i\,2\pi f_{ki}\Delta t}.

    A free smooth curve (:func:`vcor.fitting.superpose.global_shifts`) can lay E' on one curve with shifts for
    which no linear viscoelastic material has that E' *and* the measured E'' (Kramers-Kronig);
    here the shifts must make both consistent with one relaxation spectrum.  The start is
    ``log_aT_start`` (the start-free spline shifts); :math:`\lambda` is the GCV minimiser (a
    flexible master curve) at the start shifts (unless given); the final spectrum at the refined shifts uses ``lam="gcv1se"``.  Projected
    Levenberg-Marquardt with the analytic Jacobian
    (:math:`\partial E^*(\omega 10^{s})/\partial s = \ln 10\;\omega\,\partial E^*/\partial\omega`).

    The lag: a delay :math:`\Delta t` between an instrument's force and displacement signals adds
    :math:`2\pi f\Delta t` to every measured loss angle, f the *measured* frequency. A property of the
    material moves with :math:`a_T` across the reduced frequencies; an error that stays at the same
    measured frequency at every temperature does not, so with sets at several temperatures the
    superposition tells the two apart and :math:`\Delta t` is identified (a constant phase offset
    would not be: a flat tan delta absorbs it).

    Parameters
    ----------
    sets : list
        Objects with ``T`` (deg C), ``f`` (Hz), ``E_stor``, ``E_loss`` (Pa) and ``w`` (multiplicities),
        sorted by T (:func:`vcor.fitting.superpose.split_sets`).
    T_ref : float
        deg C.
    log_aT_start : array_like
        Start shifts (decades), one per set; the shifts themselves with ``free_shifts=False``.
    components : (a', a'') or "uncertainty"
        Component weights (scalars or per-point arrays in the order of the concatenated sets).
        Default (1, 0.01): inverse-variance weights for relative E' errors of ~1 % and E'' errors of
        ~10 % (on pyvisco's data the fits leave 1 % and 16 %: E'' does not superpose and rises at
        the top of every set; equal weights let those E'' errors set the shifts);
        "uncertainty": :func:`loss_weights` (per point, from a modulus and a phase uncertainty).
    per_decade, margin : float, float or (float, float)
        As in :func:`fit_spectrum`.
    min_overlap : float
        Decades adjacent sets must share.
    lam : float, optional
        Fix lambda in the joint solve (default: GCV minimiser, see above).
    final_lam : "gcv1se", "gcv", "lcurve" or float
        lambda of the final spectrum at the refined shifts.
    start_spectrum : SpectrumFit, optional
        Start spectrum (e.g. the full-data fit in a bootstrap); with ``lam`` given no lambda scan is
        run at all.
    lag : bool
        Fit the instrument's time lag :math:`\Delta t` (s), its phase at the highest measured frequency
        bounded by :data:`MAX_LAG_PHASE`.
    free_shifts : bool
        False: hold the shifts at ``log_aT_start`` (given shift factors) and fit the rest.

    Returns
    -------
    JointFit
    """
    t0 = time.perf_counter()
    K = len(sets)
    T = np.array([s.T for s in sets])
    k_ref = int(np.argmin(np.abs(T - T_ref)))
    f = np.concatenate([s.f for s in sets])
    idx = np.concatenate([np.full(s.f.size, k) for k, s in enumerate(sets)])
    es = np.concatenate([s.E_stor for s in sets])
    el = np.concatenate([s.E_loss for s in sets])
    m = np.concatenate([s.w for s in sets])
    x = [np.log10(s.f) for s in sets]
    lb = np.array([x[k].min() - x[k + 1].max() + min_overlap for k in range(K - 1)])
    ub = np.array([x[k].max() - x[k + 1].min() - min_overlap for k in range(K - 1)])
    S = np.tril(np.ones((K, K - 1)), -1)
    S = S - S[k_ref]
    d = np.diff(np.asarray(log_aT_start, float))
    if free_shifts:
        d = np.clip(d, lb + 1e-9, ub - 1e-9)
    a1, a2, _ = _components(components, es, el)
    s_held = np.asarray(log_aT_start, float)                 # the shifts when they are held
    fr = f * 10 ** (S @ d if free_shifts else s_held)[idx]
    if start_spectrum is not None and lam is not None:
        first = start_spectrum
    else:
        first = fit_spectrum(fr, es, el, weight=m, per_decade=per_decade, margin=margin,
                             components=(a1, a2, 1.0), lam="gcv" if lam is None else float(lam))
    lam_j = first.lam if lam is None else float(lam)
    # fixed grid wide enough for the shifts to move by 1.5 decades at either end
    tau = tau_grid(float(fr.min()), float(fr.max()), per_decade, _margins(margin, 1.5))
    dl = math.log(tau[1] / tau[0])
    H = np.interp(np.log(tau), np.log(first.tau), np.log(first.h)) + math.log(dl)
    nd, nq = (K - 1 if free_shifts else 0), int(bool(lag))   # free steps, lag parameter
    iq, ie = nd, nd + nq                                     # where the lag and ln E_inf sit in p
    w_top = 2 * math.pi * float(f.max())                     # the lag parameter: its phase at the top frequency
    g = f / float(f.max())
    p = np.concatenate([d[:nd], np.zeros(nq), [math.log(max(first.E_inf, 1e-9 * float(es.max())))], H])
    n, nt = f.size, tau.size
    Dm = _d2(nt)
    sm = np.sqrt(m)
    big = math.log(float(np.max(es)))
    lo = np.concatenate([lb[:nd], np.full(nq, -MAX_LAG_PHASE), np.full(1 + nt, big - 40.0)])  # moduli e^-40..e^3 of max E'
    hi = np.concatenate([ub[:nd], np.full(nq, MAX_LAG_PHASE), np.full(1 + nt, big + 3.0)])
    p = np.clip(p, lo + 1e-9, hi - 1e-9)

    def unpack(p):
        """Kernel argument w tau at the shifts of p, mode moduli, E_inf, cos and sin of the phase error."""
        s = S @ p[:nd] if free_shifts else s_held
        wt = np.multiply.outer(2 * math.pi * f * 10 ** s[idx], tau)
        phi = g * p[iq] if lag else np.zeros(n)
        return wt, np.exp(p[ie + 1:]), math.exp(p[ie]), np.cos(phi), np.sin(phi)

    c1, c2 = np.sqrt(a1), np.sqrt(a2)
    r1, r2 = c1 * sm / es, c2 * sm / el                      # row scales of the E' and E'' residuals

    def measured(wt, E, Ei, cp, sp):
        """Re and Im of the model as measured, and the material's E', E''."""
        q = 1 + wt**2
        e1, e2 = Ei + (wt**2 / q) @ E, (wt / q) @ E
        return cp * e1 - sp * e2, sp * e1 + cp * e2

    def res(p):
        m1, m2 = measured(*unpack(p))
        return np.concatenate([r1 * m1 - c1 * sm, r2 * m2 - c2 * sm, math.sqrt(lam_j) * (Dm @ p[ie + 1:])])

    def jac(p):
        wt, E, Ei, cp, sp = unpack(p)
        q = 1 + wt**2
        Ks, Kl = wt**2 / q, wt / q
        J = np.zeros((2 * n + nt - 2, p.size))
        if free_shifts:
            ds1, ds2 = shift_derivative(wt, E)
            Js = np.zeros((2 * n, K))
            Js[np.arange(n), idx] = r1 * (cp * ds1 - sp * ds2)
            Js[n + np.arange(n), idx] = r2 * (sp * ds1 + cp * ds2)
            Js[:, k_ref] = 0.0
            J[:2 * n, :nd] = Js @ S
        if lag:
            m1, m2 = measured(wt, E, Ei, cp, sp)
            J[:n, iq], J[n:2 * n, iq] = -r1 * g * m2, r2 * g * m1
        J[:n, ie], J[n:2 * n, ie] = r1 * cp * Ei, r2 * sp * Ei
        J[:n, ie + 1:] = r1[:, None] * (cp[:, None] * Ks - sp[:, None] * Kl) * E
        J[n:2 * n, ie + 1:] = r2[:, None] * (sp[:, None] * Ks + cp[:, None] * Kl) * E
        J[2 * n:, ie + 1:] = math.sqrt(lam_j) * Dm
        return J

    notes = []
    def cost(p):
        r = res(p)
        return float(r @ r), r

    def normal(p, r):
        J = jac(p)
        return J.T @ J, J.T @ r

    p, nfev, ok = _lm(cost, normal, p, lo=lo, hi=hi, max_iter=MAX_ITER, tol=1e-10)
    if not ok:
        notes.append(f"joint solve: not converged in {MAX_ITER} iterations")
    if free_shifts:
        d = p[:nd]
    at_bound = [int(k) for k in np.flatnonzero(np.isclose(d, lb, atol=1e-5) | np.isclose(d, ub, atol=1e-5))] \
        if free_shifts else []
    for k in at_bound:
        notes.append(f"the step between {T[k]:.4g} and {T[k + 1]:.4g} deg C sits at the minimum overlap "
                     f"({min_overlap} decades): these sets do not superpose with horizontal shifts")
    if lag and abs(p[iq]) > MAX_LAG_PHASE - 1e-6:
        notes.append(f"the instrument lag sits at its bound (a phase error of {MAX_LAG_PHASE} rad at "
                     f"{f.max():.4g} Hz): the lag model does not describe these data")
    # covariance of the parameters: the sandwich (A^-1 B A^-1) of the joint Gauss-Newton matrix A and the
    # squared data residuals B, so that each residual counts by its own size whatever the weights a', a''
    J = jac(p)
    r = res(p)
    Jd, rd = J[:2 * n], r[:2 * n]
    A_inv = np.linalg.pinv(J.T @ J)
    edf = float(np.trace(A_inv @ (Jd.T @ Jd)))
    dof = 2 * float(np.sum(m))
    cov_p = A_inv @ ((Jd * rd[:, None] ** 2).T @ Jd) @ A_inv * dof / max(dof - edf, 1.0)
    if free_shifts:
        G = anchor_matrix(T, T_ref) @ S
        cov = G @ cov_p[:nd, :nd] @ G.T
        log_aT = G @ d
    else:
        cov, log_aT = np.zeros((K, K)), s_held.copy()
    lag_s = float(p[iq]) / w_top if lag else 0.0
    lag_std = math.sqrt(max(cov_p[iq, iq], 0.0)) / w_top if lag else 0.0
    fr = f * 10 ** log_aT[idx]
    spec = fit_spectrum(fr, es, el, weight=m, per_decade=per_decade, margin=margin,
                        components=(a1, a2, 1.0), lam=final_lam,
                        start=start_spectrum if not isinstance(final_lam, str) else None,
                        phase=2 * math.pi * f * lag_s if lag else None)
    return JointFit(T, log_aT, np.sqrt(np.maximum(np.diag(cov), 0)), at_bound, (a1, a2), lam_j, spec, float(r @ r),
                    int(nfev), time.perf_counter() - t0, cov, notes, lag_s, lag_std, bool(lag), bool(free_shifts),
                    k_ref if free_shifts else -1)
