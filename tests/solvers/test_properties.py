"""Limits and invariants: Zener's elastic plate solved independently, and property tests on random
Prony materials and geometries (hypothesis, derandomised so CI is reproducible)."""

import collections
import math

import pytest
from hypothesis import HealthCheck, Phase, given, seed, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

import vcor
from vcor import materials as M
from vcor.contact.impact import make_impact


def zener_cor(lam):
    """Zener's elastic-plate equation z'' + lam (z^1.5)' + z^1.5 = 0, z(0) = 0, z'(0) = 1, written
    without the derivative: w = z' + lam z^1.5, z' = w - lam z^1.5, w' = -z^1.5; COR = |z'| at z = 0."""

    def rhs(t, y):
        z = max(y[0], 0.0)
        return [y[1] - lam * z**1.5, -(z**1.5)]

    ev = lambda t, y: y[0] if t > 1e-3 else 1.0
    ev.terminal, ev.direction = True, -1
    sol = solve_ivp(rhs, (0, 50), [0.0, 1.0], events=ev, rtol=1e-13, atol=1e-15, method="DOP853")
    z, w = sol.y_events[0][0]
    return abs(w - lam * max(z, 0.0) ** 1.5)


def test_elastic_plate_matches_zener():
    imp = make_impact("elastic", 10.0, {})
    k, m, v0, alpha = imp.kappa * 15e6, imp.m, 10.0, float(imp.alpha(0.0))
    t_star = (m / (k * math.sqrt(v0))) ** 0.4
    lam = alpha * k * math.sqrt(v0 * t_star) * t_star
    assert lam == pytest.approx(0.138, abs=5e-4)  # the paper's inelasticity parameter
    ref = zener_cor(lam)
    r = vcor.simulate("elastic", 10.0)
    print(f"\nZener lambda = {lam:.5f}: COR independent {ref:.9f}, vcor {r.cor:.9f}")
    assert abs(r.cor - ref) < 1e-6
    assert round(ref, 2) == 0.79


def test_elastic_rigid_is_unity():
    for v0 in (0.01, 1.0, 100.0):
        assert abs(vcor.simulate("elastic", v0, rigid=True).cor - 1.0) < 1e-6


prony = st.builds(
    lambda e_inf, terms: M.Prony(e_inf, tuple(t[0] for t in terms), tuple(t[1] for t in terms)),
    st.floats(1e5, 1e8),
    st.lists(st.tuples(st.floats(1e5, 1e9), st.floats(10.0, 1e6)), min_size=1, max_size=3),
)
geometry = st.fixed_dictionaries({
    "r": st.floats(2e-3, 0.05),
    "rho_a": st.floats(500.0, 20000.0),
    "rho_b": st.floats(500.0, 3000.0),
    "h": st.floats(0.02, 0.2),
    "nu": st.floats(0.0, 0.5),
})


#: at most this many of the examples may end without a verdict (step-budget); each is printed
MAX_FLAGGED = 2
N_EXAMPLES = 25


