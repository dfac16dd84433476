"""Front end: ``simulate(material, v0, ...)`` validates, chooses dt and T_max, dispatches."""

from __future__ import annotations

import math

from .. import materials as _materials
from ..checks import interned
from ..impact import GEOMETRY_DEFAULTS, Geometry, Impact
from ..options import FIXED_STEP_METHODS, METHODS, SolverOptions, solver_options
from .adaptive import run_adaptive
from .direct import MAX_T_FACTOR, run_direct, run_paper
from .ive import run_ive_fixed, run_ive_scipy
from .modes import run_soe

__all__ = ["METHODS", "default_dt", "make_impact", "simulate", "split_keywords"]

#: T_max starts at this many contact-time estimates and doubles while the impact has not separated
T_MAX_START = 1.5
#: time horizon of the methods whose cost is linear in time (soe, ive-numba, ive), in contact-time
#: estimates (direct and paper, O(N^2) or a baseline: MAX_T_FACTOR = 32): the long contacts of thin
#: plates (600 t_c at h = 1 mm) fit
LINEAR_MAX_T_FACTOR = 2048.0
LINEAR_METHODS = ("soe", "ive-numba", "ive")


def split_keywords(kwargs: dict) -> tuple[dict, dict]:
    """Split keyword arguments into (solver options, geometry); anything else is an error."""
    solver = {k: v for k, v in kwargs.items() if k in SolverOptions.names()}
    geometry = {k: v for k, v in kwargs.items() if k in GEOMETRY_DEFAULTS}
    unknown = set(kwargs) - set(solver) - set(geometry)
    if unknown:
        raise ValueError(f"unknown keyword(s) {sorted(unknown)}; geometry: {sorted(GEOMETRY_DEFAULTS)}; "
                         f"solver options: {sorted(SolverOptions.names())}")
    return solver, geometry


def make_impact(material, v0, geometry: dict) -> Impact:
    unknown = set(geometry) - set(GEOMETRY_DEFAULTS)
    if unknown:
        raise ValueError(f"unknown geometry keyword(s) {sorted(unknown)}; allowed: {sorted(GEOMETRY_DEFAULTS)}")
    mat = _materials.get(material) if isinstance(material, str) else material
    if not isinstance(mat, _materials.Material):
        raise ValueError(f"material must be a preset name or a vcor.materials.Material, got {material!r}")
    return Impact(mat, v0, _geometry(**geometry))


#: Geometry(**keywords), validated once per distinct keyword set (immutable: a sweep's points share it)
_geometry = interned(Geometry)


def default_dt(impact: Impact, steps_per_contact: int, tc: float | None = None) -> float:
    """dt = t_c / N, t_c the rigid-target Hertz contact-time estimate (``Impact.contact_time_estimate``),
    N = steps_per_contact.

    t_c is an estimate, not a bound: in the paper's SLS case the contact is shorter (t0/t_c = 0.845,
    0.82..0.91 for h = 12..100 mm; ``tests/test_solver.py`` prints it), so the default 2000 steps per
    t_c are about 1690 steps per real contact; on thin plates the contact is longer (T_max grows).
    A fast relaxation rate alone does not limit dt: kernels are integrated exactly over each step,
    and a relaxation time tau << dt enters only as O(tau dt / t_c^2) times the relaxing fraction.
    When the modulus relaxes by orders of magnitude during the contact, t_c can overestimate the
    contact; ``simulate`` then refines dt from the measured t0 (see ``MIN_STEPS_FRACTION``).
    """
    return (impact.contact_time_estimate() if tc is None else tc) / steps_per_contact


#: with automatic dt, a run that separates in fewer than this fraction of steps_per_contact steps is
#: repeated once with dt = t0 / (0.8 steps_per_contact) (e.g. rubbery/glassy = 1e-4 at v0 = 1 mm/s,
#: where the rubbery t_c estimate is 50 times the real contact)
MIN_STEPS_FRACTION = 0.25


