"""The adaptive march in numba: variable power-of-two steps, the history as exponential modes, local
error control; and :func:`adaptive_grids`, the march and its Richardson replays in one call. A
plain NumPy reference is :func:`vcor.solvers.reference.adaptive_reference`.

Step n spans [t_{n-1}, t_n] with size h_n = h_base 2^l (level l, one row of the level tables per
level); on it u' = d_n + c_n (tau - mid_n) + q_n ((tau - mid_n)^2 - h_n^2/12), d_n = (u_n - u_{n-1}) / h_n
the mean of u' over the step, and c_n, q_n the slope and half the curvature at mid_n of the parabola
whose means over steps n, n-1, n-2 are d_n, d_{n-1}, d_{n-2} (:func:`slope_weights`; c_n second-order
accurate, one-sided; step 2: c_2 = 2 (d_2 - d_1) / (h_2 + h_1), step 1: c_1 = 0; q_n = 0 on steps 1, 2).
The newest step uses the exact kernel with all three terms (weights int_0^h k, int_0^h k(x) (h/2 - x) dx
and int_0^h k(x) ((x - h/2)^2 - h^2/12) dx); older steps, with the linear part d_j + c_j (tau - mid_j),
live in one variable per exponential mode,

.. math:: P_k(t_{n-1}) = \\sum_{j<n} e^{-\\beta_k (t_{n-1} - t_j)} (d_j G^A_{l_j,k} + c_j G^B_{l_j,k}),

decayed by R_{l,k} = e^{-beta_k h_l} to the new node. A trial step changes nothing until it is
accepted, so a rejection needs no roll-back.

Why these terms: with first-order slopes (the direct scheme's c_n = 2 (d_n - d_{n-1}) / (h_n + h_{n-1}))
the error expands in h^2 (the trapezoidal rule), h^2.5 and h^3 (the slope's O(h) error, and the
parabola's remainder against a t^-1/2 kernel near lag 0); the second-order slope and the newest step's
curvature term remove them, and on the method's graded grids the error is h^2 + h^3.5 + h^4
(``vcor.solvers.adaptive.RICHARDSON_EXPONENTS``; docs/theory.md).

The cubic specialisation (``singular``: kernels with a t^-1/2 singularity, the fractional and CERF laws;
numba compiles it as a second specialisation, and prunes it from the plain march of the other kernels):
while u' > 0 the newest step's u' is the cubic d_n + c_n x + q_n (x^2 - h^2/12) + r_n (x^3 - 0.15 h^2 x)
(x = tau - mid_n) whose means over steps n..n-3 are d_n..d_{n-3} (:func:`cubic_weights`), with the exact
weight int_0^h k(x) P3(h/2 - x) dx of its cubic term; the start is graded (a step grows only while it
stays <= t / GRADE) and steps do not grow while unloading. The h^3.5 term of the error is then small
enough for three grids (h^2, h^4: ``vcor.solvers.adaptive.CUBIC``). The NumPy reference
(:func:`vcor.solvers.reference.adaptive_reference`) has it too (``reference.mean_cubic``, a 4 x 4 solve, and
the cubic weight by adaptive quadrature).
"""

from __future__ import annotations

import math

import numpy as np

from ._jit import jit, jit_inline, jit_sum
from ._records import (
    DECAYED,
    FROZEN,
    LAST,
    LEVEL,
    LOADED,
    MOTION_FLOOR,
    REJECTED,
    SEPARATION,
    STATUS,
    STATUS_END,
    STATUS_FULL,
    STATUS_RUNNING,
    STATUS_SEPARATED,
    WAIVED,
    AdaptiveControl,
    Body,
    Grids,
    LevelTables,
    Modes,
    Plate,
    Stop,
)
from ._separation import locate_separation
from ._step import advance, implicit_step_inline, separated
from .erfcx import erfcx_slope

__all__ = ["FEW_MODES", "GRADE", "UNLOAD_HOLD", "adaptive_grids", "cubic_weights", "force_zero_cor", "march_adaptive",
           "slope_weights"]

#: sums over more modes than this go through the helpers below, whose additions may be reassociated
#: (``_jit.jit_sum``: numba then vectorises them); shorter sums stay in the march (a call costs more
#: than it saves)
FEW_MODES = 8
_NO_VOLTERRA = (0.0, 0.0, 0.0)
#: kernels with a t^-1/2 singularity (march_adaptive's ``singular``): a step grows only while it stays <= t / GRADE
#: (a graded start: near t = 0, u' ~ t^1/2, whose error the cubic does not remove on steps comparable to t)
GRADE = 4.0
#: ... and its steps do not grow while unloading before UNLOAD_HOLD contact-time estimates
UNLOAD_HOLD = 2.0


