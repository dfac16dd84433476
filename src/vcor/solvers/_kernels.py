"""Private numba kernels. Arrays and scalars in, arrays and integer codes out.

All compile flags live here (``cache=True``, ``error_model="numpy"``, no fastmath, except
reassociation in two sums of the adaptive march over many exponential modes: ``_JIT_SUM``).

Discretisation (shared by the direct and the fixed-step internal-variable kernels)
-------------------------------------------------------------------------------
First-order system (DESIGN 1.1): s' = g = v0 - J/m - alpha'(t) J - alpha(t) F,  J' = F.
Trapezoidal rule for s and J (implicit, A-stable, order 2); the unknown s_n of each step is
found by Newton's method, so the local contact term alpha k(0) sqrt(s) is treated implicitly.
The hereditary force uses product integration with u = s^{3/2} linear on each step:

    F_n = sum_{j<n} (u_{j+1} - u_j) w_{n-1-j} + eta u'_n (+ Volterra term),
    w_i = (1/dt) int_{i dt}^{(i+1) dt} k(sigma) d sigma (exact, from the material),

(the internal-variable march uses exactly this). The direct march adds the quadratic correction:
on every step but the first, u' is the derivative of the parabola through three nodes,
u' = du_j/dt + (du_j - du_{j-1}) (tau - t_{j+1/2})/dt^2, which adds the first kernel moments
v_i = (1/dt^2) int_{step i} k(sigma) (sigma_mid - sigma) d sigma. Folded into one set of weights,
F_n = sum_j du_j wt_{n-1-j} - du_0 v_{n-1}, wt_0 = w_0 + v_0, wt_i = w_i + v_i - v_{i-1}.
Without it a weakly singular kernel (k ~ t^-1/2) converges only as dt^1.5 (the L1 scheme of
fractional calculus); with it the march is second order for every kernel here.

where eta is the weight of a Dirac term of the kernel (Kelvin-Voigt) and u'_n = 3/2 sqrt(s_n) g_n.
For u = sgn(s)|s|^{3/2} (odd extension, used only by the "ghost" solution after separation).
"""

from __future__ import annotations

import math

import numba
import numpy as np

_JIT = dict(cache=True, nogil=True, error_model="numpy")

STATUS_RUNNING = 0
STATUS_SEPARATED = 1
STATUS_DIVERGED = 2
STATUS_END = 3  # reached the end of the arrays without separating
STATUS_FULL = 4  # adaptive march: arrays full, grow them and call again (resumable)
#: adaptive march: a mode whose decay factor over one step (or whose plate factor exp(-beta t)) is
#: below this has decayed (e^-41.4; far below rounding of the history it would add to)
DECAYED = 1e-18


@numba.njit(**_JIT)
def _newton_step(s_prev, g_prev, u_prev, F_prev, J_prev, H, w0, eta, a2, b2, c2q, alpha_n, alphad_n, inv_m, v0, dt,
                 s_scale, g_guess):
    """Solve the implicit trapezoidal step for s_n.

    F(s) = w0 u(s) + H + V(u(s) - u_prev) + eta p(s) g, V(d) = a2 + b2 d + c2q d^2,
    g = B - c F, R(s) = s - s_prev - dt/2 (g_prev + g) = 0.
    inv_m = 1 / m (the caller's, once per march). Returns (s, g, F, u, J, ok).
    """
    half = 0.5 * dt
    kin = inv_m + alphad_n
    Jb = J_prev + half * F_prev
    B = v0 - Jb * kin
    c = alpha_n + half * kin
    s = s_prev + half * (g_prev + g_guess)  # predictor: the trapezoidal rule with a guess of g (g_prev: Euler)
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
        A = w0 * u + H + a2 + (b2 + c2q * d) * d
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
        # converged: the correction is below 1e-15 (relative to |s| + v0 dt); or, relative to |s| alone
        # (in a slow creep v0 dt is far larger than s and its changes): below 1e-12 while contracting by
        # 1e-3 or more, so that the error left, ds^3/ds_prev^2 (quadratic) or ds theta/(1 - theta)
        # (linear), is below 1e-15 |s|; or (no Dirac term) Newton's error estimate |R''/(2 R')| ds^2 is
        # below 1e-16 |s| (R'' = dt/2 c F'', F'' = (dF/du) u'' + 2 c2q u'^2, u'' = 3/4 |s|^-1/2 sgn s)
        if ads <= 1e-15 * (abs(s) + s_scale) or (ads <= 1e-12 * a and ads <= 1e-3 * ds_prev):
            ok = True
            break
        if eta == 0.0 and ads <= 1e-6 * a and sq > 0.0:
            d2F = (w0 + b2 + 2.0 * c2q * d) * 0.75 / sq + 2.0 * c2q * up * up
            if abs(half * c * d2F) * ads * ads <= 2e-16 * a * abs(dR):
                ok = True
                e2 = 0.5 * ads * ads
                if e2 * abs(d2F) <= 1e-16 * abs(F) and e2 * 0.75 / sq <= 1e-16 * abs(u):
                    # u and F at the new s to first order in ds: their second-order terms are below
                    # 1e-16 of their values, so a final evaluation would change them by rounding only
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
    A = w0 * u + H + a2 + (b2 + c2q * d) * d
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


