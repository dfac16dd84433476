"""The separation step in numba: where the force (or the overlap) returns to zero inside the last
step, and the outcome there. A plain NumPy reference is :func:`vcor.solvers.reference.separation_reference`.
"""

from __future__ import annotations

import math

import numpy as np

from ._jit import jit
from ._records import Body, Nodes

__all__ = ["locate_separation", "parabola_peak", "separation_point"]


@jit
def _divided(tn, yn):
    """Newton divided differences of the interpolating polynomial through (tn, yn)."""
    c = yn.copy()
    k = c.shape[0]
    for j in range(1, k):
        for i in range(k - 1, j - 1, -1):
            c[i] = (c[i] - c[i - 1]) / (tn[i] - tn[i - j])
    return c


@jit
def _newton_value(c, tn, x):
    """The Newton-form polynomial with divided differences ``c`` on nodes ``tn``, at x."""
    total = c[c.shape[0] - 1]
    for i in range(c.shape[0] - 2, -1, -1):
        total = total * (x - tn[i]) + c[i]
    return total


@jit
def _singular_value(tn, g, F, un, x):
    """g at x from the four nodes when the force is proportional to u = sgn(s)|s|^{3/2} there (an elastic
    kernel, F = k u) and s crosses zero: g = B - alpha F with B smooth and alpha the plate's mobility,
    so g is fitted as a parabola minus a multiple of F (F ~ |t - t0|^{3/2} is not smooth at the root,
    and a cubic through g misses it by O(h^{3/2})); NaN when F is not proportional to u (the caller
    then interpolates g by the cubic)."""
    ref = 0
    for j in range(1, 4):
        if abs(un[j]) > abs(un[ref]):
            ref = j
    if un[ref] == 0.0:
        return math.nan
    k = F[ref] / un[ref]
    scale = abs(F[ref])
    for j in range(4):
        if abs(F[j] - k * un[j]) > 1e-9 * scale:
            return math.nan
    # rows [1, d, d^2, -F] c = g, d = t - tn[3], solved by Gaussian elimination with partial pivoting
    a = np.empty((4, 5))
    for j in range(4):
        d = tn[j] - tn[3]
        a[j, 0] = 1.0
        a[j, 1] = d
        a[j, 2] = d * d
        a[j, 3] = -F[j]
        a[j, 4] = g[j]
    for c in range(4):
        p = c
        for r in range(c + 1, 4):
            if abs(a[r, c]) > abs(a[p, c]):
                p = r
        if a[p, c] == 0.0:
            return math.nan
        for q in range(5):
            a[c, q], a[p, q] = a[p, q], a[c, q]
        for r in range(c + 1, 4):
            f = a[r, c] / a[c, c]
            for q in range(c, 5):
                a[r, q] -= f * a[c, q]
    coef = np.empty(4)
    for c in range(3, -1, -1):
        v = a[c, 4]
        for q in range(c + 1, 4):
            v -= a[c, q] * coef[q]
        coef[c] = v / a[c, c]
    d = x - tn[3]
    return coef[0] + coef[1] * d + coef[2] * d * d


@jit
def parabola_peak(t, y, n):
    """Maximum of samples y[0..n] refined by the parabola through the largest one and its neighbours
    (any spacing); the largest sample itself at an end or where the parabola is not concave."""
    i = 0
    for j in range(1, n + 1):
        if y[j] > y[i]:
            i = j
    if i == 0 or i == n:
        return y[i]
    h1 = t[i] - t[i - 1]
    h2 = t[i + 1] - t[i]
    d1 = (y[i] - y[i - 1]) / h1
    curv = ((y[i + 1] - y[i]) / h2 - d1) / (h1 + h2)
    if curv >= 0.0:
        return y[i]
    x = 0.5 * (t[i - 1] + t[i]) - 0.5 * d1 / curv
    return y[i - 1] + d1 * (x - t[i - 1]) + curv * (x - t[i - 1]) * (x - t[i])


