"""The plain NumPy/SciPy references (``vcor.solvers.reference``) against the numba kernels, at small N.

Every march is compared on the presets it takes, at v0 = 1 and 10 m/s, on the paper's plate and a
rigid target, at STEPS_PER_CONTACT steps per contact-time estimate (the adaptive method: its own grid
at the default step_tol): separation scalars to RTOL relative (each against its own scale, SCALES), node
arrays s, s', F, J to RTOL relative to their largest value, the adaptive level sequence exactly.
``pytest -s`` prints the largest differences found per method and quantity.
"""

from __future__ import annotations

import math
import warnings
from collections import defaultdict

import numpy as np
import pytest

import vcor
from vcor.contact import bodies, pair
from vcor.contact.impact import make_impact
from vcor.solvers import adaptive, direct, ive, nearly_elastic
from vcor.solvers import reference as R
from vcor.solvers import soe as soe_method
from vcor.solvers.common import separation

PRESETS = ["sls", "butyl-fc", "butyl-cerf", "butyl-prony3", "kelvin-voigt", "elastic"]
PRONY = [p for p in PRESETS if vcor.materials.get(p).is_prony]
FINITE_K0 = [p for p in PRESETS if math.isfinite(vcor.materials.get(p).glassy)]
NO_DIRAC = [p for p in PRESETS if vcor.materials.get(p).viscosity == 0]
TARGETS = {"plate": {}, "rigid": {"rigid": True}}
SPEEDS = (1.0, 10.0)
STEPS_PER_CONTACT = 150
#: the fixed-step budget in contact times (march.MAX_T_FACTOR); the soe horizon follows from it
MAX_T_FACTOR = 32
RTOL = 1e-12
STEP_TOL = vcor.SolverOptions().step_tol


def cases(presets):
    return [pytest.param(p, v0, t, id=f"{p}-{v0:g}-{t}") for p in presets for v0 in SPEEDS for t in TARGETS]


#: largest difference seen, per (method, quantity)
WORST = defaultdict(float)


@pytest.fixture(scope="module", autouse=True)
def print_worst():
    yield
    print(f"\nlargest differences, reference - numba (vcor from {vcor.__file__}):")
    for method in sorted({m for m, _ in WORST}):
        row = {q: d for (m, q), d in WORST.items() if m == method}
        print(f"  {method:24s}" + " ".join(f"{q}={d:.1e}" for q, d in row.items()))


#: the COR's scale is at least this: 1e-14 absolute. s'(t0) is a difference of terms of size v0 (v0 - J/m
#: - ...), so its rounding is relative to v0, like the sphere velocity's; after the 2 400 steps of the
#: creeping contact of SLS on the plate with the overlap rule (COR 2.6e-4) the two marches' s'(t0)
#: differ by 2.4e-15 v0
COR_FLOOR = 1e-2


def scales(impact, numba):
    """Scale of each separation scalar: the value itself for cor (at least COR_FLOOR), t0, s_max,
    f_max; s_max for the residual interference; m v0^2/2 for the works; v0 for the sphere velocity;
    1 for the (already relative) energy residual."""
    e_in = 0.5 * impact.m * impact.v0**2
    return {"cor": max(numba["cor"], COR_FLOOR), "t0": numba["t0"], "s_residual": numba["s_max"], "w_h": e_in,
            "w_plate": e_in, "sphere_velocity": impact.v0, "energy_residual": 1.0, "s_max": numba["s_max"],
            "f_max": numba["f_max"]}


def check_scalars(method, impact, ref, numba):
    """numba: a Result or a dict with the names of R.OUTCOME."""
    numba = {k: (numba[k] if isinstance(numba, dict) else getattr(numba, k)) for k in R.OUTCOME}
    for key, scale in scales(impact, numba).items():
        diff = abs(ref[key] - numba[key]) / abs(scale)
        WORST[method, key] = max(WORST[method, key], diff)
        assert diff <= RTOL, (method, key, ref[key], numba[key])