@jit
def march_adaptive(nodes, levels, tables, plate, body, control, stop, modes, state, plan, row_offset, singular):
    """Variable-step march with an exponential-sum history (module docstring); resumable.

    The records (nodes, tables, plate, body, control, stop, modes) arrive as plain tuples (``_records``).

    Parameters
    ----------
    nodes : Nodes
        t, s, g, F, J, u, filled in place from node state[LAST] + 1 (node 0: t = s = F = J = u = 0, g = v0).
    levels : int64 array
        The level of each accepted step (levels[n] for step n).
    tables : LevelTables
        Per level: steps, weights of the newest step and of each mode, decays, live modes; the newest
        step's weight of the cubic term, int_0^h k(x) P3(h/2 - x) dx, P3(z) = z^3 - 0.15 h^2 z
        (N m^-1.5 s^4), is read only with ``singular`` (else empty).
    plate : Plate
        The plate's mobility: kind 0, constant; 1, E_b(t) on exponential modes with their own decay
        table (the kernel's, when the plate is of the contact's material); 2 and 3, in closed form.
    body : Body
    control : AdaptiveControl
    stop : Stop
    modes : Modes
        history P_k (N, one per kernel mode) and plate X_k = exp(-b_k t) (one per plate mode), whole
        on entry and on return.
    state : int64 array
        [loaded, separation, last, status, rejected, waived, level, frozen] (``_records``); set the
        level to the first step's before the first call.
    plan : int64 array
        Levels of the first len(plan) steps (a replay of a grid: no error control, no separation
        refinement); after the plan the march goes on with error control from the plan's last level.
    row_offset : int
        Level l uses table row l + row_offset (the tables of the Richardson grids are shifted copies).
    singular : None or True
        None for a kernel without a t^-1/2 singularity: numba prunes every branch below that tests it, so
        those kernels run the plain march. True (a second specialisation): the newest step's u' gets a
        cubic term while u' > 0 (the cubic through the means of the last four steps, :func:`cubic_weights`),
        the start is graded (a step grows only while it stays <= t / GRADE) and steps do not grow while
        unloading (module docstring: the cubic specialisation).

    Notes
    -----
    Decayed modes: on level l only the first live_modes[l] modes have a decay >= DECAYED over one step,
    so a step touches only those. A mode k >= live_modes[l] after an accepted step on level l holds that
    step's contribution alone: P_k = d G^A + c G^B, kept implicit (the last step's d, c and level) and
    written into P when a finer step needs the mode again, and for every mode before returning. Plate
    factors X_k below DECAYED are zero from then on (t only grows).

    Plate mobility (kind 1): alpha = scale / sqrt(E_b), E_b(t) = factor (e_inf + sum moduli_k X_k),
    X_k = exp(-b_k t) carried with the plate's decays (rate_moduli = b_k moduli_k); kinds 2 and 3: the
    fractional and the CERF law in closed form (:func:`_closed_form_mobility`); kind 0: alpha = const.

    Error control (per unit step): est = h^2 |g''| / 12 from the second divided difference of g over
    the last three nodes (the trapezoidal rule's local error is h^3 g''/12) against
    tol = step_tol min(v0, max(|g_n| + s_n / max(t_n, tc), MOTION_FLOOR v0)), the motion's own scale (in
    a long contact the motion falls by orders of magnitude below v0, where an error relative to v0 would
    move the separation time; s_n / t_n is the speed of a creep that has lasted t_n). Reject: down 1..4
    levels, one per factor 4 of est/tol (not below level_floor, where the test is waived). Accept: up
    one level when est < tol/8, two when est < tol/32 (not above level_top). A separation found with
    h_n > sep_fraction t_n is rejected and re-stepped finer; after it the level is frozen for the
    stop.n_extra steps and the ghost continuation to (1 + ghost) t_sep.
    Returns STATUS_FULL with the state intact when the arrays are full.
    """
    tables, plate, body = LevelTables(*tables), Plate(*plate), Body(*body)
    control, stop, modes = AdaptiveControl(*control), Stop(*stop), Modes(*modes)
    t, s, g, F, J, u = nodes
    step, inv_step = tables.step, tables.inv_step
    newest_integral, newest_moment, newest_curvature = (tables.newest_integral, tables.newest_moment,
                                                        tables.newest_curvature)
    newest_cubic = tables.newest_cubic
    mode_integral, mode_moment, mode_decay, live_modes = (tables.mode_integral, tables.mode_moment,
                                                          tables.mode_decay, tables.live_modes)
    P, X = modes.history, modes.plate
    pe, pbe, plate_decay = plate.moduli, plate.rate_moduli, plate.decay
    pscale, pc, pe_inf = plate.scale, plate.factor, plate.e_inf
    m, v0 = body.m, body.v0
    step_tol, inv_tc, sep_frac, ghost = control.step_tol, control.inv_tc, control.sep_fraction, control.ghost
    v0_floor = MOTION_FLOOR * v0
    lev_floor, lev_max, t_horizon = control.level_floor, control.level_top, control.horizon
    inv_m = 1.0 / m
    nk = mode_decay.shape[1]
    nmax = t.shape[0] - 1
    inv_pscale2 = 1.0 / (pscale * pscale) if pscale > 0.0 else 0.0
    trial_history = np.empty(nk)
    trial_plate = np.empty(X.shape[0])
    # P is whole on entry; modes n_explicit.. are implicit after the first accepted step (see Notes)
    n_explicit = nk
    last_d = 0.0
    last_c = 0.0
    last_row = np.int64(0)  # (not a literal 0: numba would compile _fill a second time for it)
    # the cubic specialisation's state (dead, and removed by the compiler, in the plain march)
    prev2_d = 0.0
    prev2_h = 0.0
    k_h0 = -1.0
    k_h1 = -1.0
    k_h2 = -1.0
    k_h3 = -1.0
    kc1 = kc2 = kc3 = kq1 = kq2 = kq3 = 0.0
    k_cs = k_w0 = k_r2 = k_a1 = k_a2 = k_a3 = 0.0
    n_plate = pe.shape[0]
    while n_plate > 1 and X[n_plate - 1] == 0.0:
        n_plate -= 1
    lev = state[LEVEL]
    n = state[LAST] + 1
    # slopes of u and g over the last step (of g also over the one before), 2 / (the two steps' sum)
    last_dg = 0.0
    prev_dg = 0.0
    last_r2 = 0.0
    if n >= 2:
        last_d = (u[n - 1] - u[n - 2]) / (t[n - 1] - t[n - 2])
        last_dg = (g[n - 1] - g[n - 2]) / (t[n - 1] - t[n - 2])
    # mean of u' over the step before the last one; the sizes of the last two accepted steps (t_n are
    # exact, so these are the steps' h); and what depends only on the last three steps' sizes (and so on
    # the newest step's table row), recomputed only when they change: the weights of (d_n, d_{n-1},
    # d_{n-2}) in c_n and q_n, 2 / (h_n + h_{n-1}), and the newest step's weight of u_n
    prev_d = 0.0
    last_h = 0.0
    prev_h = 0.0
    w_h0 = -1.0
    w_h1 = -1.0
    w_h2 = -1.0
    c1 = 0.0
    c2 = 0.0
    q1 = 0.0
    q2 = 0.0
    w_cs = 0.0
    w_qs = 0.0
    w_r2 = 0.0
    w_w0 = 0.0
    w_moment = 0.0
    w_curvature = 0.0
    if n >= 2:
        last_h = t[n - 1] - t[n - 2]
    if n >= 3:
        prev_h = t[n - 2] - t[n - 3]
        prev_dg = (g[n - 2] - g[n - 3]) / (t[n - 2] - t[n - 3])
        last_r2 = 2.0 / (t[n - 1] - t[n - 3])
        prev_d = (u[n - 2] - u[n - 3]) / (t[n - 2] - t[n - 3])
    if singular is not None:  # noqa: SIM102 (numba prunes a branch whose whole condition tests None)
        if n >= 4:
            prev2_h = t[n - 3] - t[n - 4]
            prev2_d = (u[n - 3] - u[n - 4]) / (t[n - 3] - t[n - 4])
    frozen = state[FROZEN] == 1
    state[STATUS] = STATUS_RUNNING
    tol_abs = step_tol * v0
    n_plan = plan.shape[0]
    ahead_t = -1.0
    ahead_alpha = 0.0
    ahead_rate = 0.0
    while n <= nmax:
        planned = n - 1 < n_plan
        if planned:
            lev = plan[n - 1]
        row = lev + row_offset
        h = step[row]
        tn = t[n - 1] + h
        # history of all steps before this one
        n_live = live_modes[row]
        if n_live > n_explicit:
            _fill(P, n_explicit, n_live, last_d, last_c, mode_integral, mode_moment, last_row)
            n_explicit = n_live
        if n_live > FEW_MODES:
            Hh = _decay_sum(mode_decay, row, P, trial_history, n_live)
        else:
            Hh = 0.0
            for k in range(n_live):
                v = mode_decay[row, k] * P[k]
                trial_history[k] = v
                Hh += v
        hp = last_h
        inv_h = inv_step[row]
        # the newest step's force: I d_n + M c_n + Q q_n with c_n = cs d_n + c0, q_n = qs d_n + q0
        # (cs, qs: the weights of d_n; c0, q0: of the older means), d_n = (u_n - u_{n-1}) / h
        if singular is not None and n >= 4 and last_d > 0.0:
            # the cubic through the means of the last four steps (module docstring: the cubic specialisation)
            if h != k_h0 or hp != k_h1 or prev_h != k_h2 or prev2_h != k_h3:
                k_h0, k_h1, k_h2, k_h3 = h, hp, prev_h, prev2_h
                kc1, kc2, kc3, kq1, kq2, kq3, kr1, kr2, kr3 = cubic_weights(h, hp, prev_h, prev2_h)
                k_r2 = 2.0 / (h + hp)
                k_cs = -(kc1 + kc2 + kc3)
                k_m = newest_moment[row]
                k_q = newest_curvature[row]
                k_r = newest_cubic[row]
                k_w0 = (newest_integral[row] + k_cs * k_m - (kq1 + kq2 + kq3) * k_q - (kr1 + kr2 + kr3) * k_r) * inv_h
                # the older means' weights in the force: c0 k_m + q0 k_q + r0 k_r
                k_a1 = kc1 * k_m + kq1 * k_q + kr1 * k_r
                k_a2 = kc2 * k_m + kq2 * k_q + kr2 * k_r
                k_a3 = kc3 * k_m + kq3 * k_q + kr3 * k_r
            r2 = k_r2
            cs = k_cs
            c0 = kc1 * last_d + kc2 * prev_d + kc3 * prev2_d
            w0 = k_w0
            H = Hh - w0 * u[n - 1] + k_a1 * last_d + k_a2 * prev_d + k_a3 * prev2_d
        elif n >= 3:
            if h != w_h0 or hp != w_h1 or prev_h != w_h2:
                w_h0, w_h1, w_h2 = h, hp, prev_h
                c1, c2, q1, q2 = slope_weights(h, hp, prev_h)
                w_r2 = 2.0 / (h + hp)
                w_cs = -(c1 + c2)
                w_qs = -(q1 + q2)
                w_moment = newest_moment[row]
                w_curvature = newest_curvature[row]
                w_w0 = (newest_integral[row] + w_cs * w_moment + w_qs * w_curvature) * inv_h
            r2 = w_r2
            cs = w_cs
            qs = w_qs
            c0 = c1 * last_d + c2 * prev_d
            q0 = q1 * last_d + q2 * prev_d
            w0 = w_w0
            H = Hh - w0 * u[n - 1] + c0 * w_moment + q0 * w_curvature
        else:
            if n == 2:
                r2 = 2.0 / (h + hp)
                cs = r2
                c0 = -r2 * last_d
            else:
                r2 = 0.0
                cs = 0.0
                c0 = 0.0
            qs = 0.0
            q0 = 0.0
            w0 = (newest_integral[row] + cs * newest_moment[row] + qs * newest_curvature[row]) * inv_h
            H = Hh - w0 * u[n - 1] + c0 * newest_moment[row] + q0 * newest_curvature[row]
        if plate.kind == 1:
            if n_plate > FEW_MODES:
                eb, ebd = _plate_sums(plate_decay, row, X, trial_plate, pe, pbe, n_plate)
                eb = pc * (pe_inf + eb)
                ebd = -pc * ebd
            else:
                eb = pe_inf
                ebd = 0.0
                for k in range(n_plate):
                    x = plate_decay[row, k] * X[k]
                    trial_plate[k] = x
                    eb += pe[k] * x
                    ebd -= pbe[k] * x
                eb *= pc
                ebd *= pc
            a_n = pscale / math.sqrt(eb)
            ad_n = -0.5 * a_n * a_n * a_n * ebd * inv_pscale2  # 1 / eb = alpha^2 / pscale^2
        elif plate.kind >= 2:
            # the roots and the division are a long chain: computed one step ahead, for the step on the
            # same level (or the plan's next one), while this step's Newton iteration runs
            if tn == ahead_t:
                a_n = ahead_alpha
                ad_n = ahead_rate
            else:
                a_n, ad_n = _closed_form_mobility(tn, plate)
            ahead_t = tn + step[(plan[n] if n < n_plan else lev) + row_offset]
            ahead_alpha, ahead_rate = _closed_form_mobility(ahead_t, plate)
        else:
            a_n = plate.const
            ad_n = 0.0
        # predictor: g extrapolated by the parabola through the last three nodes (a line through two);
        # the slopes of g over the last two steps and 2 / (their sum) are carried from their acceptance
        # (divisions are the march's bottleneck)
        g_guess = g[n - 1]
        if n >= 2:
            g_guess += h * last_dg
            if n >= 3:
                g_guess += 0.5 * h * (h + hp) * (last_dg - prev_dg) * last_r2
        sn, gn, Fn, un, Jn, ok = implicit_step_inline((s[n - 1], g[n - 1], u[n - 1], F[n - 1], J[n - 1]), H, w0,
                                                      body, _NO_VOLTERRA, (a_n, ad_n), inv_m, h, v0 * h, g_guess)
        # local error estimate and step control
        est = -1.0
        if not frozen and not planned and ok and n >= 2 and math.isfinite(gn):
            creep = abs(sn) * (inv_tc if tn * inv_tc <= 1.0 else 1.0 / tn)  # s / max(t, tc): no division in t < tc
            tol_abs = step_tol * min(v0, max(abs(gn) + creep, v0_floor))
            dd = ((gn - g[n - 1]) * inv_h - last_dg) * r2
            est = h * h * abs(dd) * (1.0 / 12.0)
            if est > tol_abs and lev > lev_floor:
                drop = 1
                ratio = est / tol_abs
                while drop < 4 and ratio > 4.0 ** drop and lev - drop > lev_floor:
                    drop += 1
                lev -= drop
                state[LEVEL] = lev
                state[REJECTED] += 1
                continue
            if est > tol_abs:
                state[WAIVED] += 1
        elif not frozen and not planned and not ok and lev > lev_floor:
            lev -= 1
            state[LEVEL] = lev
            state[REJECTED] += 1
            continue
        # separation found on a coarse step: re-step finer
        if (not frozen and not planned and state[SEPARATION] < 0 and state[LOADED] == 1
                and separated(stop.rule, state[LOADED] == 1, Fn, sn) and h > sep_frac * tn and lev > lev_floor):
            lev -= 1
            state[LEVEL] = lev
            state[REJECTED] += 1
            continue
        # accept
        t[n] = tn
        s[n] = sn
        g[n] = gn
        F[n] = Fn
        u[n] = un
        J[n] = Jn
        levels[n] = lev
        d = (un - u[n - 1]) * inv_h
        c = cs * d + c0
        prev_dg = last_dg
        last_dg = (gn - g[n - 1]) * inv_h
        last_r2 = r2
        for k in range(n_live):
            P[k] = trial_history[k] + d * mode_integral[row, k] + c * mode_moment[row, k]
        if singular is not None:
            prev2_d = prev_d
            prev2_h = prev_h
        n_explicit = n_live
        prev_d = last_d
        last_d = d
        last_c = c
        last_row = row
        prev_h = last_h
        last_h = h
        if plate.kind == 1:
            for k in range(n_plate):
                X[k] = trial_plate[k]
            while n_plate > 1 and X[n_plate - 1] < DECAYED:
                X[n_plate - 1] = 0.0
                n_plate -= 1
        if advance(state, n, ok, sn, gn, Fn, stop):
            if state[STATUS] != STATUS_SEPARATED or tn >= t[state[SEPARATION]] * (1.0 + ghost):
                _fill(P, n_explicit, nk, last_d, last_c, mode_integral, mode_moment, last_row)
                return
            state[STATUS] = STATUS_RUNNING
        if state[SEPARATION] >= 0:
            frozen = True
            state[FROZEN] = 1
        elif est >= 0.0:
            # grow, from the estimate of this accepted step
            up = 0
            if singular is None:
                while up < 2 and est * 4.0 ** (up + 1) < 0.5 * tol_abs and lev + up + 1 <= lev_max:
                    up += 1
            else:
                # graded start (near t = 0, u' ~ t^1/2), and no growth while unloading within UNLOAD_HOLD
                # contact-time estimates (steps grown there leave the coarse grids a t0 and COR error that is
                # not yet asymptotic: up to 1.1e-7 on plates; a long creep, as on a thin plate, grows)
                while (up < 2 and (gn >= 0.0 or tn * inv_tc > UNLOAD_HOLD) and est * 4.0 ** (up + 1) < 0.5 * tol_abs
                       and lev + up + 1 <= lev_max and step[lev + up + 1 + row_offset] * GRADE <= tn):
                    up += 1
            lev += up
            state[LEVEL] = lev
        if tn >= t_horizon:
            state[STATUS] = STATUS_END
            _fill(P, n_explicit, nk, last_d, last_c, mode_integral, mode_moment, last_row)
            return
        n += 1
    state[STATUS] = STATUS_FULL
    _fill(P, n_explicit, nk, last_d, last_c, mode_integral, mode_moment, last_row)