def simulate(material, v0, *, options: SolverOptions | dict | None = None, history: bool = False, **kwargs):
    """Simulate one impact and return a :class:`~vcor.solvers.common.Result`.

    Parameters
    ----------
    material : str or Material
        Preset name (``vcor.materials.PRESETS``) or material object.
    v0 : float
        Impact speed, m/s, > 0.
    options : SolverOptions or dict, optional
        Solver options (``vcor.options.SolverOptions``: method, dt, steps_per_contact, max_steps,
        volterra, c2, form, rule, rtol, ive_method, ghost). They may instead be given as keywords;
        not both. An option the chosen method does not use is an error.
    history : bool
        Keep time histories (``result.history``), continued ``ghost`` * t0 past separation.
    **kwargs :
        Solver options (see ``options``) and geometry: r, rho_a, rho_b, h, nu, case, rigid, E_plate,
        nu_plate (see ``vcor.impact``).
    """
    solver_kw, geometry = split_keywords(kwargs)
    opts = solver_options(options, **solver_kw)
    impact = make_impact(material, v0, geometry)
    tc = impact.contact_time_estimate()
    if opts.dt is not None and not opts.dt < tc:
        raise ValueError(f"dt must be in (0, {tc:.4g}) s (below the estimated contact time), got {opts.dt!r}")
    res = _dispatch(impact, opts, tc, history)
    if (opts.dt is None and opts.method in FIXED_STEP_METHODS and res.ok
            and res.steps < MIN_STEPS_FRACTION * opts.steps_per_contact):
        wall = res.wall_time
        res = _dispatch(impact, opts.replace(dt=res.t0 / (0.8 * opts.steps_per_contact)), tc, history)
        res.wall_time += wall
        res.message = (res.message + "; " if res.message else "") + "dt refined from the measured t0"
    return res


def _dispatch(impact, opts: SolverOptions, tc: float, history: bool):
    if opts.method == "adaptive":
        return run_adaptive(impact, tc, step_tol=opts.step_tol, max_steps=opts.max_adaptive_steps, rule=opts.rule,
                            history=history, ghost=opts.ghost, tol=opts.soe_tol, extrapolate=opts.richardson)
    if opts.method == "ive":
        return run_ive_scipy(impact, rtol=opts.rtol, method=opts.ive_method, tc=tc, t_max=T_MAX_START * tc,
                             max_t=LINEAR_MAX_T_FACTOR * tc, history=history, ghost=opts.ghost, rule=opts.rule,
                             volterra=opts.volterra, c2=opts.c2 if opts.volterra else 0.0)
    dt = default_dt(impact, opts.steps_per_contact, tc) if opts.dt is None else opts.dt
    n_steps = max(math.ceil(T_MAX_START * tc / dt), 16)
    t_factor = LINEAR_MAX_T_FACTOR if opts.method in LINEAR_METHODS else MAX_T_FACTOR
    max_n = min(opts.max_steps, max(n_steps, int(t_factor * tc / dt)))
    n_steps = min(n_steps, max_n)
    if opts.method == "direct":
        return run_direct(impact, dt, n_steps, max_steps=max_n, rule=opts.rule, volterra=opts.volterra,
                          c2=opts.c2 if opts.volterra else 0.0, form=opts.form, history=history, ghost=opts.ghost)
    if opts.method == "paper":
        if history:
            raise ValueError("method 'paper' (benchmark baseline) has no history option")
        return run_paper(impact, dt, n_steps, max_steps=max_n, rule=opts.rule)
    if opts.method == "soe":
        return run_soe(impact, dt, n_steps, max_steps=max_n, rule=opts.rule, history=history, ghost=opts.ghost,
                       tol=opts.soe_tol)
    return run_ive_fixed(impact, dt, n_steps, max_steps=max_n, rule=opts.rule, history=history, ghost=opts.ghost)

