"""Validity of a result, separate from its status: is an ``ok`` number inside the model's range?

A result can be computed accurately and still lie outside what the model describes. Each check sets
one bit of ``Result.validity`` (CF ``flag_masks``) and adds a sentence to ``Result.validity_message``;
the status stays ``ok`` (the number is the model's), the flag says how far to trust the model or, for
the flags the solver sets (``SOLVER_FLAGS``), the number:

=======================  ====  =====================================================================
flag                     mask  set when
=======================  ====  =====================================================================
large_indentation        1     s_max / r > MAX_INDENTATION: Hertz contact assumes s << r
fast_impact              2     v0 > MAX_SPEED_FRACTION c, c = sqrt(E(t0/4) / rho) of the
                               viscoelastic body: the contact is no longer quasi-static
energy_residual          4     ``|energy residual|`` > MAX_ENERGY_RESIDUAL: the energy balance does
                               not close (fixed steps: ~1e-9 in a correct march; adaptive steps:
                               up to ~1e-4, the trapezoid quadrature on a variable grid)
under_resolved           8     a fixed-step method and a Kelvin-Voigt (Dirac) kernel whose damping
                               stops the sphere within fewer than MIN_DAMPING_STEPS steps: the
                               fixed-step error there decays only as (dt / t_d)^1.4 (use adaptive)
no_rebound               16    the sphere still moves towards the target at separation,
                               ``sphere_velocity`` > 0: the plate's surface recedes faster than the
                               sphere (thin viscoelastic plates, whose deflection keeps growing as
                               they relax); the COR describes this contact only, not the sphere's
                               final rebound (a plate of bounded deflection is struck again)
grids_disagree           32    method ``adaptive``: its nested grids are not in the asymptotic range
                               of the Richardson extrapolation, or it would give a negative COR, or
                               the COR is below ``extrapolation.COR_FLOOR`` (the sphere leaves
                               slower than the step control follows; ``vcor.solvers.extrapolation``),
                               so the values are the finest grid's and their error is not held to
                               the method's accuracy (the message gives the grids' differences): a
                               separation time that is ill-conditioned, as where a creeping force
                               returns to zero over hours and the sphere is captured
uncertain_extrapolation  64    method ``adaptive``: its nested grids pass the checks above, but t0
                               is not held to the method's accuracy: the grids are further apart
                               in t0 than ``extrapolation.RICHARDSON_MAX_GAP_STEPS`` step_tol (an
                               error the step control did not see), or, where they differ by more
                               than ``RICHARDSON_T0_GAP``, t0's differences do not yet shrink as
                               h^2 (``RICHARDSON_T0_RATIO``); the values are
                               extrapolated (closer than the finest grid's) but their error is not
                               held to the method's accuracy (a Kelvin-Voigt gel whose dashpot
                               holds the sphere; an SLS relaxing within a step)
=======================  ====  =====================================================================

A result whose outputs are not finite is never ``ok``: :func:`finalised` gives it the status
``diverged`` and a message naming the outputs. An ok result whose exponential sums are less accurate
than the method's tolerance (the fitted two-body modulus of a pair no fit reaches it for, taken within
``vcor.materials.expsums.FIT_ACCEPT``) says so in its message.
"""

from __future__ import annotations

import math
import operator

import numpy as np

from ..materials.expsums import FIT_ACCEPT
from .common import OUTCOME
from .extrapolation import COR_FLOOR
from .options import SUM_TOL

__all__ = ["FLAGS", "MAX_ENERGY_RESIDUAL", "MAX_INDENTATION", "MAX_SPEED_FRACTION", "MIN_DAMPING_STEPS", "SOLVER_FLAGS",
           "cf_attrs", "damping_time", "finalised"]

#: flag name -> bit mask (stable: archived datasets keep their meaning)
FLAGS = {"large_indentation": 1, "fast_impact": 2, "energy_residual": 4, "under_resolved": 8, "no_rebound": 16,
         "grids_disagree": 32, "uncertain_extrapolation": 64}
#: the flags a method sets on its result (:func:`finalised` keeps them and says why)
SOLVER_FLAGS = FLAGS["grids_disagree"] | FLAGS["uncertain_extrapolation"]
# (names, not look-ups, on every result's path)
_GRIDS_DISAGREE, _UNCERTAIN = FLAGS["grids_disagree"], FLAGS["uncertain_extrapolation"]
MAX_INDENTATION = 0.1
MAX_SPEED_FRACTION = 0.1
MAX_ENERGY_RESIDUAL = 1e-4
MIN_DAMPING_STEPS = 2000


def cf_attrs() -> dict:
    """CF attributes of a validity variable."""
    return {"long_name": "validity flags of an ok result (0: inside the model's stated range)",
            "standard_name": "quality_flag", "units": "1",
            "comment": "0 also where the status is not ok: such a point has no numbers to flag (select by status)",
            "flag_masks": np.array(list(FLAGS.values()), dtype=np.int8), "flag_meanings": " ".join(FLAGS)}


