"""The ``adaptive`` method: product integration on a variable time grid, history as internal variables.

Every kernel is split into its newest step (exact product integration, which holds the t^-1/2
singularity of the fractional law) and older history carried by the exponential sum of
:func:`vcor.materials.expsums.soe` (exact for Prony, SLS, elastic and Kelvin-Voigt; relative error <= ``soe_tol``
for the fractional and CERF laws and the fitted two-body modulus of Eq. 1 on [smallest step, horizon];
the plate's modulus likewise, on its own modes when the plate is of another material than the
contact). One variable per exponential is updated in O(1) per step for any step size, so the cost is
O(N K) and steps can grow by orders of magnitude in long, slow contacts (thin plates) and shrink near
t = 0 and at separation. A mode that decays below 1e-18 over one step (``_records.DECAYED``) is not
touched on that step's level (its value is the last step's contribution, kept implicitly), so the fast
modes of the fractional and CERF sums cost nothing on coarse steps.

Step sizes are powers of two times h_base = 2^(floor(log2 t_c) - FLOOR_BITS) (t_c the contact-time
estimate), so every table (local weights, mode factors) is computed once per level and shared by the
points of a sweep (cached); t_n are sums of powers of two and exact in floating point.

Error control (``_adaptive_kernels.march_adaptive``): the trapezoidal rule's local error h^3 g''/12, with
g'' from the last three nodes, per unit step against ``step_tol * min(v0, max(|s'| + s / max(t, t_c),
MOTION_FLOOR v0))``: relative to the motion's own scale, so that long contacts whose motion has slowed by
orders of magnitude keep their separation time and COR (with v0 as the scale, t0 of the 1 mm SLS plate is
6-12 % off; s / max(t, t_c) is the speed of a creep that has lasted t, which s / t_c overstates in a contact
of a thousand estimates: ``tests/solvers/test_adaptive.py::test_a_creeping_capture_keeps_its_cor``). Steps are not
refined below h_base (t_c / 65536 .. t_c / 131072), where the test is waived: near t = 0 the exact
solution's u = s^3/2 makes g'' ~ t^-1/2 and the local errors there are O(h^2.5), far below the
global error. A separation is located on a step <= t / SEP_STEPS (finer where an exact exponential mode
would relax within it: :func:`separation_steps`);
the time horizon starts at HORIZON_START t_c and grows by 32 up to MAX_HORIZON t_c (the march is
restarted with an exponential sum for the longer horizon) before the run ends as ``step-budget``.

By default (``extrapolate``, option ``richardson``) the accepted grid is replayed with every step
divided by 2, 4 and 8 and the results are Richardson-extrapolated (errors h^2, h^3.5 and h^4
eliminated, see ``RICHARDSON_EXPONENTS``); the four marches share one set of level tables (exponential
sum on [h_base / 8, 2 horizon]). Where the error has no h^3.5 term (an exact exponential-sum kernel
without a Dirac term, whose modes are resolved on the accepted grid, on a rigid target or a plate of
the same kind; and the fractional and CERF laws in the cubic march, ``CUBIC``: :func:`grid_count`), the
replays stop at every step divided by 4 and three grids
eliminate h^2 and h^4 (``SMOOTH_EXPONENTS``): half the work.
"""

from __future__ import annotations

import functools
import math
import time
from dataclasses import dataclass

import numpy as np

from ..contact.impact import Impact
from ._adaptive_kernels import adaptive_grids, force_zero_cor, march_adaptive, slope_weights
from ._records import (
    LAST,
    MOTION_FLOOR,
    SEPARATION,
    STATUS,
    STATUS_DIVERGED,
    STATUS_END,
    STATUS_FULL,
    STATUS_RUNNING,
    AdaptiveControl,
    Grids,
    Modes,
    Nodes,
    Plate,
    Stop,
)
from .adaptive_tables import level_tables, plate_record, singular_kernel
from .common import OUTCOME, Result, separation_scalars
from .extrapolation import extrapolate, weights_for
from .march import N_EXTRA, Arrays, March, finish
from .nearly_elastic import contact_octave, glassy_stiffness, octave_stiffness
from .validity import FLAGS

