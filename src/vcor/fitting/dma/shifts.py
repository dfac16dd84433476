r"""Start-free global time-temperature superposition (horizontal shifts only).

All sets' shift factors are found at once by fitting one smooth master curve per quantity (a
penalised cubic B-spline, a "P-spline", in :math:`x = \log_{10} f_\mathrm{red}`) to every set
simultaneously while optimising the shifts (variable projection).

Model
-----
Set :math:`k` (temperature :math:`T_k`, deg C) holds points :math:`(f_{ki}, E'_{ki}, E''_{ki})`.  Its
reduced frequencies are :math:`f_\mathrm{red} = f\,a_{T,k}`; in logarithms

.. math:: \tilde x_{ki} = \log_{10} f_{ki} + s_k, \qquad s_k = \log_{10} a_{T,k}.

For each quantity :math:`q` (``"E_stor"``: :math:`y = \log_{10}E'`, ``"E_loss"``: :math:`\log_{10}E''`,
``"tan_delta"``: :math:`\log_{10}\tan\delta`) the master curve is
:math:`g_q(\tilde x) = \sum_b c_{qb} B_b(\tilde x)`, cubic B-splines on a fixed lattice of knots
(spacing :math:`h` = 1/``knots_per_decade`` decades).  The shifts minimise

.. math::

   \Phi(s) = \sum_q w_q \min_{c_q} \Big[ \sum_{k,i} \omega_{qki}\,\big(y_{qki} - g_q(x_{ki}+s_k)\big)^2
             + \mu_q \lVert D_2 c_q \rVert^2 \Big]

subject to every pair of temperature-adjacent sets overlapping by at least ``min_overlap``
decades of reduced frequency.  :math:`D_2` is the second-difference matrix, :math:`\mu_q` the
smoothing parameter of quantity :math:`q` (generalised cross-validation, GCV, at the current
shifts), :math:`w_q = 1/\hat\sigma_q^2` the inverse residual variance of quantity :math:`q` (each
quantity counts by its own noise) and :math:`\omega_{qki}` per-point weights: 1, or Huber weights
(``robust``), times 0 for points of a fall-back quantity that no pair needs (below).  For fixed
shifts the inner problem is linear least squares (banded, O(number of knots)); the objective does
not depend on how far the knot lattice extends beyond the data.

Which quantities
----------------
``quantities`` are always used.  For a pair of adjacent sets whose values of every primary quantity
share less than ``2 sigma_q`` of range (a monotone quantity cannot then be superposed), the first
of ``fallback`` whose ranges do overlap is added for the points of that pair.  A pair with no usable
quantity is refused (``ValueError`` naming the temperatures).

Solving it, and why it is start-free
------------------------------------
The unknowns are the :math:`K-1` steps :math:`d_k = s_{k+1} - s_k` (box-bounded by the overlap
requirement); the set nearest ``T_ref`` is held at 0 during the solve.

1. Start (needs no start): for every adjacent pair, an exhaustive scan (step ``scan_step``) of the
   pair's mutual mismatch (:func:`pairwise_shifts`) gives the global minimiser of that pair's
   objective.
2. Block sweeps: for each :math:`k`, all sets hotter than :math:`k` are moved rigidly: the full
   objective :math:`\Phi` is scanned over the whole admissible interval of :math:`d_k` (grid
   ``block_step``) and the global minimum on that grid is refined by a bounded scalar search.
   Sweeps repeat until no step moves by more than ``block_step``; each 1-D problem is solved
   globally, so a wrong start is not a trap: a block that sits a few decades away is pulled back
   in one move.
3. Polish: trust-region Gauss-Newton (``scipy.optimize.least_squares``, bounds) on all steps with
   the exact variable-projection Jacobian (Golub & Pereyra 1973).

Steps 2-3 are repeated with :math:`\mu_q, w_q, \omega` re-estimated at the current shifts
(``passes``; the first estimate is always made at the data-derived start of step 1).  Afterwards all
shifts are moved so that :math:`\log_{10}a_T(T_\mathrm{ref}) = 0` (linear interpolation in :math:`T`
between the two sets around ``T_ref``).

Uncertainty
-----------
:math:`\mathrm{Cov}(d) = \hat\sigma^2 (J^\top J)^{-1}` at the solution (:math:`J` the projected
Jacobian with respect to the steps, :math:`\hat\sigma^2` the residual variance of the weighted fit),
mapped to the shifts and through the re-anchoring to ``T_ref``.  It assumes independent residuals;
the non-superposing parts of real data are systematic, so the bootstrap (:mod:`vcor.fitting.resample`) is the
more honest spread.

Units: frequencies Hz, moduli Pa (only logarithms enter), temperatures deg C, shifts decades.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import least_squares, minimize_scalar

from ._spline import SplineObjective, step_matrix
from .sets import QUANTITIES, split_sets

__all__ = ["BLOCK_STEP", "MAX_SWEEPS", "MIN_OVERLAP", "PASSES", "SCAN_STEP", "TOL", "ShiftResult", "anchor_matrix",
           "global_shifts", "pairwise_shifts", "step_matrix", "superposition_rms"]

#: Huber's constant (in units of the residual sd): 95 % efficiency at normal errors
HUBER = 1.345
#: grid step (decades) of the pairwise scan that starts the solve
SCAN_STEP = 0.01
#: grid step (decades) of the block sweeps
BLOCK_STEP = 0.1
#: block sweeps per pass, and passes (re-estimating smoothing and weights)
MAX_SWEEPS, PASSES = 10, 6
#: convergence: no shift moves by more than this (decades) in a pass
TOL = 1e-3
#: decades of reduced frequency adjacent sets must share
MIN_OVERLAP = 0.5
#: smallest noise scale of a quantity, log10 units: a noise-free set still weighs finitely
NOISE_FLOOR = 1e-4
#: a point this close (decades) to the edge of an overlap counts as inside
EDGE = 1e-12
#: points (multiplicity) a trial step's overlap needs for its mismatch to count
MIN_PAIR_POINTS = 4
#: the bounded 1-D search of a block step stops at this step tolerance, decades
XATOL = 1e-4
#: a given start wins when its objective is within this relative margin of the data-derived start's
SAME_OBJECTIVE = 1e-9
#: a step this close (decades) to its bound sits at the bound
AT_BOUND = 1e-6


def _quadfit(x, y, w):
    """Weighted quadratic fit (np.polyval coefficients) and its residual rms."""
    deg = 2 if np.unique(x).size >= 4 else 1
    p = np.polyfit(x, y, deg, w=np.sqrt(w))
    r = y - np.polyval(p, x)
    return p, math.sqrt(float(np.sum(w * r**2) / max(np.sum(w) - deg - 1, 1.0)))


def _step_bounds(a, b, min_overlap):
    """Admissible d = s_b - s_a for which the reduced log-frequency ranges overlap >= min_overlap."""
    lo = a.x.min() - b.x.max() + min_overlap
    hi = a.x.max() - b.x.min() - min_overlap
    if not lo <= hi:
        raise ValueError(f"the sets at {a.T:.4g} and {b.T:.4g} deg C span less than min_overlap = "
                         f"{min_overlap} decades")
    return lo, hi


def _noise(sets, quantities):
    """Pooled quadratic-fit residual rms per quantity (log10 units): a noise scale from each set alone."""
    return {q: max(math.sqrt(float(np.mean([_quadfit(s.x, s.y(q), s.w)[1] ** 2 for s in sets]))), NOISE_FLOOR)
            for q in quantities}


def _pair_quantities(a, b, quantities, fallback, sigma):
    """Quantities usable for the pair: primaries always; a fall-back only if no primary's value
    ranges overlap by 2 sigma (then the first fall-back whose ranges overlap at all)."""
    def overlap(q):
        ya, yb = a.y(q), b.y(q)
        return min(ya.max(), yb.max()) - max(ya.min(), yb.min())

    if any(overlap(q) > 2 * sigma[q] for q in quantities):
        return list(quantities), []
    for q in fallback:
        if overlap(q) > 0:
            return list(quantities), [q]
    raise ValueError(f"the sets at {a.T:.4g} and {b.T:.4g} deg C share no range of "
                     f"{', '.join(tuple(quantities) + tuple(fallback))}: their shift cannot be found "
                     f"from the data")



def pairwise_shifts(sets, quantities=("E_stor",), fallback=("tan_delta", "E_loss"), *, scan_step=SCAN_STEP,
                    min_overlap=MIN_OVERLAP, sigma=None):
    r"""Step of each set relative to its colder neighbour by an exhaustive 1-D scan.

    For the pair (a, b) and a trial step :math:`d` (b's reduced log frequency is :math:`x_b + d` in
    a's frame) the mismatch is

    .. math:: m(d) = \frac{1}{n_\mathrm{ov}(d)} \sum_q \frac{1}{\sigma_q^2}\Big[
              \sum_{i \in b,\,\mathrm{ov}} (y_{qbi} - p_{qa}(x_{bi}+d))^2 +
              \sum_{i \in a,\,\mathrm{ov}} (y_{qai} - p_{qb}(x_{ai}-d))^2 \Big],

    :math:`p_{qa}` a quadratic least-squares fit of set a's :math:`y_q` against :math:`\log_{10} f`,
    "ov" the points inside the shared reduced range (at least ``min_overlap`` decades),
    :math:`\sigma_q` the pooled residual rms of the quadratic fits.  The scan covers every
    admissible :math:`d`, so the minimiser is global (on the grid).

    Parameters
    ----------
    sets : list of DMASet
        Sorted by temperature.
    quantities, fallback : tuple of str
        Primary and fall-back quantities (see the module docstring).
    scan_step, min_overlap : float
        Scan grid step and minimum overlap, decades.
    sigma : dict, optional
        Noise scale per quantity (log10 units); default: the pooled residual rms of each set's quadratic fit.

    Returns
    -------
    steps : ndarray, shape (K-1,)
        :math:`s_{k+1} - s_k`, decades.
    info : list of dict
        Per pair: temperatures, quantities used, best mismatch, the scan (d, m(d)).
    """
    sigma = sigma or _noise(sets, tuple(quantities) + tuple(fallback))
    steps, info = [], []
    for k in range(len(sets) - 1):
        a, b = sets[k], sets[k + 1]
        prim, extra = _pair_quantities(a, b, quantities, fallback, sigma)
        lo_d, hi_d = _step_bounds(a, b, min_overlap)
        d = np.arange(lo_d, hi_d + scan_step / 2, scan_step)
        xa, xb = a.x, b.x
        lo = np.maximum(xa.min(), xb.min() + d)
        hi = np.minimum(xa.max(), xb.max() + d)
        tot = np.zeros(d.size)
        cnt = np.zeros(d.size)
        for q in prim + extra:
            pa, pb = _quadfit(xa, a.y(q), a.w)[0], _quadfit(xb, b.y(q), b.w)[0]
            xbs = xb[None, :] + d[:, None]
            inb = (xbs >= lo[:, None] - EDGE) & (xbs <= hi[:, None] + EDGE)
            rb = (b.y(q)[None, :] - np.polyval(pa, xbs)) ** 2
            ina = (xa[None, :] >= lo[:, None] - EDGE) & (xa[None, :] <= hi[:, None] + EDGE)
            ra = (a.y(q)[None, :] - np.polyval(pb, xa[None, :] - d[:, None])) ** 2
            tot += (np.sum(np.where(inb, rb * b.w, 0), 1) + np.sum(np.where(ina, ra * a.w, 0), 1)) / sigma[q] ** 2
            cnt += np.sum(np.where(inb, b.w, 0), 1) + np.sum(np.where(ina, a.w, 0), 1)
        m = np.where(cnt >= MIN_PAIR_POINTS, tot / np.maximum(cnt, 1), np.inf)
        i = int(np.argmin(m))
        steps.append(float(d[i]))
        info.append({"T": (a.T, b.T), "quantities": prim + extra, "mismatch": float(m[i]), "scan": (d, m)})
    return np.array(steps), info


@dataclass(frozen=True, kw_only=True)
class ShiftResult:
    """Shift factors of a set of isothermal sweeps (:func:`global_shifts`).

    Attributes
    ----------
    T : ndarray
        Set temperatures, deg C, ascending.
    log_aT : ndarray
        log10 a_T of each set, 0 at ``T_ref`` (f_red = f a_T; hot sets have log_aT < 0).
    log_aT_std : ndarray
        Standard error of each log_aT (linearised), decades.
    T_ref : float
        Reference temperature, deg C.
    quantities : dict
        Per quantity: which sets' points entered the objective (bool array).
    sigma : dict
        Residual rms per quantity (log10 units) about the master splines, over the points used.
    set_rms : dict
        Per quantity: residual rms of each set (log10 units), all its points.
    start : ndarray
        The data-derived start (chained pairwise steps, anchored to T_ref).
    mu : dict
        Smoothing parameter per quantity (GCV), normalised problem.
    objective : float
        Final Phi.
    sweeps : int
        Block sweeps done; ``n_eval``: objective evaluations in total.
    time : float
        Wall time, s.
    cov : ndarray
        Covariance matrix of log_aT, decades^2.
    notes : list of str
    pairwise : list of dict
        The pairwise scans (:func:`pairwise_shifts`).
    candidates : list of dict
        With a given ``start``: the refinements from it and from the data-derived start (objective
        under the same weights, log_aT); the lower one is the result.
    """

    T: np.ndarray
    log_aT: np.ndarray
    log_aT_std: np.ndarray
    T_ref: float
    quantities: dict
    sigma: dict
    set_rms: dict
    start: np.ndarray
    mu: dict
    objective: float
    sweeps: int
    n_eval: int
    time: float
    cov: np.ndarray
    notes: list = field(default_factory=list)
    pairwise: list = field(default_factory=list, repr=False)
    candidates: list = field(default_factory=list, repr=False)


def anchor_matrix(T, T_ref):
    r"""Matrix :math:`A` with :math:`\log_{10} a_T = A s`: subtract from per-set shifts :math:`s` their linear
    interpolation in T at ``T_ref`` (extrapolation from the two end sets outside), so that
    :math:`\log_{10} a_T(T_\mathrm{ref}) = 0`.

    Parameters
    ----------
    T : ndarray
        Set temperatures, deg C, ascending.
    T_ref : float
        Reference temperature, deg C.

    Returns
    -------
    ndarray, shape (K, K)
    """
    n = T.size
    if T_ref <= T[0]:
        i, j = 0, 1
    elif T_ref >= T[-1]:
        i, j = n - 2, n - 1
    else:
        j = int(np.searchsorted(T, T_ref))
        i = j - 1
    wj = (T_ref - T[i]) / (T[j] - T[i])
    A = np.eye(n)
    A[:, i] -= 1 - wj
    A[:, j] -= wj
    return A


@dataclass(kw_only=True)
class _Setup:
    """What every refinement shares: the sets, the quantities used where, the step bounds, the start."""

    sets: list
    k_ref: int
    used: list
    masks: dict
    lb: np.ndarray
    ub: np.ndarray
    steps0: np.ndarray
    info: list
    knots_per_decade: float
    n_pen: int = 0

    def objective(self):
        return SplineObjective(self.sets, self.k_ref, self.used, self.masks, self.knots_per_decade)


def _setup(sets, T_ref, quantities, fallback, knots_per_decade, min_overlap) -> _Setup:
    """The data-derived start (:func:`pairwise_shifts`), the quantities each set enters with, the bounds."""
    K = len(sets)
    for q in tuple(quantities) + tuple(fallback):
        if q not in QUANTITIES:
            raise ValueError(f"quantities must be from {QUANTITIES}, got {q!r}")
    T = np.array([s.T for s in sets])
    sigma0 = _noise(sets, tuple(quantities) + tuple(fallback))
    steps0, info = pairwise_shifts(sets, quantities, fallback, scan_step=SCAN_STEP, min_overlap=min_overlap,
                                   sigma=sigma0)
    used = list(quantities) + [q for q in fallback if any(q in p["quantities"] for p in info)]
    masks = {q: np.ones(K, bool) if q in quantities else np.zeros(K, bool) for q in used}
    for k, p in enumerate(info):
        for q in p["quantities"]:
            masks[q][k] = masks[q][k + 1] = True
    bounds = np.array([_step_bounds(sets[k], sets[k + 1], min_overlap) for k in range(K - 1)])
    setup = _Setup(sets=sets, k_ref=int(np.argmin(np.abs(T - T_ref))), used=used, masks=masks, lb=bounds[:, 0],
                   ub=bounds[:, 1], steps0=steps0, info=info, knots_per_decade=knots_per_decade)
    # largest reduced span any admissible steps can give: fixes the residual length of the polish
    S, lb, ub = step_matrix(K, setup.k_ref), setup.lb, setup.ub
    s_lo, s_hi = S.clip(max=0) @ ub + S.clip(min=0) @ lb, S.clip(min=0) @ ub + S.clip(max=0) @ lb
    span = (max(st.x.max() + hi_ for st, hi_ in zip(sets, s_hi, strict=True))
            - min(st.x.min() + lo_ for st, lo_ in zip(sets, s_lo, strict=True)))
    setup.n_pen = math.ceil(span * knots_per_decade) + 8
    return setup


def _value_at(z, pr, d, k):
    """Phi with step k at z, the others at d."""
    t = d.copy()
    t[k] = z
    return pr.value(t)


class _Refinement:
    """Passes of (re-estimate mu, w, omega; block sweeps; polish) from given steps (module docstring)."""

    def __init__(self, setup: _Setup, *, mu, robust):
        self.setup, self.mu, self.robust = setup, mu, robust
        self.n_eval, self.sweeps = 0, 0

    def estimate(self, pr, s):
        """Smoothing mu, weight w_q = 1/variance and (robust) Huber weights of every quantity at shifts s."""
        for q in self.setup.used:
            pr.omega[q] = np.ones(pr.x.size)
            if self.mu is not None and q in self.mu:
                pr.mu[q] = float(self.mu[q])
                _, _, g, edf = pr.fit(q, s, edf=True)
                rss = float(np.sum(pr.W(q) * (pr.y[q] - g) ** 2))
            else:
                pr.mu[q], rss, edf = pr.gcv(q, s)
            var = rss / max(float(np.sum(pr.W(q))) - edf, 1.0)
            pr.wq[q] = 1.0 / max(var, 1e-14)
            if self.robust:
                _, _, g = pr.fit(q, s)
                a = np.abs(pr.y[q] - g) / math.sqrt(var)
                pr.omega[q] = np.where(a <= HUBER, 1.0, HUBER / np.maximum(a, 1e-12))

    def block(self, pr, d, k):
        """Step k moved globally over its admissible interval (grid, then a bounded search), the others
        rigid: the new value of d[k]."""
        grid = np.arange(self.setup.lb[k], self.setup.ub[k] + BLOCK_STEP / 2, BLOCK_STEP)
        trial = np.repeat(d[None, :], grid.size, 0)
        trial[:, k] = grid
        vals = np.array([pr.value(t) for t in trial])
        self.n_eval += grid.size
        i = int(np.argmin(vals))
        a_, b_ = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
        cur = pr.value(d)
        r1 = minimize_scalar(_value_at, bounds=(a_, b_), args=(pr, d, k), method="bounded", options={"xatol": XATOL})
        self.n_eval += r1.nfev + 1
        return r1.x if r1.fun < cur - 1e-12 else d[k]

    def sweeps_until_still(self, pr, d):
        """Block sweeps until no step moves by more than :data:`BLOCK_STEP` (at most :data:`MAX_SWEEPS`)."""
        d = d.copy()
        for _ in range(MAX_SWEEPS):
            self.sweeps += 1
            moved = 0.0
            for k in range(d.size):
                new = self.block(pr, d, k)
                moved = max(moved, abs(new - d[k]))
                d[k] = new
            if moved <= BLOCK_STEP:
                break
        return d

    def polish(self, pr, d):
        """Trust-region Gauss-Newton on all steps with the variable-projection Jacobian."""
        n_pen = self.setup.n_pen
        sol = least_squares(lambda z: pr.residual(z, n_pen=n_pen)[0], d, jac=lambda z: pr.residual(z, True, n_pen)[1],
                            bounds=(self.setup.lb, self.setup.ub), method="trf", xtol=1e-10, ftol=1e-12, gtol=1e-10,
                            max_nfev=100)
        self.n_eval += sol.nfev
        return sol.x

    def run(self, d):
        """(objective, steps, notes) of the passes from steps d."""
        pr = self.setup.objective()
        d = d.copy()
        prev_mu, moved_pass = None, math.inf
        for p in range(PASSES + 1):
            # the first estimate of smoothing and noise is made at the data-derived start even when
            # another start is given: at a wrong arrangement GCV picks a stiff, nearly straight master
            # curve whose best arrangement is the wrong one
            self.estimate(pr, pr.shifts(d if p > 0 else self.setup.steps0))
            if p > 0 and moved_pass < TOL and dict(pr.mu) == prev_mu:
                break   # converged: smoothing unchanged and the last pass moved nothing
            if p == PASSES:
                return pr, d, [f"not converged in {PASSES} passes (last pass moved {moved_pass:.3g} decades)"]
            prev_mu, d_pass = dict(pr.mu), d.copy()
            d = self.polish(pr, self.sweeps_until_still(pr, d))
            moved_pass = float(np.max(np.abs(pr.shifts(d) - pr.shifts(d_pass))))
        return pr, d, []


def _best_of_starts(refinement, setup, start, T, T_ref):
    """(objective, steps, notes, candidates): from the data-derived start, and from a given one when
    given (the lower objective under the data-derived start's weights wins)."""
    if start is None:
        return (*refinement.run(setup.steps0), [])
    pr_s, d_s, notes_s = refinement.run(np.clip(np.diff(np.asarray(start, float)), setup.lb, setup.ub))
    pr, d, notes = refinement.run(setup.steps0)
    v_s, v_0 = pr.value(d_s), pr.value(d)
    A = anchor_matrix(T, T_ref)
    candidates = [{"start": "given", "objective": v_s, "log_aT": A @ pr.shifts(d_s)},
                  {"start": "data-derived", "objective": v_0, "log_aT": A @ pr.shifts(d)}]
    if v_s <= v_0 * (1 + SAME_OBJECTIVE):
        return pr_s, d_s, notes_s, candidates
    notes.append(f"the given start led to a worse minimum (objective {v_s:.6g} against {v_0:.6g}); "
                 f"the data-derived start's solution is returned")
    return pr, d, notes, candidates


def _spread(pr, d, used, K):
    """(covariance of the steps, residual rms per quantity, per set): the linearised uncertainty."""
    s = pr.shifts(d)
    r, J = pr.residual(d, jac=True)
    n_data = sum(float(np.sum(pr.W(q) > 0)) for q in used)
    edf = sum(pr.fit(q, s, edf=True)[3] for q in used)
    s2 = float(np.sum(r**2)) / max(n_data - edf - (K - 1), 1.0)
    cov_d = s2 * np.linalg.pinv(J.T @ J)
    sig, set_rms = {}, {}
    for q in used:
        _, _, g = pr.fit(q, s)
        res = pr.y[q] - g
        m = pr.mask[q] > 0
        sig[q] = float(np.sqrt(np.average(res[m] ** 2, weights=pr.mult[m])))
        set_rms[q] = np.array([math.sqrt(float(np.average(res[pr.idx == k] ** 2, weights=pr.mult[pr.idx == k])))
                               for k in range(K)])
    return cov_d, sig, set_rms


def global_shifts(raw, T_ref, quantities=("E_stor",), fallback=("tan_delta", "E_loss"), *, start=None,
                  knots_per_decade=3.0, robust=False, min_overlap=MIN_OVERLAP, mu=None) -> ShiftResult:
    r"""Start-free shift factors of all sets at once (module docstring).

    Parameters
    ----------
    raw : DMATable, mapping, or list of DMASet
        Raw sets (:func:`vcor.fitting.dma.sets.split_sets`).
    T_ref : float
        Reference temperature, deg C (log_aT(T_ref) = 0; T_ref may lie between sets).
    quantities : tuple of str
        Primary quantities, from ``"E_stor"``, ``"E_loss"``, ``"tan_delta"`` (log10 E', E'', tan delta).
    fallback : tuple of str
        Used for a pair only where no primary quantity's ranges overlap.
    start : array_like, optional
        log10 a_T per set: an extra starting point (to check start-independence).  The refinement
        runs from it and from the data-derived start (the chained pairwise scan, which needs no
        start); the lower objective wins (``candidates`` keeps both).
    knots_per_decade : float
        Knot density of the master splines.
    robust : bool
        Huber weights (c = 1.345 sigma_q) against outliers (e.g. a first point off equilibrium).
    min_overlap : float
        Adjacent sets must share at least this many decades of reduced frequency.
    mu : dict, optional
        Smoothing parameter per quantity, held fixed (default: GCV in every pass).  A bootstrap
        passes the full-data values: GCV on resampled (weighted) data undersmooths, a heavily
        weighted point acting like a duplicate that cross-validation cannot see.

    Returns
    -------
    ShiftResult
    """
    t0 = time.perf_counter()
    sets = split_sets(raw)
    K = len(sets)
    T = np.array([s.T for s in sets])
    setup = _setup(sets, T_ref, quantities, fallback, knots_per_decade, min_overlap)
    refinement = _Refinement(setup, mu=mu, robust=robust)
    pr, d, notes, candidates = _best_of_starts(refinement, setup, start, T, T_ref)
    at_bound = np.flatnonzero(np.isclose(d, setup.lb, atol=AT_BOUND) | np.isclose(d, setup.ub, atol=AT_BOUND))
    for k in at_bound:
        notes.append(f"the step between {T[k]:.4g} and {T[k + 1]:.4g} deg C sits at the minimum overlap "
                     f"({min_overlap} decades): these sets do not superpose; the shift is a bound, not a fit")
    cov_d, sig, set_rms = _spread(pr, d, setup.used, K)
    A = anchor_matrix(T, T_ref)
    cov = A @ pr.S @ cov_d @ pr.S.T @ A.T
    return ShiftResult(T=T, log_aT=A @ pr.shifts(d), log_aT_std=np.sqrt(np.maximum(np.diag(cov), 0.0)),
                       T_ref=float(T_ref), quantities=setup.masks, sigma=sig, set_rms=set_rms,
                       start=A @ pr.shifts(setup.steps0), mu=dict(pr.mu), objective=float(pr.value(d)),
                       sweeps=refinement.sweeps, n_eval=int(refinement.n_eval), time=time.perf_counter() - t0,
                       cov=cov, notes=notes, pairwise=setup.info, candidates=candidates)


def superposition_rms(raw, log_aT, quantities=("E_stor",), knots_per_decade=3.0, mu=None):
    """How well given shift factors superpose the sets: per quantity, the rms (log10 units) of the
    residuals about one P-spline master curve through all sets (mu by GCV unless given), e.g. to
    compare shift sets from different tools.

    Parameters
    ----------
    raw : DMATable, mapping, or list of DMASet
    log_aT : array_like
        Shifts per set (split_sets order), decades.
    quantities : tuple of str
    knots_per_decade, mu : float

    Returns
    -------
    dict
        {quantity: rms of log10 residuals}.
    """
    sets = split_sets(raw)
    K = len(sets)
    pr = SplineObjective(sets, 0, quantities, {q: np.ones(K) for q in quantities}, knots_per_decade)
    s = np.asarray(log_aT, float) - float(log_aT[0])
    rms = {}
    for q in quantities:
        pr.mu[q] = pr.gcv(q, s)[0] if mu is None else mu
        _, _, g = pr.fit(q, s)
        rms[q] = float(np.sqrt(np.average((pr.y[q] - g) ** 2, weights=pr.mult)))
    return rms