def check_nodes(method, ref, history):
    """Node arrays s, s', F, J (and t) of the reference against a march's ``Histories``."""
    assert ref["t"].size == history.t.size, (method, ref["t"].size, history.t.size)
    assert np.array_equal(ref["t"], history.t), method  # n dt, or sums of powers of two: exact
    for key, numba in (("s", history.s), ("g", history.sdot), ("F", history.F), ("J", history.J)):
        diff = np.max(np.abs(ref[key] - numba)) / np.max(np.abs(numba))
        WORST[method, key] = max(WORST[method, key], diff)
        assert diff <= RTOL, (method, key, diff)


def fixed_step_case(name, v0, target):
    """(impact, dt, n_steps, max_steps) as ``simulate`` chooses them for STEPS_PER_CONTACT."""
    impact = make_impact(name, v0, TARGETS[target])
    tc = impact.contact_time_estimate()
    dt = tc / STEPS_PER_CONTACT
    return impact, dt, max(math.ceil(1.5 * tc / dt), 16), MAX_T_FACTOR * STEPS_PER_CONTACT


# ------------------------------------------------------------------------------------------------
# fixed-step marches
# ------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("name, v0, target", cases(PRESETS))
def test_direct(name, v0, target):
    impact, dt, n, budget = fixed_step_case(name, v0, target)
    ref = R.direct_reference(impact, dt, budget)
    res = direct.run_direct(impact, dt, n, max_steps=budget, history=True, ghost=0.0)
    assert res.ok and res.steps == ref["n_sep"]
    check_scalars("direct-a", impact, ref, res)
    check_nodes("direct-a", ref, res.history)


@pytest.mark.parametrize("name, v0, target", cases(PRESETS))
def test_direct_volterra(name, v0, target):
    impact, dt, n, budget = fixed_step_case(name, v0, target)
    ref = R.direct_reference(impact, dt, budget, volterra=True, c2=1.0)
    res = direct.run_direct(impact, dt, n, max_steps=budget, volterra=True, c2=1.0, history=True, ghost=0.0)
    assert res.ok and res.steps == ref["n_sep"]
    check_scalars("direct-a+volterra", impact, ref, res)
    check_nodes("direct-a+volterra", ref, res.history)


@pytest.mark.parametrize("name, v0, target", cases(FINITE_K0))
def test_direct_form_b(name, v0, target):
    impact, dt, n, budget = fixed_step_case(name, v0, target)
    ref = R.direct_reference(impact, dt, budget, form="b")
    res = direct.run_direct(impact, dt, n, max_steps=budget, form="b", history=True, ghost=0.0)
    assert res.ok and res.steps == ref["n_sep"]
    check_scalars("direct-b", impact, ref, res)
    check_nodes("direct-b", ref, res.history)


@pytest.mark.parametrize("name, v0, target", cases(PRONY))
def test_prony(name, v0, target):
    impact, dt, n, budget = fixed_step_case(name, v0, target)
    ref = R.prony_reference(impact, dt, budget)
    res = ive.run_ive_fixed(impact, dt, n, max_steps=budget, history=True, ghost=0.0)
    assert res.ok and res.steps == ref["n_sep"]
    check_scalars("ive-numba", impact, ref, res)
    check_nodes("ive-numba", ref, res.history)


@pytest.mark.parametrize("name, v0, target", cases(PRESETS))
def test_soe(name, v0, target):
    impact, dt, n, budget = fixed_step_case(name, v0, target)
    ref = R.soe_reference(impact, dt, budget, t_max=(budget + 8) * dt)  # run_soe's horizon, ghost 0
    res = soe_method.run_soe(impact, dt, n, max_steps=budget, history=True, ghost=0.0)
    assert res.ok and res.steps == ref["n_sep"]
    check_scalars("soe", impact, ref, res)
    check_nodes("soe", ref, res.history)