__all__ = ["FLOOR_BITS", "GRIDS", "HORIZON_START", "MAX_FLOOR_LOWERING", "MAX_HORIZON", "MAX_SEP_STEPS",
           "MOTION_FLOOR", "RESOLVED_DECAY", "RICHARDSON_WEIGHTS", "SEP_DECAY", "SEP_STEPS",
           "SMOOTH_GRIDS", "SMOOTH_WEIGHTS",
           "exact_rate", "first_level", "grid_count", "grid_outcomes", "impact_tables", "one_call", "plate_kind",
           "richardson_outcome", "run_adaptive", "separation_steps", "slope_weights", "smooth_step", "solve"]

#: smallest step = 2^-FLOOR_BITS times the power of two at or below t_c
FLOOR_BITS = 16
#: first step, in levels above the floor (t_c / 8192 .. t_c / 16384)
START_LEVEL = 3
#: separation is located on a step <= t / SEP_STEPS, or finer for fast modes (:func:`separation_steps`)
SEP_STEPS = 1024
MAX_SEP_STEPS = 16384
SEP_DECAY = 0.1
#: time horizon: start and largest, in contact-time estimates
HORIZON_START = 64.0
MAX_HORIZON = 2.0**30
#: initial size of the solution arrays (they double when full)
INITIAL_SIZE = 2048
#: the largest step is this fraction of the horizon
MAX_STEP_FRACTION = 1.0 / 16.0
#: the grids of the Richardson extrapolation are the accepted grid and the grids with every step divided
#: by 2, 4, ... 2^SPLIT_LEVELS: their tables are the coarse grid's levels shifted by one, two, ..., so
#: one table with SPLIT_LEVELS extra levels (and its exponential sum from h_base / 2^SPLIT_LEVELS)
#: serves every march
SPLIT_LEVELS = 3
#: the number of grids of the extrapolation (the most: see SMOOTH_GRIDS)
GRIDS = SPLIT_LEVELS + 1
#: the number of grids where the error has no h^3.5 term (:func:`grid_count`)
SMOOTH_GRIDS = GRIDS - 1


def solve(impact, options, tc, history):
    """Runner of method ``adaptive`` (``vcor.solvers.simulate.METHODS``)."""
    return run_adaptive(impact, tc, step_tol=options.step_tol, max_steps=options.max_adaptive_steps,
                        rule=options.rule, history=history, ghost=options.ghost, tol=options.soe_tol,
                        extrapolate=options.richardson)


#: kernels with a t^-1/2 singularity (fractional, CERF): the newest step's u' gets a cubic term while u' > 0,
#: the start is graded (``_adaptive_kernels.GRADE``), steps do not grow while unloading, and the first step is
#: on level START_LEVEL_SINGULAR (START_LEVEL_FRACTIONAL for the fractional law: :func:`first_level`); their error
#: then has no h^3.5 term to speak of and they take SMOOTH_GRIDS grids (:func:`smooth_step`). False: the plain
#: march and GRIDS grids (benchmarks)
CUBIC = True
START_LEVEL_SINGULAR = 6
#: the fractional law's first level at step_tol FRACTIONAL_TOL: its kernel is t^-1/2 at every lag, with no time scale
#: of its own, and its start takes two levels coarser (8 graded steps fewer on the accepted grid of butyl-fc at 10 m/s)
#: at no loss over the dense scans; the CERF law's kernel (glassy below 1 / b1^2) does not (level 8: errors up to 4e-7)
START_LEVEL_FRACTIONAL = 8
FRACTIONAL_TOL = 4e-4


def first_level(material, step_tol: float = FRACTIONAL_TOL) -> int:
    """The first step's level for a kernel of ``material`` at ``step_tol``: START_LEVEL, or in the cubic march
    (:func:`_singular`) START_LEVEL_SINGULAR for the CERF law and for the fractional law START_LEVEL_FRACTIONAL
    one level lower for each factor 4, or part of one, of step_tol below FRACTIONAL_TOL (the error-controlled
    steps go as step_tol^1/2: the start stays at most their ratio to it at FRACTIONAL_TOL), not below
    START_LEVEL_SINGULAR."""
    if not _singular(material):
        return START_LEVEL
    if material.sqrt_law() is None:
        return START_LEVEL_SINGULAR
    shift = math.floor(0.5 * math.log2(step_tol / FRACTIONAL_TOL) + 1e-9)
    return max(START_LEVEL_SINGULAR, min(START_LEVEL_FRACTIONAL, START_LEVEL_FRACTIONAL + shift))


