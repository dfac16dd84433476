r"""Shift factors (and an instrument lag) refined together with the smooth spectrum: the master curve
is the Prony model itself.

Minimised over the steps :math:`d_k = s_{k+1} - s_k` (bounded so that adjacent sets overlap by
:data:`vcor.fitting.dma.shifts.MIN_OVERLAP` decades, as in the start-free shifts), :math:`\ln E_\infty`,
the log-spectrum :math:`H` and, with ``lag``, a time lag :math:`\Delta t` of the instrument:

.. math:: \sum_{k,i} m_{ki}\Big[a'\Big(\frac{\mathrm{Re}\,M_{ki}}{E'_{ki}} - 1\Big)^2
          + a''\Big(\frac{\mathrm{Im}\,M_{ki}}{E''_{ki}} - 1\Big)^2\Big]
          + \lambda \lVert D_2 H \rVert^2, \qquad
          M_{ki} = E^*_{\rm fit}(2\pi f_{ki}10^{s_k})\, e^{\,i\,2\pi f_{ki}\Delta t}.

The data rows and their Jacobian are the smooth fit's (:mod:`vcor.fitting.spectrum.residual`), with
columns for the steps and the lag added; the roughness enters as rows :math:`\sqrt\lambda D_2 H`.

A free smooth curve (:func:`vcor.fitting.dma.shifts.global_shifts`) can lay E' on one curve with
shifts for which no linear viscoelastic material has that E' *and* the measured E'' (Kramers-Kronig);
here the shifts must make both consistent with one relaxation spectrum.

The lag: a delay :math:`\Delta t` between an instrument's force and displacement signals adds
:math:`2\pi f\Delta t` to every measured loss angle, f the *measured* frequency. A property of the
material moves with :math:`a_T` across the reduced frequencies; an error that stays at the same
measured frequency at every temperature does not, so with sets at several temperatures the
superposition tells the two apart and :math:`\Delta t` is identified (a constant phase offset would not
be: a flat tan delta absorbs it).

A refit of perturbed data (a bootstrap sample) can start from another joint solve's optimum
(:class:`JointStart`, :attr:`JointFit.solution`): its relaxation-time grid, spectrum and lag, with the
shifts started at that fit's; the solve then stops on the same criterion (:data:`TOL`) from a start
near its own optimum.

Every joint solve, of the full data and of a bootstrap sample alike, takes geodesically accelerated
Levenberg-Marquardt steps (:func:`vcor.fitting.spectrum.lm.levenberg_marquardt` with ``curvature``;
Transtrum & Sethna 2012, arXiv:1201.5885): the shifts and the spectrum trade off along a long curved
valley of the objective, which plain steps follow slowly; one solver for both, so that a refit started
at the full-data optimum stops where the full-data solve would.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..spectrum.lm import curvature_gradient, levenberg_marquardt
from ..spectrum.model import MARGIN, PER_DECADE, margins, tau_grid
from ..spectrum.residual import Design, Residual, second_differences
from ..spectrum.smooth import SpectrumFit, component_weights, fit_spectrum, log_spectrum
from .shifts import MIN_OVERLAP, anchor_matrix, step_matrix

__all__ = ["LOSS_WEIGHT", "MAX_ITER", "MAX_LAG_PHASE", "SHIFT_ROOM", "TOL", "JointFit", "JointStart", "fit_with_shifts"]

#: weight a'' of the relative E'' residuals against E': inverse variances for relative errors of about 1 % in
#: E' and 10 % in E'' (:mod:`vcor.fitting.dma.pipeline`: on pyvisco's data E'' carries an instrument phase
#: error and does not superpose, and equal weights let those errors set the shifts)
LOSS_WEIGHT = 0.01
#: largest instrument phase error (rad) at the highest measured frequency that :func:`fit_with_shifts`
#: may fit (17 deg; a lag that large says the data need an instrument correction, not a fit)
MAX_LAG_PHASE = 0.3
#: iteration budget of each joint solve (projected Levenberg-Marquardt)
MAX_ITER = 500
#: convergence of each joint solve, cold or warm: the decrease a full Gauss-Newton step predicts is below
#: this fraction of the objective (:func:`vcor.fitting.spectrum.lm.levenberg_marquardt`)
TOL = 1e-10
#: decades the relaxation-time grid reaches beyond the smooth fit's margins: room for the shifts to move
SHIFT_ROOM = 1.5
#: bounds of ln(mode modulus / largest E'): e^-40 (a mode with no weight) .. e^3
LOG_MODULUS_RANGE = (-40.0, 3.0)
#: a start this far (decades, rad) inside its bounds: the projected solver starts from an interior point
INSIDE = 1e-9


@dataclass(frozen=True, kw_only=True)
class JointStart:
    """Where a joint solve starts other than from scratch: the optimum of another joint solve.

    Attributes
    ----------
    tau : ndarray
        Relaxation times of the joint solve's grid, s (the solve keeps this grid).
    E_inf : float
        Equilibrium modulus, Pa (> 0).
    E : ndarray
        Mode moduli on ``tau``, Pa (> 0).
    lag : float
        The instrument's time lag, s (0 when not fitted).
    """

    tau: np.ndarray
    E_inf: float
    E: np.ndarray
    lag: float = 0.0


@dataclass(frozen=True, kw_only=True)
class JointFit:
    """Shift factors (and an instrument lag) refined together with the spectrum
    (:func:`fit_with_shifts`), and the smooth spectrum at them.

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
        Levenberg-Marquardt iterations of the joint solve.
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
    solution : JointStart or None
        The joint solve's own optimum (its grid, spectrum at ``lam_joint`` and lag): the start of a refit of
        perturbed data (``start`` of :func:`fit_with_shifts`).
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
    solution: JointStart | None = None

    @property
    def smoothing(self) -> dict:
        """lambda of the joint solve and of the final spectrum (to hold fixed in a bootstrap)."""
        return {"lam_joint": float(self.lam_joint), "lam": float(self.spectrum.lam)}


