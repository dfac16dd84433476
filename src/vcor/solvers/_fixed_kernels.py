"""Fixed-step numba marches: ``direct`` (full history), ``ive-numba`` (internal variables), ``soe``
(exponential-sum history) and ``paper`` (the explicit baseline). Arrays and records in
(``_records``), node arrays and the state filled in place; plain NumPy references of each are in
:mod:`vcor.solvers.reference`.

Discretisation (direct, soe): the trapezoidal step of :mod:`._step` with product integration of the
hereditary force, u = s^{3/2} linear on the first step and quadratic (the parabola through three
nodes) on every later one,

.. math:: F_n = \\sum_{j<n} \\Delta u_j\\, \\tilde w_{n-1-j} - \\Delta u_0\\, v_{n-1} + \\eta u'_n,

w_i = (1/dt) int_{i dt}^{(i+1) dt} k (exact, from the material), v_i = (1/dt^2) int_{step i}
k(sigma) (sigma_mid - sigma) dsigma, and the folded weights wt_0 = w_0 + v_0, wt_i = w_i + v_i - v_{i-1}.
Without the quadratic correction a weakly singular kernel (k ~ t^-1/2) converges only as dt^1.5
(the L1 scheme); with it the march is second order for every kernel here. The internal-variable
march (``ive-numba``) is the recursive form of the *linear* product integration (form b).
"""

from __future__ import annotations

import math

import numpy as np

from ._jit import jit
from ._records import STATUS, STATUS_END, Body, Internal, PlateArrays, Stop, Volterra
from ._step import advance, implicit_step

__all__ = ["march_direct", "march_paper", "march_prony", "march_soe"]

_NO_VOLTERRA = (0.0, 0.0, 0.0)


@jit
def march_direct(n_start, n_end, nodes, weights, volterra, plate, body, dt, stop, state):
    """March the direct (full-history) scheme from step ``n_start`` to at most ``n_end``.

    The records arrive as plain tuples (``_records``).

    Parameters
    ----------
    n_start, n_end : int
        First and last step to compute (node arrays hold at least n_end + 1 nodes).
    nodes : FixedNodes
        s, g, F, J, u and du (du_j = u_{j+1} - u_j), filled in place.
    weights : tuple
        (w, v): the step integrals and first moments of the kernel per unit step (N m^-1.5).
    volterra : Volterra
        Second-order term (form a, h2 = c2 k(t1 + t2)): cells[c] = double cell integral of k for
        c = 2n - (i + j) - 1 >= 1, autoconvolution[m] = sum_{i+j=m} du_i du_j (updated in place).
    plate : PlateArrays
        alpha(t_n), alpha'(t_n) per node.
    body : Body
    dt : float
        Time step, s.
    stop : Stop
    state : int64 array
        [loaded, separation, last, status], updated in place.
    """
    volterra, plate, body, stop = Volterra(*volterra), PlateArrays(*plate), Body(*body), Stop(*stop)
    w, v = weights
    s, g, F, J, u, du = nodes
    cells, auto = volterra.cells, volterra.autoconvolution
    c2 = volterra.c2
    inv_m = 1.0 / body.m
    s_scale = body.v0 * dt
    inv_dt2 = 1.0 / (dt * dt)
    for n in range(n_start, n_end + 1):
        # history part of the first-order convolution: F1 = w0 u_n + H
        w0 = w[0] - v[0] if n == 1 else w[0]
        H = -w0 * u[n - 1]
        for j in range(n - 1):
            H += du[j] * w[n - 1 - j]
        if n >= 2:
            H -= du[0] * v[n - 1]
        coefs = _NO_VOLTERRA
        if volterra.on:
            acc = 0.0
            for mm in range(2 * n - 3):  # m = i + j <= 2(n-2)
                acc += auto[mm] * cells[2 * n - mm - 1]
            bacc = 0.0
            for j in range(n - 1):
                bacc += du[j] * cells[n - j]
            coefs = (c2 * inv_dt2 * acc, c2 * inv_dt2 * 2.0 * bacc, c2 * inv_dt2 * cells[1])
        sn, gn, Fn, un, Jn, ok = implicit_step((s[n - 1], g[n - 1], u[n - 1], F[n - 1], J[n - 1]), H, w0, body,
                                               coefs, (plate.alpha[n], plate.alpha_rate[n]), inv_m, dt, s_scale,
                                               g[n - 1])
        s[n] = sn
        g[n] = gn
        F[n] = Fn
        u[n] = un
        J[n] = Jn
        d = un - u[n - 1]
        du[n - 1] = d
        if volterra.on:
            for j in range(n - 1):
                auto[n - 1 + j] += 2.0 * d * du[j]
            auto[2 * n - 2] += d * d
        if advance(state, n, ok, sn, gn, Fn, stop):
            return
    state[STATUS] = STATUS_END


