"""Internal-variable evolution (IVE) solvers (Green 2026 Eqs. 18-22): scipy's ``solve_ivp``
(``ive``) and the fixed-step exponential update in numba (``ive-numba``, O(N)).

For a Prony kernel k(t) = G_inf + sum_k G_k exp(-b_k t) the force is F = G_inf u + sum_k Q_k with
Q_k' = -b_k Q_k + G_k u', u = s^{3/2}. With s' = v0 - J/m - alpha' J - alpha F and J' = F this is a
system of N + 2 ODEs (plus two quadrature states for W_h and int F z' dt). Separation is a terminal
event on F = 0 (direction -1). The method must be stiff-capable (default "Radau").

The two-body contact modulus of Green's Eq. 1 (:class:`vcor.materials.EqOne`) is not a Prony series;
both methods take it as its exponential-sum fit on [0, the horizon] (:mod:`vcor.materials.expfit`,
relative error <= ``vcor.solvers.options.SUM_TOL``, checked at t = 0 too, reported as ``soe_error``), when its E'(0) is
finite. ``ive``'s work is bounded by ``max_steps`` solve_ivp steps over all its horizons.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from ..materials.expsums import soe
from ..threads import one_blas_thread
from ._fixed_kernels import march_prony
from ._records import Body, Internal, Stop
from .applicability import IVE_KERNELS, IVE_VOLTERRA
from .common import Histories, Result, peak
from .march import LINEAR_MAX_T_FACTOR, T_MAX_START, drive, finish, step_plan
from .options import SUM_TOL

__all__ = ["kernel_terms", "run_ive_fixed", "run_ive_scipy", "solve_fixed", "solve_scipy"]

#: the sum's samples run from t = 0 and then log-spaced from this fraction of the horizon (s)
SUM_WINDOW_START = 2.0**-40


def solve_fixed(impact, options, tc, history):
    """Runner of method ``ive-numba`` (``vcor.solvers.simulate.METHODS``)."""
    plan = step_plan(impact, options, tc, linear=True)
    return run_ive_fixed(impact, plan.dt, plan.n_steps, max_steps=plan.max_steps, rule=options.rule,
                         history=history, ghost=options.ghost)


def solve_scipy(impact, options, tc, history):
    """Runner of method ``ive`` (scipy ``solve_ivp``; the horizon grows from T_MAX_START to
    LINEAR_MAX_T_FACTOR contact-time estimates), with one BLAS thread (:mod:`vcor.threads`: the numbers do
    not depend on the machine's cores)."""
    with one_blas_thread():
        return run_ive_scipy(impact, rtol=options.rtol, method=options.ive_method, tc=tc, t_max=T_MAX_START * tc,
                             max_t=LINEAR_MAX_T_FACTOR * tc, history=history, ghost=options.ghost, rule=options.rule,
                             volterra=options.volterra, c2=options.c2 if options.volterra else 0.0,
                             max_steps=options.max_steps)


def kernel_terms(impact, method, horizon):
    """(E_inf, E[], beta[], relative error) of the impact's kernel as internal variables: a Prony kernel's
    own terms (error 0), or the exponential sum of a two-body Eq. 1 modulus on [0, ``horizon``] (s)
    with a finite E'(0) (module docstring). ValueError naming the methods that solve other kernels."""
    mat = impact.material
    if mat.is_prony:
        return (*mat.prony_terms(), 0.0)
    what = f"got {mat.kind!r}"
    if mat.kind == "eq1" and math.isfinite(mat.glassy):
        try:
            rep = soe(mat, SUM_WINDOW_START * horizon, horizon, SUM_TOL, from_zero=True)
        except ValueError as exc:
            what = str(exc)
        else:
            return (*rep.material.prony_terms(), rep.checked_error)
    raise ValueError(f"method {method!r} needs {IVE_KERNELS}; {what}: use method 'adaptive' (or 'direct')")


def run_ive_fixed(impact, dt, n_steps, *, max_steps, rule="force", history=False, ghost=0.0):
    """Internal variables with the fixed-step exponential update (numba, O(N)); Prony kernels."""
    g_inf, e, b, sum_error = kernel_terms(impact, "ive-numba", (max_steps + 8) * dt * (1.0 + ghost))
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
    march.soe_error = sum_error
    return finish(impact, march, rule=rule, history=history, method="ive-numba")


@dataclass(frozen=True, kw_only=True)
class _System:
    """The IVE system of ``run_ive_scipy`` as ``solve_ivp`` sees it: state y = (s, J, Q_1..Q_nq, W_h,
    int F z' dt), the contact force and the right-hand side (SI: m, N s, N, J)."""

    G_inf: float  # kappa E_inf, N/m^1.5
    G: np.ndarray  # kappa E_k, N/m^1.5
    inv_G: np.ndarray  # 1/G_k (0 where G_k = 0), m^1.5/N
    b: np.ndarray  # relaxation rates, 1/s
    eta: float  # kappa times the Dirac weight, N s/m^1.5
    m: float  # sphere mass, kg
    v0: float  # impact speed, m/s
    mobility: object  # t -> (alpha(t) in m/(N s), alpha'(t) in m/(N s^2))
    rule: str  # separation rule: "force" (F = 0) or "overlap" (s = 0)
    c2: float | None  # second-order (Volterra) coefficient c2 (SI); None: no second-order term
    sum_error: float  # relative error of the kernel's exponential sum (0: a Prony kernel's own terms)

    @classmethod
    def of(cls, impact, rule, volterra, c2, horizon):
        g_inf, e, b, sum_error = kernel_terms(impact, "ive", horizon)
        if volterra and sum_error > 0.0:
            raise ValueError(IVE_VOLTERRA)
        kap = impact.kappa
        G = kap * e
        return cls(G_inf=kap * g_inf, G=G, inv_G=np.where(G > 0, 1.0 / np.where(G > 0, G, 1.0), 0.0), b=b,
                   eta=kap * impact.material.viscosity, m=impact.m, v0=impact.v0, mobility=impact.mobility_function(),
                   rule=rule, c2=c2 if volterra else None, sum_error=sum_error)

    @property
    def nq(self) -> int:
        return self.G.size

    def parts(self, t, y):
        """(F, s', u'/s' = 3/2 sqrt(s), J) at (t, y); the Kelvin-Voigt term is implicit in s'."""
        s, J = y[0], y[1]
        Q = y[2 : 2 + self.nq]
        a = abs(s)
        sq = math.sqrt(a)
        u = math.copysign(a * sq, s)
        p = 1.5 * sq
        al, ald = self.mobility(t)
        A = self.G_inf * u + Q.sum()
        if self.c2 is not None:
            A += self.c2 * (self.G_inf * u * u + (Q * Q * self.inv_G).sum())
        B = self.v0 - J / self.m - ald * J
        F = (A + self.eta * p * B) / (1.0 + self.eta * p * al)
        g = B - al * F
        return F, g, p, J

    def rhs(self, t, y):
        F, g, p, J = self.parts(t, y)
        nq = self.nq
        dy = np.empty_like(y)
        dy[0] = g
        dy[1] = F
        dy[2 : 2 + nq] = -self.b * y[2 : 2 + nq] + self.G * p * g
        dy[2 + nq] = F * g
        dy[3 + nq] = F * (self.v0 - J / self.m)
        return dy

    def event(self, t, y):
        """Separation: F (rule "force") or s (rule "overlap") crossing zero downwards, terminal."""
        return self.parts(t, y)[0] if self.rule == "force" else y[0]

    event.terminal = True
    event.direction = -1

    def atol(self, rtol, tc):
        """Absolute tolerances per state from the impact's scales (tc: contact time estimate, s)."""
        m, v0 = self.m, self.v0
        f_scale = m * v0 / tc
        s_scale = v0 * tc
        return np.concatenate([[s_scale, m * v0], np.full(self.nq, f_scale), [0.5 * m * v0**2] * 2]) * rtol * 1e-2


def _solve(system, y0, span, settings, events=None):
    """``solve_ivp`` of the system over ``span`` with dense output; ``settings`` = (method, rtol, atol,
    max_step). scipy's finite-difference Jacobian (Radau/BDF) probes far enough on very stiff cases to
    overflow in a product it then discards; the solution is checked for finiteness by the caller."""
    from scipy.integrate import solve_ivp  # on use: only method "ive" needs it (a job's start-up)

    method, rtol, atol, max_step = settings
    with np.errstate(over="ignore", invalid="ignore"):
        try:
            return solve_ivp(system.rhs, span, y0, method=method, rtol=rtol, atol=atol, events=events,
                             dense_output=True, max_step=max_step)
        except ValueError as exc:  # scipy's own check of a state or derivative (asarray_chkfinite)
            if "infs or NaNs" in str(exc):
                raise _NonFinite(str(exc)) from None
            raise


class _NonFinite(Exception):
    """solve_ivp met a non-finite state or derivative (moduli or rates whose products overflow)."""


class _StepBudget(Exception):
    """solve_ivp took the run's budget of steps (raised from the separation event, which solve_ivp
    evaluates once per step)."""


class _Steps:
    """The separation event, counting solve_ivp's steps over every horizon; at ``budget`` steps it raises
    :class:`_StepBudget`. ``t``: the time of the last step (s)."""

    terminal = True
    direction = -1

    def __init__(self, system, budget):
        self.system, self.budget, self.steps, self.t = system, budget, 0, 0.0

    def __call__(self, t, y):
        self.steps += 1
        self.t = t
        if self.steps > self.budget:
            raise _StepBudget
        return self.system.event(t, y)


def _until_separation(system, settings, t_max, max_t, steps):
    """(solution, last horizon): the horizon doubles from ``t_max`` up to ``max_t`` (s) until the
    separation event fires or the solver fails; ``steps``: the counting event (:class:`_Steps`)."""
    y0 = np.zeros(4 + system.nq)
    t_end = t_max
    while True:
        sol = _solve(system, y0, (0.0, t_end), settings, events=steps)
        if sol.status == 1 or not sol.success or t_end >= max_t:
            return sol, t_end
        t_end = min(2 * t_end, max_t)


def _refusal(sol, method, t_end, impact):
    """(status, message) when the run has no verdict (failed, non-finite, no separation by ``t_end``),
    else None."""
    if not sol.success or not np.all(np.isfinite(sol.y)):
        cause = impact.unbounded_mobility(float(sol.t[-1]))
        text = f"solve_ivp({method}) failed: {sol.message}" if not sol.success else "non-finite state"
        return "diverged", text + (f"; {cause}" if cause else "")
    if sol.status != 1:
        return "step-budget", (f"stopped by the time budget before a verdict: the contact force had not "
                               f"returned to zero at T_max = {t_end:.6g} s ({LINEAR_MAX_T_FACTOR:g} contact-time "
                               f"estimates); use method adaptive, whose horizon grows further")
    return None


def _record(res, system, sol):
    """The scalars at separation into ``res``; s_max and F_max from the accepted steps, which bracket the
    peak, refined on the dense output."""
    m, v0, nq = system.m, system.v0, system.nq
    t0 = float(sol.t_events[0][0])
    y = sol.y_events[0][0]
    _F0, g0, _, J0 = system.parts(t0, y)
    z0 = v0 - J0 / m
    w_h, w_z = y[2 + nq], y[3 + nq]
    e_in = 0.5 * m * v0**2
    ts = sol.t
    Fs = np.array([system.parts(tt, yy)[0] for tt, yy in zip(ts, sol.y.T)])
    res.t0 = t0
    res.cor = float(abs(g0) / v0)
    res.s_residual = float(y[0])
    res.w_h = float(w_h)
    res.w_plate = float(w_z - w_h)
    res.omega_min = 2 * math.pi / t0
    res.sphere_velocity = float(z0)
    res.energy_residual = float((e_in - 0.5 * m * z0 * z0 - w_z) / e_in)
    res.s_max = peak(ts, sol.y[0], lambda x: sol.sol(x)[0])
    res.f_max = peak(ts, Fs, lambda x: system.parts(x, sol.sol(x))[0])


def _ghost(system, sol, settings, ghost, n):
    """(times, states, message) past separation t0 up to t0 (1 + ghost) without the event (the "ghost"
    solution, for plots); the message says where a failed continuation stopped ("" otherwise)."""
    t0 = float(sol.t_events[0][0])
    y = sol.y_events[0][0]
    t1 = t0 * (1.0 + ghost)
    sol2 = _solve(system, y, (t0, t1), settings)
    message = ""
    if not sol2.success:
        t1 = float(sol2.t[-1])
        message = (f"ghost continuation stopped at t = {t1:.6g} s (requested {t0 * (1 + ghost):.6g} s): "
                   f"solve_ivp({settings[0]}): {sol2.message}")
    tg = np.linspace(t0, t1, max(2, int(n * ghost)))[1:]
    states = sol2.sol(tg) if sol2.sol is not None else np.full((y.size, tg.size), np.nan)
    return tg, states, message


def _history(res, system, sol, settings, ghost, alpha):
    """The time histories on [0, t0] (and the ghost continuation) into ``res``."""
    t0 = res.t0
    n = max(400, sol.t.size)
    tt = np.linspace(0.0, t0, n)
    Y = sol.sol(tt)
    if ghost > 0:
        tg, states, message = _ghost(system, sol, settings, ghost, n)
        if message:
            res.message = message
        tt = np.concatenate([tt, tg])
        Y = np.concatenate([Y, states], axis=1)
    PF = np.array([system.parts(a, yy) for a, yy in zip(tt, Y.T)])
    F, g, J = PF[:, 0], PF[:, 1], Y[1]
    v0, m = system.v0, system.m
    res.history = Histories(t=tt, s=Y[0], sdot=g, F=F, J=J, zdot=v0 - J / m, U=alpha(tt) * J).mark(t0)


def run_ive_scipy(impact, *, rtol=1e-10, method="Radau", tc, t_max, max_t, history=False, ghost=0.0, rule="force",
                  volterra=False, c2=1.0, max_steps=60_000):
    """Internal-variable solver with ``solve_ivp`` (options validated by ``SolverOptions``). With
    ``volterra`` the second-order term for the Prony kernel is separable,
    c2 int int k(t1 + t2) u' u' = c2 (G_inf u^2 + sum_k Q_k^2 / G_k), so it costs nothing and is an
    independent check of the direct solver's O(N^2) Volterra sums. At ``max_steps`` solve_ivp steps
    (over all horizons) the run ends with status step-budget."""
    system = _System.of(impact, rule, volterra, c2, 2.0 * max_t * (1.0 + ghost))
    settings = (method, rtol, system.atol(rtol, tc), tc / 20)
    name = f"ive-{method}" + ("+volterra" if volterra else "")
    t_start = time.perf_counter()
    steps = _Steps(system, max_steps)
    try:
        sol, t_end = _until_separation(system, settings, t_max, max_t, steps)
    except _StepBudget:
        return Result(method=name, steps=max_steps, wall_time=time.perf_counter() - t_start, dt=math.nan,
                      status="step-budget", soe_error=system.sum_error,
                      message=f"stopped by the step budget before a verdict: solve_ivp({method}) took max_steps = "
                              f"{max_steps} steps (counted over its horizons) and had reached t = {steps.t:.6g} s "
                              f"without the contact force returning to zero; raise max_steps, or use method "
                              f"adaptive (it solves long contacts such as thin plates)")
    except _NonFinite as exc:
        return Result(method=name, steps=steps.steps, wall_time=time.perf_counter() - t_start, dt=math.nan,
                      status="diverged", soe_error=system.sum_error,
                      message=f"solve_ivp({method}) met a non-finite value ({exc}): the system's scales overflow "
                              f"in double precision")
    wall = time.perf_counter() - t_start
    largest = float(np.max(np.diff(sol.t))) if sol.t.size > 1 else float(sol.t[-1])  # solve_ivp's largest step
    res = Result(method=name, steps=int(sol.t.size), wall_time=wall, dt=largest, soe_error=system.sum_error)
    refusal = _refusal(sol, method, t_end, impact)
    if refusal is not None:
        res.status, res.message = refusal
        return res
    _record(res, system, sol)
    if history:
        _history(res, system, sol, settings, ghost, impact.alpha)
    return res