@pytest.mark.parametrize("name, v0, target", cases(NO_DIRAC))
def test_paper(name, v0, target):
    impact, dt, n, budget = fixed_step_case(name, v0, target)
    ref = R.paper_reference(impact, dt, budget)
    res = direct.run_paper(impact, dt, n, max_steps=budget, history=True)
    assert res.ok and res.steps == ref["n_sep"]
    check_scalars("paper", impact, ref, res)
    check_nodes("paper", ref, res.history)


# ------------------------------------------------------------------------------------------------
# adaptive march
# ------------------------------------------------------------------------------------------------
def geometry_of(impact):
    """The geometry keywords that give ``impact`` back through ``vcor.simulate``."""
    g = impact.geometry
    return {k: getattr(g, k) for k in ("r", "rho_a", "rho_b", "h", "nu", "case", "rigid", "E_plate", "nu_plate",
                                       "plate_material")}


def levels_of(t, h_base, split=0):
    """Levels of the steps of a grid t (steps h_base 2^(level - split), exact powers of two)."""
    return np.rint(np.log2(np.diff(t) / h_base)).astype(int) + split


def numba_grids(impact, tc):
    """The outcome rows of the Richardson grids as the one-call path computes them
    (``adaptive.grid_outcomes``, with one grid fewer where the kernel is smooth and resolved): per grid
    the 9 values of R.OUTCOME, separation index, largest step."""
    out = adaptive.grid_outcomes(impact, tc, adaptive.GRIDS, step_tol=STEP_TOL, max_steps=10**6, rule="force",
                                 tol=1e-10, fewer=True)
    assert out is not None
    return out


def two_bodies(name, v0, target):
    """The impact of an elastic sphere (E = 70 GPa, nu 0.3) on a plate of ``name`` (``target`` body-plate), or
    of a ``name`` sphere on a butyl-prony3 sphere (``target`` body-sphere): the Eq. 1 contact modulus as a
    fitted exponential sum, the plate's mobility from the plate's own modulus."""
    if target == "body-plate":
        a = bodies.body_from_spec("sphere", {"material": {"model": "elastic", "E": 7e10}})
        material, geometry = bodies.impact_inputs(a, bodies.body_from_spec("plate", {"material": name}))
    else:
        a = bodies.body_from_spec("sphere", {"material": name})
        material, geometry = pair.sphere_pair(a, bodies.body_from_spec("sphere", {"material": "butyl-prony3"}))
    return make_impact(material, v0, geometry)


#: the two-body cases: a plate of every viscoelastic law under an elastic sphere, and sphere pairs
BODY_CASES = [pytest.param(p, 10.0, t, id=f"{p}-10-{t}") for p in ("sls", "butyl-fc", "butyl-cerf")
              for t in ("body-plate", "body-sphere")]


def adaptive_case(name, v0, target):
    impact = two_bodies(name, v0, target) if target.startswith("body-") else make_impact(name, v0, TARGETS[target])
    return impact, impact.contact_time_estimate()


@pytest.mark.parametrize("name, v0, target", cases(PRESETS) + BODY_CASES)
def test_adaptive_grid(name, v0, target):
    """The controlled grid: the same levels step by step (the reference's own error control), then
    the same nodes and scalars. Should rounding ever flip a decision, the reference replays the
    kernel's levels instead (and the test says so)."""
    impact, tc = adaptive_case(name, v0, target)
    res = adaptive.run_adaptive(impact, tc, step_tol=STEP_TOL, max_steps=10**6, history=True, ghost=0.0)
    assert res.ok
    numba_levels = levels_of(res.history.t, R.AdaptiveGrid.of(impact, tc).h_base)
    ref = R.adaptive_reference(impact, tc, STEP_TOL)
    WORST["adaptive", "level changes"] = max(WORST["adaptive", "level changes"],
                                             float(not np.array_equal(ref["levels"], numba_levels)))
    if not np.array_equal(ref["levels"], numba_levels):
        warnings.warn(f"{name} {v0} {target}: the reference's error control chose other levels than the kernel "
                      "(a decision flipped by rounding?); comparing the replay of the kernel's levels instead",
                      stacklevel=1)
        ref = R.adaptive_reference(impact, tc, STEP_TOL, plan=numba_levels)
    assert res.steps == ref["n_sep"]
    check_scalars("adaptive grid", impact, ref, res)
    check_nodes("adaptive grid", ref, res.history)


