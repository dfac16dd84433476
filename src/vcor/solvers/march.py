"""Driver of the fixed-step numba marches (direct and internal-variable): arrays, the T_max
extension, the ghost continuation and the post-processing into a :class:`Result`.

Budget and verdicts:

* T_max starts at ``n_steps`` and doubles while the force has not returned to zero, up to
  ``max_steps``. A run that reaches the budget without separating ends with status
  ``step-budget`` (never ``no-separation``: the budget is not a physical verdict).
* A separation found in the last steps before the budget is a separation: the march is always
  allowed the few extra steps that the separation's interpolation needs.
* The ghost continuation (histories only) runs the requested fraction of t0 past separation,
  growing the arrays as needed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ._records import (
    LAST,
    SEPARATION,
    STATUS,
    STATUS_DIVERGED,
    STATUS_END,
    STATUS_SEPARATED,
    FixedNodes,
    PlateArrays,
    fixed_state,
)
from .common import Histories, Result, separation

__all__ = ["LINEAR_MAX_T_FACTOR", "MAX_T_FACTOR", "N_EXTRA", "T_MAX_START", "Arrays", "March", "StepPlan", "default_dt",
           "drive", "finish", "step_plan"]

#: steps marched past the separation step (the cubic separation interpolant needs two)
N_EXTRA = 2
#: T_max starts at this many contact-time estimates and doubles while the impact has not separated
T_MAX_START = 1.5
#: ... up to this many contact-time estimates for the O(N^2) methods (direct, paper)
MAX_T_FACTOR = 32.0
#: ... and this many for the methods whose cost is linear in time (soe, ive-numba, ive): the long
#: contacts of thin plates (600 t_c at h = 1 mm) fit
LINEAR_MAX_T_FACTOR = 2048.0


def default_dt(impact, steps_per_contact: int, tc: float | None = None) -> float:
    """dt = t_c / N (s), t_c the rigid-target Hertz contact-time estimate
    (``Impact.contact_time_estimate``), N = steps_per_contact.

    t_c is an estimate, not a bound: in the paper's SLS case the contact is shorter (t0/t_c = 0.845,
    0.82..0.91 for h = 12..100 mm), so the default 2000 steps per t_c are about 1690 steps per real
    contact; on thin plates the contact is longer (T_max grows). A fast relaxation rate alone does
    not limit dt: kernels are integrated exactly over each step, and a relaxation time tau << dt
    enters only as O(tau dt / t_c^2) times the relaxing fraction.
    """
    return (impact.contact_time_estimate() if tc is None else tc) / steps_per_contact


@dataclass(frozen=True)
class StepPlan:
    """A fixed-step run's time step ``dt`` (s), first horizon ``n_steps`` and budget ``max_steps``."""

    dt: float
    n_steps: int
    max_steps: int


def step_plan(impact, options, tc: float, *, linear: bool) -> StepPlan:
    """dt (``options.dt`` or automatic), the first horizon T_MAX_START t_c and the budget: the
    smaller of ``options.max_steps`` and the method's horizon (MAX_T_FACTOR t_c, or
    LINEAR_MAX_T_FACTOR t_c for a method whose cost is linear in time)."""
    dt = default_dt(impact, options.steps_per_contact, tc) if options.dt is None else options.dt
    if not (dt * dt > 0.0 and math.isfinite(tc / dt)):  # the weights divide by dt^2
        given = f"dt = {dt!r} s" if options.dt is not None else (f"steps_per_contact = {options.steps_per_contact} "
                                                                f"(dt = {dt!r} s)")
        raise ValueError(f"{given}: dt^2 underflows in double precision (t_c = {tc:.4g} s); give a dt above "
                         f"1e-150 s, or fewer steps per contact")
    n_steps = max(math.ceil(min(T_MAX_START * tc / dt, options.max_steps)), 16)
    t_factor = LINEAR_MAX_T_FACTOR if linear else MAX_T_FACTOR
    max_n = min(options.max_steps, max(n_steps, int(min(t_factor * tc / dt, options.max_steps))))
    return StepPlan(dt, min(n_steps, max_n), max_n)


class Arrays:
    """Growable solution arrays s, s', F, J, u = s^{3/2} and du (increments of u)."""

    names = ("s", "g", "F", "J", "u", "du")

    def __init__(self, n):
        for k in self.names:
            setattr(self, k, np.zeros(n + 1))
        self.n = n

    def nodes(self) -> tuple:
        """The arrays as the kernels take them (a :class:`~._records.FixedNodes` as a plain tuple)."""
        return tuple(FixedNodes(self.s, self.g, self.F, self.J, self.u, self.du))

    def grow(self, n):
        for k in self.names:
            old = getattr(self, k)
            new = np.zeros(n + 1)
            new[: old.size] = old
            setattr(self, k, new)
        self.n = n