@jit
def march_prony(n_start, n_end, nodes, internal, plate, body, dt, stop, state):
    """Fixed-step internal-variable march for a Prony kernel (O(N); method ``ive-numba``).

    ``internal.Q`` holds the internal variables (Green Eqs. 18-19) at the last computed step; each
    step updates them exactly for u linear on the step: Q_k <- decay_k Q_k + weight_k (u_n - u_{n-1}),
    decay_k = exp(-b_k dt), weight_k = G_k (1 - exp(-b_k dt)) / (b_k dt), and F_n = G_inf u_n + sum Q_k.
    This is the recursive form of the linear product integration (the direct scheme's form b), so
    the two give the same numbers to rounding. Other arguments as :func:`march_direct`.
    """
    internal, plate, body, stop = Internal(*internal), PlateArrays(*plate), Body(*body), Stop(*stop)
    s, g, F, J, u, _ = nodes
    Q, G, decay, weight = internal.Q, internal.G, internal.decay, internal.weight
    inv_m = 1.0 / body.m
    s_scale = body.v0 * dt
    nq = G.shape[0]
    w0 = internal.G_inf
    for k in range(nq):
        w0 += weight[k]
    for n in range(n_start, n_end + 1):
        # F_n = G_inf u_n + sum_k (decay_k Q_k + weight_k (u_n - u_{n-1})) = w0 u_n + H
        H = 0.0
        for k in range(nq):
            H += decay[k] * Q[k] - weight[k] * u[n - 1]
        sn, gn, Fn, un, Jn, ok = implicit_step((s[n - 1], g[n - 1], u[n - 1], F[n - 1], J[n - 1]), H, w0, body,
                                               _NO_VOLTERRA, (plate.alpha[n], plate.alpha_rate[n]), inv_m, dt,
                                               s_scale, g[n - 1])
        d = un - u[n - 1]
        for k in range(nq):
            Q[k] = decay[k] * Q[k] + weight[k] * d
        s[n] = sn
        g[n] = gn
        F[n] = Fn
        u[n] = un
        J[n] = Jn
        if advance(state, n, ok, sn, gn, Fn, stop):
            return
    state[STATUS] = STATUS_END