@jit_inline
def slope_weights(h0, h1, h2):
    """(c1, c2, q1, q2): the slope c and half the curvature q, at the middle of the newest of three
    consecutive steps of sizes h2, h1, h0 (oldest first, s), of the parabola p(tau) = d0 + c (tau - mid)
    + q ((tau - mid)^2 - h0^2/12) whose means over the three steps are d0, d1, d2:
    c = c1 (d1 - d0) + c2 (d2 - d0), q = q1 (d1 - d0) + q2 (d2 - d0) (1/s and 1/s^2).

    The mean of p over a step of size h_j whose middle is e_j before mid is d0 - c e_j + q a_j with
    a_j = e_j^2 + (h_j^2 - h0^2) / 12; e_1 = (h0 + h1) / 2, e_2 = e_1 + (h1 + h2) / 2. Equal steps h:
    c = (3 d0 - 4 d1 + d2) / (2 h), q = (d0 - 2 d1 + d2) / (2 h^2)."""
    e1 = 0.5 * (h0 + h1)
    e2 = e1 + 0.5 * (h1 + h2)
    a1 = e1 * e1 + (h1 * h1 - h0 * h0) * (1.0 / 12.0)
    a2 = e2 * e2 + (h2 * h2 - h0 * h0) * (1.0 / 12.0)
    # d_j - d0 = -c e_j + q a_j (j = 1, 2), solved for c and q
    inv = 1.0 / (e1 * a2 - e2 * a1)
    return -a2 * inv, a1 * inv, -e2 * inv, e1 * inv


