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
from scipy.linalg import solveh_banded
from scipy.optimize import least_squares, minimize_scalar

from ..materials.shift import GAS_CONSTANT, wlf_log_aT

__all__ = ["QUANTITIES", "DMASet", "MasterCurve", "ShiftResult", "anchor_matrix", "arrhenius_fit", "global_shifts",
           "master_curve", "pairwise_shifts", "split_sets", "superposition_rms", "wlf_fit"]

#: quantities a shift objective may use: log10 E', log10 E'', log10 tan delta
QUANTITIES = ("E_stor", "E_loss", "tan_delta")
_HUBER = 1.345
_MU_GRID = np.logspace(-3, 4, 29)
#: grid step (decades) of the pairwise scan that starts the solve
SCAN_STEP = 0.01
#: grid step (decades) of the block sweeps
BLOCK_STEP = 0.1
#: block sweeps per pass, and passes (re-estimating smoothing and weights)
MAX_SWEEPS, PASSES = 10, 6
#: convergence: no shift moves by more than this (decades) in a pass
TOL = 1e-3


@dataclass(frozen=True)
class DMASet:
    """One isothermal frequency sweep.

    Attributes
    ----------
    T : float
        Temperature, deg C (mean of the set's T column).
    f, E_stor, E_loss : ndarray
        Frequencies (Hz, ascending) and storage / loss moduli (Pa).
    label : float
        The set's identifier in the raw table (``Set`` column).
    weight : ndarray or None
        Multiplicity of each point (bootstrap); None means 1 for every point.
    """

    T: float
    f: np.ndarray
    E_stor: np.ndarray
    E_loss: np.ndarray
    label: float = 0.0
    weight: np.ndarray | None = None

    def y(self, q: str) -> np.ndarray:
        """log10 of quantity ``q`` (one of :data:`QUANTITIES`)."""
        if q == "E_stor":
            return np.log10(self.E_stor)
        if q == "E_loss":
            return np.log10(self.E_loss)
        if q == "tan_delta":
            return np.log10(self.E_loss / self.E_stor)
        raise ValueError(f"quantity must be one of {QUANTITIES}, got {q!r}")

    @property
    def x(self) -> np.ndarray:
        """log10 f (f in Hz)."""
        return np.log10(self.f)

    @property
    def w(self) -> np.ndarray:
        """Point multiplicities (1 unless resampled)."""
        return np.ones(self.f.size) if self.weight is None else np.asarray(self.weight, float)


def split_sets(raw) -> list[DMASet]:
    """Group a raw multi-temperature table into sets sorted by temperature.

    Parameters
    ----------
    raw : mapping, object with ``.columns``, or list of DMASet
        Columns ``f`` (Hz), ``E_stor``, ``E_loss`` (Pa), ``T`` (deg C), ``Set`` (identifier), e.g.
        ``vcor.fitting.dma.read_table(path).columns``; optional column ``weight`` (point multiplicity).

    Returns
    -------
    list of DMASet
        One per distinct ``Set`` value, sorted by mean temperature.

    Raises
    ------
    ValueError
        Missing columns, non-positive values, fewer than two sets, a set with fewer than three
        distinct frequencies, or two sets at the same temperature.
    """
    if isinstance(raw, list):
        return raw
    c = raw.columns if hasattr(raw, "columns") else raw
    for k in ("f", "E_stor", "E_loss", "T", "Set"):
        if k not in c:
            raise ValueError(f"raw data need columns f, E_stor, E_loss, T, Set; missing {k!r}")
    f, es, el = (np.asarray(c[k], float) for k in ("f", "E_stor", "E_loss"))
    if not (np.all(f > 0) and np.all(es > 0) and np.all(el > 0)):
        raise ValueError("f, E_stor and E_loss must all be > 0")
    sid = np.asarray(c["Set"])
    tt = np.asarray(c["T"], float)
    wt = np.asarray(c["weight"], float) if "weight" in c else None
    out = []
    for s in np.unique(sid):
        m = sid == s
        o = np.argsort(f[m], kind="stable")
        if np.unique(f[m]).size < 3:
            raise ValueError(f"set {s!r} has fewer than three distinct frequencies")
        out.append(DMASet(float(np.mean(tt[m])), f[m][o], es[m][o], el[m][o], float(s),
                          None if wt is None else wt[m][o]))
    out.sort(key=lambda d: d.T)
    if len(out) < 2:
        raise ValueError(f"superposition needs sets at two or more temperatures, got {len(out)}")
    if np.any(np.diff([d.T for d in out]) <= 0):
        raise ValueError("two sets have the same mean temperature")
    return out