#: the same step inlined (numba IR) into the adaptive march, where the call and its 18 arguments cost
#: ~3-4 % of a butyl-fc impact; the fixed-step marches keep the call (their history sums dominate, and
#: inlining into all four lengthened a cold compile more: README, "One numba call per impact")
#: (NUMBA_DISABLE_JIT: _newton_step is the plain function, without py_func)
_newton_step_inline = numba.njit(inline="always", **_JIT)(getattr(_newton_step, "py_func", _newton_step))


@numba.njit(**_JIT)
def _separated(rule, loaded, F, s):
    if rule == 0:
        return loaded and F <= 0.0
    return loaded and s <= 0.0


@numba.njit(**_JIT)
def _advance(state, n, ok, sn, gn, Fn, rule, n_extra):
    """Book-keeping after step n: divergence, loading, separation. True when the march must stop."""
    state[2] = n
    if not (ok and math.isfinite(sn) and math.isfinite(Fn) and math.isfinite(gn)):
        state[3] = STATUS_DIVERGED
        return True
    if state[1] < 0:
        if Fn > 0.0 and sn > 0.0:
            state[0] = 1
        if _separated(rule, state[0] == 1, Fn, sn):
            state[1] = n
    if state[1] >= 0 and n >= state[1] + n_extra:
        state[3] = STATUS_SEPARATED
        return True
    return False


@numba.njit(**_JIT)
def march_direct(n_start, n_end, s, g, F, J, u, du, w, v, eta, alpha, alphad, m, v0, dt,
                 volterra, c2, Q2, S2, rule, n_extra, state):
    """March the direct (full-history) scheme from step n_start to at most n_end.

    Arrays s, g, F, J, u (length >= n_end + 1) hold the solution; du[j] = u_{j+1} - u_j.
    Volterra (form a, h2 = c2 k(t1 + t2)): Q2[c] = double cell integral of k for index
    c = 2n - (i + j) - 1 >= 1, S2[m] = running auto-convolution sum_{i+j=m} du_i du_j.
    ``state`` = [loaded flag, separation index, last index, status] (int64), updated in place.
    """
    inv_m = 1.0 / m
    s_scale = v0 * dt
    inv_dt2 = 1.0 / (dt * dt)
    for n in range(n_start, n_end + 1):
        # history part of the first-order convolution: F1 = w0 u_n + H
        w0 = w[0] - v[0] if n == 1 else w[0]
        H = -w0 * u[n - 1]
        for j in range(n - 1):
            H += du[j] * w[n - 1 - j]
        if n >= 2:
            H -= du[0] * v[n - 1]
        a2 = 0.0
        b2 = 0.0
        c2q = 0.0
        if volterra:
            acc = 0.0
            for mm in range(2 * n - 3):  # m = i + j <= 2(n-2)
                acc += S2[mm] * Q2[2 * n - mm - 1]
            bacc = 0.0
            for j in range(n - 1):
                bacc += du[j] * Q2[n - j]
            a2 = c2 * inv_dt2 * acc
            b2 = c2 * inv_dt2 * 2.0 * bacc
            c2q = c2 * inv_dt2 * Q2[1]
        sn, gn, Fn, un, Jn, ok = _newton_step(s[n - 1], g[n - 1], u[n - 1], F[n - 1], J[n - 1], H, w0, eta,
                                              a2, b2, c2q, alpha[n], alphad[n], inv_m, v0, dt, s_scale,
                                              g[n - 1])
        s[n] = sn
        g[n] = gn
        F[n] = Fn
        u[n] = un
        J[n] = Jn
        d = un - u[n - 1]
        du[n - 1] = d
        if volterra:
            for j in range(n - 1):
                S2[n - 1 + j] += 2.0 * d * du[j]
            S2[2 * n - 2] += d * d
        if _advance(state, n, ok, sn, gn, Fn, rule, n_extra):
            return
    state[3] = STATUS_END