def drive(impact, dt, n_steps, max_steps, ghost, step_fn):
    """Run ``step_fn(n0, n1, arrays, plate, state, n_extra)`` with T_max extension (``plate``: a
    :class:`~._records.PlateArrays` on the grid dt n, as a plain tuple).

    Returns a :class:`March` (its status SEPARATED, DIVERGED, or END: the budget reached) with the
    budget text of the fixed-step methods."""
    arr = Arrays(n_steps)
    arr.g[0] = impact.v0
    state = fixed_state()
    n_done = 0
    n_cap = n_steps
    while True:
        t = dt * np.arange(n_cap + 1)
        step_fn(n_done + 1, n_cap, arr, tuple(PlateArrays(impact.alpha(t), impact.alpha_rate(t))), state, N_EXTRA)
        n_done = int(state[LAST])
        if state[STATUS] != STATUS_END:
            break
        if state[SEPARATION] >= 0:  # separated within the last N_EXTRA steps: finish the interpolation steps
            n_cap = n_done + N_EXTRA
        elif n_cap >= max_steps:
            break
        else:
            n_cap = min(2 * n_cap, max_steps)
        arr.grow(n_cap)
    note = ""
    if state[STATUS] == STATUS_SEPARATED and ghost > 0:
        n_sep = int(state[SEPARATION])
        n_ghost = max(math.ceil(n_sep * (1.0 + ghost)), n_done)
        if n_ghost > n_cap:
            arr.grow(n_ghost)
            n_cap = n_ghost
        if n_ghost > n_done:
            t = dt * np.arange(n_cap + 1)
            st = state.copy()
            step_fn(n_done + 1, n_ghost, arr, tuple(PlateArrays(impact.alpha(t), impact.alpha_rate(t))), st, n_ghost)
            reached = int(st[LAST])
            if st[STATUS] == STATUS_DIVERGED:
                note = (f"ghost continuation stopped at t = {reached * dt:.6g} s ({reached - n_sep} of "
                        f"{n_ghost - n_sep} steps past separation): the march diverged")
                reached -= 1
            n_done = reached
    budget = (f"stopped by the step budget before a verdict: the contact force had not returned to zero at "
              f"T_max = {n_done * dt:.6g} s ({n_done} steps of dt = {dt:.3g} s; budget {max_steps} steps, the "
              f"smaller of max_steps and the method's horizon: {MAX_T_FACTOR:g} contact-time estimates for direct "
              f"and paper, {LINEAR_MAX_T_FACTOR:g} for soe, ive-numba and ive); s_max and f_max are over that "
              f"window. To reach a verdict use method adaptive (it solves long contacts such as thin plates), or "
              f"raise max_steps")
    return March(arrays=arr, state=state, n_done=n_done, dt=dt, note=note, budget=budget)


@dataclass(kw_only=True)
class March:
    """What a march leaves for :func:`finish`: the node ``arrays``, the ``state`` (``_records``), the
    last node ``n_done``, the step ``dt`` (s; the largest step on a variable grid), the time grid ``t``
    (None: uniform, dt n), a ``note`` for the message, the ``budget`` text of a step-budget verdict, the
    solver's ``wall`` time (s), the relative error of the exponential sums it used (0: none, or exact) and
    the kernel's k(0) the separation is located with (``_records.Stop``; 0: on F itself)."""

    arrays: Arrays
    state: np.ndarray
    n_done: int
    dt: float
    t: np.ndarray | None = None
    note: str = ""
    budget: str = ""
    wall: float = 0.0
    soe_error: float = 0.0
    glassy: float = 0.0


def finish(impact, march: March, *, rule, history, method):
    """Result of a march: the separation's outcome, or the status and a message that says what to do."""
    m, v0 = impact.m, impact.v0
    arr, state, n_done, dt = march.arrays, march.state, march.n_done, march.dt
    t = dt * np.arange(n_done + 1) if march.t is None else march.t[: n_done + 1]
    s, g, F, J = arr.s[: n_done + 1], arr.g[: n_done + 1], arr.F[: n_done + 1], arr.J[: n_done + 1]
    res = Result(steps=n_done, wall_time=march.wall, dt=dt, method=method, soe_error=march.soe_error)
    status = int(state[STATUS])
    if status == STATUS_SEPARATED or (state[SEPARATION] >= 0 and n_done >= state[SEPARATION] + N_EXTRA):
        out = separation(t, s, g, F, J, int(state[SEPARATION]), rule, m, v0, impact.mobility_is_constant,
                         march.glassy)
        res.message = out.pop("message")
        res.__dict__.update(out)
        res.steps = int(state[SEPARATION])
    elif status == STATUS_DIVERGED:
        res.status = "diverged"
        cause = impact.unbounded_mobility(float(t[-1]))
        instead = ("a smaller step_tol" if method.startswith("adaptive") else
                   "method adaptive, or a smaller dt (or a larger steps_per_contact)")
        res.message = (f"the march stopped at step {n_done}: {cause}" if cause else
                       f"Newton iteration failed or a non-finite value appeared at step {n_done} "
                       f"(t = {t[-1]:.6g} s, step {dt:.3g} s); try {instead}")
    else:
        res.status = "step-budget"
        res.message = march.budget
        res.s_max = float(np.max(s))
        res.f_max = float(np.max(F))
    if march.note:
        res.message = (res.message + "; " if res.message else "") + march.note
    if history:
        zd = v0 - J / m
        h = Histories(t=t.copy(), s=s.copy(), sdot=g.copy(), F=F.copy(), J=J.copy(), zdot=zd, U=impact.alpha(t) * J)
        res.history = h.mark(res.t0 if res.ok else math.inf)
    return res
