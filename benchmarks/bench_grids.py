"""Three or four Richardson grids: the adaptive method's COR error on a family of SLS laws against the
resolution of their mode on the accepted grid (``vcor.solvers.adaptive.RESOLVED_DECAY``).

Family: SLS with E_glassy = 15 MPa, relaxation rate b = 1e2 .. 1e7 1/s (21 values, log-spaced: up to
modes that relax within a ten-thousandth of the contact), glassy/rubbery modulus 4 and 50, on the
paper's plate and on a sphere of the same law (head-on pair), at v0 = 0.001, 1, 10, 100 m/s (336
impacts). Reference: ``ive`` (scipy Radau) at rtol 1e-12 (exact
internal variables; not computed by adaptive). For every impact the accepted grid at the default
step_tol and its replays (``adaptive.grid_outcomes``, four grids) give the COR extrapolated from the
first three grids (h^2, h^4 eliminated: ``SMOOTH_WEIGHTS``) and from all four (h^2, h^3.5, h^4:
``RICHARDSON_WEIGHTS``), and the four grids again on an accepted grid at LOOSER times the step_tol (what a
looser tolerance for four-grid impacts would give); rows group the impacts by b h_max (the rate times
the default accepted grid's largest step). The last column is what a user gets: ``vcor.simulate`` at
its defaults (grid choice, separation and Richardson checks), COR and t0. The errors do not depend on
the machine: one process computes them.

Run: python benchmarks/bench_grids.py [--quick] [--out FILE]
"""

from __future__ import annotations

import numpy as np

import timing

RATES = tuple(float(b) for b in np.logspace(2.0, 7.0, 21))
RATIOS = (4.0, 50.0)
TARGETS = ("plate", "pair")
SPEEDS = (0.001, 1.0, 10.0, 100.0)
#: the looser tolerance's factor on step_tol (the last column)
LOOSER = 2.5
#: upper edges of the rows' b h_max ranges
EDGES = (0.01, 0.03, 0.05, 0.1, 0.3, 1.0, 3.0, 10.0, 100.0, 1e3, 1e4, 1e5)


def impact_of(rate, ratio, target, v0):
    """(material, target argument of simulate, Impact) of one case."""
    import vcor
    from vcor.contact.impact import make_impact
    from vcor.contact.pair import target_inputs

    material = vcor.materials.SLS(1.5e7, rate / ratio, rate)
    where = "plate" if target == "plate" else {"sphere": {}}
    inputs = (material, {}) if target == "plate" else target_inputs(material, where, {})
    return material, where, make_impact(inputs[0], v0, inputs[1])


def measure(quick: bool) -> list:
    """Per case: (b h_max, error of three grids, error of four grids, grids the default takes, error of four
    grids at LOOSER step_tol, steps of the four grids at step_tol and at LOOSER step_tol, the default's
    (vcor.simulate's) COR error and t0 error)."""
    import vcor
    from vcor.solvers import adaptive

    opts = vcor.SolverOptions(method="adaptive")
    rates = RATES[::4] if quick else RATES
    out = []
    for rate in rates:
        for ratio in RATIOS:
            for target in TARGETS:
                for v0 in SPEEDS:
                    material, where, impact = impact_of(rate, ratio, target, v0)
                    reference = vcor.simulate(material, v0, target=where, method="ive", rtol=1e-12)
                    ref = reference.cor
                    res = vcor.simulate(material, v0, target=where)
                    tc = impact.contact_time_estimate()
                    kw = {"step_tol": opts.step_tol, "max_steps": opts.max_adaptive_steps, "rule": "force",
                          "tol": opts.soe_tol}
                    rows = adaptive.grid_outcomes(impact, tc, adaptive.GRIDS, **kw)
                    cor = rows[:, adaptive.EXTRAPOLATED.index("cor")]
                    three = float(np.dot(adaptive.SMOOTH_WEIGHTS, cor[: adaptive.SMOOTH_GRIDS]))
                    four = float(np.dot(adaptive.RICHARDSON_WEIGHTS, cor))
                    default = len(adaptive.grid_outcomes(impact, tc, adaptive.GRIDS, fewer=True, **kw))
                    loose = adaptive.grid_outcomes(impact, tc, adaptive.GRIDS,
                                                   **{**kw, "step_tol": LOOSER * kw["step_tol"]})
                    four_loose = float(np.dot(adaptive.RICHARDSON_WEIGHTS,
                                              loose[:, adaptive.EXTRAPOLATED.index("cor")]))
                    out.append((rate * float(rows[0, 10]), abs(three / ref - 1), abs(four / ref - 1), default,
                                abs(four_loose / ref - 1), float(rows[:, 9].sum()), float(loose[:, 9].sum()),
                                abs(res.cor / ref - 1), abs(res.t0 / reference.t0 - 1)))
    return out


def report(cases) -> list:
    from vcor.solvers import adaptive

    rows, lo = [], 0.0
    for hi in EDGES:
        inside = [c for c in cases if lo < c[0] <= hi]
        if inside:
            takes = sorted({c[3] for c in inside})
            rows.append([f"({lo:g}, {hi:g}]", str(len(inside)), f"{max(c[1] for c in inside):.1e}",
                         f"{max(c[2] for c in inside):.1e}", " or ".join(map(str, takes)),
                         f"{max(c[4] for c in inside):.1e}",
                         f"{max(c[7] for c in inside):.1e} / {max(c[8] for c in inside):.1e}"])
        lo = hi
    chosen = [c[1] if c[3] == adaptive.SMOOTH_GRIDS else c[2] for c in cases]
    return [f"COR error of the adaptive method (default step_tol) against scipy Radau at rtol 1e-12, on "
            f"{len(cases)} SLS impacts (rates {RATES[0]:g}..{RATES[-1]:g} 1/s, glassy/rubbery "
            f"{' and '.join(f'{r:g}' for r in RATIOS)}, plate and sphere pair, v0 "
            f"{', '.join(f'{v:g}' for v in SPEEDS)} m/s), grouped by b h_max (rate times the accepted grid's "
            f"largest step): the largest error from three grids (h^2, h^4) and from four (h^2, h^3.5, h^4), "
            f"and how many the default takes (three where b h_max <= RESOLVED_DECAY = "
            f"{adaptive.RESOLVED_DECAY:g}). Largest error of the default's choice over all cases: "
            f"{max(chosen):.1e}. Last column: four grids on an accepted grid at {LOOSER:g} times the step_tol "
            f"(largest error {max(c[4] for c in cases):.1e}; steps of the four grids, mean over the impacts: "
            f"{np.mean([c[6] for c in cases]):.0f} against {np.mean([c[5] for c in cases]):.0f} at the step_tol). "
            f"The default's own result (vcor.simulate, its separation and Richardson checks included): largest "
            f"relative error of the COR {max(c[7] for c in cases):.1e}, of t0 {max(c[8] for c in cases):.1e}.",
            timing.table(["b h_max", "impacts", "three grids: largest error", "four grids: largest error",
                          "default takes", f"four grids at {LOOSER:g} step_tol: largest error",
                          "default (simulate): largest COR / t0 error"], rows)]


def main():
    timing.one_process_main(__doc__, measure, report, quick="every fourth rate only")


if __name__ == "__main__":
    main()