@numba.njit(**_JIT)
def march_prony(n_start, n_end, s, g, F, J, u, Q, G_inf, G, decay, weight, eta, alpha, alphad, m, v0, dt,
                rule, n_extra, state):
    """Fixed-step internal-variable march for a Prony kernel (O(N)).

    Q[k] holds the internal variables (Green Eq. 18-19) at the last computed step; each step
    updates them exactly for u linear on the step: Q_k <- decay_k Q_k + weight_k (u_n - u_{n-1}),
    decay_k = exp(-b_k dt), weight_k = G_k (1 - exp(-b_k dt)) / (b_k dt). This is the recursive
    form of the direct scheme's product integration, so both give the same numbers.
    """
    inv_m = 1.0 / m
    s_scale = v0 * dt
    nq = G.shape[0]
    w0 = G_inf
    for k in range(nq):
        w0 += weight[k]
    for n in range(n_start, n_end + 1):
        # F_n = G_inf u_n + sum_k (decay_k Q_k + weight_k (u_n - u_{n-1})) = w0 u_n + H
        H = 0.0
        for k in range(nq):
            H += decay[k] * Q[k] - weight[k] * u[n - 1]
        sn, gn, Fn, un, Jn, ok = _newton_step(s[n - 1], g[n - 1], u[n - 1], F[n - 1], J[n - 1], H, w0, eta,
                                              0.0, 0.0, 0.0, alpha[n], alphad[n], inv_m, v0, dt, s_scale,
                                              g[n - 1])
        d = un - u[n - 1]
        for k in range(nq):
            Q[k] = decay[k] * Q[k] + weight[k] * d
        s[n] = sn
        g[n] = gn
        F[n] = Fn
        u[n] = un
        J[n] = Jn
        if _advance(state, n, ok, sn, gn, Fn, rule, n_extra):
            return
    state[3] = STATUS_END


@numba.njit(**_JIT)
def march_soe(n_start, n_end, s, g, F, J, u, du, wt, v, n_local, c, vc, r, S, P, eta, alpha, alphad, m, v0, dt,
              rule, n_extra, state):
    """The direct scheme with an exponential-sum history (O(N (L + K)), L = n_local, K = modes).

    The folded weights of the first L + 1 steps, wt[0..L] and v[0..L], are the exact kernel's (they
    hold any singularity at t = 0); beyond, wt_i = sum_k c_k r_k^(i-L-1) and v_i = sum_k vc_k
    r_k^(i-L-1), the weights of the kernel's exponential sum (r_k = exp(-beta_k dt)). So the history
    sum over du_j with lag i > L is carried by one recursive variable per mode,
    S_k = sum_{j <= n-2-L} du_j r_k^(n-2-L-j), and P_k = r_k^(n-2-L) gives v_{n-1} for the first
    step's correction. Everything else is the direct march (``march_direct``).
    """
    inv_m = 1.0 / m
    s_scale = v0 * dt
    nk = c.shape[0]
    for n in range(n_start, n_end + 1):
        w0 = wt[0] - v[0] if n == 1 else wt[0]
        H = -w0 * u[n - 1]
        for j in range(max(0, n - 1 - n_local), n - 1):
            H += du[j] * wt[n - 1 - j]
        for k in range(nk):
            H += c[k] * S[k]
        if n >= 2:
            if n - 1 <= n_local:
                H -= du[0] * v[n - 1]
            else:
                vv = 0.0
                for k in range(nk):
                    vv += vc[k] * P[k]
                H -= du[0] * vv
        sn, gn, Fn, un, Jn, ok = _newton_step(s[n - 1], g[n - 1], u[n - 1], F[n - 1], J[n - 1], H, w0, eta,
                                              0.0, 0.0, 0.0, alpha[n], alphad[n], inv_m, v0, dt, s_scale,
                                              g[n - 1])
        s[n] = sn
        g[n] = gn
        F[n] = Fn
        u[n] = un
        J[n] = Jn
        du[n - 1] = un - u[n - 1]
        jn = n - 1 - n_local  # the increment whose lag becomes L + 1 at step n + 1
        if jn >= 0:
            for k in range(nk):
                S[k] = r[k] * S[k] + du[jn]
        if n == n_local + 1:
            for k in range(nk):
                P[k] = 1.0
        elif n > n_local + 1:
            for k in range(nk):
                P[k] *= r[k]
        if _advance(state, n, ok, sn, gn, Fn, rule, n_extra):
            return
    state[3] = STATUS_END