def _local(u):
    """First basis index j and the 4 nonzero values (and d/du) of uniform cubic B-splines at u
    (knot units, u in [0, nb - 3])."""
    j = np.floor(u).astype(int)
    t = u - j
    v = np.stack([(1 - t) ** 3, 3 * t**3 - 6 * t**2 + 4, -3 * t**3 + 3 * t**2 + 3 * t + 1, t**3], 1) / 6
    dv = np.stack([-3 * (1 - t) ** 2, 9 * t**2 - 12 * t, -9 * t**2 + 6 * t + 3, 3 * t**2], 1) / 6
    return j, v, dv


class _Lattice:
    """Knots at integer multiples of h; the basis covers the points' range plus one knot."""

    def __init__(self, xr, h):
        self.h = h
        self.i0 = math.floor(float(np.min(xr)) / h) - 1
        self.nb = math.ceil(float(np.max(xr)) / h) + 1 - self.i0 + 3
        self.j, self.v, self.dv = _local(np.asarray(xr) / h - self.i0)
        self.dv = self.dv / h

    def dense(self, deriv=False):
        B = np.zeros((self.j.size, self.nb))
        rows = np.repeat(np.arange(self.j.size), 4)
        B[rows, (self.j[:, None] + np.arange(4)).ravel()] = (self.dv if deriv else self.v).ravel()
        return B

    def gram(self, W):
        """B^T diag(W) B in lower banded storage (4, nb)."""
        ab = np.zeros((4, self.nb))
        for a in range(4):
            wa = W * self.v[:, a]
            for b in range(a + 1):
                ab[a - b] += np.bincount(self.j + b, weights=wa * self.v[:, b], minlength=self.nb)
        return ab

    def rhs(self, W, y):
        wy = W * y
        return sum(np.bincount(self.j + a, weights=wy * self.v[:, a], minlength=self.nb) for a in range(4))

    def penalty(self):
        """D2^T D2 in lower banded storage (4, nb)."""
        n = self.nb
        ab = np.zeros((4, n))
        ab[0] = 6.0
        ab[0, [0, -1]] = 1.0
        ab[0, [1, -2]] = 5.0
        ab[1, : n - 1] = -4.0
        ab[1, [0, n - 2]] = -2.0
        ab[2, : n - 2] = 1.0
        return ab