def _singular(material):
    """A kernel the method marches with the cubic specialisation (:func:`~.adaptive_tables.singular_kernel`,
    while CUBIC)."""
    return CUBIC and singular_kernel(material)


def _start_level(tables, material, step_tol):
    """The first step's level on ``tables`` (:class:`~.adaptive_tables.Tables`) of ``material``'s kernel:
    START_LEVEL, or :func:`first_level` for the cubic march."""
    return START_LEVEL if tables.singular is None else first_level(material, step_tol)


def _grown(a, n):
    out = np.zeros(n + 1, dtype=a.dtype)
    out[: a.size] = a
    return out


def plate_kind(impact) -> int:
    """How the march evaluates the plate's mobility: 0, a rigid target or a constant mobility; 1, the
    plate's modulus on exponential modes (the kernel's own when the plate is of the contact's material,
    else the plate material's exact Prony terms or exponential sum, :func:`~.adaptive_tables.plate_tables`);
    in closed form, 2 for the fractional law (``Material.sqrt_law``) and 3 for the CERF law
    (``Material.erfcx_law``; its ~100 modes would cost a third of the impact)."""
    g = impact.geometry
    plate = impact.material if g.plate_material is None else g.plate_material
    if g.rigid or g.case == 4 or plate.is_elastic:  # (is_elastic: cached per material)
        return 0
    if plate.sqrt_law() is not None:
        return 2
    return 3 if plate.erfcx_law() is not None else 1


def smooth_step(impact, kind: int | None = None, tc: float | None = None) -> float:
    """The largest step (s) of an accepted grid on which the error has no h^3.5 term
    (``SMOOTH_EXPONENTS``): RESOLVED_DECAY over :func:`exact_rate`, or 0 where the error may have that term
    at any step: a kernel or plate that is not an exact exponential sum without a Dirac term, an elastic
    kernel (its force vanishes with the overlap, as ``|t - t0|^1.5``: the step across the separation leaves
    an error that depends on where t0 falls in it, which three grids do not remove), a nearly elastic one
    (:func:`glassy_stiffness`; likewise). ``kind``: the impact's :func:`plate_kind` and ``tc`` its
    contact-time estimate (s), where the caller has them. Also 0 where RESOLVED_DECAY is 0 or the grid
    constants have been set to another number of grids (SMOOTH_GRIDS is then not GRIDS - 1: benchmarks)."""
    return 0.0 if glassy_stiffness(impact, tc) else _resolved_step(impact, kind)


def _resolved_step(impact, kind):
    """:func:`smooth_step` but for its nearly elastic kernels (a decision that depends on the speed: the
    level tables, cached for every speed, hold this)."""
    if not (RESOLVED_DECAY > 0.0 and SMOOTH_GRIDS == GRIDS - 1) or impact.material.is_elastic:
        return 0.0
    if _singular(impact.material):
        return math.inf
    rate = exact_rate(impact, plate_kind(impact) if kind is None else kind)
    return 0.0 if rate < 0.0 else RESOLVED_DECAY / rate if rate > 0.0 else math.inf


def exact_rate(impact, kind: int) -> float:
    """The fastest rate (1/s) of the kernel's and the plate's exponential modes where both are exact
    exponential sums without a Dirac term (0: no modes), or -1 where not (fractional, CERF, Kelvin-Voigt,
    a plate in closed form: :func:`plate_kind` 2, 3). ``kind``: the impact's :func:`plate_kind`."""
    mat, plate = impact.material, impact.geometry.plate_material
    if (not mat.is_prony or mat.viscosity != 0.0 or kind >= 2
            or (kind == 1 and plate is not None and not (plate.is_prony and plate.viscosity == 0.0))):
        return -1.0
    return max(mat.fastest_rate, plate.fastest_rate) if kind == 1 and plate is not None else mat.fastest_rate