@jit_inline
def cubic_weights(h0, h1, h2, h3):
    """(c1, c2, c3, q1, q2, q3, r1, r2, r3): c, q, r of p(x) = d0 + c x + q (x^2 - h0^2/12)
    + r (x^3 - 0.15 h0^2 x) (x = tau - mid of the newest step, size h0) whose means over the newest and the
    three steps before it (sizes h1, h2, h3) are d0..d3: c = sum_j cj (d_j - d0), likewise q, r.
    Mean over step j (middle e_j before mid): d0 - c e_j + q a_j + r b_j,
    a_j = e_j^2 + (h_j^2 - h0^2)/12, b_j = -e_j^3 - e_j h_j^2/4 + 0.15 h0^2 e_j."""
    e1 = 0.5 * (h0 + h1)
    e2 = e1 + 0.5 * (h1 + h2)
    e3 = e2 + 0.5 * (h2 + h3)
    g = h0 * h0
    a1 = e1 * e1 + (h1 * h1 - g) * (1.0 / 12.0)
    a2 = e2 * e2 + (h2 * h2 - g) * (1.0 / 12.0)
    a3 = e3 * e3 + (h3 * h3 - g) * (1.0 / 12.0)
    b1 = e1 * (0.15 * g - e1 * e1 - 0.25 * h1 * h1)
    b2 = e2 * (0.15 * g - e2 * e2 - 0.25 * h2 * h2)
    b3 = e3 * (0.15 * g - e3 * e3 - 0.25 * h3 * h3)
    # M = [[-e1, a1, b1], [-e2, a2, b2], [-e3, a3, b3]]; (c, q, r) = M^-1 (d1 - d0, d2 - d0, d3 - d0)
    m00, m01, m02 = -e1, a1, b1
    m10, m11, m12 = -e2, a2, b2
    m20, m21, m22 = -e3, a3, b3
    C00 = m11 * m22 - m12 * m21
    C01 = -(m10 * m22 - m12 * m20)
    C02 = m10 * m21 - m11 * m20
    C10 = -(m01 * m22 - m02 * m21)
    C11 = m00 * m22 - m02 * m20
    C12 = -(m00 * m21 - m01 * m20)
    C20 = m01 * m12 - m02 * m11
    C21 = -(m00 * m12 - m02 * m10)
    C22 = m00 * m11 - m01 * m10
    inv = 1.0 / (m00 * C00 + m01 * C01 + m02 * C02)
    # inverse = adjugate / det, adjugate = cofactor transpose: row i of the inverse = (C0i, C1i, C2i)
    return (C00 * inv, C10 * inv, C20 * inv, C01 * inv, C11 * inv, C21 * inv, C02 * inv, C12 * inv, C22 * inv)