def empty_state() -> np.ndarray:
    return np.array([0, -1, 0, STATUS_RUNNING], dtype=np.int64)


@numba.njit(**_JIT)
def march_paper(n_end, s, g, J, F, kc, alpha, alphad, m, v0, dt, rule, n_extra, state):
    """Baseline in the spirit of the paper's scheme (Green Sec. 5): explicit Adams-Bashforth 4
    (started with AB1..AB3 instead of Runge-Kutta, which would need the hereditary force between
    nodes) and the kernel *clamped*, k(max(sigma, dt)), evaluated at points (no step integrals):
    F_n = sum_{j=1..n} kc[n - j] (u_j - u_{j-1}). It marches the same first-order form as the other
    solvers (s' = v0 - J/m - alpha' J - alpha F, J' = F): the paper's route, a 6-point backward
    difference for (alpha J)'' inside an explicit march, was unstable in our hands (COR = 32 for the
    SLS at dt = t_c/500), so this baseline isolates the two ingredients that matter here,
    explicit stepping and the clamped kernel.
    """
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
            Fn += kc[n - j] * (u[j] - u[j - 1])
        F[n] = Fn
        g[n] = v0 - J[n] / m - alphad[n] * J[n] - alpha[n] * Fn
        fs[n, 0] = g[n]
        fs[n, 1] = Fn
        # (n > 0 rather than a literal True: a literal argument would compile a second _advance)
        if n > 0 and _advance(state, n, n > 0, s[n], g[n], Fn, rule, n_extra):
            return
    state[3] = STATUS_END