def separation_steps(rate: float, tc: float) -> int:
    """A separation is located on a step <= t / this (and not below the smallest step, h_base): SEP_STEPS,
    doubled (up to MAX_SEP_STEPS) until the fastest exact mode (``rate``, 1/s; :func:`exact_rate`) decays
    by at most SEP_DECAY over a step of ``tc`` / it (s): a mode relaxing within the separation step leaves
    t0 with an error that follows no power of the step (the SLS family of bench_grids.py)."""
    n = SEP_STEPS
    while n < MAX_SEP_STEPS and n * SEP_DECAY < rate * tc:
        n *= 2
    return n


def grid_count(largest_step: float, smooth: float) -> int:
    """The number of Richardson grids for an accepted grid whose largest step is ``largest_step`` (s):
    SMOOTH_GRIDS when it is at most ``smooth`` (:func:`smooth_step`), else GRIDS."""
    return SMOOTH_GRIDS if largest_step <= smooth else GRIDS


def _body(impact) -> tuple:
    """The impact's :class:`~._records.Body` as a plain tuple (the kernels' boundary: ``_records``)."""
    return (float(impact.kappa * impact.material.viscosity), float(impact.m), float(impact.v0))


@functools.lru_cache(maxsize=64)
def _stop(rule, glassy):
    """(Cached: a few per sweep.) The march's :class:`~._records.Stop` record as a plain tuple: the separation
    ``rule`` and the kernel's k(0) (N m^-1.5, :func:`glassy_stiffness`)."""
    return tuple(Stop(0 if rule == "force" else 1, N_EXTRA, glassy))


@dataclass(kw_only=True, frozen=True)
class _Grid:
    """One march's grid: h_base (s), the contact-time estimate tc (s), split (0, 1, 2: the grid,
    halved, quartered), an optional fixed level and a replayed level plan."""

    h_base: float
    tc: float
    split: int = 0
    fixed_level: int | None = None
    plan: np.ndarray | None = None


def _tables_for(impact, h_base, factor, tol, kind, tc):
    """(horizon (s), number of levels, tables, plate record as a plain tuple, largest relative error of
    the kernel's and the plate's exponential sums, :func:`smooth_step`, :func:`exact_rate`,
    :func:`glassy_stiffness`) for the horizon ``factor`` estimates.
    They depend on the impact's material and geometry, not on its speed: cached on those (a sweep's points
    and repeated calls share them). The key also holds the module's grid constants and its
    :func:`level_tables` as they are at the call, so that a benchmark or test that sets them is never
    served tables made under others."""
    tables = impact_tables(impact.material, impact.geometry, h_base, factor, tol, kind,
                           (level_tables, FLOOR_BITS, SPLIT_LEVELS, MAX_STEP_FRACTION, RESOLVED_DECAY, SMOOTH_GRIDS,
                            CUBIC, START_LEVEL_SINGULAR, START_LEVEL_FRACTIONAL, FRACTIONAL_TOL),
                           contact_octave(tc))
    glassy = tables[7]
    return (*tables[:5], 0.0 if glassy else tables[5], tables[6], glassy)


@functools.lru_cache(maxsize=256)
def impact_tables(material, geometry, h_base, factor, tol, kind, module, octave):
    """(Cached.) :func:`_tables_for` of an impact of ``material`` and ``geometry`` (any speed) but for its 0
    smooth step where nearly elastic, with :func:`glassy_stiffness` last; ``module``: (level_tables, FLOOR_BITS,
    SPLIT_LEVELS, MAX_STEP_FRACTION, RESOLVED_DECAY, SMOOTH_GRIDS) at the call; ``octave``: the power of two at or
    below the contact-time estimate (s, ``nearly_elastic.contact_octave``; h_base's unless the floor is lowered)."""
    impact = Impact(material, 1.0, geometry)  # the speed enters none of the tables
    level_tables, FLOOR_BITS, SPLIT_LEVELS, MAX_STEP_FRACTION = module[:4]  # noqa: N806 (the module's, as keyed)
    top = h_base * 2.0**FLOOR_BITS
    horizon = factor * 2.0 * top  # a power of two >= factor t_c: the tables of a sweep's points are shared
    n_levels = round(math.log2(MAX_STEP_FRACTION * horizon / h_base)) + 1
    tables = level_tables(impact.material, float(impact.kappa), h_base * 2.0**-SPLIT_LEVELS, n_levels + SPLIT_LEVELS,
                          2.0 * horizon, tol, module[6])
    plate, plate_error = plate_record(impact, tables, kind)
    return (horizon, n_levels, tables, tuple(plate), max(tables.soe_error, plate_error), _resolved_step(impact, kind),
            exact_rate(impact, kind), octave_stiffness(impact.material, float(impact.kappa), octave))


