"""Front end: ``simulate(material, v0, ...)`` validates, estimates the contact time, dispatches to
the method's runner (``METHODS``, one signature for all) and refines a fixed step when needed."""

from __future__ import annotations

import math

from ..contact.impact import GEOMETRY_DEFAULTS, make_impact
from ..contact.pair import target_inputs
from . import adaptive, direct, ive, soe
from .applicability import refusal
from .common import OUTCOME
from .options import (
    FIXED_STEP_METHODS,
    MAX_STEPS_PER_CONTACT,
    METHOD_NAMES,
    MIN_STEPS_PER_CONTACT,
    SolverOptions,
    solver_options,
)
from .validity import finalised

__all__ = ["METHODS", "MIN_STEPS_FRACTION", "simulate", "split_keywords"]

#: method name -> runner ``run(impact, options, tc, history) -> Result`` (``tc``: the contact-time
#: estimate, s; ``history``: keep time histories)
METHODS = {
    "adaptive": adaptive.solve,
    "direct": direct.solve,
    "ive": ive.solve_scipy,
    "ive-numba": ive.solve_fixed,
    "paper": direct.solve_paper,
    "soe": soe.solve,
}
assert tuple(sorted(METHODS)) == tuple(sorted(METHOD_NAMES))

#: with automatic dt, a fixed-step run that separates in fewer than this fraction of steps_per_contact
#: steps is repeated once with dt = t0 / (0.8 steps_per_contact) (e.g. rubbery/glassy = 1e-4 at
#: v0 = 1 mm/s, where the rubbery t_c estimate is 50 times the real contact)
MIN_STEPS_FRACTION = 0.25


def split_keywords(kwargs: dict) -> tuple[dict, dict]:
    """Split keyword arguments into (solver options, geometry); anything else is an error.

    Examples
    --------
    >>> from vcor.solvers.simulate import split_keywords
    >>> split_keywords({"r": 0.005, "method": "direct"})
    ({'method': 'direct'}, {'r': 0.005})
    """
    if not kwargs:
        return {}, {}
    solver = {k: v for k, v in kwargs.items() if k in SolverOptions.names()}
    geometry = {k: v for k, v in kwargs.items() if k in GEOMETRY_DEFAULTS}
    unknown = set(kwargs) - set(solver) - set(geometry)
    if unknown:
        raise ValueError(f"unknown keyword(s) {sorted(unknown)}; geometry: {sorted(GEOMETRY_DEFAULTS)}; "
                         f"solver options: {sorted(SolverOptions.names())}")
    return solver, geometry