@numba.njit(**_JIT)
def march_adaptive(t, s, g, F, J, u, lev, hl, IH, I0, M, GA, GB, R, live, eta, plate, pscale, pc, pe_inf, p_half, alpha_c,
                   pe, pbe, m, v0, step_tol, inv_tc, lev_floor, lev_max, t_horizon, sep_frac, rule, n_extra, ghost, P, X,
                   state, plan, off):
    """Variable-step march with an exponential-sum history (see ``adaptive``).

    Steps are hl[l] = h_base 2^l (levels l = 0..L-1, tables per level). Step n spans [t_{n-1}, t_n]
    with size h_n; on it u' = d_n + c_n (tau - mid), d_n = (u_n - u_{n-1})/h_n and
    c_n = 2 (d_n - d_{n-1})/(h_n + h_{n-1}) (the parabola through three nodes; c_1 = 0): the direct
    scheme's quadratic product integration on an arbitrary grid. The newest step uses the exact
    kernel (I0[l] = int_0^h k, M[l] = int_0^h k(x) (h/2 - x) dx); older steps live in one variable
    per exponential mode, P_k(t_{n-1}) = sum_{j<n} e^{-beta_k (t_{n-1} - t_j)} (d_j GA[l_j,k] + c_j GB[l_j,k]),
    decayed by R[l,k] = exp(-beta_k h_l) to the new node. A trial step changes nothing until it is accepted, so a
    rejection needs no roll-back.

    Decayed modes: on level l only the first live[l] modes have R[l,k] >= DECAYED (every later one has
    decayed below it within one step), so a step touches only those. A mode k >= live[l] after an
    accepted step on level l holds that step's contribution alone (its older history is multiplied
    by R < DECAYED): P_k = d GA[l,k] + c GB[l,k], kept implicit (the last step's d, c and level) and
    written into P when a finer step needs the mode again, and for every mode before returning (so
    that P is whole when the march resumes). Modes of the plate's X_k = exp(-beta_k t) below
    DECAYED are zero from then on (t only grows).

    Plate mobility (plate = 1): alpha = pscale / sqrt(E_b), E_b(t) = pc (pe_inf + sum pe_k X_k),
    X_k = exp(-b_k t) carried with the same factors (pbe = b_k pe_k, b the modes' rates); plate = 2: in closed
    form, E_b(t) = pc (pe_inf + p_half t^-1/2) (the fractional law); plate = 0: alpha_c.

    Error control (per unit step): est = h^2 |g''| / 12 from the second divided difference of g over
    the last three nodes (the trapezoidal rule's local error is h^3 g''/12) against
    step_tol min(v0, |g_n| + s_n inv_tc): relative to the motion's own scale, which in a long contact
    (thin plate) falls by orders of magnitude below v0, where an error relative to v0 would move the
    separation time (inv_tc = 1 / contact-time estimate).
    Reject: down 1..4 levels (not below lev_floor, where the test is waived); accept with est <
    step_tol v0 / 8: up to 2 levels. A separation found with h_n > sep_frac t_n is rejected and
    re-stepped finer; after it the level is frozen for the n_extra steps and the ghost continuation
    to (1 + ghost) t_sep.

    Level l uses table row l + off (the tables of the Richardson grids are shifted copies of one).

    plan (levels, may be empty): step n <= len(plan) is taken on level plan[n - 1], with no error
    control and no separation refinement (the replay of a grid); after the plan, the march goes on
    with error control from the plan's last level.

    state = [loaded, separation index, last index, status, rejected steps, floor steps, level, frozen]
    (set level to the first step's before the first call). Resumable: when the arrays are full it
    returns STATUS_FULL with P, X and state intact.
    """
    inv_m = 1.0 / m
    nk = R.shape[1]
    nmax = t.shape[0] - 1
    inv_pscale2 = 1.0 / (pscale * pscale) if pscale > 0.0 else 0.0
    St = np.empty(nk)
    Xt = np.empty(nk)
    # P is whole on entry; modes kv.. are implicit after the first accepted step (see above)
    kv = nk
    last_d = 0.0
    last_c = 0.0
    last_lt = np.int64(0)  # (not a literal 0: numba would compile _fill a second time for it)
    kx = nk
    while kx > 1 and X[kx - 1] == 0.0:
        kx -= 1
    l = state[6]
    n = state[2] + 1
    # slopes of u and g over the last step (of g also over the one before), 2 / (the two steps' sum)
    last_dg = 0.0
    prev_dg = 0.0
    last_r2 = 0.0
    if n >= 2:
        last_d = (u[n - 1] - u[n - 2]) / (t[n - 1] - t[n - 2])
        last_dg = (g[n - 1] - g[n - 2]) / (t[n - 1] - t[n - 2])
    if n >= 3:
        prev_dg = (g[n - 2] - g[n - 3]) / (t[n - 2] - t[n - 3])
        last_r2 = 2.0 / (t[n - 1] - t[n - 3])
    frozen = state[7] == 1
    state[3] = STATUS_RUNNING
    tol_abs = step_tol * v0
    n_plan = plan.shape[0]
    spec_t = -1.0
    spec_a = 0.0
    spec_ad = 0.0
    while n <= nmax:
        planned = n - 1 < n_plan
        if planned:
            l = plan[n - 1]
        lt = l + off
        h = hl[lt]
        tn = t[n - 1] + h
        # history of all steps before this one
        kl = live[lt]
        if kl > kv:
            _fill(P, kv, kl, last_d, last_c, GA, GB, last_lt)
            kv = kl
        if kl > FEW_MODES:
            Hh = _decay_sum(R, lt, P, St, kl)
        else:
            Hh = 0.0
            for k in range(kl):
                v = R[lt, k] * P[k]
                St[k] = v
                Hh += v
        hp = t[n - 1] - t[n - 2] if n >= 2 else 0.0
        inv_h = IH[lt]
        if n >= 2:
            r2 = 2.0 / (h + hp)
            w0 = (I0[lt] + r2 * M[lt]) * inv_h
            dprev = last_d
            H = Hh - w0 * u[n - 1] - r2 * M[lt] * dprev
        else:
            r2 = 0.0
            w0 = I0[lt] * inv_h
            H = Hh - w0 * u[n - 1]
        if plate == 1:
            if kx > FEW_MODES:
                eb, ebd = _plate_sums(R, lt, X, Xt, pe, pbe, kx)
                eb = pc * (pe_inf + eb)
                ebd = -pc * ebd
            else:
                eb = pe_inf
                ebd = 0.0
                for k in range(kx):
                    x = R[lt, k] * X[k]
                    Xt[k] = x
                    eb += pe[k] * x
                    ebd -= pbe[k] * x
                eb *= pc
                ebd *= pc
            a_n = pscale / math.sqrt(eb)
            ad_n = -0.5 * a_n * a_n * a_n * ebd * inv_pscale2  # 1 / eb = alpha^2 / pscale^2
        elif plate == 2:
            # the roots and the division are a long chain: computed one step ahead, for the step on the
            # same level (or the plan's next one), while this step's Newton iteration runs
            if tn == spec_t:
                a_n = spec_a
                ad_n = spec_ad
            else:
                a_n, ad_n = _sqrt_law_mobility(tn, pscale, pc, pe_inf, p_half)
            spec_t = tn + hl[(plan[n] if n < n_plan else l) + off]
            spec_a, spec_ad = _sqrt_law_mobility(spec_t, pscale, pc, pe_inf, p_half)
        else:
            a_n = alpha_c
            ad_n = 0.0
        # predictor: g extrapolated by the parabola through the last three nodes (a line through two)
        # (the slopes of g over the last two steps and 2 / (their sum) are carried from their acceptance:
        # divisions are the march's bottleneck)
        g_guess = g[n - 1]
        if n >= 2:
            g_guess += h * last_dg
            if n >= 3:
                g_guess += 0.5 * h * (h + hp) * (last_dg - prev_dg) * last_r2
        sn, gn, Fn, un, Jn, ok = _newton_step_inline(s[n - 1], g[n - 1], u[n - 1], F[n - 1], J[n - 1], H, w0,
                                                     eta, 0.0, 0.0, 0.0, a_n, ad_n, inv_m, v0, h, v0 * h,
                                                     g_guess)
        # local error estimate and step control
        est = -1.0
        if not frozen and not planned and ok and n >= 2 and math.isfinite(gn):
            tol_abs = step_tol * min(v0, abs(gn) + abs(sn) * inv_tc)
            dd = ((gn - g[n - 1]) * inv_h - last_dg) * r2
            est = h * h * abs(dd) * (1.0 / 12.0)
            if est > tol_abs and l > lev_floor:
                drop = 1
                ratio = est / tol_abs
                while drop < 4 and ratio > 4.0 ** drop and l - drop > lev_floor:
                    drop += 1
                l -= drop
                state[6] = l
                state[4] += 1
                continue
            if est > tol_abs:
                state[5] += 1
        elif not frozen and not planned and not ok and l > lev_floor:
            l -= 1
            state[6] = l
            state[4] += 1
            continue
        # separation found on a coarse step: re-step finer
        if (not frozen and not planned and state[1] < 0 and state[0] == 1 and _separated(rule, state[0] == 1, Fn, sn)
                and h > sep_frac * tn and l > lev_floor):
            l -= 1
            state[6] = l
            state[4] += 1
            continue
        # accept
        t[n] = tn
        s[n] = sn
        g[n] = gn
        F[n] = Fn
        u[n] = un
        J[n] = Jn
        lev[n] = l
        d = (un - u[n - 1]) * inv_h
        c = (d - dprev) * r2 if n >= 2 else 0.0
        prev_dg = last_dg
        last_dg = (gn - g[n - 1]) * inv_h
        last_r2 = r2
        for k in range(kl):
            P[k] = St[k] + d * GA[lt, k] + c * GB[lt, k]
        kv = kl
        last_d = d
        last_c = c
        last_lt = lt
        if plate == 1:
            for k in range(kx):
                X[k] = Xt[k]
            while kx > 1 and X[kx - 1] < DECAYED:
                X[kx - 1] = 0.0
                kx -= 1
        if _advance(state, n, ok, sn, gn, Fn, rule, n_extra):
            if state[3] != STATUS_SEPARATED or tn >= t[state[1]] * (1.0 + ghost):
                _fill(P, kv, nk, last_d, last_c, GA, GB, last_lt)
                return
            state[3] = STATUS_RUNNING
        if state[1] >= 0:
            frozen = True
            state[7] = 1
        elif est >= 0.0:
            # grow, from the estimate of this accepted step
            up = 0
            while up < 2 and est * 4.0 ** (up + 1) < 0.5 * tol_abs and l + up + 1 <= lev_max:
                up += 1
            l += up
            state[6] = l
        if tn >= t_horizon:
            state[3] = STATUS_END
            _fill(P, kv, nk, last_d, last_c, GA, GB, last_lt)
            return
        n += 1
    state[3] = STATUS_FULL
    _fill(P, kv, nk, last_d, last_c, GA, GB, last_lt)


