"""The fixed-step soe method against direct (and ive-numba for Prony kernels), per impact at the
default fixed-step settings (2000 steps per contact-time estimate), v0 = 10 m/s, whole simulate call
(the adaptive method, thin plates and cost against plate thickness: bench_adaptive.py).

Each run is a fresh process with an empty numba cache; each number is the median of CALLS warm calls
after one untimed call; cells give the median over runs (min–max).

Run: python benchmarks/bench_soe.py [--runs 2] [--calls 15] [--quick] [--out FILE]
"""

from __future__ import annotations

import timing
import vcor

MATERIALS = ("sls", "butyl-fc", "butyl-cerf", "butyl-prony3")
PRONY = ("sls", "butyl-prony3")  # ive-numba takes Prony kernels only


def measure(args):
    out = {}
    for name in MATERIALS:
        def call(method, n=name):
            return lambda: vcor.simulate(n, 10.0, method=method)

        td, rd = timing.warm_timed(call("direct"), timing.calls(args, 2))
        ts, rs = timing.warm_timed(call("soe"), timing.calls(args, 2))
        ti = timing.warm_median(call("ive-numba"), timing.calls(args, 2)) if name in PRONY else None
        out[name] = {"direct": td, "soe": ts, "ive": ti, "gap": abs(rs.cor - rd.cor)}
    return out


def report(args, results):
    c = timing.cell
    rows = []
    for name in MATERIALS:
        runs = timing.column(results, name)
        ive = c([r["ive"] for r in runs], 1e3, ".3f") if name in PRONY else "-"
        rows.append([name, c([r["direct"] for r in runs], 1e3, ".3f"), c([r["soe"] for r in runs], 1e3, ".3f"),
                     c([r["soe"] / r["direct"] for r in runs]), ive, f"{runs[-1]['gap']:.1e}"])
    return [f"Per impact, v0 = 10 m/s, whole simulate call, fixed-step defaults; warm: median of "
            f"{timing.calls(args, 2)} calls after one untimed call, one fresh process with an empty numba cache "
            "per run; cells: median over runs (min–max).",
            timing.table(["material", "direct [ms]", "soe [ms]", "soe / direct", "ive-numba [ms]",
                          "abs(COR soe − COR direct)"], rows)]


if __name__ == "__main__":
    timing.main(__doc__, measure, report, quick="2 warm calls per median", calls=15)