class _Stacked:
    """The sets' points stacked in set order: measured f (Hz), E', E'' (Pa), multiplicities, set index."""

    def __init__(self, sets, T_ref, min_overlap):
        self.K = len(sets)
        self.T = np.array([s.T for s in sets])
        self.k_ref = int(np.argmin(np.abs(self.T - T_ref)))
        self.f = np.concatenate([s.f for s in sets])
        self.idx = np.concatenate([np.full(s.f.size, k) for k, s in enumerate(sets)])
        self.es = np.concatenate([s.E_stor for s in sets])
        self.el = np.concatenate([s.E_loss for s in sets])
        self.m = np.concatenate([s.w for s in sets])
        x = [np.log10(s.f) for s in sets]
        self.lb = np.array([x[k].min() - x[k + 1].max() + min_overlap for k in range(self.K - 1)])
        self.ub = np.array([x[k].max() - x[k + 1].min() - min_overlap for k in range(self.K - 1)])
        self.S = step_matrix(self.K, self.k_ref)


class _JointProblem:
    """The joint objective in p = (steps d [free shifts], lag phase [with lag], ln E_inf, H)."""

    def __init__(self, data: _Stacked, residual: Residual, tau, lam, *, s_held, lag):
        self.data, self.residual, self.tau, self.lam = data, residual, tau, lam
        self.s_held = s_held                                     # the shifts when they are held, else None
        self.nd = data.K - 1 if s_held is None else 0            # free steps
        self.nq = int(bool(lag))                                 # lag parameter
        self.iq, self.ie = self.nd, self.nd + self.nq            # where the lag and ln E_inf sit in p
        self.g = data.f / float(data.f.max())                    # the lag parameter: its phase at the top frequency
        self.Dm = second_differences(tau.size)
        self._jac = (None, None)                                 # (p, Jacobian at p) of the last normal()

    def shifts(self, p):
        return self.data.S @ p[:self.nd] if self.s_held is None else self.s_held

    def unpack(self, p):
        """The design at the shifts and lag of p, E_inf and the mode moduli (Pa)."""
        wt = np.multiply.outer(2 * math.pi * self.data.f * 10 ** self.shifts(p)[self.data.idx], self.tau)
        return Design(wt, self.g * p[self.iq] if self.nq else None), math.exp(p[self.ie]), np.exp(p[self.ie + 1:])

    def value(self, p):
        design, E_inf, E = self.unpack(p)
        roughness = math.sqrt(self.lam) * (self.Dm @ p[self.ie + 1:])
        return np.concatenate([self.residual.value(design, E_inf, E), roughness])

    def jacobian(self, p):
        design, E_inf, E = self.unpack(p)
        n, nt = self.data.f.size, self.tau.size
        J = np.zeros((2 * n + nt - 2, p.size))
        if self.nd:
            Js = self.residual.shift_columns(design, E, self.data.idx, self.data.K)
            Js[:, self.data.k_ref] = 0.0
            J[:2 * n, :self.nd] = Js @ self.data.S
        if self.nq:
            J[:2 * n, self.iq] = self.residual.lag_column(design, E_inf, E, self.g)
        J[:2 * n, self.ie:] = self.residual.spectrum_columns(design, E_inf, E)
        J[2 * n:, self.ie + 1:] = math.sqrt(self.lam) * self.Dm
        return J

    def cost(self, p):
        r = self.value(p)
        return float(r @ r), r

    def normal(self, p, r):
        J = self.jacobian(p)
        self._jac = (p.copy(), J)
        return J.T @ J, J.T @ r

    def curvature(self, p, r, v):
        """J^T r_vv at p along v (:func:`vcor.fitting.spectrum.lm.curvature_gradient`), with the Jacobian
        of the last :meth:`normal` when that was at p (the solver asks at the point it just linearised)."""
        at, J = self._jac
        if at is None or not np.array_equal(at, p):
            J = self.jacobian(p)
        lo, hi = self.bounds()
        return curvature_gradient(self.value, J, p, r, v, lo=lo, hi=hi)

    def bounds(self):
        big = math.log(float(np.max(self.data.es)))
        n_mod = 1 + self.tau.size
        lo = np.concatenate([self.data.lb[:self.nd], np.full(self.nq, -MAX_LAG_PHASE),
                             np.full(n_mod, big + LOG_MODULUS_RANGE[0])])
        hi = np.concatenate([self.data.ub[:self.nd], np.full(self.nq, MAX_LAG_PHASE),
                             np.full(n_mod, big + LOG_MODULUS_RANGE[1])])
        return lo, hi

    def covariance(self, p):
        """The sandwich covariance (A^-1 B A^-1) of p: the joint Gauss-Newton matrix A and the squared data
        residuals B, so that each residual counts by its own size whatever the weights a', a''."""
        J, r = self.jacobian(p), self.value(p)
        n2 = 2 * self.data.f.size
        Jd, rd = J[:n2], r[:n2]
        A_inv = np.linalg.pinv(J.T @ J)
        edf = float(np.trace(A_inv @ (Jd.T @ Jd)))
        dof = 2 * float(np.sum(self.data.m))
        return A_inv @ ((Jd * rd[:, None] ** 2).T @ Jd) @ A_inv * dof / max(dof - edf, 1.0)