def simulate(material, v0, *, options: SolverOptions | dict | None = None, history: bool = False, target="plate",
             **kwargs):
    """Simulate one impact and return a :class:`~vcor.solvers.common.Result`.

    Parameters
    ----------
    material : str, dict or Material
        Preset name (``vcor.materials.PRESETS``), a spec ``{model: ..., <parameters>}`` as a config's
        ``materials:`` block takes it, or a material object.
    v0 : float
        Impact speed, m/s, > 0.
    options : SolverOptions or dict, optional
        Solver options (:class:`vcor.SolverOptions`; method ``adaptive`` unless given). They may
        instead be given as keywords; not both. An option the chosen method does not use is an error.
    history : bool
        Keep time histories (``result.history``), continued ``ghost`` * t0 past separation.
    target : str or dict
        What the sphere hits: ``"plate"`` (the default: the plate of the geometry keywords),
        ``"rigid"`` (an immovable target: the geometry's ``rigid=True``, with the case's densities, so that
        in the default case 3 an unstated rho_a is steel's, 7800 kg/m^3), ``{"sphere": {material, r, rho,
        nu}}`` (a second sphere, head-on: the COR of the relative velocity) or ``{"plate": {material, h,
        rho, nu}}`` (:mod:`vcor.contact.pair`). With a sphere or plate target the impacting sphere takes
        only r, rho_a and nu, an unstated rho_a being its material's (a viscoelastic one the polymer's,
        1100 kg/m^3: ``{"plate": {"material": "rigid"}}`` is ``"rigid"`` with that density); the target's
        keys default to the impacting sphere's material.
    **kwargs :
        Solver options (see ``options``) and geometry: r (m), rho_a, rho_b (kg/m^3), h (m), nu, case,
        rigid, E_plate (Pa), nu_plate (see :mod:`vcor.contact.impact`).

    Returns
    -------
    Result
        COR, separation time t0 (s), peaks, work integrals (J), status and message, and validity flags
        of an ok result outside the model's stated range (:mod:`vcor.solvers.validity`).

    Examples
    --------
    A steel sphere (r = 10 mm) on the paper's SLS plate at 1 m/s:

    >>> import vcor
    >>> r = vcor.simulate("sls", 1.0)
    >>> r.status, f"COR {r.cor:.3f}", f"t0 {r.t0 * 1e3:.2f} ms", r.validity
    ('ok', 'COR 0.388', 't0 2.19 ms', 0)

    At 10 m/s the indentation is 45 % of the radius: the result is ``ok`` but flagged, because
    Hertz contact assumes s << r:

    >>> r = vcor.simulate("sls", 10.0)
    >>> f"COR {r.cor:.3f}", r.validity, r.validity_message.split(":")[0]
    ('COR 0.432', 1, 's_max / r = 0.451 > 0.1')

    Other targets, geometry and solver options as keywords (``r.method`` names the method and its
    variant, here Hertz law form a):

    >>> r = vcor.simulate("sls", 1.0, target="rigid", r=0.005, method="direct")
    >>> r.method, f"COR {r.cor:.3f}"
    ('direct-a', 'COR 0.667')
    """
    if not isinstance(history, bool):
        raise ValueError(f"history must be true or false, got {history!r}")
    solver_kw, geometry = split_keywords(kwargs)
    opts = solver_options(options, **solver_kw)
    if target != "plate":
        material, geometry = target_inputs(material, target, geometry)
    impact = make_impact(material, v0, geometry)
    why = refusal(impact.material, opts)
    if why:
        raise ValueError(why)
    tc = impact.contact_time_estimate()
    if opts.dt is not None and not tc / MAX_STEPS_PER_CONTACT <= opts.dt <= tc / MIN_STEPS_PER_CONTACT:
        raise ValueError(f"dt must be in [{tc / MAX_STEPS_PER_CONTACT:.4g}, {tc / MIN_STEPS_PER_CONTACT:.4g}] s (from "
                         f"{MIN_STEPS_PER_CONTACT} to {MAX_STEPS_PER_CONTACT} steps per contact-time estimate "
                         f"{tc:.4g} s, as steps_per_contact), got {opts.dt!r}")
    run = METHODS[opts.method]
    res = run(impact, opts, tc, history)
    if (opts.dt is None and opts.method in FIXED_STEP_METHODS and res.ok
            and res.steps < MIN_STEPS_FRACTION * opts.steps_per_contact):
        wall, first_t0 = res.wall_time, res.t0
        res = run(impact, opts.replace(dt=res.t0 / (0.8 * opts.steps_per_contact)), tc, history)
        res.wall_time += wall
        res.message = (res.message + "; " if res.message else "") + "dt refined from the measured t0"
        if res.ok and res.steps < MIN_STEPS_FRACTION * opts.steps_per_contact and res.t0 < 0.5 * first_t0:
            for name in (*OUTCOME, "omega_min"):  # numbers of no contact: none is kept
                setattr(res, name, math.nan)
            res.status = "diverged"
            res.message = (f"the separation came after {res.steps} steps again with dt refined to t0 / "
                           f"{0.8 * opts.steps_per_contact:g}: it moves with the step (a zero of the force on the "
                           f"first steps, as on a plate that recedes at once), so it is not a resolved separation; "
                           f"method adaptive locates a separation on steps far below this one, or reports its step "
                           f"budget")
    return finalised(res, impact, opts)
