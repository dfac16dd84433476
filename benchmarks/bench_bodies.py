"""Two deformable bodies (Green 2026 Eq. 1): per impact, the default method against direct.

Pairs: an elastic sphere (E = 70 GPa, nu 0.3, steel density) on the SLS and on the butyl-prony3 plate,
an SLS sphere on a butyl-prony3 plate. Per pair at v0 = 10 m/s: the whole ``vcor.simulate`` call of
``adaptive`` (its defaults; the contact modulus as a fitted exponential sum, built in the untimed first
call and cached) and of ``direct`` (its defaults, 2000 steps per contact-time estimate), warm medians,
their ratio, and each one's COR against direct at 16000 steps per contact time.

Each run is a fresh process with an empty numba cache; cells give the median over runs (min–max).

Run: python benchmarks/bench_bodies.py [--runs 2] [--calls 31] [--quick] [--out FILE]
"""

from __future__ import annotations

import timing

PAIRS = (
    ("elastic 70 GPa on sls", {"material": {"model": "elastic", "E": 7e10}}, {"material": "sls"}),
    ("elastic 70 GPa on butyl-prony3", {"material": {"model": "elastic", "E": 7e10}}, {"material": "butyl-prony3"}),
    ("sls on butyl-prony3", {"material": "sls"}, {"material": "butyl-prony3"}),
)


def measure(args):
    import vcor
    from vcor.contact import bodies

    calls = timing.calls(args, 3)
    out = {}
    for label, sphere, plate in PAIRS:
        material, geometry = bodies.impact_inputs(bodies.body_from_spec("sphere", sphere),
                                                  bodies.body_from_spec("plate", plate))

        def call(m=material, g=geometry, **kw):
            return lambda: vcor.simulate(m, 10.0, **g, **kw)

        ta, ra = timing.warm_timed(call(), calls)
        td, rd = timing.warm_timed(call(method="direct"), max(3, calls // 5))
        ref = call(method="direct", steps_per_contact=16000)()
        out[label] = {"adaptive": ta, "direct": td, "err_a": abs(ra.cor / ref.cor - 1),
                      "err_d": abs(rd.cor / ref.cor - 1), "soe_error": ra.soe_error, "steps": [ra.steps, rd.steps]}
    return out


def report(args, results):
    c = timing.cell
    rows = []
    for label, _, _ in PAIRS:
        runs = timing.column(results, label)
        first = runs[0]
        rows.append([label, c([r["adaptive"] for r in runs], 1e6, ".0f"), c([r["direct"] for r in runs], 1e3, ".2f"),
                     c([r["adaptive"] / r["direct"] for r in runs], 1.0, ".3f"), f"{first['err_a']:.1e}",
                     f"{first['err_d']:.1e}", f"{first['soe_error']:.0e}", "/".join(map(str, first["steps"]))])
    return [f"Per impact at v0 = 10 m/s, whole simulate call, warm: median of {timing.calls(args, 3)} calls "
            "(direct: a fifth of them) after one untimed call; COR error against direct at 16000 steps per "
            "contact-time estimate; sum error: the fitted contact modulus's checked relative error (soe_error).",
            timing.table(["pair", "adaptive [µs]", "direct [ms]", "adaptive / direct", "adaptive COR error",
                          "direct COR error", "sum error", "steps adaptive/direct"], rows)]


if __name__ == "__main__":
    timing.main(__doc__, measure, report, quick="3 warm calls per median", calls=31)