@pytest.mark.parametrize("name, v0, target", cases(PRESETS) + BODY_CASES)
def test_adaptive_richardson(name, v0, target):
    """The grids (controlled, and its replays with every step divided by 2, 4, 8; by 2, 4 where the
    reference finds the kernel smooth and resolved) one by one against the kernel's ``adaptive_grids``
    (the same number of grids), the finest grid's nodes against the general path's history, and the
    extrapolated scalars against ``simulate(method="adaptive")`` (its default)."""
    check_richardson(*adaptive_case(name, v0, target))


#: a nearly elastic kernel (it relaxes by 1e-5..5e-5 within the contact: ``nearly_elastic.glassy_stiffness``), whose
#: separation the method locates on k(0) u(s) + (F - k(0) u)
NEARLY_ELASTIC = vcor.materials.Prony(1e7, (5e7,), (1.0 / 30.0,))


@pytest.mark.parametrize("v0", [0.1, 10.0])
@pytest.mark.parametrize("target", list(TARGETS))
def test_adaptive_richardson_of_a_nearly_elastic_kernel(target, v0):
    """As test_adaptive_richardson, for a kernel whose separation is located with its k(0)."""
    impact = make_impact(NEARLY_ELASTIC, v0, TARGETS[target])
    tc = impact.contact_time_estimate()
    assert nearly_elastic.glassy_stiffness(impact, tc) > 0.0
    check_richardson(impact, tc)


def check_richardson(impact, tc):
    """The body of test_adaptive_richardson for ``impact`` and its contact-time estimate ``tc`` (s)."""
    v0 = impact.v0
    ref = R.adaptive_richardson_reference(impact, tc, STEP_TOL)
    for k, (grid, row) in enumerate(zip(ref["grids"], numba_grids(impact, tc), strict=True)):
        assert grid["n_sep"] == int(row[9])
        check_scalars(f"adaptive grid/{2**k}", impact, grid, dict(zip(R.OUTCOME, row)))
    fine = adaptive.run_adaptive(impact, tc, step_tol=STEP_TOL, max_steps=10**6, history=True, ghost=0.0,
                                 extrapolate=True)
    check_nodes(f"adaptive grid/{2**(len(ref['grids']) - 1)}", ref["grids"][-1], fine.history)
    res = vcor.simulate(impact.material, v0, method="adaptive", **geometry_of(impact))
    assert res.ok and res.message == ""  # extrapolated (the method's guards let it)
    check_scalars("adaptive extrapolated", impact, ref, res)


# ------------------------------------------------------------------------------------------------
# the overlap rule, the separation alone, and the references among themselves
# ------------------------------------------------------------------------------------------------
#: impacts that separate by the overlap rule within the fixed-step budget (the Butyl laws' and the 3-term
#: Prony's s creeps back to zero far later); SLS on the plate: 2 392 steps (T_max doubled four times)
OVERLAP_CASES = [("sls", "plate"), ("sls", "rigid"), ("kelvin-voigt", "plate"), ("elastic", "plate")]