def _march(impact, grid, factor, *, step_tol, max_steps, rule, ghost, tol, kind):
    """One adaptive march on ``grid`` with the horizon extension (``kind``: :func:`plate_kind`).
    Returns (March, levels, horizon, factor)."""
    plan = _NO_PLAN if grid.plan is None else grid.plan
    while True:
        horizon, n_levels, tables, plate, soe_error, _, rate, glassy = _tables_for(impact, grid.h_base, factor, tol,
                                                                                   kind, grid.tc)
        nk = tables.levels.mode_decay.shape[1]
        modes = tuple(Modes(np.zeros(nk), np.ones(Plate(*plate).moduli.size)))
        first = _start_level(tables, impact.material, step_tol) if grid.fixed_level is None else int(grid.fixed_level)
        lo, hi = (0, n_levels - 1) if grid.fixed_level is None else (first, first)
        control = tuple(AdaptiveControl(step_tol, 1.0 / grid.tc, lo, hi, horizon, 1.0 / separation_steps(rate, grid.tc),
                                        ghost))
        state = np.array([0, -1, 0, STATUS_RUNNING, 0, 0, first, 0], dtype=np.int64)
        size = INITIAL_SIZE if plan.size == 0 else plan.size + 2 * N_EXTRA + 8
        arr = Arrays(min(size, max_steps))
        t, lev = np.zeros(arr.n + 1), np.zeros(arr.n + 1, dtype=np.int64)
        arr.g[0] = impact.v0
        while True:
            march_adaptive(tuple(Nodes(t, arr.s, arr.g, arr.F, arr.J, arr.u)), lev, tuple(tables.levels), plate,
                           _body(impact), control, _stop(rule, glassy), modes, state, plan, SPLIT_LEVELS - grid.split,
                           tables.singular)
            if state[STATUS] != STATUS_FULL or (state[SEPARATION] < 0 and arr.n >= max_steps):
                break  # a verdict, or the step budget (the steps after a separation are not budgeted)
            arr.grow(2 * arr.n if state[SEPARATION] >= 0 else min(2 * arr.n, max_steps))
            t, lev = _grown(t, arr.n), _grown(lev, arr.n)
        n_done = int(state[LAST])
        if not (state[STATUS] == STATUS_END and state[SEPARATION] < 0 and t[n_done] >= horizon
                and factor < MAX_HORIZON):
            step = float(np.max(np.diff(t[: n_done + 1]))) if n_done else math.nan
            march = March(arrays=arr, state=state, n_done=n_done, dt=step, t=t, note=_ghost_note(state, t, n_done),
                          budget=_budget_text(t, n_done, horizon, grid.tc, max_steps), soe_error=soe_error,
                          glassy=glassy)
            return march, lev, horizon, factor
        factor *= 32.0


_NO_PLAN = np.zeros(0, dtype=np.int64)


def _ghost_note(state, t, n_done):
    if state[STATUS] == STATUS_DIVERGED and state[SEPARATION] >= 0 and n_done >= state[SEPARATION] + N_EXTRA:
        return f"ghost continuation stopped at t = {t[n_done]:.6g} s: the march diverged"
    return ""


def _budget_text(t, n_done, horizon, tc, max_steps):
    """The message of a march that ended without a verdict: at the largest time horizon ``horizon`` (s; the
    march returns there only when the horizon can grow no further) or at the step budget."""
    said = (f"before a verdict: the contact force had not returned to zero at t = {t[n_done]:.6g} s ({n_done} "
            f"adaptive steps); s_max and f_max are over that window")
    if t[n_done] >= horizon:
        return (f"stopped by the largest time horizon, {horizon:.6g} s ({horizon / tc:.3g} contact-time estimates), "
                f"{said}. A contact that long does not separate in any practical sense")
    return (f"stopped by the step budget max_adaptive_steps = {max_steps} {said}. To reach a verdict raise "
            f"max_adaptive_steps")