@pytest.mark.slow  # 25 random Prony materials, each solved several ways: ~7 s
def test_invariants_random_prony():
    """Invariants over random Prony materials and geometries. Every example is counted: a flagged one
    (step-budget, with its message) is allowed at most MAX_FLAGGED times, any other status fails."""
    outcomes = collections.Counter()

    # a fixed seed: the same examples whatever the test's source (derandomize=True seeds from the source).
    # Hypothesis also mixes literal constants of the loaded local modules into its draws, so a run of
    # this file alone and the whole suite draw different examples: every example must pass either way
    @seed(20261121)
    # no shrink phase: a failing example is reported as drawn (shrinking it took minutes of solves)
    @settings(max_examples=N_EXAMPLES, deadline=None, database=None, phases=[Phase.explicit, Phase.generate],
              suppress_health_check=[HealthCheck.too_slow])
    @given(material=prony, geom=geometry, v0=st.floats(0.1, 50.0))
    def check(material, geom, v0):
        r = vcor.simulate(material, v0, method="direct", **geom)
        outcomes[r.status] += 1
        if r.status == "step-budget":
            print(f"\nflagged: {material}, {geom}, v0 = {v0}: {r.message}")
            return
        assert r.status == "ok", r.message
        assert r.cor > 0 and r.t0 > 0
        # README: no COR > 1 has occurred; it could (s' includes the plate surface's velocity), and a
        # counter-example would be a finding to record in the README, not a tolerance to widen
        assert r.cor <= 1.0, f"COR > 1: {material}, {geom}, v0 = {v0}: {r.cor}"
        assert abs(r.sphere_velocity) <= v0 * (1 + 1e-9)  # the sphere cannot leave faster than it came
        worst["energy_residual"] = max(worst["energy_residual"], abs(r.energy_residual))
        # the energy residual checks the momentum book-keeping, not the hereditary force: a wrong J or W
        # update shows at 1e-4 and above; the residual of a correct march is a discretisation mismatch,
        # (h^2 / 8m) (F_end^2 - F_0^2) / E_in on a uniform grid (3e-8 in the smallest, lightest sphere here)
        assert abs(r.energy_residual) < 1e-6
        assert r.s_residual >= -1e-6 * r.s_max
        assert r.w_h > 0
        ive = vcor.simulate(material, v0, method="ive", rtol=1e-9, **geom)
        assert ive.status == "ok", ive.message
        worst["direct - ive"] = max(worst["direct - ive"], abs(ive.cor - r.cor))
        assert abs(ive.cor - r.cor) < 2e-6  # direct = ive to 2e-6 (docs, "Validation")
        fast = vcor.simulate(material, v0, **geom)  # the default method, adaptive
        assert fast.status == "ok", fast.message
        worst["adaptive - ive"] = max(worst["adaptive - ive"], abs(ive.cor - fast.cor))
        worst["adaptive energy_residual"] = max(worst["adaptive energy_residual"], abs(fast.energy_residual))
        # adaptive = ive to 1e-5 at the default step_tol (docs, "Validation"; the stiffest drawn material's own
        # error: test_adaptive_error_on_the_stiffest_example_falls_with_step_tol)
        assert abs(ive.cor - fast.cor) < 1e-5
        # on a variable grid the trapezoid quadrature of int F z' dt and the trapezoidal momentum update differ
        # by sum h_n^2 (F_n^2 - F_{n-1}^2) / (8 m), which telescopes only on a uniform grid (docs, "Theory")
        assert abs(fast.energy_residual) < 1e-4

    worst = {"energy_residual": 0.0, "direct - ive": 0.0, "adaptive - ive": 0.0, "adaptive energy_residual": 0.0}
    check()
    print(f"\nrandom Prony examples: {dict(outcomes)}; largest "
          + ", ".join(f"|{k}| {v:.1e}" for k, v in worst.items()))
    assert sum(outcomes.values()) >= N_EXAMPLES  # every example ran (none filtered away)
    assert outcomes["step-budget"] <= MAX_FLAGGED
    assert set(outcomes) <= {"ok", "step-budget"}


def test_stiff_prony_found_by_hypothesis():
    """A case hypothesis found (glassy/rubbery ~ 100, fast relaxation, thin light plate): scipy's
    numerical Jacobian overflowed in Radau; the solution itself is fine and matches direct."""
    m = M.Prony(10421000.0, (999999999.9999999,), (172015.88059577186,))
    g = {"r": 0.026023144776597902, "rho_a": 4357.0, "rho_b": 500.0, "h": 0.01171875, "nu": 0.0}
    d = vcor.simulate(m, 11.0, method="direct", **g)
    i = vcor.simulate(m, 11.0, method="ive", **g)
    assert d.ok and i.ok
    assert abs(d.cor - i.cor) < 1e-6


#: the stiffest example the property test has drawn: fast terms 3.9e5..7.6e5 1/s, glassy/rubbery 170
STIFF = (M.Prony(10614500.686930114, (807766737.1840174, 96319916.97766414, 922503759.4920471),
                 (391862.76545272046, 691513.752641596, 760000.0)),
         {"nu": 0.0, "r": 0.026123361415416116, "rho_a": 3308.9488960353897, "h": 0.028126206053523166,
          "rho_b": 1928.0348460683576}, 12.296116364853408)


def test_adaptive_error_on_the_stiffest_example_falls_with_step_tol():
    """The adaptive march converges on the stiffest drawn material (reference: ive at rtol 1e-12): its COR
    error is below 1e-7 at the default step_tol and below 1e-8 at every step_tol from 1e-4 down (printed).
    Its fast terms relax within a fraction of a step, outside the range where the error follows a power of
    the step, so the test asks for levels, not a rate."""
    material, geom, v0 = STIFF
    ref = vcor.simulate(material, v0, method="ive", rtol=1e-12, **geom).cor
    tols = (vcor.SolverOptions().step_tol, 1e-4, 3e-5, 1e-5)
    errors = [abs(vcor.simulate(material, v0, step_tol=tol, **geom).cor - ref) for tol in tols]
    print("\nstep_tol " + ", ".join(f"{t:g}" for t in tols) + ": COR error " + ", ".join(f"{e:.2e}" for e in errors))
    assert errors[0] < 1e-7
    assert max(errors[1:]) < 1e-8
