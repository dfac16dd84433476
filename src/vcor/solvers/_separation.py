"""The separation step in numba: where the force (or the overlap) returns to zero inside the last
step, and the outcome there. A plain NumPy reference is :func:`vcor.solvers.reference.separation_reference`.
"""

from __future__ import annotations

import math

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
def _elastic_kernel(F, un):
    """F = k u on the four nodes (to 1e-9 of the largest F): an elastic kernel, whose force
    F ~ |t - t0|^{3/2} is not smooth where s crosses zero."""
    ref = 0
    for j in range(1, 4):
        if abs(un[j]) > abs(un[ref]):
            ref = j
    if un[ref] == 0.0:
        return False
    k = F[ref] / un[ref]
    deviation = 0.0
    for j in range(4):
        deviation = max(deviation, abs(F[j] - k * un[j]))
    return deviation <= 1e-9 * abs(F[ref])


@jit
def _hertz(s):
    """u = sgn(s) |s|^{3/2} (computed from s here, not taken from a march's u: the same number on every path)."""
    return math.copysign(abs(s) * math.sqrt(abs(s)), s)


@jit
def _force_value(c, cs, glassy, tn, x):
    """The force at x: the cubic with divided differences ``c`` (of F, or with ``glassy`` > 0 of
    F - glassy u), plus glassy u(s(x)) with s(x) the cubic ``cs`` of s."""
    value = _newton_value(c, tn, x)
    if glassy > 0.0:
        value += glassy * _hertz(_newton_value(cs, tn, x))
    return value


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
def separation_point(nodes, n, lo, by_overlap, force_rule, body, still_plate, glassy, out):
    """Separation inside [t_{n-1}, t_n] and the outcome there.

    The root of the cubic through nodes lo..lo+3 of the target (s when ``by_overlap``, else F) is found
    by the Illinois variant of regula falsi to 1e-15 t_n; s, s' and J (and F unless ``force_rule``) are
    interpolated by the same cubics there. Where s crosses zero with F proportional to u (an elastic
    kernel, :func:`_elastic_kernel`: F ~ |t - t0|^{3/2}, so that a cubic through
    s' = v0 - J/m - alpha' J - alpha F misses it by O(h^{3/2})) on a plate of constant mobility
    (``still_plate``: alpha' = 0), the model gives s'(t0) = v0 - J(t0)/m exactly (F(t0) = 0), and J is
    smooth there. The work integrals are trapezoidal on nodes 0..n-1 plus the
    partial interval [t_{n-1}, t0]; the peaks of s and F are parabola-refined (:func:`parabola_peak`).

    Parameters
    ----------
    nodes : Nodes
        t (s), s (m), g (m/s), F (N), J (N s), u (m^1.5) of the march; a plain tuple (``_records``).
    n : int
        The separation node; lo: the first of the four interpolation nodes.
    by_overlap, force_rule : bool
        Interpolate the root of s (else of F); F(t0) = 0 in the work integrals.
    still_plate : bool
        The plate's mobility is constant in time (a rigid target, an elastic plate).
    glassy : float
        A nearly elastic kernel's k(0) (N m^-1.5; ``_records.Stop``, ``nearly_elastic.glassy_stiffness``), or 0.
        When > 0 a root of F (not of s) is that of glassy u(s(t)) + R(t), R = F - glassy u =
        int k'(t - tau) u(tau) dtau, with s and R by their cubics: R is smooth where F is not (F ~ u =
        s^{3/2} falls steeply where a nearly elastic contact leaves a small residual overlap, and the
        cubic through F misses its root there by far more than the march's error).
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
    y = s if by_overlap else F
    split = 0.0 if by_overlap else glassy
    cs = _divided(tn, s[lo:lo + 4])
    if by_overlap:
        c = cs
    elif split == 0.0:
        c = _divided(tn, F[lo:lo + 4])
    else:
        rest = F[lo:lo + 4].copy()
        for j in range(4):
            rest[j] -= split * _hertz(s[lo + j])
        c = _divided(tn, rest)
    a = t[n - 1]
    b = t[n]
    fa = _force_value(c, cs, split, tn, a)
    fb = _force_value(c, cs, split, tn, b)
    if not (fa > 0.0 >= fb) and lo <= n - 1 and n <= lo + 3:
        # the bracket's ends are nodes, where the interpolant is the node value; evaluated, a value a few
        # roundings from zero (a force creeping to zero) may round across it
        fa, fb = y[n - 1], y[n]
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
            fx = _force_value(c, cs, split, tn, x)
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
    s0 = _newton_value(cs, tn, t0)
    J0 = _newton_value(_divided(tn, J[lo:lo + 4]), tn, t0)
    F0 = 0.0 if force_rule else _newton_value(_divided(tn, F[lo:lo + 4]), tn, t0)
    if by_overlap and still_plate and _elastic_kernel(F[lo:lo + 4], u[lo:lo + 4]):
        g0 = v0 - J0 / m
    else:
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
def locate_separation(nodes, n, size, overlap_rule, body, still_plate, glassy, out):
    """:func:`separation_point` for the separation step n of a march whose first ``size`` nodes are
    valid: the four interpolation nodes end at n + 1 when it exists, and s is the target for the
    overlap rule, or when s also crossed zero in step n and ``glassy`` is 0 (F ~ s^{3/2} is not smooth at
    its root, s is). With ``glassy`` (a nearly elastic kernel's k(0), :func:`separation_point`) the force's
    root is located on glassy u(s) + (F - glassy u) also then: such a contact's force returns to zero at a
    small residual overlap, close to where s crosses zero (inside the same step on a coarse grid, where
    the root of s would be another time)."""
    s = Nodes(*nodes).s
    lo = max(0, min(n - 2, size - 4))
    split = 0.0 if overlap_rule else glassy
    by_overlap = overlap_rule or (split == 0.0 and s[n] <= 0.0 < s[n - 1])
    return separation_point(nodes, n, lo, by_overlap, not overlap_rule, body, still_plate, split, out)
