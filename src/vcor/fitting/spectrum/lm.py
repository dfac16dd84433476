r"""Levenberg-Marquardt, projected onto a box: the solver of the smooth and the joint spectrum fits.

With geodesic acceleration (Transtrum & Sethna 2012, "Improvements to the Levenberg-Marquardt algorithm
for nonlinear least-squares minimization", arXiv:1201.5885) each step adds to the Levenberg-Marquardt
velocity :math:`v` half a second-order correction :math:`a` along the curvature of the residual: in a
long curved valley (the joint DMA fit's shifts against its spectrum) plain steps zig-zag across the
valley floor and the damping stays high, while the corrected step follows the valley.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.linalg import cho_factor, cho_solve

__all__ = ["GEODESIC_ALPHA", "GEODESIC_H", "curvature_gradient", "levenberg_marquardt"]

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
#: finite-difference step along the velocity, as a fraction of it, of the residual's second directional
#: derivative: the value Transtrum & Sethna use (arXiv:1201.5885); the difference only needs the
#: acceleration's direction and rough size, and a step that large stays clear of rounding
GEODESIC_H = 0.1
#: largest ratio ``2 |a| / |v|`` of the acceleration to the velocity for which the accelerated step v + a/2 is
#: taken (else the plain step v): the second-order correction must stay small for the expansion to hold;
#: Transtrum & Sethna take alpha below 1 and use 0.75 (arXiv:1201.5885)
GEODESIC_ALPHA = 0.75


def _active(x, g, lo, hi):
    """Variables held at a bound by the gradient (it points out of the box there)."""
    return ((x <= lo + AT_BOUND) & (g > 0)) | ((x >= hi - AT_BOUND) & (g < 0))


def _predicted(A, g, dA):
    """The decrease a full Gauss-Newton step predicts, g^T A^-1 g (inf where A is not positive definite)."""
    try:
        return float(g @ cho_solve(cho_factor(A + RIDGE * np.diag(dA)), g))
    except np.linalg.LinAlgError:
        return math.inf


def curvature_gradient(value, J, x, r, v, *, lo=None, hi=None, h=GEODESIC_H):
    r"""The right-hand side :math:`J^\top r_{vv}` of the geodesic acceleration at x along the velocity v.

    The second directional derivative of the residual along v by a finite difference of step h
    (Transtrum & Sethna 2012, arXiv:1201.5885):

    .. math:: r_{vv} \approx \frac{2}{h}\Big(\frac{r(x + h v) - r(x)}{h} - J v\Big),

    the point :math:`x + h v` clipped to the box lo <= x <= hi when given (the residual need not exist
    outside it).  One residual evaluation, no Jacobian: the acceleration costs a fraction of a step.

    Parameters
    ----------
    value : callable
        ``value(x)``: the residual vector at x.
    J : ndarray
        The residual's Jacobian at x (rows: residuals, columns: variables).
    x, r, v : ndarray
        The point, the residual there (``value(x)``) and the velocity (the Levenberg-Marquardt step).
    lo, hi : ndarray, optional
        Bounds of x.
    h : float
        Finite-difference step as a fraction of v (default :data:`GEODESIC_H`).

    Returns
    -------
    ndarray
        :math:`J^\top r_{vv}`, one entry per variable.
    """
    xh = x + h * v if lo is None else np.clip(x + h * v, lo, hi)
    rvv = (2.0 / h) * ((value(xh) - r) / h - J @ v)
    return J.T @ rvv


def _step(F, g, accel):
    """The Levenberg-Marquardt velocity v of the factored damped matrix F, plus half its geodesic
    acceleration a when ``accel`` (v -> J^T r_vv) is given and ``2 |a| / |v|`` <= :data:`GEODESIC_ALPHA`."""
    v = -cho_solve(F, g)
    if accel is None:
        return v
    a = -cho_solve(F, accel(v))
    if np.all(np.isfinite(a)) and 2.0 * np.linalg.norm(a) <= GEODESIC_ALPHA * np.linalg.norm(v):
        return v + 0.5 * a
    return v


def _damped_step(cost, x, c, A, g, dA, nu, box, nu_max, accel=None):
    """Raise the damping nu until a step does not raise the cost: (x, r, c, nu), or None above ``nu_max``;
    ``accel``: v -> J^T r_vv at x (active variables zeroed) for geodesic acceleration, or None."""
    lo, hi = box
    while True:
        try:
            step = _step(cho_factor(A + nu * np.diag(dA)), g, accel)
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


def _accelerator(curvature, x, r, act):
    """v -> curvature(x, r, v) with the active variables' entries zeroed (they are held), or None."""
    if curvature is None:
        return None

    def accel(v):
        b = np.asarray(curvature(x, r, v), float).copy()
        if act is not None:
            b[act] = 0.0
        return b
    return accel


def levenberg_marquardt(cost, normal, x0, *, lo=None, hi=None, max_iter=300, tol=1e-10, nu_max=1e14,
                        curvature=None):
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

    With ``curvature`` the step is geodesically accelerated (Transtrum & Sethna 2012, arXiv:1201.5885):
    the velocity :math:`v` above, the acceleration
    :math:`a = -(A + \nu\,\mathrm{diag}\,A)^{-1} J^\top r_{vv}` (active variables held), and the step
    :math:`v + a/2` when :math:`2|a|/|v| \le` :data:`GEODESIC_ALPHA`, else :math:`v`; acceptance, damping,
    bounds and the convergence test are those above.  ``curvature(x, r, v)`` returns
    :math:`J^\top r_{vv}` at x (r as ``cost`` returns it; e.g. :func:`curvature_gradient`).
    """
    x = np.asarray(x0, float).copy()
    if lo is not None:
        x = np.clip(x, lo, hi)
    c, r = cost(x)
    nu = NU_START
    for it in range(1, max_iter + 1):
        A, g = normal(x, r)
        act = None
        if lo is not None:
            act = _active(x, g, lo, hi)
            if act.any():
                A[act, :], A[:, act], g[act] = 0.0, 0.0, 0.0
                A[act, act] = 1.0
        dA = np.diag(A).copy()
        dA[dA <= 0] = 1.0
        if _predicted(A, g, dA) <= tol * c + TINY:
            return x, it - 1, True
        accepted = _damped_step(cost, x, c, A, g, dA, nu, (lo, hi), nu_max, _accelerator(curvature, x, r, act))
        if accepted is None:
            return x, it, False
        x, r, c, nu = accepted
        nu = max(nu / 3, NU_MIN)
    return x, max_iter, False
