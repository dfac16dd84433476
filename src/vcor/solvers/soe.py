"""The ``soe`` method: the direct scheme's numbers at internal-variable cost, for every kernel.

The hereditary force is the direct scheme's product integration (quadratic u, second order for
every kernel, ``_fixed_kernels``) split in two: the last ``N_LOCAL`` + 1 steps use the exact kernel's step
integrals (the local part, which holds the t^-1/2 singularity of the fractional law); older history
uses the weights of the kernel's exponential sum (:func:`vcor.materials.expsums.soe` on
[(N_LOCAL + 1) dt, budget], relative error <= ``tol``), one recursive variable per exponential.
Cost per step O(N_LOCAL + K) instead of O(n). For Prony kernels the sum is exact, so ``soe`` and
``direct`` agree to rounding.
"""

from __future__ import annotations

import time

import numpy as np

from ..materials.expsums import soe
from ._fixed_kernels import march_soe
from ._records import Body, ExponentialModes, Stop
from .direct import folded_weights
from .march import drive, finish, step_plan

__all__ = ["N_LOCAL", "run_soe", "solve"]

#: steps of exact local history (lags 0..N_LOCAL)
N_LOCAL = 8


def solve(impact, options, tc, history):
    """Runner of method ``soe`` (``vcor.solvers.simulate.METHODS``)."""
    plan = step_plan(impact, options, tc, linear=True)
    return run_soe(impact, plan.dt, plan.n_steps, max_steps=plan.max_steps, rule=options.rule, history=history,
                   ghost=options.ghost, tol=options.soe_tol)


def mode_weights(material, kappa, dt, tol, t_max):
    """(c, vc, r, error) of the exponential sum of ``material`` on [(N_LOCAL + 1) dt, t_max]: per mode its
    folded weights at lag N_LOCAL + 1 (as in ``direct.folded_weights``) and r = exp(-beta dt), and the
    sum's checked relative error. The constant E(inf) is a mode with r = 1. Modes decayed before that
    lag are wholly local: dropped."""
    built = soe(material, (N_LOCAL + 1) * dt, max(t_max, 2 * (N_LOCAL + 1) * dt), tol)
    rep = built.material
    lag = N_LOCAL + 1
    w = kappa * rep.term_step_integrals(dt, lag + 1)[lag - 1 :] / dt  # lags L, L + 1
    v = -kappa * rep.term_step_moments(dt, lag + 1)[lag - 1 :] / dt**2
    c = np.concatenate(([kappa * rep.E_inf], w[1] + v[1] - v[0]))
    vc = np.concatenate(([0.0], v[1]))
    r = np.concatenate(([1.0], np.exp(-np.asarray(rep.beta, dtype=float) * dt)))
    keep = (c != 0.0) | (vc != 0.0)
    return c[keep], vc[keep], r[keep], built.checked_error


def run_soe(impact, dt, n_steps, *, max_steps, rule="force", history=False, ghost=0.0, tol=1e-10):
    """Fixed-step march with an exponential-sum history (see the module docstring)."""
    mat = impact.material
    eta = impact.kappa * mat.viscosity
    t_start = time.perf_counter()
    wt, v = folded_weights(mat, impact.kappa, dt, N_LOCAL + 1)
    horizon = (max_steps + 8) * dt * (1.0 + max(ghost, 0.0) if history else 1.0)
    c, vc, r, soe_error = mode_weights(mat, impact.kappa, dt, tol, horizon)
    modes = tuple(ExponentialModes(c, vc, r, np.zeros(c.size), np.zeros(c.size)))
    body = tuple(Body(float(eta), float(impact.m), float(impact.v0)))

    def step_fn(n0, n1, arr, plate, state, n_extra):
        march_soe(n0, n1, arr.nodes(), (wt, v, N_LOCAL), modes, plate, body, dt,
                  tuple(Stop(0 if rule == "force" else 1, n_extra)), state)

    march = drive(impact, dt, n_steps, max_steps, ghost if history else 0.0, step_fn)
    march.wall = time.perf_counter() - t_start
    march.soe_error = soe_error
    return finish(impact, march, rule=rule, history=history, method="soe")