#: Richardson extrapolation from GRIDS nested grids (the accepted grid, every step divided by 2, 4, 8):
#: on the method's graded grids the error expands in h^2 (the trapezoidal rule), then h^3.5 (the
#: fractional law's t^-1/2 kernel near lag 0, and a Kelvin-Voigt Dirac term eta u' with u' ~ t^1/2 at
#: impact, against the quadratic u' of the newest step) and h^4 (every kernel). The second-order slopes
#: and the newest step's curvature term (``_adaptive_kernels``) leave no h^3 term, and the grading near
#: t = 0 (steps of h_base where u = s^{3/2} is not smooth) leaves the h^2.5 term of uniform grids below
#: the others: with h^2 removed the grids' differences fall as h^3.3..h^3.8 (Kelvin-Voigt, and the fractional
#: law in the plain march) and h^3.8..h^4.5 (``tests/solvers/test_adaptive.py::test_graded_grids_error_expansion``;
#: the fractional and CERF laws' cubic march, ``CUBIC``: faster than h^4 on the coarse grids, 1/53 and 1/37 of
#: the plain march's residual at 1 m/s, and three grids); against
#: independent references (bench_accuracy.py) (2, 3.5, 4) leave half the error of (2, 3, 4)
RICHARDSON_EXPONENTS = (2.0, 3.5, 4.0)
RICHARDSON_WEIGHTS = weights_for(RICHARDSON_EXPONENTS)
#: Three grids (the accepted grid, every step divided by 2 and 4) eliminating h^2 and h^4, where the error
#: has no h^3.5 term: a relaxing kernel that is an exact exponential sum (Prony, SLS; no Dirac term, no
#: t^-1/2 singularity) on a rigid target, a plate of constant mobility or one whose modulus is an exact
#: exponential sum, and every one of their modes resolved on the accepted grid (rate times the largest
#: step <= RESOLVED_DECAY; :func:`grid_count`); modes that relax within a step leave a pre-asymptotic
#: error that three grids do not remove and four do (``benchmarks/bench_grids.py``, SLS family)
SMOOTH_EXPONENTS = (2.0, 4.0)
SMOOTH_WEIGHTS = weights_for(SMOOTH_EXPONENTS)
#: a mode of rate b is resolved on a grid whose largest step h has b h <= RESOLVED_DECAY (it decays by at
#: most 10 % over any step); the three grids' largest COR error on bench_grids.py's SLS family at step_tol
#: 4e-4 stays below 1e-7 up to b h = 0.1 and reaches 1.5e-7..2.2e-7 at b h = 0.5..1
RESOLVED_DECAY = 0.1
#: scalars of a Result that are Richardson-extrapolated: all of a separation's outcome (omega_min follows t0)
EXTRAPOLATED = OUTCOME


def run_adaptive(impact, tc, *, step_tol, max_steps, rule="force", history=False, ghost=0.0, tol=1e-10,
                 fixed_level=None, extrapolate=False, one_call_path=True):
    """Adaptive march (see the module docstring). ``tc``: contact-time estimate, s.

    ``extrapolate``: march again on the accepted grid with every step divided by 2, 4, ... 2^SPLIT_LEVELS
    (the same levels on tables for h_base / 2, h_base / 4, ...; no error control) and
    Richardson-extrapolate the scalars with ``RICHARDSON_WEIGHTS`` (eliminates the error terms of
    RICHARDSON_EXPONENTS), or with one replay fewer and ``SMOOTH_WEIGHTS`` where :func:`grid_count`
    says so; histories are those of the finest grid.
    ``fixed_level`` (tests): march every step on that level (h = h_base 2^level, no error control),
    a uniform grid on which the march is the direct scheme with an exponential-sum history.
    ``one_call_path`` (tests): False runs the general path also where :func:`one_call` would do.

    A separation earlier than SEP_STEPS smallest steps cannot be located on a step <= t / SEP_STEPS: it
    fell on steps the error control could not refine (a contact far shorter than tc, or a spurious
    zero of the force on the first, unresolved steps of a plate that recedes at once). The march is then
    run again with the smallest step lowered below t0 / SEP_STEPS (the horizon kept), up to
    MAX_FLOOR_LOWERING levels; a separation still unresolved there is ``diverged``."""
    t_start = time.perf_counter()
    h_base = 2.0 ** math.floor(math.log2(tc)) * 2.0**-FLOOR_BITS
    lowered = 0
    opts = (step_tol, max_steps, rule, history, ghost, tol, fixed_level, extrapolate)  # as _run_on_floor unpacks
    while True:
        res = _run_on_floor(impact, tc, h_base, HORIZON_START * 2.0**lowered, one_call_path and lowered == 0, opts)
        if fixed_level is not None or not res.ok or res.t0 >= SEP_STEPS * h_base:
            break
        if lowered >= MAX_FLOOR_LOWERING:
            res.status = "diverged"
            res.message = (f"the separation at t0 = {res.t0:.6g} s falls on unresolved steps: the smallest step "
                           f"{h_base:.3g} s, {lowered} levels below the usual, is still above t0 / {SEP_STEPS}")
            break
        k = min(max(1, math.ceil(math.log2(2.0 * SEP_STEPS * h_base / res.t0))), MAX_FLOOR_LOWERING - lowered)
        h_base *= 2.0**-k
        lowered += k
    res.wall_time = time.perf_counter() - t_start
    return res


