"""Direct (full-history) solver, numba, any kernel; and the paper-like explicit baseline.

See ``_fixed_kernels`` for the discretisation. This module prepares the weights (exact kernel step
integrals and first moments) and runs the march through :mod:`.march` (T_max extension, ghost
continuation, post-processing).
"""

from __future__ import annotations

import math
import time

import numpy as np

from ._fixed_kernels import march_direct, march_paper
from ._records import (
    LAST,
    STATUS,
    STATUS_END,
    Body,
    PlateArrays,
    Stop,
    Volterra,
    fixed_state,
)
from .applicability import PAPER_NO_DIRAC, form_b_singular
from .march import Arrays, March, drive, finish, step_plan

__all__ = ["folded_weights", "kernel_weights", "run_direct", "run_paper", "solve", "solve_paper", "volterra_weights"]


def solve(impact, options, tc, history):
    """Runner of method ``direct`` (``vcor.solvers.simulate.METHODS``)."""
    plan = step_plan(impact, options, tc, linear=False)
    return run_direct(impact, plan.dt, plan.n_steps, max_steps=plan.max_steps, rule=options.rule,
                      volterra=options.volterra, c2=options.c2 if options.volterra else 0.0, form=options.form,
                      history=history, ghost=options.ghost)


def solve_paper(impact, options, tc, history):
    """Runner of method ``paper``, the explicit baseline (histories end at the separation: no ghost)."""
    plan = step_plan(impact, options, tc, linear=False)
    return run_paper(impact, plan.dt, plan.n_steps, max_steps=plan.max_steps, rule=options.rule, history=history)


def kernel_weights(impact, dt, n):
    """Folded weights (wt, v) of the quadratic product integration (see ``_fixed_kernels``), N m^-1.5."""
    return folded_weights(impact.material, impact.kappa, dt, n)


def folded_weights(material, kappa, dt, n):
    """Folded weights (wt, v) of ``material`` scaled by the contact stiffness ``kappa`` (m^0.5)."""
    w = kappa * material.step_integrals(dt, n) / dt
    v = -kappa * material.step_moments(dt, n) / dt**2
    wt = w + v
    wt[1:] -= v[:-1]
    return wt, v


def volterra_weights(impact, dt, n):
    """Q_c = double cell integrals of k: K2((c+1)dt) - 2 K2(c dt) + K2((c-1)dt), c = 0..2n."""
    nodes = dt * np.arange(2 * n + 2, dtype=float)
    k2 = impact.kappa * impact.material.antiderivative(nodes, 2)
    q = np.zeros(2 * n + 1)
    q[1:] = k2[2:] - 2.0 * k2[1:-1] + k2[:-2]
    return q


def run_direct(impact, dt, n_steps, *, max_steps, rule="force", volterra=False, c2=1.0, form="a",
               history=False, ghost=0.0):
    """Direct scheme, any kernel (O(N^2); the Volterra term keeps O(N^2))."""
    mat = impact.material
    eta = impact.kappa * mat.viscosity
    if form == "b":
        if not math.isfinite(mat.glassy):
            raise ValueError(form_b_singular(mat.kind))
        if volterra:
            raise ValueError("volterra=True is implemented for form 'a' (h2 = c2 k(t1 + t2)) only")
    cache = {}
    body = tuple(Body(float(eta), float(impact.m), float(impact.v0)))

    def step_fn(n0, n1, arr, plate, state, n_extra):
        if cache.get("n") != arr.n:
            cache["n"] = arr.n
            cache["w"], cache["v"] = (_form_b_weights if form == "b" else kernel_weights)(impact, dt, arr.n)
            if volterra:
                q2 = volterra_weights(impact, dt, arr.n)
                s2 = np.zeros(2 * arr.n + 1)
                if "S2" in cache:
                    s2[: cache["S2"].size] = cache["S2"]
                cache["Q2"], cache["S2"] = q2, s2
            else:
                cache["Q2"] = cache["S2"] = np.zeros(1)
        march_direct(n0, n1, arr.nodes(), (cache["w"], cache["v"]),
                     tuple(Volterra(bool(volterra), float(c2), cache["Q2"], cache["S2"])), plate, body, dt,
                     tuple(Stop(0 if rule == "force" else 1, n_extra)), state)

    t_start = time.perf_counter()
    march = drive(impact, dt, n_steps, max_steps, ghost if history else 0.0, step_fn)
    march.wall = time.perf_counter() - t_start
    name = f"direct-{form}" + ("+volterra" if volterra else "")
    return finish(impact, march, rule=rule, history=history, method=name)