@jit_inline
def _closed_form_mobility(t, plate):
    """(alpha, alpha') at t of a plate whose modulus is in closed form.

    Kind 2, the fractional law, E_b = factor (e_inf + coef t^-1/2): with D = E_b t^1/2 and
    y = 1 / (D t), alpha = scale (t^1/2 / D)^1/2 = scale (t^1/2 y t)^1/2 and
    alpha' = alpha factor coef / (4 D t) (one division, two roots).

    Kind 3, the CERF law, E_b = factor (e_inf + coef erfcx(x)), x = rate t^1/2: with
    erfcx'(x) = 2 x erfcx(x) - 2 / sqrt(pi) (:func:`vcor.solvers.erfcx.erfcx_slope`: a piecewise
    polynomial, without the cancellation at large x) and dx/dt = x / (2 t), alpha = scale E_b^-1/2 and
    alpha' = -alpha E_b' / (2 E_b)."""
    rt = math.sqrt(t)
    if plate.kind == 2:
        y = 1.0 / (plate.factor * (plate.e_inf * rt + plate.coef) * t)
        a = plate.scale * math.sqrt(rt * y * t)
        return a, 0.25 * a * plate.factor * plate.coef * y
    x = plate.rate * rt
    ex, slope = erfcx_slope(x)
    eb = plate.factor * (plate.e_inf + plate.coef * ex)
    a = plate.scale / math.sqrt(eb)
    rate_eb = plate.factor * plate.coef * slope * plate.rate / (2.0 * rt) if t > 0.0 else 0.0
    return a, -0.5 * a * rate_eb / eb