#: the most levels by which :func:`run_adaptive` lowers its smallest step to resolve an early separation
MAX_FLOOR_LOWERING = 40


def _run_on_floor(impact, tc, h_base, factor, one_call_path, opts):
    """:func:`run_adaptive` (its options ``opts``) on the smallest step ``h_base`` (s), first horizon ``factor``."""
    step_tol, max_steps, rule, history, ghost, tol, fixed_level, extrapolate = opts
    kind = plate_kind(impact)
    t_start = time.perf_counter()
    if one_call_path and not history and fixed_level is None:
        res = _one_call(impact, tc, kind, h_base, GRIDS if extrapolate else 1, step_tol, max_steps, rule, tol)
        if res is not None:
            return res
    kw = {"step_tol": step_tol, "max_steps": max_steps, "rule": rule, "tol": tol, "kind": kind}
    last_history = history and not extrapolate
    march, lev, _, factor = _march(impact, _Grid(h_base=h_base, tc=tc, fixed_level=fixed_level), factor,
                                   ghost=ghost if last_history else 0.0, **kw)
    march.wall = time.perf_counter() - t_start
    coarse = _force_zero(finish(impact, march, rule=rule, history=last_history, method="adaptive"), impact, rule,
                         _tables_for(impact, h_base, factor, tol, kind, tc)[3])
    if not (extrapolate and coarse.ok):
        return coarse
    n_plan = min(march.n_done, int(march.state[SEPARATION]) + N_EXTRA)
    runs = [coarse]
    n_grids = grid_count(march.dt, smooth_step(impact, kind, tc))  # march.dt: its largest step
    for shift in range(1, n_grids):
        last = history and shift == n_grids - 1
        grid = _Grid(h_base=h_base, tc=tc, split=shift, plan=np.repeat(lev[1: n_plan + 1], 2**shift))
        march, _, _, factor = _march(impact, grid, factor, ghost=ghost if last else 0.0,
                                     **{**kw, "max_steps": 2**shift * max_steps})
        march.wall = time.perf_counter() - t_start
        run = _force_zero(finish(impact, march, rule=rule, history=last, method="adaptive"), impact, rule,
                          _tables_for(impact, h_base, factor, tol, kind, tc)[3])
        if not run.ok:
            said = run.message.replace(f"steps = {2**shift * max_steps}", f"steps = {2**shift} x {max_steps}")
            run.message = f"the replay of the accepted grid with every step divided by {2**shift} failed: {said}"
            return run
        runs.append(run)
    fine = runs[-1]
    fine.steps = sum(r.steps for r in runs)
    values, message, flag = richardson_outcome([[float(getattr(r, k)) for k in OUTCOME] for r in runs], step_tol)
    fine.__dict__.update(separation_scalars(values))
    fine.message = "; ".join(m for m in (fine.message, message) if m)
    if flag:
        fine.validity |= FLAGS[flag]
    return fine