def _first_spectrum(data, fr, comp, *, lam, start_spectrum, per_decade, margin):
    """The spectrum the joint solve starts from (at the start shifts), and the joint solve's lambda."""
    if start_spectrum is not None and lam is not None:
        first = start_spectrum
    else:
        first = fit_spectrum(fr, data.es, data.el, weight=data.m, per_decade=per_decade, margin=margin,
                             components=comp, lam="gcv" if lam is None else float(lam))
    return first, (first.lam if lam is None else float(lam))


def _start_point(data, fr, comp, *, lam, start_spectrum, start, grid):
    """(relaxation-time grid [s], the joint solve's lambda, ln E_inf, H, lag phase [rad]) the solve starts
    from: another solve's optimum (``start``, on its own grid, lambda held), or the smooth spectrum at the
    start shifts on a grid wide enough for the shifts to move by :data:`SHIFT_ROOM` decades at either end."""
    if start is not None:
        if lam is None:
            raise ValueError("lam: a joint solve started from another's optimum (start) holds that solve's lambda; "
                             "give lam (JointFit.lam_joint)")
        tau, E = np.asarray(start.tau, float), np.asarray(start.E, float)
        if not (tau.ndim == 1 and tau.shape == E.shape and tau.size >= 3 and np.all(E > 0) and start.E_inf > 0):
            raise ValueError(f"start: a grid tau of 3 or more relaxation times (s) and as many moduli E > 0 (Pa), with "
                             f"E_inf > 0 (Pa); got {tau.size} times, {E.size} moduli, E_inf {start.E_inf!r}")
        return tau, float(lam), math.log(start.E_inf), np.log(E), 2 * math.pi * float(data.f.max()) * start.lag
    per_decade, margin = grid
    first, lam_j = _first_spectrum(data, fr, comp, lam=lam, start_spectrum=start_spectrum,
                                   per_decade=per_decade, margin=margin)
    tau = tau_grid(float(fr.min()), float(fr.max()), per_decade, margins(margin, SHIFT_ROOM))
    ln_e_inf, H = log_spectrum(first, tau, float(data.es.max()))
    return tau, lam_j, ln_e_inf, H, 0.0