@jit
def force_zero_cor(t0, z0, plate, m, v0):
    """The COR |s'(t0)| / v0 of a separation where the force returns to zero (rule "force"), from the
    model's s' = v0 - J/m - alpha' J - alpha F at F(t0) = 0: s'(t0) = z0 - alpha'(t0) J0 with the sphere's
    velocity z0 = v0 - J0/m (m/s) and alpha' of the march's ``plate`` record (a plain tuple, ``_records``)
    at t0 (s). J is smooth where F vanishes and stationary there (J' = F), so this s'(t0) does not inherit
    the error of t0 or of a cubic through s' (whose alpha F part is as rough as F: F ~ u = s^3/2 falls
    steeply where a nearly elastic contact leaves a small residual overlap)."""
    return abs(z0 - _mobility_rate(t0, Plate(*plate)) * m * (v0 - z0)) / v0


@jit_inline
def _mobility_rate(t, plate):
    """alpha'(t) (m N^-1 s^-2) of a :class:`~._records.Plate` (kind 1: from its modes' moduli and rates;
    kinds 2, 3: :func:`_closed_form_mobility`; kind 0: constant)."""
    if plate.kind == 0 or t <= 0.0:
        return 0.0
    if plate.kind >= 2:
        return _closed_form_mobility(t, plate)[1]
    eb = plate.e_inf
    ebd = 0.0
    for k in range(plate.moduli.shape[0]):
        if plate.moduli[k] != 0.0:
            x = math.exp(-(plate.rate_moduli[k] / plate.moduli[k]) * t)
            eb += plate.moduli[k] * x
            ebd -= plate.rate_moduli[k] * x
    eb *= plate.factor
    ebd *= plate.factor
    a = plate.scale / math.sqrt(eb)
    return -0.5 * a * ebd / eb