@jit
def separation_point(nodes, n, lo, by_overlap, force_rule, body, out):
    """Separation inside [t_{n-1}, t_n] and the outcome there.

    The root of the cubic through nodes lo..lo+3 of the target (s when ``by_overlap``, else F) is found
    by the Illinois variant of regula falsi to 1e-15 t_n; s, s' and J (and F unless ``force_rule``) are
    interpolated by the same cubics there, except s' when s crosses zero with F proportional to u (an
    elastic kernel: :func:`_singular_value`). The work integrals are trapezoidal on nodes 0..n-1 plus the
    partial interval [t_{n-1}, t0]; the peaks of s and F are parabola-refined (:func:`parabola_peak`).

    Parameters
    ----------
    nodes : Nodes
        t (s), s (m), g (m/s), F (N), J (N s), u (m^1.5) of the march; a plain tuple (``_records``).
    n : int
        The separation node; lo: the first of the four interpolation nodes.
    by_overlap, force_rule : bool
        Interpolate the root of s (else of F); F(t0) = 0 in the work integrals.
    body : Body
        m (kg), v0 (m/s).
    out : float64 array
        Filled with the outcome in the order of ``common.OUTCOME``: COR |s'(t0)|/v0, t0 (s), s(t0) (m),
        W_h = int F s' dt (J), W_z - W_h (J), z'0 = v0 - J(t0)/m (m/s), the energy residual
        (E_in - m z'0^2/2 - W_z)/E_in with E_in = m v0^2/2, s_max (m), f_max (N).

    Returns
    -------
    bool
        True; False (nothing filled) when the target does not change sign in the step.
    """
    t, s, g, F, J, u = nodes
    m, v0 = Body(*body).m, Body(*body).v0
    tn = t[lo:lo + 4]
    c = _divided(tn, s[lo:lo + 4] if by_overlap else F[lo:lo + 4])
    a = t[n - 1]
    b = t[n]
    fa = _newton_value(c, tn, a)
    fb = _newton_value(c, tn, b)
    if not (fa > 0.0 >= fb):
        return False
    t0 = b
    if fb != 0.0:
        lo_t, hi_t, flo, fhi = a, b, fa, fb
        side = 0
        xtol = 1e-15 * b
        for _ in range(200):
            x = (lo_t * fhi - hi_t * flo) / (fhi - flo)
            if not (lo_t < x < hi_t):
                x = 0.5 * (lo_t + hi_t)
            fx = _newton_value(c, tn, x)
            t0 = x
            if fx == 0.0:
                break
            if fx > 0.0:
                lo_t, flo = x, fx
                if side == 1:
                    fhi *= 0.5
                side = 1
            else:
                hi_t, fhi = x, fx
                if side == -1:
                    flo *= 0.5
                side = -1
            if hi_t - lo_t <= xtol:
                t0 = lo_t if flo < -fhi else hi_t
                break
    s0 = _newton_value(_divided(tn, s[lo:lo + 4]), tn, t0)
    J0 = _newton_value(_divided(tn, J[lo:lo + 4]), tn, t0)
    F0 = 0.0 if force_rule else _newton_value(_divided(tn, F[lo:lo + 4]), tn, t0)
    g0 = math.nan
    if by_overlap:
        g0 = _singular_value(tn, g[lo:lo + 4], F[lo:lo + 4], u[lo:lo + 4], t0)
    if math.isnan(g0):
        g0 = _newton_value(_divided(tn, g[lo:lo + 4]), tn, t0)
    z0 = v0 - J0 / m
    # trapezoid on nodes 0..n-1 plus the partial interval [t_{n-1}, t0]; each node's powers F s' and
    # F z' computed once (carried to the next interval)
    w_h = 0.0
    w_z = 0.0
    ph = F[0] * g[0]
    pz = F[0] * (v0 - J[0] / m)
    for j in range(1, n):
        half = 0.5 * (t[j] - t[j - 1])
        qh = F[j] * g[j]
        qz = F[j] * (v0 - J[j] / m)
        w_h += half * (qh + ph)
        w_z += half * (qz + pz)
        ph = qh
        pz = qz
    w_h += 0.5 * (t0 - a) * (ph + F0 * g0)
    w_z += 0.5 * (t0 - a) * (pz + F0 * z0)
    e_in = 0.5 * m * v0 * v0
    out[0] = abs(g0) / v0
    out[1] = t0
    out[2] = s0
    out[3] = w_h
    out[4] = w_z - w_h
    out[5] = z0
    out[6] = (e_in - 0.5 * m * z0 * z0 - w_z) / e_in
    out[7] = parabola_peak(t, s, n)
    out[8] = parabola_peak(t, F, n)
    return True


@jit
def locate_separation(nodes, n, size, overlap_rule, body, out):
    """:func:`separation_point` for the separation step n of a march whose first ``size`` nodes are
    valid: the four interpolation nodes end at n + 1 when it exists, and s is the target for the
    overlap rule, or when s also crossed zero in step n (F ~ s^{3/2} is not smooth at its root, s is)."""
    s = Nodes(*nodes).s
    lo = max(0, min(n - 1, size - 4))
    by_overlap = overlap_rule or (s[n] <= 0.0 < s[n - 1])
    return separation_point(nodes, n, lo, by_overlap, not overlap_rule, body, out)
