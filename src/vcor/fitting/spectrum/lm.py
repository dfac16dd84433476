r"""Levenberg-Marquardt, projected onto a box: the solver of the smooth and the joint spectrum fits."""

from __future__ import annotations

import math

import numpy as np
from scipy.linalg import cho_factor, cho_solve

__all__ = ["levenberg_marquardt"]

#: damping nu of the first step; it falls 3x after a success and rises 10x after a failure
NU_START = 1e-3
#: smallest damping: the step stays a (regularised) Gauss-Newton step
NU_MIN = 1e-12
#: relative ridge added to the Gauss-Newton matrix to tell its predicted decrease where it is singular
RIDGE = 1e-12
#: below this predicted decrease the cost is zero to rounding (Pa-free: the residuals are relative)
TINY = 1e-24
#: a variable this close to its bound counts as on it (the active set)
AT_BOUND = 1e-12


def _active(x, g, lo, hi):
    """Variables held at a bound by the gradient (it points out of the box there)."""
    return ((x <= lo + AT_BOUND) & (g > 0)) | ((x >= hi - AT_BOUND) & (g < 0))


def _predicted(A, g, dA):
    """The decrease a full Gauss-Newton step predicts, g^T A^-1 g (inf where A is not positive definite)."""
    try:
        return float(g @ cho_solve(cho_factor(A + RIDGE * np.diag(dA)), g))
    except np.linalg.LinAlgError:
        return math.inf


def _damped_step(cost, x, c, A, g, dA, nu, box, nu_max):
    """Raise the damping nu until a step does not raise the cost: (x, r, c, nu), or None above ``nu_max``."""
    lo, hi = box
    while True:
        try:
            step = -cho_solve(cho_factor(A + nu * np.diag(dA)), g)
        except np.linalg.LinAlgError:
            nu *= 10
            continue
        xn = x + step if lo is None else np.clip(x + step, lo, hi)
        cn, rn = cost(xn)
        if np.isfinite(cn) and cn <= c:
            return xn, rn, cn, nu
        nu *= 10
        if nu > nu_max:
            return None


def levenberg_marquardt(cost, normal, x0, *, lo=None, hi=None, max_iter=300, tol=1e-10, nu_max=1e14):
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
    nu = NU_START
    for it in range(1, max_iter + 1):
        A, g = normal(x, r)
        if lo is not None:
            act = _active(x, g, lo, hi)
            if act.any():
                A[act, :], A[:, act], g[act] = 0.0, 0.0, 0.0
                A[act, act] = 1.0
        dA = np.diag(A).copy()
        dA[dA <= 0] = 1.0
        if _predicted(A, g, dA) <= tol * c + TINY:
            return x, it - 1, True
        accepted = _damped_step(cost, x, c, A, g, dA, nu, (lo, hi), nu_max)
        if accepted is None:
            return x, it, False
        x, r, c, nu = accepted
        nu = max(nu / 3, NU_MIN)
    return x, max_iter, False