def _banded_to_dense(ab):
    n = ab.shape[1]
    M = np.zeros((n, n))
    for d in range(ab.shape[0]):
        i = np.arange(n - d)
        M[i + d, i] = ab[d, : n - d]
        M[i, i + d] = ab[d, : n - d]
    return M


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
    return {q: max(math.sqrt(float(np.mean([_quadfit(s.x, s.y(q), s.w)[1] ** 2 for s in sets]))), 1e-4)
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


def pairwise_shifts(sets, quantities=("E_stor",), fallback=("tan_delta", "E_loss"), *, scan_step=0.01,
                    min_overlap=0.5, sigma=None):
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
            inb = (xbs >= lo[:, None] - 1e-12) & (xbs <= hi[:, None] + 1e-12)
            rb = (b.y(q)[None, :] - np.polyval(pa, xbs)) ** 2
            ina = (xa[None, :] >= lo[:, None] - 1e-12) & (xa[None, :] <= hi[:, None] + 1e-12)
            ra = (a.y(q)[None, :] - np.polyval(pb, xa[None, :] - d[:, None])) ** 2
            tot += (np.sum(np.where(inb, rb * b.w, 0), 1) + np.sum(np.where(ina, ra * a.w, 0), 1)) / sigma[q] ** 2
            cnt += np.sum(np.where(inb, b.w, 0), 1) + np.sum(np.where(ina, a.w, 0), 1)
        m = np.where(cnt >= 4, tot / np.maximum(cnt, 1), np.inf)
        i = int(np.argmin(m))
        steps.append(float(d[i]))
        info.append({"T": (a.T, b.T), "quantities": prim + extra, "mismatch": float(m[i]), "scan": (d, m)})
    return np.array(steps), info


class _Problem:
    """Stacked data of all sets per quantity, the step <-> shift map, weights and smoothing."""

    def __init__(self, sets, k_ref, quantities, masks, knots_per_decade):
        self.sets, self.k_ref = sets, k_ref
        self.quantities = tuple(quantities)
        self.h = 1.0 / knots_per_decade
        self.x = np.concatenate([s.x for s in sets])
        self.idx = np.concatenate([np.full(s.f.size, k) for k, s in enumerate(sets)])
        self.mult = np.concatenate([s.w for s in sets])
        self.y = {q: np.concatenate([s.y(q) for s in sets]) for q in quantities}
        self.mask = {q: np.concatenate([np.full(s.f.size, float(masks[q][k])) for k, s in enumerate(sets)])
                     for q in quantities}
        self.omega = {q: np.ones(self.x.size) for q in quantities}
        self.wq = {q: 1.0 for q in quantities}
        self.mu = {q: 1.0 for q in quantities}
        K = len(sets)
        # s = S d: s_k = sum_{j<k} d_j - sum_{j<k_ref} d_j
        S = np.tril(np.ones((K, K - 1)), -1)
        self.S = S - S[k_ref]

    def W(self, q):
        return self.omega[q] * self.mask[q] * self.mult

    def shifts(self, d):
        return self.S @ d

    def fit(self, q, s, mu=None, edf=False):
        """Master spline of quantity q at shifts s: (lattice, c, fitted values, [edf]) minimising
        sum W (y - g)^2 + mu ||D2 c||^2 (the normalised problem, without w_q)."""
        mu = self.mu[q] if mu is None else mu
        lat = _Lattice(self.x + s[self.idx], self.h)
        W = self.W(q)
        G = lat.gram(W)
        M = G + mu * lat.penalty()
        M[0] += 1e-10 * (1.0 + mu)
        c = solveh_banded(M, lat.rhs(W, self.y[q]), lower=True)
        g = np.einsum("ij,ij->i", lat.v, c[lat.j[:, None] + np.arange(4)])
        if not edf:
            return lat, c, g
        return lat, c, g, float(np.trace(solveh_banded(M, _banded_to_dense(G), lower=True)))

    def value(self, d):
        """Phi(s(d)): the minimised weighted objective summed over quantities."""
        s = self.shifts(d)
        tot = 0.0
        for q in self.quantities:
            _lat, c, g = self.fit(q, s)
            W = self.W(q)
            r = self.y[q] - g
            Dc = np.diff(c, 2)
            tot += self.wq[q] * (float(np.sum(W * r * r)) + self.mu[q] * float(Dc @ Dc))
        return tot

    def gcv(self, q, s, grid=None):
        """(mu, rss, edf) minimising GCV(mu) = N RSS / (N - edf)^2 (N = total weight) over ``grid``
        (default 10^-3 .. 10^4, 4 per decade)."""
        grid = _MU_GRID if grid is None else grid
        W = self.W(q)
        N = float(np.sum(W))
        best = None
        for mu in grid:
            _, _, g, edf = self.fit(q, s, mu, edf=True)
            rss = float(np.sum(W * (self.y[q] - g) ** 2))
            v = N * rss / max(N - edf, 1.0) ** 2
            if best is None or v < best[0]:
                best = (v, mu, rss, edf)
        return best[1], best[2], best[3]

    def residual(self, d, jac=False, n_pen=None):
        r"""Stacked residuals :math:`\sqrt{w_q}\,[\sqrt{W}(y - Bc);\ -\sqrt{\mu} D_2 c]` over quantities
        and (optionally) their exact variable-projection Jacobian with respect to the steps d.

        With :math:`A = [\sqrt{W}B; \sqrt{\mu}D_2]`, :math:`M = A^\top A` (banded) and
        :math:`c = M^{-1}A^\top \bar y`, the derivative with respect to shift :math:`s_k` is
        (Golub & Pereyra) :math:`-\big(v_k - A M^{-1}(A^\top v_k - u_k)\big)` where
        :math:`v_k = (\partial A/\partial s_k)\,c` (set k's rows: :math:`\sqrt{W}g'`) and
        :math:`u_k = (\partial A/\partial s_k)^\top r`; everything is banded or sparse."""
        s = self.shifts(d)
        lat = _Lattice(self.x + s[self.idx], self.h)
        K = len(self.sets)
        cols = lat.j[:, None] + np.arange(4)
        res, jacs = [], []
        for q in self.quantities:
            W = self.W(q)
            sw = np.sqrt(W)
            M = lat.gram(W) + self.mu[q] * lat.penalty()
            M[0] += 1e-10 * (1.0 + self.mu[q])
            c = solveh_banded(M, lat.rhs(W, self.y[q]), lower=True)
            g = np.einsum("ij,ij->i", lat.v, c[cols])
            rd = sw * (self.y[q] - g)
            smu = math.sqrt(self.mu[q])
            npen = lat.nb - 2 if n_pen is None else n_pen
            if npen < lat.nb - 2:
                raise ValueError("n_pen too small for the lattice")
            r = np.concatenate([rd, -smu * np.diff(c, 2), np.zeros(npen - lat.nb + 2)])
            sq = math.sqrt(self.wq[q])
            res.append(sq * r)
            if not jac:
                continue
            gp = np.einsum("ij,ij->i", lat.dv, c[cols])
            vk = sw * gp                                   # v_k on set k's rows
            AtV = np.zeros((lat.nb, K))
            U = np.zeros((lat.nb, K))
            for a in range(4):
                np.add.at(AtV, (lat.j + a, self.idx), sw * vk * lat.v[:, a])
                np.add.at(U, (lat.j + a, self.idx), lat.dv[:, a] * sw * rd)
            Z = solveh_banded(M, AtV - U, lower=True)
            BZ = np.einsum("ia,iak->ik", lat.v, Z[cols])
            V = np.zeros((self.x.size, K))
            V[np.arange(self.x.size), self.idx] = vk
            Js = np.vstack([sw[:, None] * BZ - V, smu * np.diff(Z, 2, axis=0), np.zeros((npen - lat.nb + 2, K))])
            Js[:, self.k_ref] = 0.0
            jacs.append(sq * (Js @ self.S))
        return np.concatenate(res), (np.vstack(jacs) if jac else None)


def superposition_rms(raw, log_aT, quantities=("E_stor",), knots_per_decade=3.0, mu=None):
    """How well given shift factors superpose the sets: per quantity, the rms (log10 units) of the
    residuals about one P-spline master curve through all sets (mu by GCV unless given), e.g. to
    compare shift sets from different tools.

    Parameters
    ----------
    raw : mapping, object with ``.columns`` or list of DMASet
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
    pr = _Problem(sets, 0, quantities, {q: np.ones(K) for q in quantities}, knots_per_decade)
    s = np.asarray(log_aT, float) - float(log_aT[0])
    rms = {}
    for q in quantities:
        pr.mu[q] = pr.gcv(q, s)[0] if mu is None else mu
        _, _, g = pr.fit(q, s)
        rms[q] = float(np.sqrt(np.average((pr.y[q] - g) ** 2, weights=pr.mult)))
    return rms


@dataclass
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


def global_shifts(raw, T_ref, quantities=("E_stor",), fallback=("tan_delta", "E_loss"), *, start=None,
                  knots_per_decade=3.0, robust=False, min_overlap=0.5, mu=None) -> ShiftResult:
    r"""Start-free shift factors of all sets at once (module docstring).

    Parameters
    ----------
    raw : mapping, object with ``.columns``, or list of DMASet
        Raw sets (:func:`split_sets`).
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
    scan_step, block_step, max_sweeps, passes, tol = SCAN_STEP, BLOCK_STEP, MAX_SWEEPS, PASSES, TOL
    sets = split_sets(raw)
    K = len(sets)
    for q in tuple(quantities) + tuple(fallback):
        if q not in QUANTITIES:
            raise ValueError(f"quantities must be from {QUANTITIES}, got {q!r}")
    T = np.array([s.T for s in sets])
    k_ref = int(np.argmin(np.abs(T - T_ref)))
    sigma0 = _noise(sets, tuple(quantities) + tuple(fallback))
    steps0, info = pairwise_shifts(sets, quantities, fallback, scan_step=scan_step, min_overlap=min_overlap,
                                   sigma=sigma0)
    used = list(quantities) + [q for q in fallback if any(q in p["quantities"] for p in info)]
    masks = {q: np.ones(K, bool) if q in quantities else np.zeros(K, bool) for q in used}
    for k, p in enumerate(info):
        for q in p["quantities"]:
            masks[q][k] = masks[q][k + 1] = True
    bounds = np.array([_step_bounds(sets[k], sets[k + 1], min_overlap) for k in range(K - 1)])
    lb, ub = bounds[:, 0], bounds[:, 1]
    pr0 = _Problem(sets, k_ref, used, masks, knots_per_decade)
    # largest reduced span any admissible steps can give: fixes the residual length of the polish
    s_lo, s_hi = pr0.S.clip(max=0) @ ub + pr0.S.clip(min=0) @ lb, pr0.S.clip(min=0) @ ub + pr0.S.clip(max=0) @ lb
    span = (max(st.x.max() + hi_ for st, hi_ in zip(sets, s_hi, strict=True))
            - min(st.x.min() + lo_ for st, lo_ in zip(sets, s_lo, strict=True)))
    n_pen = math.ceil(span * knots_per_decade) + 8
    stats = {"n_eval": 0, "sweeps": 0}

    def refine(d):
        """Passes of (re-estimate mu, w, omega; block sweeps; polish) from steps d."""
        pr = _Problem(sets, k_ref, used, masks, knots_per_decade)
        d = d.copy()
        notes = []
        prev_mu, moved_pass = None, math.inf
        for p in range(passes + 1):
            # the first estimate of smoothing and noise is made at the data-derived start even when
            # another start is given: at a wrong arrangement GCV picks a stiff, nearly straight master
            # curve whose best arrangement is the wrong one
            s = pr.shifts(d if p > 0 else steps0)
            for q in used:
                pr.omega[q] = np.ones(pr.x.size)
                if mu is not None and q in mu:
                    pr.mu[q] = float(mu[q])
                    _, _, g, edf = pr.fit(q, s, edf=True)
                    rss = float(np.sum(pr.W(q) * (pr.y[q] - g) ** 2))
                else:
                    pr.mu[q], rss, edf = pr.gcv(q, s)
                var = rss / max(float(np.sum(pr.W(q))) - edf, 1.0)
                pr.wq[q] = 1.0 / max(var, 1e-14)
                if robust:
                    _, _, g = pr.fit(q, s)
                    a = np.abs(pr.y[q] - g) / math.sqrt(var)
                    pr.omega[q] = np.where(a <= _HUBER, 1.0, _HUBER / np.maximum(a, 1e-12))
            if p > 0 and moved_pass < tol and dict(pr.mu) == prev_mu:
                break   # converged: smoothing unchanged and the last pass moved nothing
            if p == passes:
                notes.append(f"not converged in {passes} passes (last pass moved {moved_pass:.3g} decades)")
                break
            prev_mu = dict(pr.mu)
            d_pass = d.copy()
            # block sweeps: each step globally over its admissible interval, the rest rigid
            for _ in range(max_sweeps):
                stats["sweeps"] += 1
                moved = 0.0
                for k in range(K - 1):
                    grid = np.arange(lb[k], ub[k] + block_step / 2, block_step)
                    trial = np.repeat(d[None, :], grid.size, 0)
                    trial[:, k] = grid
                    vals = np.array([pr.value(t) for t in trial])
                    stats["n_eval"] += grid.size
                    i = int(np.argmin(vals))
                    a_, b_ = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]

                    def f1(z, k=k):
                        t = d.copy()
                        t[k] = z
                        return pr.value(t)

                    cur = pr.value(d)
                    r1 = minimize_scalar(f1, bounds=(a_, b_), method="bounded", options={"xatol": 1e-4})
                    stats["n_eval"] += r1.nfev + 1
                    if r1.fun < cur - 1e-12:
                        moved = max(moved, abs(r1.x - d[k]))
                        d[k] = r1.x
                if moved <= block_step:
                    break
            sol = least_squares(lambda z: pr.residual(z, n_pen=n_pen)[0], d,
                                jac=lambda z: pr.residual(z, True, n_pen)[1],
                                bounds=(lb, ub), method="trf", xtol=1e-10, ftol=1e-12, gtol=1e-10, max_nfev=100)
            stats["n_eval"] += sol.nfev
            d = sol.x
            moved_pass = float(np.max(np.abs(pr.shifts(d) - pr.shifts(d_pass))))
        return pr, d, notes

    candidates = []
    if start is None:
        pr, d, notes = refine(steps0)
    else:
        # a given start is one more candidate: the result is the lower objective of the refinements
        # from it and from the data-derived start (both judged with the latter's weights)
        pr_s, d_s, notes_s = refine(np.clip(np.diff(np.asarray(start, float)), lb, ub))
        pr, d, notes = refine(steps0)
        v_s, v_0 = pr.value(d_s), pr.value(d)
        candidates = [{"start": "given", "objective": v_s, "log_aT": anchor_matrix(T, T_ref) @ pr.shifts(d_s)},
                      {"start": "data-derived", "objective": v_0, "log_aT": anchor_matrix(T, T_ref) @ pr.shifts(d)}]
        if v_s <= v_0 * (1 + 1e-9):
            pr, d, notes = pr_s, d_s, notes_s
        else:
            notes.append(f"the given start led to a worse minimum (objective {v_s:.6g} against {v_0:.6g}); "
                         f"the data-derived start's solution is returned")
    n_eval, sweeps_total = stats["n_eval"], stats["sweeps"]
    at_bound = np.flatnonzero(np.isclose(d, lb, atol=1e-6) | np.isclose(d, ub, atol=1e-6))
    for k in at_bound:
        notes.append(f"the step between {T[k]:.4g} and {T[k + 1]:.4g} deg C sits at the minimum overlap "
                     f"({min_overlap} decades): these sets do not superpose; the shift is a bound, not a fit")
    s = pr.shifts(d)
    r, J = pr.residual(d, jac=True)
    n_data = sum(float(np.sum(pr.W(q) > 0)) for q in used)
    edf = sum(pr.fit(q, s, edf=True)[3] for q in used)
    s2 = float(np.sum(r**2)) / max(n_data - edf - (K - 1), 1.0)
    cov_d = s2 * np.linalg.pinv(J.T @ J)
    A = anchor_matrix(T, T_ref)
    log_aT = A @ s
    cov = A @ pr.S @ cov_d @ pr.S.T @ A.T
    sig, set_rms = {}, {}
    for q in used:
        _, _, g = pr.fit(q, s)
        res = pr.y[q] - g
        m = pr.mask[q] > 0
        sig[q] = float(np.sqrt(np.average(res[m] ** 2, weights=pr.mult[m])))
        set_rms[q] = np.array([math.sqrt(float(np.average(res[pr.idx == k] ** 2, weights=pr.mult[pr.idx == k])))
                               for k in range(K)])
    start_s = pr.shifts(steps0)
    return ShiftResult(T, log_aT, np.sqrt(np.maximum(np.diag(cov), 0.0)), float(T_ref), masks, sig, set_rms,
                       A @ start_s, dict(pr.mu), float(pr.value(d)), sweeps_total, int(n_eval),
                       time.perf_counter() - t0, cov, notes, info, candidates)