def _form_b_weights(impact, dt, n):
    """Form b: F_n = k(0) u_n + sum_j int phi_j(tau) kdot(t_n - tau) d tau u_j (phi_j: hat functions).

    Integrating kdot against the hat functions exactly (by parts, from k at the nodes and the step
    integrals of k) and regrouping into increments of u gives weights for the same march. With the
    same piecewise-linear u this is algebraically the linear product integration of form a; the
    direct form a adds the quadratic correction, so the two are different O(dt^2) discretisations
    and their agreement is a real check.
    """
    mat = impact.material
    nodes = dt * np.arange(n + 1, dtype=float)
    k = impact.kappa * mat.relaxation_modulus(nodes)
    W = impact.kappa * mat.step_integrals(dt, n)  # int over step i of k
    # int_{i dt}^{(i+1)dt} kdot(sigma) (linear weight) -> contributions to u_j coefficients:
    # c_i^- = int kdot (sigma - i dt)/dt = k_{i+1} - W_i/dt,  c_i^+ = int kdot ((i+1)dt - sigma)/dt = W_i/dt - k_i
    cm = k[1:] - W / dt
    cp = W / dt - k[:-1]
    # F_n = k0 u_n + sum_{i} [c_i^+ u_{n-i} + c_i^- u_{n-1-i}] (sigma = t_n - tau)
    # coefficient of u_{n-l}: a_0 = k0 + c_0^+, a_l = c_l^+ + c_{l-1}^- (l >= 1)
    a = np.empty(n + 1)
    a[0] = k[0] + cp[0]
    a[1:n] = cp[1:] + cm[:-1]
    a[n] = cm[-1]
    # sum_l a_l u_{n-l} = sum_j du_j w_{n-1-j} with w_i = sum_{l <= i} a_l (u_0 = 0)
    return np.cumsum(a)[:n], np.zeros(n)


def run_paper(impact, dt, n_steps, *, max_steps, rule="force", history=False):
    """The paper-like explicit baseline (see ``_fixed_kernels.march_paper``); for benchmarks only."""
    if impact.material.viscosity > 0:
        raise ValueError(PAPER_NO_DIRAC)
    t_start = time.perf_counter()
    body = tuple(Body(0.0, float(impact.m), float(impact.v0)))
    n = n_steps
    while True:
        t = dt * np.arange(n + 1)
        kc = impact.kernel(np.maximum(t, dt))  # clamped kernel, k(max(sigma, dt))
        arr = Arrays(n)
        state = fixed_state()
        march_paper(n, arr.nodes(), kc, tuple(PlateArrays(impact.alpha(t), impact.alpha_rate(t))), body, dt,
                    tuple(Stop(0 if rule == "force" else 1, 2)), state)
        if state[STATUS] != STATUS_END or n >= max_steps:
            break
        n = min(2 * n, max_steps)
    march = March(arrays=arr, state=state, n_done=int(state[LAST]), dt=dt, wall=time.perf_counter() - t_start,
                  budget=f"stopped by the step budget before a verdict ({n} steps of dt = {dt:.3g} s, max_steps "
                         f"{max_steps}); method paper is a benchmark baseline: use method adaptive")
    return finish(impact, march, rule=rule, history=history, method="paper-explicit")
