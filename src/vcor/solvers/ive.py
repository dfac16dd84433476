"""Internal-variable evolution (IVE) solvers (Green 2026 Eqs. 18-22): scipy's ``solve_ivp``
(``ive``) and the fixed-step exponential update in numba (``ive-numba``, O(N)).

For a Prony kernel k(t) = G_inf + sum_k G_k exp(-b_k t) the force is F = G_inf u + sum_k Q_k with
Q_k' = -b_k Q_k + G_k u', u = s^{3/2}. With s' = v0 - J/m - alpha' J - alpha F and J' = F this is a
system of N + 2 ODEs (plus two quadrature states for W_h and int F z' dt). Separation is a terminal
event on F = 0 (direction -1). The method must be stiff-capable (default "Radau").
"""

from __future__ import annotations

import math
import time

import numpy as np
from scipy.integrate import solve_ivp

from ._fixed_kernels import march_prony
from ._records import Body, Internal, Stop
from .common import Histories, Result, peak
from .march import LINEAR_MAX_T_FACTOR, T_MAX_START, drive, finish, step_plan

__all__ = ["run_ive_fixed", "run_ive_scipy", "solve_fixed", "solve_scipy"]


def solve_fixed(impact, options, tc, history):
    """Runner of method ``ive-numba`` (``vcor.solvers.simulate.METHODS``)."""
    plan = step_plan(impact, options, tc, linear=True)
    return run_ive_fixed(impact, plan.dt, plan.n_steps, max_steps=plan.max_steps, rule=options.rule,
                         history=history, ghost=options.ghost)


def solve_scipy(impact, options, tc, history):
    """Runner of method ``ive`` (scipy ``solve_ivp``; the horizon grows from T_MAX_START to
    LINEAR_MAX_T_FACTOR contact-time estimates)."""
    return run_ive_scipy(impact, rtol=options.rtol, method=options.ive_method, tc=tc, t_max=T_MAX_START * tc,
                         max_t=LINEAR_MAX_T_FACTOR * tc, history=history, ghost=options.ghost, rule=options.rule,
                         volterra=options.volterra, c2=options.c2 if options.volterra else 0.0)


def prony_terms(impact, method):
    """(E_inf, E[], beta[]) of the impact's kernel; ValueError naming the method for other kernels."""
    mat = impact.material
    if not mat.is_prony:
        raise ValueError(f"method {method!r} needs a Prony kernel (sls, butyl-prony3, prony, elastic, "
                         f"kelvin-voigt); got {mat.kind!r}: use method 'direct'")
    return mat.prony_terms()


def run_ive_fixed(impact, dt, n_steps, *, max_steps, rule="force", history=False, ghost=0.0):
    """Internal variables with the fixed-step exponential update (numba, O(N)); Prony kernels."""
    g_inf, e, b = prony_terms(impact, "ive-numba")
    kap = impact.kappa
    bdt = b * dt
    decay = np.exp(-bdt)
    frac = np.where(b > 0, -np.expm1(-bdt) / np.where(bdt > 0, bdt, 1.0), 1.0)
    weight = kap * e * frac
    internal = tuple(Internal(np.zeros(e.size), float(kap * g_inf), kap * e, decay, weight))
    body = tuple(Body(float(kap * impact.material.viscosity), float(impact.m), float(impact.v0)))

    def step_fn(n0, n1, arr, plate, state, n_extra):
        march_prony(n0, n1, arr.nodes(), internal, plate, body, dt, tuple(Stop(0 if rule == "force" else 1, n_extra)),
                    state)

    t_start = time.perf_counter()
    march = drive(impact, dt, n_steps, max_steps, ghost if history else 0.0, step_fn)
    march.wall = time.perf_counter() - t_start
    return finish(impact, march, rule=rule, history=history, method="ive-numba")