@jit
def march_soe(n_start, n_end, nodes, local, modes, plate, body, dt, stop, state):
    """The direct scheme with an exponential-sum history (O(N (L + K)), L local lags, K modes).

    ``local`` = (wt, v, L): the folded weights of the first L + 1 lags are the exact kernel's (they
    hold any singularity at t = 0); beyond, wt_i = sum_k weight_k decay_k^(i-L-1) and
    v_i = sum_k slope_weight_k decay_k^(i-L-1), the weights of the kernel's exponential sum
    (decay_k = exp(-b_k dt)). The history over du_j with lag i > L is carried by one recursive
    variable per mode, S_k = sum_{j <= n-2-L} du_j decay_k^(n-2-L-j), and P_k = decay_k^(n-2-L) gives
    v_{n-1} for the first step's correction. Everything else is :func:`march_direct`.
    """
    plate, body, stop = PlateArrays(*plate), Body(*body), Stop(*stop)
    wt, v, n_local = local
    weight, slope_weight, decay, S, P = modes
    s, g, F, J, u, du = nodes
    inv_m = 1.0 / body.m
    s_scale = body.v0 * dt
    nk = weight.shape[0]
    for n in range(n_start, n_end + 1):
        w0 = wt[0] - v[0] if n == 1 else wt[0]
        H = -w0 * u[n - 1]
        for j in range(max(0, n - 1 - n_local), n - 1):
            H += du[j] * wt[n - 1 - j]
        for k in range(nk):
            H += weight[k] * S[k]
        if n >= 2:
            if n - 1 <= n_local:
                H -= du[0] * v[n - 1]
            else:
                vv = 0.0
                for k in range(nk):
                    vv += slope_weight[k] * P[k]
                H -= du[0] * vv
        sn, gn, Fn, un, Jn, ok = implicit_step((s[n - 1], g[n - 1], u[n - 1], F[n - 1], J[n - 1]), H, w0, body,
                                               _NO_VOLTERRA, (plate.alpha[n], plate.alpha_rate[n]), inv_m, dt,
                                               s_scale, g[n - 1])
        s[n] = sn
        g[n] = gn
        F[n] = Fn
        u[n] = un
        J[n] = Jn
        du[n - 1] = un - u[n - 1]
        jn = n - 1 - n_local  # the increment whose lag becomes L + 1 at step n + 1
        if jn >= 0:
            for k in range(nk):
                S[k] = decay[k] * S[k] + du[jn]
        if n == n_local + 1:
            for k in range(nk):
                P[k] = 1.0
        elif n > n_local + 1:
            for k in range(nk):
                P[k] *= decay[k]
        if advance(state, n, ok, sn, gn, Fn, stop):
            return
    state[STATUS] = STATUS_END


@jit
def march_paper(n_end, nodes, clamped_kernel, plate, body, dt, stop, state):
    """Baseline in the spirit of the paper's scheme (Green Sec. 5): explicit Adams-Bashforth 4 (started
    with AB1..AB3 instead of Runge-Kutta, which would need the hereditary force between nodes) and the
    kernel *clamped*, kc[i] = k(max(i dt, dt)), evaluated at points (no step integrals):
    F_n = sum_{j=1..n} kc[n - j] (u_j - u_{j-1}). It marches the same first-order form as the other
    solvers: the paper's route, a 6-point backward difference for (alpha J)'' inside an explicit march,
    was unstable (COR = 32 for the SLS at dt = t_c/500), so this baseline isolates the two ingredients
    that matter here, explicit stepping and the clamped kernel. ``nodes``: FixedNodes (du unused).
    """
    plate, body, stop = PlateArrays(*plate), Body(*body), Stop(*stop)
    s, g, F, J, _, _ = nodes
    m, v0 = body.m, body.v0
    alpha, alphad = plate.alpha, plate.alpha_rate
    u = np.zeros(n_end + 1)
    fs = np.zeros((n_end + 1, 2))  # derivatives of (s, J)
    for n in range(n_end + 1):
        if n > 0:
            k = min(n, 4)
            for c in range(2):
                if k == 1:
                    inc = fs[n - 1, c]
                elif k == 2:
                    inc = 1.5 * fs[n - 1, c] - 0.5 * fs[n - 2, c]
                elif k == 3:
                    inc = (23.0 * fs[n - 1, c] - 16.0 * fs[n - 2, c] + 5.0 * fs[n - 3, c]) / 12.0
                else:
                    inc = (55.0 * fs[n - 1, c] - 59.0 * fs[n - 2, c] + 37.0 * fs[n - 3, c] - 9.0 * fs[n - 4, c]) / 24.0
                if c == 0:
                    s[n] = s[n - 1] + dt * inc
                else:
                    J[n] = J[n - 1] + dt * inc
        a = abs(s[n])
        u[n] = math.copysign(a * math.sqrt(a), s[n])
        Fn = 0.0
        for j in range(1, n + 1):
            Fn += clamped_kernel[n - j] * (u[j] - u[j - 1])
        F[n] = Fn
        g[n] = v0 - J[n] / m - alphad[n] * J[n] - alpha[n] * Fn
        fs[n, 0] = g[n]
        fs[n, 1] = Fn
        # (n > 0 rather than a literal True: a literal argument would compile a second advance)
        if n > 0 and advance(state, n, n > 0, s[n], g[n], Fn, stop):
            return
    state[STATUS] = STATUS_END