@numba.njit(inline="always", **_JIT)
def _sqrt_law_mobility(t, pscale, pc, pe_inf, p_half):
    """(alpha, alpha') at t of a plate of the fractional law, E_b = pc (pe_inf + p_half t^-1/2):
    with D = E_b t^1/2 and y = 1 / (D t), alpha = pscale (t^1/2 / D)^1/2 = pscale (t^1/2 y t)^1/2 and
    alpha' = alpha pc p_half / (4 D t) (one division, two roots)."""
    rt = math.sqrt(t)
    y = 1.0 / (pc * (pe_inf * rt + p_half) * t)
    a = pscale * math.sqrt(rt * y * t)
    return a, 0.25 * a * pc * p_half * y


#: adaptive march: sums over more modes than this go through the helpers below, whose additions may be
#: reassociated (fastmath "reassoc" only: numba then vectorises the sum; 0.17 -> 0.14 ms per butyl-fc
#: impact with ~80 live modes; tests/test_adaptive.py::test_reassociated_sums_are_safe); shorter sums
#: stay in the march (a call costs more than it saves)
FEW_MODES = 8
_JIT_SUM = dict(_JIT, fastmath={"reassoc"})


@numba.njit(**_JIT_SUM)
def _decay_sum(R, lt, P, St, kl):
    """St[:kl] = R[lt] P (the modes decayed over a trial step on table row lt) and their sum, in any
    order (rows indexed, not sliced: a row view costs two reference-count calls)."""
    acc = 0.0
    for k in range(kl):
        v = R[lt, k] * P[k]
        St[k] = v
        acc += v
    return acc


