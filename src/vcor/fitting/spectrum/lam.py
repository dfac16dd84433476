r"""The choice of the regularisation parameter :math:`\lambda` of a smooth spectrum fit.

A scan of :data:`LAM_GRID` from large to small values, each solve warm-started from the previous one
(pyReSpect does the same), so every solve starts near its solution; then, by ``lam``:

* ``"gcv1se"`` (default): the *largest* :math:`\lambda` whose generalised cross-validation score
  :math:`\mathrm{GCV}(\lambda) = N\lVert r\rVert^2 / (N - \gamma\,\mathrm{tr}A_\lambda)^2` is within one
  standard error of the minimum, :math:`\mathrm{GCV} \le \mathrm{GCV}_\min (1 + \sqrt{2/(N - \mathrm{tr}A)})`
  (GCV estimates the residual variance, whose relative standard deviation is :math:`\sqrt{2/\mathrm{dof}}`),
  found by bisection in :math:`\log\lambda` (Hastie, Tibshirani & Friedman, sec. 7.10);
* ``"gcv"``: the minimiser, refined by a parabola in :math:`\log\lambda`;
* ``"lcurve"``: the point of largest curvature of :math:`(\log\lVert r\rVert, \log\lVert LH\rVert)`;
* a number: that :math:`\lambda`, reached by continuation down the grid unless a warm start is given.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["BISECTIONS", "GCV_GAMMA", "LAM_CHOICES", "LAM_GRID", "choose_lambda", "gcv_score"]

#: candidates of the regularisation parameter lambda, scanned from large to small
LAM_GRID = np.logspace(5, -5, 21)
#: GCV inflation gamma of the effective degrees of freedom, (N - gamma tr A)^2 (1: plain GCV; Kim & Gu
#: 2004 and mgcv suggest 1.4 against undersmoothing, which the one-standard-error rule already guards against)
GCV_GAMMA = 1.0
#: bisections of log lambda on the one-standard-error threshold: the grid's half decade to 1/64 of it
BISECTIONS = 5
#: the ways of choosing lambda by name (module docstring)
LAM_CHOICES = ("gcv1se", "gcv", "lcurve")


def gcv_score(N, rho, edf):
    """GCV = N rho^2 / (N - gamma edf)^2 (rho the data residual norm, edf the effective dof)."""
    return N * rho**2 / max(N - GCV_GAMMA * edf, 1.0) ** 2


def _scan(problem, th):
    """Solve at every lambda of :data:`LAM_GRID` from large to small (warm starts): the scan table and
    the solutions."""
    sols, rows = [], []
    for lm in LAM_GRID:
        th, it, ok = problem.solve(th, lm)
        rho, eta, edf, N = problem.diagnostics(th, lm)
        rows.append((lm, gcv_score(N, rho, edf), rho, eta, edf, it, ok))
        sols.append(th.copy())
    keys = ("lam", "gcv", "rho", "eta", "edf", "iterations", "converged")
    return {k: np.array([r[i] for r in rows]) for i, k in enumerate(keys)}, sols


def _lcurve_corner(scan):
    """Index of the largest curvature of the L-curve (interior points only)."""
    x, y = np.log(scan["rho"]), np.log(np.maximum(scan["eta"], 1e-300))
    s = np.log(scan["lam"])
    dx, dy = np.gradient(x, s), np.gradient(y, s)
    ddx, ddy = np.gradient(dx, s), np.gradient(dy, s)
    kappa = (dx * ddy - dy * ddx) / np.maximum((dx**2 + dy**2) ** 1.5, 1e-300)
    return int(np.argmax(np.abs(kappa[1:-1]))) + 1


def _parabola(problem, scan, i, th):
    """The GCV minimiser refined by a parabola through (log lam, log GCV) at i-1, i, i+1: (lam, theta)."""
    L, G = scan["lam"], scan["gcv"]
    xs, ys = np.log(L[i - 1:i + 2]), np.log(G[i - 1:i + 2])
    a, b, _ = np.polyfit(xs, ys, 2)
    if a > 0:
        lam_ref = float(np.exp(np.clip(-b / (2 * a), xs.min(), xs.max())))
        th_ref, _, ok = problem.solve(th, lam_ref)
        if ok:
            return lam_ref, th_ref
    return float(L[i]), th


def _one_se(problem, scan, sols, i, N):
    """The smoothest lambda whose GCV is within one standard error of the minimum at i: (lam, theta)."""
    L, gcv = scan["lam"], scan["gcv"]
    thr = gcv[i] * (1 + math.sqrt(2.0 / max(N - scan["edf"][i], 1.0)))
    j = int(np.flatnonzero(gcv <= thr)[0])        # grid descends: first = largest lam
    if j == 0:
        return float(L[j]), sols[j]
    # bisect log lam on the threshold crossing between L[j-1] (above) and L[j] (below)
    a_, b_, th_b = math.log(L[j - 1]), math.log(L[j]), sols[j]
    for _ in range(BISECTIONS):
        mid = 0.5 * (a_ + b_)
        th_m, _, _ = problem.solve(th_b, math.exp(mid))
        rho, _, edf, n_ = problem.diagnostics(th_m, math.exp(mid))
        if gcv_score(n_, rho, edf) <= thr:
            b_, th_b = mid, th_m
        else:
            a_ = mid
    return math.exp(b_), th_b


def _edge_note(lam: str, value: float, largest: bool) -> str:
    """The fit's note when ``lam`` chose an end of LAM_GRID (``value``; the ``largest`` or the smallest):
    what it says of the data. The fit stands at that lambda; an end of the grid's ten decades means data that
    ask for more smoothing than its largest value (very noisy) or less than its smallest (noise-free, e.g.
    synthetic)."""
    scanned = f"{LAM_GRID[0]:.0e}..{LAM_GRID[-1]:.0e}"
    if largest:
        return (f"lambda by {lam}: {value:.3g}, the largest of the scanned {scanned}: the data ask for at least "
                f"this much smoothing (very noisy data?); the fit is the smoothest of the scan")
    return (f"lambda by {lam}: {value:.3g}, the smallest of the scanned {scanned}: the data ask for no more "
            f"smoothing than this (noise-free data, e.g. synthetic); the fit follows them that closely")


def _by_name(problem, th, lam, notes):
    """(lam, theta, scan) for a lambda chosen by name (module docstring)."""
    scan, sols = _scan(problem, th)
    L = scan["lam"]
    N = problem.data_residual(sols[-1]).size
    i = _lcurve_corner(scan) if lam == "lcurve" else int(np.argmin(scan["gcv"]))
    if i in (0, L.size - 1):
        notes.append(_edge_note(lam, float(L[i]), i == 0))
    lam_used, th = float(L[i]), sols[i]
    if lam == "gcv" and 0 < i < L.size - 1:
        lam_used, th = _parabola(problem, scan, i, th)
    elif lam == "gcv1se":
        lam_used, th = _one_se(problem, scan, sols, i, N)
    return lam_used, th, scan


def choose_lambda(problem, th, lam, *, warm=False):
    """Solve ``problem`` (:class:`vcor.fitting.spectrum.smooth.SmoothProblem`) from ``th`` with lambda
    chosen by ``lam`` (module docstring); ``warm``: ``th`` is a warm start (a given lam is solved directly).

    Returns
    -------
    (lam, theta, scan, method, notes)
        The lambda used, the solution, the scan table (empty for a given lam), ``lam`` or "given", notes.
    """
    notes = []
    if isinstance(lam, str):
        if lam not in LAM_CHOICES:
            raise ValueError(f"lam must be 'gcv1se', 'gcv', 'lcurve' or a number, got {lam!r}")
        lam_used, th, scan = _by_name(problem, th, lam, notes)
        return lam_used, th, scan, lam, notes
    lam_used = float(lam)
    if not warm:
        # continuation down to the given lam
        for lm in LAM_GRID[LAM_GRID > lam_used]:  # noqa: SIM300 (the NumPy mask idiom a[a > x])
            th, _, _ = problem.solve(th, lm)
    th, _, ok = problem.solve(th, lam_used)
    if not ok:
        notes.append("the solve at the given lam did not converge")
    return lam_used, th, {}, "given", notes