@dataclass
class MasterCurve:
    """Superposed data at T_ref, sorted by reduced frequency.

    Attributes
    ----------
    f_red : ndarray
        Reduced frequency f a_T, Hz.
    E_stor, E_loss : ndarray
        Storage and loss moduli, Pa.
    T_point : ndarray
        Temperature of each point's set, deg C.
    set_index : ndarray
        Index (in :func:`split_sets` order) of each point's set.
    weight : ndarray
        Point multiplicities.
    """

    f_red: np.ndarray
    E_stor: np.ndarray
    E_loss: np.ndarray
    T_point: np.ndarray
    set_index: np.ndarray
    weight: np.ndarray


def master_curve(raw, log_aT) -> MasterCurve:
    """Apply shift factors: f_red = f 10^log_aT per set (``log_aT`` in :func:`split_sets` order,
    i.e. ascending temperature, decades)."""
    sets = split_sets(raw)
    log_aT = np.asarray(log_aT, float)
    if log_aT.size != len(sets):
        raise ValueError(f"need {len(sets)} shift factors, got {log_aT.size}")
    fr = np.concatenate([s.f * 10.0**a for s, a in zip(sets, log_aT)])
    es = np.concatenate([s.E_stor for s in sets])
    el = np.concatenate([s.E_loss for s in sets])
    tp = np.concatenate([np.full(s.f.size, s.T) for s in sets])
    ix = np.concatenate([np.full(s.f.size, k) for k, s in enumerate(sets)])
    w = np.concatenate([s.w for s in sets])
    o = np.argsort(fr, kind="stable")
    return MasterCurve(fr[o], es[o], el[o], tp[o], ix[o], w[o])