@jit_sum
def _decay_sum(R, row, P, trial, n_live):
    """trial[:n_live] = R[row] P (the modes decayed over a trial step) and their sum, in any order (rows
    indexed, not sliced: a row view costs two reference-count calls)."""
    acc = 0.0
    for k in range(n_live):
        v = R[row, k] * P[k]
        trial[k] = v
        acc += v
    return acc


@jit_sum
def _plate_sums(R, row, X, trial, pe, pbe, n_plate):
    """trial[:n_plate] = R[row] X (the plate's exp(-beta t) at the trial node) and the sums of pe trial
    and pbe trial (transient of E_b and minus its rate, before the factor), in any order."""
    eb = 0.0
    ebd = 0.0
    for k in range(n_plate):
        x = R[row, k] * X[k]
        trial[k] = x
        eb += pe[k] * x
        ebd += pbe[k] * x
    return eb, ebd


@jit
def _fill(P, k0, k1, d, c, GA, GB, row):
    """P[k0:k1] = the last accepted step's own contribution (modes that had decayed on its level; its
    table row ``row``)."""
    for k in range(k0, k1):
        P[k] = d * GA[row, k] + c * GB[row, k]


@jit
def _node_arrays(n):
    """Six uninitialised node arrays (t, s, s', F, J, u) of length n."""
    return np.empty(n), np.empty(n), np.empty(n), np.empty(n), np.empty(n), np.empty(n)


