"""The implicit trapezoidal step every march shares, and the book-keeping after a step.

First-order form of Green's Eq. 2 (docs/theory.md, "The model"):

.. math:: s' = g = v_0 - J/m - \\alpha'(t) J - \\alpha(t) F, \\qquad J' = F,

with the hereditary force F = A(u) + eta u', u = sgn(s) |s|^{3/2}, A the march's discrete convolution
(linear in u_n: A = w0 u_n + H + V(u_n - u_{n-1}), V the Volterra term) and eta u' a Kelvin-Voigt
kernel's Dirac part. The trapezoidal rule (implicit, A-stable, order 2) for s and J leaves one scalar
equation for s_n, solved by Newton's method, so the stiff local term alpha k(0) sqrt(s) is implicit.
"""

from __future__ import annotations

import math

from ._jit import jit, jit_inline
from ._records import (
    LAST,
    LOADED,
    SEPARATION,
    STATUS,
    STATUS_DIVERGED,
    STATUS_SEPARATED,
)

__all__ = ["advance", "implicit_step", "implicit_step_inline", "separated"]


def _implicit_step(prev, history, w0, body, volterra, mobility, inv_m, dt, s_scale, g_guess):
    """Solve the implicit trapezoidal step for s_n (m).

    Parameters
    ----------
    prev : tuple
        (s, g, u, F, J) at the previous node: m, m/s, m^1.5, N, N s.
    history : float
        H, the part of the convolution that does not depend on u_n (N).
    w0 : float
        Weight of u_n in the convolution (N m^-1.5).
    body : Body
        eta (N s m^-1.5), m (kg), v0 (m/s).
    volterra : tuple
        (a2, b2, c2q): V(d) = a2 + b2 d + c2q d^2, d = u_n - u_{n-1} (N; zeros without the term).
    mobility : tuple
        (alpha(t_n), alpha'(t_n)): m N^-1 s^-1, m N^-1 s^-2.
    inv_m : float
        1 / m (1/kg; the caller's, once per march).
    dt : float
        The step, s.
    s_scale : float
        v0 dt (m): the absolute scale of Newton's stopping test.
    g_guess : float
        Predicted g_n (m/s): the first iterate is s_{n-1} + dt/2 (g_{n-1} + g_guess).

    Returns
    -------
    tuple
        (s, g, F, u, J, ok) at the new node; ok is False when Newton did not converge.

    Notes
    -----
    F(s) = w0 u(s) + H + V(u(s) - u_{n-1}) + eta p(s) g with p = 3/2 |s|^{1/2}; with
    J_b = J_{n-1} + dt/2 F_{n-1}, B = v0 - J_b (1/m + alpha'_n) and c = alpha_n + dt/2 (1/m + alpha'_n):
    g = B - c F, J_n = J_b + dt/2 F and R(s) = s - s_{n-1} - dt/2 (g_{n-1} + g) = 0.

    Newton stops when its correction is below 1e-15 (|s| + v0 dt); or below 1e-12 |s| while
    contracting by 1e-3 or more (in a slow creep v0 dt is far larger than s); or (no Dirac term) when
    its own error estimate |R''/(2 R')| ds^2 is below 1e-16 |s|. In that last case u, F and g are
    taken to first order in the last correction where their second-order terms are below 1e-16 of
    their values (a final evaluation would change them by rounding only).
    """
    s_prev, g_prev, u_prev, F_prev, J_prev = prev
    eta = body.eta
    v0 = body.v0
    a2, b2, c2q = volterra
    alpha_n, alphad_n = mobility
    half = 0.5 * dt
    kin = inv_m + alphad_n
    Jb = J_prev + half * F_prev
    B = v0 - Jb * kin
    c = alpha_n + half * kin
    s = s_prev + half * (g_prev + g_guess)
    ok = False
    F = 0.0
    g = 0.0
    u = 0.0
    ds_prev = math.inf
    for _ in range(50):
        a = abs(s)
        sq = math.sqrt(a)
        sgn = 1.0 if s >= 0.0 else -1.0
        u = sgn * a * sq
        up = 1.5 * sq  # du/ds
        d = u - u_prev
        A = w0 * u + history + a2 + (b2 + c2q * d) * d
        dA = (w0 + b2 + 2.0 * c2q * d) * up
        if eta > 0.0:
            p = 1.5 * sq
            pp = 0.75 / max(sq, 1e-300) * sgn
            den = 1.0 + eta * p * c
            num = A + eta * p * B
            F = num / den
            dF = (dA + eta * pp * B) / den - num * eta * pp * c / (den * den)
        else:  # no Dirac term: the same numbers without the divisions
            F = A
            dF = dA
        g = B - c * F
        R = s - s_prev - half * (g_prev + g)
        dR = 1.0 + half * c * dF
        if dR == 0.0 or not math.isfinite(dR):
            break
        ds = R / dR
        s -= ds
        ads = abs(ds)
        if ads <= 1e-15 * (abs(s) + s_scale) or (ads <= 1e-12 * a and ads <= 1e-3 * ds_prev):
            ok = True
            break
        if eta == 0.0 and ads <= 1e-6 * a and sq > 0.0:
            # Newton's error estimate: R'' = dt/2 c F'', F'' = (dF/du) u'' + 2 c2q u'^2, u'' = 3/4 |s|^-1/2
            d2F = (w0 + b2 + 2.0 * c2q * d) * 0.75 / sq + 2.0 * c2q * up * up
            if abs(half * c * d2F) * ads * ads <= 2e-16 * a * abs(dR):
                ok = True
                e2 = 0.5 * ads * ads
                if e2 * abs(d2F) <= 1e-16 * abs(F) and e2 * 0.75 / sq <= 1e-16 * abs(u):
                    u -= up * ds
                    F -= dF * ds
                    g = B - c * F
                    return s, g, F, u, Jb + half * F, True
                break
        ds_prev = ads
    # final consistent evaluation at the converged s
    a = abs(s)
    sq = math.sqrt(a)
    sgn = 1.0 if s >= 0.0 else -1.0
    u = sgn * a * sq
    d = u - u_prev
    A = w0 * u + history + a2 + (b2 + c2q * d) * d
    if eta > 0.0:
        p = 1.5 * sq
        F = (A + eta * p * B) / (1.0 + eta * p * c)
    else:  # the same number without the division
        F = A
    g = B - c * F
    J = Jb + half * F
    if not ok:
        R = s - s_prev - half * (g_prev + g)
        ok = abs(R) <= 1e-10 * (abs(s) + s_scale)
    return s, g, F, u, J, ok