def _shifts_and_lag(problem, p, T_ref, held):
    """(log10 a_T anchored at T_ref, its covariance [decades^2], lag [s], its standard error [s]) at p;
    ``held``: the held shifts (None when free)."""
    data = problem.data
    cov_p = problem.covariance(p)
    w_top = 2 * math.pi * float(data.f.max())
    lag_s = float(p[problem.iq]) / w_top if problem.nq else 0.0
    lag_std = math.sqrt(max(cov_p[problem.iq, problem.iq], 0.0)) / w_top if problem.nq else 0.0
    if held is None:
        G = anchor_matrix(data.T, T_ref) @ data.S
        return G @ p[:problem.nd], G @ cov_p[:problem.nd, :problem.nd] @ G.T, lag_s, lag_std
    return held.copy(), np.zeros((data.K, data.K)), lag_s, lag_std


def _notes(problem, d, p, at_bound, ok, iterations):
    notes = [] if ok else [f"joint solve: not converged (stopped after {iterations} of at most {MAX_ITER} iterations)"]
    T = problem.data.T
    for k in at_bound:
        notes.append(f"the step between {T[k]:.4g} and {T[k + 1]:.4g} deg C sits at the minimum overlap "
                     f"({MIN_OVERLAP} decades): these sets do not superpose with horizontal shifts")
    if problem.nq and abs(p[problem.iq]) > MAX_LAG_PHASE - 1e-6:
        notes.append(f"the instrument lag sits at its bound (a phase error of {MAX_LAG_PHASE} rad at "
                     f"{problem.data.f.max():.4g} Hz): the lag model does not describe these data")
    return notes