def wlf_fit(T, log_aT, T_ref, sigma=None):
    r"""Least-squares WLF constants through per-set shifts (several starts, best kept).

    Parameters
    ----------
    T, log_aT : array_like
        Temperatures (deg C) and log10 a_T.
    T_ref : float
        Reference temperature, deg C (the WLF curve is 0 there).
    sigma : array_like, optional
        Standard errors of log_aT: weights 1/sigma^2, sigma floored at 0.01 decade.

    Returns
    -------
    dict
        ``C1`` (-), ``C2`` (K), ``C1_std``, ``C2_std`` (linearised), ``residual`` (decades, fit - data)
        and its ``rms``.
    """
    T, y = np.asarray(T, float), np.asarray(log_aT, float)
    dT = T - T_ref
    w = np.ones_like(y) if sigma is None else 1.0 / np.maximum(np.asarray(sigma, float), 0.01)
    lo = max(1e-3, -dT.min() + 1e-3)

    def res(p):
        return (wlf_log_aT(T, T_ref, p[0], p[1]) - y) * w

    best = None
    for c2 in (51.6, 101.6, 300.0, 1000.0):
        for c1 in (8.86, 17.44, 40.0):
            fit = least_squares(res, x0=[c1, max(c2, 2 * lo)], bounds=([0.0, lo], [1e4, 1e5]), method="trf")
            if best is None or fit.cost < best.cost:
                best = fit
    dof = max(y.size - 2, 1)
    cov = np.linalg.pinv(best.jac.T @ best.jac) * (2 * best.cost / dof)
    r = wlf_log_aT(T, T_ref, *best.x) - y
    return {"C1": float(best.x[0]), "C2": float(best.x[1]), "C1_std": float(math.sqrt(max(cov[0, 0], 0))),
            "C2_std": float(math.sqrt(max(cov[1, 1], 0))), "residual": r, "rms": float(np.sqrt(np.mean(r**2)))}


def arrhenius_fit(T, log_aT, T_ref, sigma=None):
    r"""Arrhenius: :math:`\log_{10} a_T = \frac{E_a}{R \ln 10}\left(\frac1T - \frac1{T_\mathrm{ref}}\right)`
    (T in K inside), weighted least squares through the origin.

    Returns
    -------
    dict
        ``E_a`` (J/mol), ``E_a_std``, ``residual`` (decades, fit - data), ``rms``.
    """
    x = 1.0 / (np.asarray(T, float) + 273.15) - 1.0 / (T_ref + 273.15)
    y = np.asarray(log_aT, float)
    w = np.ones_like(y) if sigma is None else 1.0 / np.maximum(np.asarray(sigma, float), 0.01) ** 2
    slope = float(np.sum(w * x * y) / np.sum(w * x * x))
    r = slope * x - y
    se = math.sqrt(float(np.sum(w * r**2)) / max(y.size - 1, 1) / float(np.sum(w * x * x)))
    k = GAS_CONSTANT * math.log(10.0)
    return {"E_a": slope * k, "E_a_std": se * k, "residual": r, "rms": float(np.sqrt(np.mean(r**2)))}