def _force_zero(res, impact, rule, plate):
    """``res`` with the COR of a separation by the force rule from the sphere's velocity and the plate's
    mobility at t0 (``_adaptive_kernels.force_zero_cor``, as the one-call path's grids have it; ``plate``:
    the march's plate record as a plain tuple)."""
    if rule == "force" and res.ok:
        res.cor = float(force_zero_cor(res.t0, res.sphere_velocity, plate, impact.m, impact.v0))
    return res


def one_call(impact, tc, n_grids, *, step_tol, max_steps, rule, tol):
    """The usual case of :func:`run_adaptive` (no histories; ``n_grids`` GRIDS with extrapolation, of which
    :func:`grid_count` may take one fewer, else 1) in one numba call (``_adaptive_kernels.adaptive_grids``):
    the same marches and separations as the general path, without its Python between them. None when a
    grid did not simply separate within the first time horizon and 2048 steps (the general path then
    runs and reports it)."""
    h_base = 2.0 ** math.floor(math.log2(tc)) * 2.0**-FLOOR_BITS
    return _one_call(impact, tc, plate_kind(impact), h_base, n_grids, step_tol, max_steps, rule, tol)


def grid_outcomes(impact, tc, n_grids, *, step_tol, max_steps, rule, tol, fewer=False):
    """The rows :func:`one_call` extrapolates (tests): per grid (coarse to fine) the OUTCOME values, the
    separation index and the largest step (s), as a (grids, 11) array: ``n_grids`` rows, or with
    ``fewer`` one fewer where :func:`grid_count` says so (as :func:`one_call`); None where
    :func:`one_call` declines."""
    h_base = 2.0 ** math.floor(math.log2(tc)) * 2.0**-FLOOR_BITS
    rows, _ = _grid_rows(impact, tc, plate_kind(impact), h_base, n_grids, step_tol, max_steps, rule, tol,
                         smooth_step(impact, tc=tc) if fewer else 0.0)
    return rows


def _grid_rows(impact, tc, kind, h_base, n_grids, step_tol, max_steps, rule, tol, smooth):
    """(rows, the exponential sums' relative error) of :func:`grid_outcomes`; rows None where declined.
    ``smooth``: :func:`smooth_step` (None: the impact's, cached with its tables), or 0 for all ``n_grids``."""
    horizon, n_levels, tables, plate, soe_error, own, rate, glassy = _tables_for(impact, h_base, HORIZON_START, tol,
                                                                                 kind, tc)
    control = (step_tol, 1.0 / tc, 0, n_levels - 1, horizon, 1.0 / separation_steps(rate, tc), 0.0)  # AdaptiveControl
    out = np.empty((max(GRIDS, n_grids), 11))
    stop = _stop(rule, glassy)
    grids = tuple(Grids(n_grids, SPLIT_LEVELS, own if smooth is None else smooth))
    done = adaptive_grids(grids, tables.plain_levels, plate, _body(impact), control, stop, max_steps,
                          _start_level(tables, impact.material, step_tol), INITIAL_SIZE, out, tables.singular)
    if not done:
        return None, soe_error
    return out[:done], soe_error


def _one_call(impact, tc, kind, h_base, n_grids, step_tol, max_steps, rule, tol):
    rows, soe_error = _grid_rows(impact, tc, kind, h_base, n_grids, step_tol, max_steps, rule, tol,
                                 None if n_grids == GRIDS else 0.0)
    if rows is None:
        return None
    rows = rows.tolist()
    values, message, flag = richardson_outcome(rows, step_tol) if n_grids == GRIDS else (rows[-1], "", "")
    res = Result(**separation_scalars(values), steps=int(sum([row[9] for row in rows])), dt=rows[-1][10],
                 method="adaptive", soe_error=soe_error)
    res.message = message
    if flag:
        res.validity |= FLAGS[flag]
    return res


def richardson_outcome(runs, step_tol):
    """(values, message, flag) of :func:`vcor.solvers.extrapolation.extrapolate` for ``runs`` (GRIDS rows, coarse to
    fine: ``RICHARDSON_WEIGHTS``; SMOOTH_GRIDS rows: ``SMOOTH_WEIGHTS``) of an accepted grid marched at
    ``step_tol``."""
    return extrapolate(runs, RICHARDSON_WEIGHTS if len(runs) == len(RICHARDSON_WEIGHTS) else SMOOTH_WEIGHTS,
                       step_tol=step_tol)