@numba.njit(**_JIT_SUM)
def _plate_sums(R, lt, X, Xt, pe, pbe, kx):
    """Xt[:kx] = R[lt] X (the plate's exp(-beta t) at the trial node) and the sums of pe Xt and
    pbe Xt (transient of E_b and minus its rate, before the factor pc), in any order."""
    eb = 0.0
    ebd = 0.0
    for k in range(kx):
        x = R[lt, k] * X[k]
        Xt[k] = x
        eb += pe[k] * x
        ebd += pbe[k] * x
    return eb, ebd


@numba.njit(**_JIT)
def _fill(P, k0, k1, d, c, GA, GB, lt):
    """P[k0:k1] = the last accepted step's own contribution (modes that had decayed on its level; its
    table row lt)."""
    for k in range(k0, k1):
        P[k] = d * GA[lt, k] + c * GB[lt, k]


@numba.njit(**_JIT)
def _divided(tn, yn):
    """Newton divided differences of the interpolating polynomial through (tn, yn)."""
    c = yn.copy()
    k = c.shape[0]
    for j in range(1, k):
        for i in range(k - 1, j - 1, -1):
            c[i] = (c[i] - c[i - 1]) / (tn[i] - tn[i - j])
    return c


@numba.njit(**_JIT)
def _newton_value(c, tn, x):
    total = c[c.shape[0] - 1]
    for i in range(c.shape[0] - 2, -1, -1):
        total = total * (x - tn[i]) + c[i]
    return total


@numba.njit(**_JIT)
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


@numba.njit(**_JIT)
def separation_point(t, s, g, F, J, n, lo, by_overlap, force_rule, m, v0, out):
    """Separation inside [t_{n-1}, t_n] (see ``common.separation``): the root of the cubic through
    nodes lo..lo+3 of the target (s when ``by_overlap``, else F) by the Illinois variant of regula
    falsi to 1e-15 t_n, then s, s', J (and F for the overlap rule) there, the trapezoidal work
    integrals and the parabola-refined peaks of s and F. Fills ``out`` with the outcome in the order
    of ``common.OUTCOME``: [COR |s'0|/v0, t0, s0, W_h, W_z - W_h, z'0 = v0 - J0/m, energy residual
    (E_in - m z'0^2/2 - W_z)/E_in with E_in = m v0^2/2, s_max, f_max] (SI units) and returns True;
    False (nothing filled) when the target does not change sign."""
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
    g0 = _newton_value(_divided(tn, g[lo:lo + 4]), tn, t0)
    J0 = _newton_value(_divided(tn, J[lo:lo + 4]), tn, t0)
    F0 = 0.0 if force_rule else _newton_value(_divided(tn, F[lo:lo + 4]), tn, t0)
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


