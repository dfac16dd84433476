"""Front end: ``simulate(material, v0, ...)`` validates, chooses dt and T_max, dispatches."""

from __future__ import annotations

import math

from .. import materials as _materials
from ..impact import GEOMETRY_DEFAULTS, Geometry, Impact
from .direct import MAX_T_FACTOR, run_direct, run_ive_fixed, run_paper
from .ive import run_ive_scipy

__all__ = ["simulate", "METHODS", "default_dt", "STEPS_PER_CONTACT", "MAX_STEPS"]

METHODS = ("direct", "ive", "ive-numba", "paper")
#: default resolution: dt = (rigid-target Hertz contact-time estimate) / STEPS_PER_CONTACT
STEPS_PER_CONTACT = 2000
#: T_max starts at this many contact-time estimates and doubles while the impact has not separated
T_MAX_START = 1.5
#: hard bound on the number of steps when T_max is extended (direct is O(N^2))
MAX_STEPS = 200_000


def make_impact(material, v0, geometry: dict) -> Impact:
    unknown = set(geometry) - set(GEOMETRY_DEFAULTS)
    if unknown:
        raise ValueError(f"unknown geometry keyword(s) {sorted(unknown)}; allowed: {sorted(GEOMETRY_DEFAULTS)}")
    mat = _materials.get(material) if isinstance(material, str) else material
    if not isinstance(mat, _materials.Material):
        raise ValueError(f"material must be a preset name or a vcor.materials.Material, got {material!r}")
    return Impact(mat, v0, Geometry(**geometry))


def default_dt(impact: Impact, steps_per_contact: int = STEPS_PER_CONTACT, tc: float | None = None) -> float:
    """dt = t_c / N, t_c the rigid-target Hertz contact time with k at t_c/4 (a lower bound on the
    contact for ordinary materials), N = steps_per_contact.

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


def simulate(material, v0, *, method="direct", dt=None, volterra=False, form="a", c2=1.0, rule="force",
             history=False, ghost=0.5, rtol=1e-10, ive_method="Radau", steps_per_contact=STEPS_PER_CONTACT,
             max_steps=MAX_STEPS, **geometry):
    """Simulate one impact and return a :class:`~vcor.solvers.common.Result`.

    Parameters
    ----------
    material : str or Material
        Preset name (``vcor.materials.PRESETS``) or material object.
    v0 : float
        Impact speed, m/s, > 0.
    method : {"direct", "ive", "ive-numba"}
        ``direct``: full-history product integration (any kernel). ``ive``: internal variables
        with scipy ``solve_ivp`` (Prony kernels). ``ive-numba``: internal variables with the
        fixed-step exponential update (Prony kernels, O(N)). ``paper``: an explicit baseline in the
        spirit of the paper's scheme (clamped kernel, Adams-Bashforth), for benchmarks only.
    dt : float, optional
        Time step, s (direct and ive-numba). ``None``: contact-time estimate / steps_per_contact.
    volterra : bool
        Add the second-order Volterra term c2 int int k(t1 + t2) u'(t - t1) u'(t - t2) (form a).
    form : {"a", "b"}
        Form of the hereditary Hertz law (Green Eq. 8); "b" needs a finite k(0).
    c2 : float
        Volterra coefficient, m^-1.5 (1 in SI as in the paper).
    rule : {"force", "overlap"}
        Separation when F returns to zero (default, the paper's) or when s returns to zero.
    history : bool
        Keep time histories (``result.history``), continued ``ghost`` * t0 past separation.
    rtol, ive_method :
        Tolerance and method of ``solve_ivp`` for ``method="ive"``.
    **geometry :
        r, rho_a, rho_b, h, nu, case, rigid, E_plate, nu_plate (see ``vcor.impact``).
    """
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}, got {method!r}")
    if form not in ("a", "b"):
        raise ValueError(f"form must be 'a' or 'b', got {form!r}")
    if rule not in ("force", "overlap"):
        raise ValueError(f"rule must be 'force' or 'overlap', got {rule!r}")
    if not (isinstance(steps_per_contact, int) and steps_per_contact >= 10):
        raise ValueError(f"steps_per_contact must be an integer >= 10, got {steps_per_contact!r}")
    if not (isinstance(max_steps, int) and max_steps >= 100):
        raise ValueError(f"max_steps must be an integer >= 100, got {max_steps!r}")
    if not (isinstance(ghost, (int, float)) and 0 <= ghost <= 10):
        raise ValueError(f"ghost must be in [0, 10] (fraction of t0), got {ghost!r}")
    if not (isinstance(c2, (int, float)) and math.isfinite(c2)):
        raise ValueError(f"c2 must be a finite number (m^-1.5), got {c2!r}")
    impact = make_impact(material, v0, geometry)
    tc = impact.contact_time_estimate()
    if dt is not None:
        dt = float(dt)
        if not (math.isfinite(dt) and 0 < dt < tc):
            raise ValueError(
                f"dt must be in (0, {tc:.4g}) s (below the estimated contact time), got {dt!r}"
            )
    auto_dt = dt is None
    if auto_dt:
        dt = default_dt(impact, steps_per_contact, tc)
    res = _dispatch(impact, method, dt, tc, max_steps, rule, volterra, c2, form, history, ghost, rtol, ive_method)
    if (auto_dt and method != "ive" and res.ok and res.steps < MIN_STEPS_FRACTION * steps_per_contact):
        dt = res.t0 / (0.8 * steps_per_contact)
        wall = res.wall_time
        res = _dispatch(impact, method, dt, tc, max_steps, rule, volterra, c2, form, history, ghost, rtol, ive_method)
        res.wall_time += wall
        res.message = (res.message + " " if res.message else "") + "dt refined from the measured t0"
    return res


def _dispatch(impact, method, dt, tc, max_steps, rule, volterra, c2, form, history, ghost, rtol, ive_method):
    n_steps = max(int(math.ceil(T_MAX_START * tc / dt)), 16)
    max_n = min(max_steps, max(n_steps, int(MAX_T_FACTOR * tc / dt)))
    n_steps = min(n_steps, max_n)
    if method == "direct":
        return run_direct(impact, dt, n_steps, max_steps=max_n, rule=rule, volterra=volterra, c2=c2, form=form,
                          history=history, ghost=ghost)
    if method == "paper":
        if volterra or history:
            raise ValueError("method 'paper' (benchmark baseline) has no volterra or history option")
        return run_paper(impact, dt, n_steps, max_steps=max_n, rule=rule)
    if method == "ive-numba":
        if volterra:
            raise ValueError("volterra=True needs method 'direct' or 'ive'")
        return run_ive_fixed(impact, dt, n_steps, max_steps=max_n, rule=rule, history=history, ghost=ghost)
    return run_ive_scipy(impact, rtol=rtol, method=ive_method, tc=tc, t_max=T_MAX_START * tc, max_t=MAX_T_FACTOR * tc,
                         history=history, ghost=ghost, rule=rule, volterra=volterra, c2=c2)