@jit
def adaptive_grids(grids, tables, plate, body, control, stop, max_steps, start_level, size0, out, singular):
    """The adaptive march (:func:`march_adaptive`), then (grids.n_grids > 1) its replays with every step
    divided by 2, 4, ... 2^(n_grids - 1), and the separation of each, in one call (no histories).

    The records arrive as plain tuples (``_records``) and are passed on so. ``grids``
    (:class:`~._records.Grids`): the tables have level_top + 1 + ``splits`` rows from h_base / 2^splits, grid
    k uses rows from splits - k; when the first grid's largest step is at most ``smooth_step`` (s), one
    grid fewer is marched (``vcor.solvers.adaptive.grid_count``; 0: never). ``singular``:
    :func:`march_adaptive`'s.
    Fills out[k] = [the 9 outcome values of ``separation_point`` (under the force rule the COR by
    :func:`force_zero_cor`), separation index, largest step (s)]
    and returns the number of grids marched when every grid separated, the first within ``size0``
    steps; 0 (out undefined) for anything else (more steps, divergence, time horizon, step budget),
    which the caller then runs through the general path.
    """
    n_grids, splits, smooth_step = Grids(*grids)
    nk = LevelTables(*tables).mode_decay.shape[1]
    n_extra, rule, glassy = Stop(*stop).n_extra, Stop(*stop).rule, Stop(*stop).glassy
    v0, m = Body(*body).v0, Body(*body).m
    pr = Plate(*plate)
    # a constant mobility: no mode changes in time (a mode of rate 0, as in SLS(E, 0, 0), is a constant)
    still = pr.kind == 0 or (pr.kind == 1 and not np.any(pr.rate_moduli != 0.0))
    n_plan = 0
    # the march writes node n before anything reads it, and reads nothing beyond the last node: the
    # arrays need only their first node set; the replays reuse the first grid's node arrays when they
    # fit (their levels go to ``lev``: the first grid's, ``base``, are the plan)
    base = np.empty(size0 + 1, dtype=np.int64)
    t, s, g, F, J, u = _node_arrays(size0 + 1)
    lev = base
    P = np.empty(nk)
    X = np.empty(Plate(*plate).moduli.shape[0])
    state = np.empty(8, dtype=np.int64)
    k = 0
    while k < n_grids:
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
        state[SEPARATION] = -1
        state[LEVEL] = start_level
        e = size + 1  # the march fills at most ``size`` steps (views: no copies)
        march_adaptive((t[:e], s[:e], g[:e], F[:e], J[:e], u[:e]), lev[:e], tables, plate, body, control, stop,
                       (P, X), state, plan, splits - k, singular)
        if state[STATUS] != STATUS_SEPARATED:
            return 0
        n_sep = state[SEPARATION]
        n_done = state[LAST]
        if k == 0:
            n_plan = min(n_done, n_sep + n_extra)
        if not locate_separation((t, s, g, F, J, u), n_sep, n_done + 1, rule == 1, body, still, glassy, out[k]):
            return 0
        if rule == 0:
            out[k, 0] = force_zero_cor(out[k, 1], out[k, 5], plate, m, v0)
        out[k, 9] = n_sep
        big = 0.0
        for j in range(1, n_done + 1):
            big = max(big, t[j] - t[j - 1])
        out[k, 10] = big
        if k == 0 and n_grids > 1 and big <= smooth_step:
            n_grids -= 1
        k += 1
    return n_grids