def damping_time(impact) -> float:
    """t_d (s): the time in which a Kelvin-Voigt kernel's viscous force eta u' alone stops the sphere,
    m v0 = eta s_d^{3/2}, t_d = s_d / v0 (inf without a Dirac term)."""
    eta = impact.kappa * impact.material.viscosity
    if not eta > 0:
        return math.inf
    return (impact.m * impact.v0 / eta) ** (2.0 / 3.0) / impact.v0


def _wave_density(impact) -> float:
    """Density (kg/m^3) of the viscoelastic body: the plate's, unless the target is rigid or the
    sphere is the viscoelastic body (case 4)."""
    g = impact.geometry
    return g.sphere_density if (g.rigid or g.case == 4) else g.plate_density


#: a result's OUTCOME values as a tuple
_outcome_values = operator.attrgetter(*OUTCOME)


def finalised(res, impact, options):
    """``res`` with non-finite outputs turned into status ``diverged`` and, for an ok result, its
    validity flags and message (module docstring)."""
    if not res.ok:
        return res
    if not all(map(math.isfinite, _outcome_values(res))):
        bad = [k for k in OUTCOME if not math.isfinite(getattr(res, k))]
        res.status = "diverged"
        res.message = (f"the outputs {', '.join(f'{k} = {getattr(res, k)!r}' for k in bad)} are not finite: the "
                       f"impact is outside the range the solver handles (sphere mass {impact.m:.3g} kg, v0 = "
                       f"{impact.v0:g} m/s); check the inputs, or try method direct as a reference")
        return res
    tol = options.soe_tol if options.soe_tol is not None else SUM_TOL
    if res.soe_error > tol:
        res.message = "; ".join(m for m in (res.message, (
            f"the exponential sum of the contact modulus of the two bodies reaches a relative error of "
            f"{res.soe_error:.2g}, not the tolerance {tol:g}: no fit of this pair does in double precision "
            f"(the best within {FIT_ACCEPT:g} is taken); the results carry an error of about that size")) if m)
    notes, flags = [], res.validity & SOLVER_FLAGS
    if flags & _GRIDS_DISAGREE:
        notes.append("the nested grids of method adaptive are not in the asymptotic range of its Richardson "
                     f"extrapolation, or it would give a negative COR, or the COR is below {COR_FLOOR:g} (the message "
                     "says which): the values are the finest grid's, their error is not held to the method's "
                     "accuracy (an ill-conditioned separation time, as of a force creeping to zero)")
    if flags & _UNCERTAIN:
        notes.append("the nested grids of method adaptive are further apart in t0 than its step tolerance stands for, "
                     "or t0's differences do not yet shrink as h^2 (the message says which): the values are "
                     "Richardson-extrapolated, but their error is not held to the method's accuracy; a smaller "
                     "step_tol reduces the error")
    r = impact.geometry.r
    if res.s_max / r > MAX_INDENTATION:
        flags |= FLAGS["large_indentation"]
        notes.append(f"s_max / r = {res.s_max / r:.3g} > {MAX_INDENTATION:g}: outside the small-indentation range of "
                     f"Hertz contact (s << r)")
    speed = math.sqrt(impact.material.modulus_at(max(res.t0, 1e-300) / 4) / _wave_density(impact))
    if impact.v0 > MAX_SPEED_FRACTION * speed:
        flags |= FLAGS["fast_impact"]
        notes.append(f"v0 = {impact.v0:g} m/s > {MAX_SPEED_FRACTION:g} of the wave speed {speed:.3g} m/s of the "
                     f"viscoelastic body: not quasi-static")
    if abs(res.energy_residual) > MAX_ENERGY_RESIDUAL:
        flags |= FLAGS["energy_residual"]
        notes.append(f"the energy balance closes only to {res.energy_residual:.3g} of the impact energy (beyond "
                     f"{MAX_ENERGY_RESIDUAL:g}): the steps are coarse for this contact (t0 = {res.t0:.3g} s); trust "
                     f"the COR to its error estimate only, or tighten the solver tolerance")
    t_d = damping_time(impact)
    if options.dt is not None or options.steps_per_contact is not None:
        steps = t_d / res.dt if math.isfinite(t_d) and res.dt > 0 else math.inf
        if steps < MIN_DAMPING_STEPS:
            flags |= FLAGS["under_resolved"]
            notes.append(f"the Kelvin-Voigt damping stops the sphere within t_d = {t_d:.3g} s, {steps:.0f} fixed "
                         f"steps (fewer than {MIN_DAMPING_STEPS}): the fixed-step error there decays only as "
                         f"(dt / t_d)^1.4; use method adaptive, or dt <= t_d / {MIN_DAMPING_STEPS}")
    if res.sphere_velocity > 0.0:
        flags |= FLAGS["no_rebound"]
        notes.append(f"the sphere still moves towards the target at separation (z'(t0) = "
                     f"{res.sphere_velocity:.3g} m/s, {res.sphere_velocity / impact.v0:.3g} v0): the target's surface "
                     f"recedes faster than the sphere follows it; this COR describes this contact only, not the "
                     f"sphere's final rebound (a plate whose deflection stays bounded is struck again)")
    res.validity = flags
    res.validity_message = "; ".join(notes)
    return res