def fit_with_shifts(sets, T_ref, log_aT_start, *, components=(1.0, LOSS_WEIGHT), per_decade=PER_DECADE, margin=MARGIN,
                    lam=None, final_lam="gcv1se", start_spectrum=None, lag=False,
                    free_shifts=True, start=None) -> JointFit:
    r"""Refine shift factors (and an instrument lag) together with the spectrum (module docstring).

    The start is ``log_aT_start`` (the start-free spline shifts); :math:`\lambda` is the GCV minimiser
    (a flexible master curve) at the start shifts (unless given); the final spectrum at the refined
    shifts uses ``final_lam``.  Projected Levenberg-Marquardt with the analytic Jacobian and geodesic
    acceleration (module docstring), converged at :data:`TOL` (or after :data:`MAX_ITER` iterations, with a
    note).

    Parameters
    ----------
    sets : list of DMASet
        Sorted by T (:func:`vcor.fitting.dma.sets.split_sets`).
    T_ref : float
        deg C.
    log_aT_start : array_like
        Start shifts (decades), one per set; the shifts themselves with ``free_shifts=False``.
    components : (a', a'') or "uncertainty"
        Component weights (scalars or per-point arrays in the order of the concatenated sets).
        Default (1, :data:`LOSS_WEIGHT`): inverse-variance weights for relative E' errors of ~1 % and E'' errors of
        ~10 % (on pyvisco's data the fits leave 1 % and 16 %: E'' does not superpose and rises at
        the top of every set; equal weights let those E'' errors set the shifts);
        "uncertainty": :func:`vcor.fitting.spectrum.smooth.loss_weights` (per point).
    per_decade, margin : float, float or (float, float)
        As in :func:`vcor.fitting.spectrum.smooth.fit_spectrum`.
    lam : float, optional
        Fix lambda in the joint solve (default: GCV minimiser, see above; required with ``start``).
    final_lam : "gcv1se", "gcv", "lcurve" or float
        lambda of the final spectrum at the refined shifts.
    start_spectrum : SpectrumFit, optional
        Start spectrum of the final smooth fit (e.g. the full-data fit in a bootstrap) and, without
        ``start``, of the joint solve; with ``lam`` given no lambda scan is run at all.
    lag : bool
        Fit the instrument's time lag :math:`\Delta t` (s), its phase at the highest measured frequency
        bounded by :data:`MAX_LAG_PHASE`.
    free_shifts : bool
        False: hold the shifts at ``log_aT_start`` (given shifts) and fit the rest.
    start : JointStart, optional
        Start the joint solve at another solve's optimum (:attr:`JointFit.solution`, e.g. the full-data
        fit's in a bootstrap): its grid, spectrum and lag, the shifts at ``log_aT_start``.

    Returns
    -------
    JointFit
    """
    t0 = time.perf_counter()
    data = _Stacked(sets, T_ref, MIN_OVERLAP)
    given = np.asarray(log_aT_start, float)
    d = np.clip(np.diff(given), data.lb + INSIDE, data.ub - INSIDE) if free_shifts else np.diff(given)
    a1, a2, _ = component_weights(components, data.es, data.el)
    fr = data.f * 10 ** (data.S @ d if free_shifts else given)[data.idx]
    tau, lam_j, ln_e_inf, H, phase = _start_point(data, fr, (a1, a2, 1.0), lam=lam, start_spectrum=start_spectrum,
                                                  start=start, grid=(per_decade, margin))
    problem = _JointProblem(data, Residual(data.es, data.el, data.m, (a1, a2)), tau, lam_j,
                            s_held=None if free_shifts else given, lag=lag)
    lo, hi = problem.bounds()
    p = np.clip(np.concatenate([d[:problem.nd], np.full(problem.nq, phase), [ln_e_inf], H]), lo + INSIDE, hi - INSIDE)
    p, iterations, ok = levenberg_marquardt(problem.cost, problem.normal, p, lo=lo, hi=hi, max_iter=MAX_ITER, tol=TOL,
                                            curvature=problem.curvature)
    d = p[:problem.nd]
    at_bound = [int(k) for k in np.flatnonzero(np.isclose(d, data.lb, atol=1e-5) | np.isclose(d, data.ub, atol=1e-5))] \
        if free_shifts else []
    notes = _notes(problem, d, p, at_bound, ok, iterations)
    log_aT, cov, lag_s, lag_std = _shifts_and_lag(problem, p, T_ref, None if free_shifts else given)
    spec = fit_spectrum(data.f * 10 ** log_aT[data.idx], data.es, data.el, weight=data.m, per_decade=per_decade,
                        margin=margin, components=(a1, a2, 1.0), lam=final_lam,
                        start=start_spectrum if not isinstance(final_lam, str) else None,
                        phase=2 * math.pi * data.f * lag_s if lag else None)
    r = problem.value(p)
    solution = JointStart(tau=tau, E_inf=math.exp(p[problem.ie]), E=np.exp(p[problem.ie + 1:]), lag=lag_s)
    return JointFit(T=data.T, log_aT=log_aT, log_aT_std=np.sqrt(np.maximum(np.diag(cov), 0)), at_bound=at_bound,
                    components=(a1, a2), lam_joint=lam_j, spectrum=spec, objective=float(r @ r), nfev=int(iterations),
                    time=time.perf_counter() - t0, cov=cov, notes=notes, lag=lag_s, lag_std=lag_std,
                    lag_fitted=bool(lag), free_shifts=bool(free_shifts), held_set=data.k_ref if free_shifts else -1,
                    solution=solution)