@pytest.mark.parametrize("name, target", OVERLAP_CASES)
def test_overlap_rule(name, target):
    impact, dt, n, budget = fixed_step_case(name, 10.0, target)
    ref = R.direct_reference(impact, dt, budget, rule="overlap")
    res = direct.run_direct(impact, dt, n, max_steps=budget, rule="overlap", history=True, ghost=0.0)
    check_scalars("direct-a overlap", impact, ref, res)
    check_nodes("direct-a overlap", ref, res.history)
    tc = impact.contact_time_estimate()
    ref = R.adaptive_reference(impact, tc, STEP_TOL, rule="overlap")
    res = adaptive.run_adaptive(impact, tc, step_tol=STEP_TOL, max_steps=10**6, rule="overlap", history=True,
                                ghost=0.0)
    assert np.array_equal(ref["levels"], levels_of(res.history.t, R.AdaptiveGrid.of(impact, tc).h_base))
    check_scalars("adaptive overlap", impact, ref, res)


@pytest.mark.parametrize("rule", ["force", "overlap"])
def test_separation_alone(rule):
    """``separation_reference`` against ``_separation.locate_separation`` (via ``common.separation``)
    on smooth random histories on a random grid, the target's root inside step n."""
    m, v0 = 0.03, 10.0
    rng = np.random.default_rng(20261121)
    for _ in range(20):
        t = np.cumsum(rng.uniform(0.5, 1.5, 40)) * 1e-5
        t -= t[0]
        n = int(rng.integers(10, 37))
        root = t[n - 1] + rng.uniform(0.05, 0.95) * (t[n] - t[n - 1])
        s = 1e-3 * np.sin(math.pi * t / root) + (0.0 if rule == "overlap" else 1e-3)
        F = 500.0 * np.sin(math.pi * t / root) * (1.0 + 0.3 * t / root)
        g, J = np.gradient(s, t), np.cumsum(F) * 1e-5
        ref = R.separation_reference(t, s, g, F, J, n, rule, m, v0)
        numba = separation(t, s, g, F, J, n, rule, m, v0)
        for key in R.OUTCOME:
            scale = np.max(np.abs(s)) if key == "s_residual" else abs(numba[key])
            WORST["separation", key] = max(WORST["separation", key], abs(ref[key] - numba[key]) / scale)
            assert abs(ref[key] - numba[key]) <= RTOL * scale, key


@pytest.mark.parametrize("name", PRONY)
def test_references_among_themselves(name):
    """Independent formulations of one scheme: internal variables = form b (both the linear product
    integration), and the soe weights = the direct ones for Prony kernels (exact sums)."""
    impact, dt, _, budget = fixed_step_case(name, 10.0, "plate")
    prony, form_b = R.prony_reference(impact, dt, budget), R.direct_reference(impact, dt, budget, form="b")
    soe, form_a = R.soe_reference(impact, dt, budget, (budget + 8) * dt), R.direct_reference(impact, dt, budget)
    for a, b in ((prony, form_b), (soe, form_a)):
        assert a["cor"] == pytest.approx(b["cor"], rel=RTOL) and a["t0"] == pytest.approx(b["t0"], rel=RTOL)


def test_adaptive_grid_of_a_mode_relaxing_within_the_separation_step():
    """A stiff SLS (rate 3.16e6 1/s) whose separation step the kernel refines below t / SEP_STEPS
    (``adaptive.separation_steps``): the reference takes the same separation step and the same levels."""
    impact = make_impact(vcor.materials.SLS(1.5e7, 3.16e6 / 4.0, 3.16e6), 1.0, {})
    tc = impact.contact_time_estimate()
    grid = R.AdaptiveGrid.of(impact, tc)
    assert 1.0 / grid.sep_frac == adaptive.separation_steps(3.16e6, tc) > adaptive.SEP_STEPS
    res = adaptive.run_adaptive(impact, tc, step_tol=STEP_TOL, max_steps=10**6, history=True, ghost=0.0)
    ref = R.adaptive_reference(impact, tc, STEP_TOL)
    assert np.array_equal(ref["levels"], levels_of(res.history.t, grid.h_base)) and res.steps == ref["n_sep"]
    check_scalars("adaptive grid", impact, ref, res)