def run_ive_scipy(impact, *, rtol=1e-10, method="Radau", tc, t_max, max_t, history=False, ghost=0.0, rule="force",
                  volterra=False, c2=1.0):
    """Internal-variable solver with ``solve_ivp`` (options validated by ``SolverOptions``). With
    ``volterra`` the second-order term for the Prony kernel is separable,
    c2 int int k(t1 + t2) u' u' = c2 (G_inf u^2 + sum_k Q_k^2 / G_k), so it costs nothing and is an
    independent check of the direct solver's O(N^2) Volterra sums."""
    mat = impact.material
    g_inf, e, b = prony_terms(impact, "ive")
    kap = impact.kappa
    G_inf, G = kap * g_inf, kap * e
    eta = kap * mat.viscosity
    m, v0 = impact.m, impact.v0
    nq = e.size
    inv_G = np.where(G > 0, 1.0 / np.where(G > 0, G, 1.0), 0.0)
    alpha = impact.alpha
    mobility = impact.mobility

    def parts(t, y):
        s, J = y[0], y[1]
        Q = y[2 : 2 + nq]
        a = abs(s)
        sq = math.sqrt(a)
        u = math.copysign(a * sq, s)
        p = 1.5 * sq
        al, ald = mobility(t)
        A = G_inf * u + Q.sum()
        if volterra:
            A += c2 * (G_inf * u * u + (Q * Q * inv_G).sum())
        B = v0 - J / m - ald * J
        F = (A + eta * p * B) / (1.0 + eta * p * al)  # Kelvin-Voigt term implicit in g
        g = B - al * F
        return F, g, p, J

    def rhs(t, y):
        F, g, p, J = parts(t, y)
        dy = np.empty_like(y)
        dy[0] = g
        dy[1] = F
        dy[2 : 2 + nq] = -b * y[2 : 2 + nq] + G * p * g
        dy[2 + nq] = F * g
        dy[3 + nq] = F * (v0 - J / m)
        return dy

    def event(t, y):
        return parts(t, y)[0] if rule == "force" else y[0]

    event.terminal = True
    event.direction = -1

    f_scale = impact.m * v0 / tc
    s_scale = v0 * tc
    atol = np.concatenate([[s_scale, m * v0], np.full(nq, f_scale), [0.5 * m * v0**2] * 2]) * rtol * 1e-2
    y0 = np.zeros(4 + nq)
    t_start = time.perf_counter()
    t_end = t_max
    sol = None
    while True:
        # scipy's finite-difference Jacobian (Radau/BDF) probes far enough on very stiff cases to
        # overflow in a product it then discards; the solution is checked for finiteness below
        with np.errstate(over="ignore", invalid="ignore"):
            sol = solve_ivp(rhs, (0.0, t_end), y0, method=method, rtol=rtol, atol=atol, events=event,
                            dense_output=True, max_step=tc / 20)
        if sol.status == 1 or not sol.success or t_end >= max_t:
            break
        t_end = min(2 * t_end, max_t)
    wall = time.perf_counter() - t_start
    res = Result(method=f"ive-{method}" + ("+volterra" if volterra else ""), steps=int(sol.t.size), wall_time=wall, dt=math.nan)
    if not sol.success or not np.all(np.isfinite(sol.y)):
        res.status = "diverged"
        res.message = f"solve_ivp({method}) failed: {sol.message}" if not sol.success else "non-finite state"
        return res
    if sol.status != 1:
        res.status = "step-budget"
        res.message = (f"stopped by the time budget before a verdict: the contact force had not returned to zero "
                       f"at T_max = {t_end:.6g} s")
        return res
    t0 = float(sol.t_events[0][0])
    y = sol.y_events[0][0]
    _F0, g0, _, J0 = parts(t0, y)
    z0 = v0 - J0 / m
    w_h, w_z = y[2 + nq], y[3 + nq]
    e_in = 0.5 * m * v0**2
    # s_max, F_max: the accepted steps bracket the peak, the dense output refines it
    ts = sol.t
    Fs = np.array([parts(tt, yy)[0] for tt, yy in zip(ts, sol.y.T)])
    s_max = peak(ts, sol.y[0], lambda x: sol.sol(x)[0])
    f_max = peak(ts, Fs, lambda x: parts(x, sol.sol(x))[0])
    res.t0 = t0
    res.cor = abs(g0) / v0
    res.s_residual = float(y[0])
    res.w_h = float(w_h)
    res.w_plate = float(w_z - w_h)
    res.omega_min = 2 * math.pi / t0
    res.sphere_velocity = float(z0)
    res.energy_residual = float((e_in - 0.5 * m * z0 * z0 - w_z) / e_in)
    res.s_max = s_max
    res.f_max = f_max
    if history:
        n = max(400, ts.size)
        t1 = t0 * (1.0 + ghost)
        tt = np.linspace(0.0, t0, n)
        Y = sol.sol(tt)
        if ghost > 0:
            # continue past t0 (the "ghost" solution) without the event
            with np.errstate(over="ignore", invalid="ignore"):
                sol2 = solve_ivp(rhs, (t0, t1), y, method=method, rtol=rtol, atol=atol, dense_output=True,
                                 max_step=tc / 20)
            if not sol2.success:
                t1 = float(sol2.t[-1])
                res.message = (f"ghost continuation stopped at t = {t1:.6g} s (requested {t0 * (1 + ghost):.6g} s): "
                               f"solve_ivp({method}): {sol2.message}")
            tg = np.linspace(t0, t1, max(2, int(n * ghost)))[1:]
            tt = np.concatenate([tt, tg])
            Y = np.concatenate([Y, sol2.sol(tg) if sol2.sol is not None else np.full((y.size, tg.size), np.nan)],
                               axis=1)
        PF = np.array([parts(a, yy) for a, yy in zip(tt, Y.T)])
        F, g, J = PF[:, 0], PF[:, 1], Y[1]
        res.history = Histories(t=tt, s=Y[0], sdot=g, F=F, J=J, zdot=v0 - J / m, U=alpha(tt) * J).mark(t0)
    return res