#: the step as a numba function (the fixed-step marches call it)
implicit_step = jit(_implicit_step)
#: the same step inlined into the adaptive march, where the call and its arguments cost ~3-4 % of an
#: impact; the fixed-step marches keep the call (their history sums dominate)
implicit_step_inline = jit_inline(_implicit_step)


@jit
def separated(rule, loaded, F, s):
    """Has a loaded contact separated? rule 0: F <= 0 (the force returns to zero); 1: s <= 0."""
    if rule == 0:
        return loaded and F <= 0.0
    return loaded and s <= 0.0


@jit
def advance(state, n, ok, sn, gn, Fn, stop):
    """Book-keeping after step n (``state``: see ``_records``): divergence (Newton failed or a value
    is not finite), loading, separation. True when the march must stop: diverged, or ``stop.n_extra``
    steps past the separation node."""
    state[LAST] = n
    if not (ok and math.isfinite(sn) and math.isfinite(Fn) and math.isfinite(gn)):
        state[STATUS] = STATUS_DIVERGED
        return True
    if state[SEPARATION] < 0:
        if Fn > 0.0 and sn > 0.0:
            state[LOADED] = 1
        if separated(stop.rule, state[LOADED] == 1, Fn, sn):
            state[SEPARATION] = n
    if state[SEPARATION] >= 0 and n >= state[SEPARATION] + stop.n_extra:
        state[STATUS] = STATUS_SEPARATED
        return True
    return False