@numba.njit(**_JIT)
def locate_separation(t, s, g, F, J, n, size, overlap_rule, m, v0, out):
    """``separation_point`` for the separation step n of a march whose first ``size`` nodes are
    valid: the four interpolation nodes end at n + 1 when it exists, and s is the target for the
    overlap rule, or when s also crossed zero in step n (F ~ s^{3/2} is not smooth at its root, s is)."""
    lo = max(0, min(n - 2, size - 4))
    by_overlap = overlap_rule or (s[n] <= 0.0 < s[n - 1])
    return separation_point(t, s, g, F, J, n, lo, by_overlap, not overlap_rule, m, v0, out)


@numba.njit(**_JIT)
def _node_arrays(n):
    """Six uninitialised node arrays (t, s, s', F, J, u) of length n."""
    return np.empty(n), np.empty(n), np.empty(n), np.empty(n), np.empty(n), np.empty(n)


@numba.njit(**_JIT)
def adaptive_grids(n_grids, hl, IH, I0, M, GA, GB, R, live, n_levels, eta, plate, pscale, pc, pe_inf, p_half, alpha_c,
                   pe, pbe, m, v0, step_tol, inv_tc, t_horizon, sep_frac, rule, n_extra, max_steps, start_level, size0,
                   out):
    """The adaptive march (``march_adaptive``), then (n_grids = 3) its replays with every step halved
    and quartered, and the separation of each, in one call (no histories). The tables have
    n_levels + 2 levels from h_base / 4: grid k (0, 1, 2) uses rows from 2 - k. Fills out[k] = [the 9
    outcome values of ``separation_point``, separation index, largest step] and returns True when every grid
    separated, the first within size0 steps; False (out undefined) for anything else (more steps,
    divergence, time horizon, step budget), which the caller then runs through the general path."""
    nk = R.shape[1]
    n_plan = 0
    # the lowest level as a variable: a literal 0 in the call would make numba compile a second
    # march_adaptive (a Literal[int] argument) besides the one the general path calls from Python
    lowest = np.int64(0)
    # the march writes node n before anything reads it, and reads nothing beyond the last node: the
    # arrays need only their first node set (np.empty: zeroing the 2049-node arrays cost ~5 us a call);
    # the replays reuse the first grid's node arrays when they fit (their levels go to ``lev``: the
    # first grid's, ``base``, are the plan)
    base = np.empty(size0 + 1, dtype=np.int64)
    t, s, g, F, J, u = _node_arrays(size0 + 1)
    lev = base
    P = np.empty(nk)
    X = np.empty(nk)
    state = np.empty(8, dtype=np.int64)
    for k in range(n_grids):
        rep = 2**k
        plan = np.empty(n_plan * rep, dtype=np.int64)
        for j in range(n_plan * rep):
            plan[j] = base[1 + j // rep]
        size = min(size0 if k == 0 else plan.shape[0] + 2 * n_extra + 8, max_steps)
        if k > 0:
            if size > t.shape[0] - 1:
                t, s, g, F, J, u = _node_arrays(size + 1)
            if k == 1 or size > lev.shape[0] - 1:
                lev = np.empty(t.shape[0], dtype=np.int64)
        t[0] = s[0] = F[0] = J[0] = u[0] = 0.0
        lev[0] = start_level
        g[0] = v0
        P[:] = 0.0
        X[:] = 1.0
        state[:] = 0
        state[1] = -1
        state[6] = start_level
        e = size + 1  # the march fills at most ``size`` steps (views: no copies)
        march_adaptive(t[:e], s[:e], g[:e], F[:e], J[:e], u[:e], lev[:e], hl, IH, I0, M, GA, GB, R, live, eta,
                       plate, pscale, pc, pe_inf, p_half, alpha_c, pe, pbe, m, v0, step_tol, inv_tc, lowest, n_levels - 1,
                       t_horizon, sep_frac, rule, n_extra, 0.0, P, X, state, plan, 2 - k)
        if state[3] != STATUS_SEPARATED:
            return False
        n_sep = state[1]
        n_done = state[2]
        if k == 0:
            n_plan = min(n_done, n_sep + n_extra)
        if not locate_separation(t, s, g, F, J, n_sep, n_done + 1, rule == 1, m, v0, out[k]):
            return False
        out[k, 9] = n_sep
        big = 0.0
        for j in range(1, n_done + 1):
            big = max(big, t[j] - t[j - 1])
        out[k, 10] = big
    return True
