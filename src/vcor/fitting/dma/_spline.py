r"""The P-spline objective of the start-free shifts: one penalised cubic B-spline master curve per
quantity through all sets at trial shifts, its value, its GCV smoothing and its exact
variable-projection residual and Jacobian (:mod:`vcor.fitting.dma.shifts`)."""

from __future__ import annotations

import math

import numpy as np
from scipy.linalg import solveh_banded

__all__ = ["MU_GRID", "Lattice", "SplineObjective", "step_matrix"]

#: candidates of the smoothing parameter mu of a master spline (GCV), 4 per decade
MU_GRID = np.logspace(-3, 4, 29)
#: ridge (times 1 + mu) on the first spline coefficient: the banded system stays positive definite
#: where no point informs the first basis function
RIDGE = 1e-10


def step_matrix(K, k_ref):
    """Matrix S with shifts s = S d from the K-1 steps d_k = s_{k+1} - s_k, set ``k_ref`` held at 0."""
    S = np.tril(np.ones((K, K - 1)), -1)
    return S - S[k_ref]


def _local(u):
    """First basis index j and the 4 nonzero values (and d/du) of uniform cubic B-splines at u
    (knot units, u in [0, nb - 3])."""
    j = np.floor(u).astype(int)
    t = u - j
    v = np.stack([(1 - t) ** 3, 3 * t**3 - 6 * t**2 + 4, -3 * t**3 + 3 * t**2 + 3 * t + 1, t**3], 1) / 6
    dv = np.stack([-3 * (1 - t) ** 2, 9 * t**2 - 12 * t, -9 * t**2 + 6 * t + 3, 3 * t**2], 1) / 6
    return j, v, dv


class Lattice:
    """Knots at integer multiples of h; the basis covers the points' range plus one knot."""

    def __init__(self, xr, h):
        self.h = h
        self.i0 = math.floor(float(np.min(xr)) / h) - 1
        self.nb = math.ceil(float(np.max(xr)) / h) + 1 - self.i0 + 3
        self.j, self.v, self.dv = _local(np.asarray(xr) / h - self.i0)
        self.dv = self.dv / h
        self.cols = self.j[:, None] + np.arange(4)

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

    def solve(self, W, y, mu):
        """The penalised fit: (M = gram + mu penalty [banded], gram, coefficients c, fitted values g)."""
        G = self.gram(W)
        M = G + mu * self.penalty()
        M[0] += RIDGE * (1.0 + mu)
        c = solveh_banded(M, self.rhs(W, y), lower=True)
        return M, G, c, np.einsum("ij,ij->i", self.v, c[self.cols])


def _banded_to_dense(ab):
    n = ab.shape[1]
    M = np.zeros((n, n))
    for d in range(ab.shape[0]):
        i = np.arange(n - d)
        M[i + d, i] = ab[d, : n - d]
        M[i, i + d] = ab[d, : n - d]
    return M


class SplineObjective:
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
        self.wq = dict.fromkeys(quantities, 1.0)
        self.mu = dict.fromkeys(quantities, 1.0)
        # s = S d: s_k = sum_{j<k} d_j - sum_{j<k_ref} d_j
        self.S = step_matrix(len(sets), k_ref)

    def W(self, q):
        return self.omega[q] * self.mask[q] * self.mult

    def shifts(self, d):
        return self.S @ d

    def fit(self, q, s, mu=None, edf=False):
        """Master spline of quantity q at shifts s: (lattice, c, fitted values, [edf]) minimising
        sum W (y - g)^2 + mu ||D2 c||^2 (the normalised problem, without w_q)."""
        mu = self.mu[q] if mu is None else mu
        lat = Lattice(self.x + s[self.idx], self.h)
        M, G, c, g = lat.solve(self.W(q), self.y[q], mu)
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
        (default :data:`MU_GRID`)."""
        grid = MU_GRID if grid is None else grid
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

    def _jacobian(self, lat, q, M, c, rd):
        """Variable-projection Jacobian of quantity q's rows with respect to the shifts (residual docstring)."""
        K = len(self.sets)
        sw = np.sqrt(self.W(q))
        vk = sw * np.einsum("ij,ij->i", lat.dv, c[lat.cols])     # v_k on set k's rows
        AtV = np.zeros((lat.nb, K))
        U = np.zeros((lat.nb, K))
        for a in range(4):
            np.add.at(AtV, (lat.j + a, self.idx), sw * vk * lat.v[:, a])
            np.add.at(U, (lat.j + a, self.idx), lat.dv[:, a] * sw * rd)
        Z = solveh_banded(M, AtV - U, lower=True)
        BZ = np.einsum("ia,iak->ik", lat.v, Z[lat.cols])
        V = np.zeros((self.x.size, K))
        V[np.arange(self.x.size), self.idx] = vk
        return sw[:, None] * BZ - V, math.sqrt(self.mu[q]) * np.diff(Z, 2, axis=0)

    def residual(self, d, jac=False, n_pen=None):
        r"""Stacked residuals :math:`\sqrt{w_q}\,[\sqrt{W}(y - Bc);\ -\sqrt{\mu} D_2 c]` over quantities
        and (optionally) their exact variable-projection Jacobian with respect to the steps d.

        With :math:`A = [\sqrt{W}B; \sqrt{\mu}D_2]`, :math:`M = A^\top A` (banded) and
        :math:`c = M^{-1}A^\top \bar y`, the derivative with respect to shift :math:`s_k` is
        (Golub & Pereyra) :math:`-\big(v_k - A M^{-1}(A^\top v_k - u_k)\big)` where
        :math:`v_k = (\partial A/\partial s_k)\,c` (set k's rows: :math:`\sqrt{W}g'`) and
        :math:`u_k = (\partial A/\partial s_k)^\top r`; everything is banded or sparse.  ``n_pen`` pads
        the penalty rows to a fixed count (a residual vector of fixed length while the lattice moves)."""
        s = self.shifts(d)
        lat = Lattice(self.x + s[self.idx], self.h)
        npen = lat.nb - 2 if n_pen is None else n_pen
        if npen < lat.nb - 2:
            raise ValueError("n_pen too small for the lattice")
        pad = npen - lat.nb + 2
        res, jacs = [], []
        for q in self.quantities:
            M, _, c, g = lat.solve(self.W(q), self.y[q], self.mu[q])
            rd = np.sqrt(self.W(q)) * (self.y[q] - g)
            sq = math.sqrt(self.wq[q])
            res.append(sq * np.concatenate([rd, -math.sqrt(self.mu[q]) * np.diff(c, 2), np.zeros(pad)]))
            if jac:
                Jd, Jp = self._jacobian(lat, q, M, c, rd)
                Js = np.vstack([Jd, Jp, np.zeros((pad, len(self.sets)))])
                Js[:, self.k_ref] = 0.0
                jacs.append(sq * (Js @ self.S))
        return np.concatenate(res), (np.vstack(jacs) if jac else None)
