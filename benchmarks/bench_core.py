"""Core solver benchmark: warm per-call costs of the fixed-step methods and the default method, the
cost of the Volterra term, the cost against the number of steps N, and the first impact of a fresh
process with an empty and with a filled numba cache.

Each run is a fresh process with an empty numba cache; warm numbers are medians of CALLS calls after
one untimed call; cells give the median over runs (min–max).

Run: python benchmarks/bench_core.py [--runs 2] [--quick] [--out FILE]
"""

from __future__ import annotations

import statistics

import timing
import vcor

SWEEP = [float(v) for v in range(1, 51)]  # v0 = 1..50 m/s
DTS = (1e-6, 0.5e-6, 0.25e-6, 0.125e-6)


def solver_time(material, v0, calls, **kw):
    """Median of ``Result.wall_time`` (the solver loop alone) over ``calls`` calls after one untimed call."""
    vcor.simulate(material, v0, **kw)
    return statistics.median(vcor.simulate(material, v0, **kw).wall_time for _ in range(calls))


def sweep(material, **kw):
    return lambda: [vcor.simulate(material, v, **kw) for v in SWEEP]


def measure(args):
    calls, sweeps = (3, 2) if args.quick else (15, 5)
    w = timing.warm_median
    rows = {
        "direct, SLS, v0 = 10 m/s, dt = 1 µs, Volterra off (simulate call)":
            w(lambda: vcor.simulate("sls", 10.0, method="direct", dt=1e-6), calls),
        "direct, SLS, v0 = 10 m/s, dt = 1 µs, solver loop only (Result.wall_time)":
            solver_time("sls", 10.0, calls, method="direct", dt=1e-6),
        "adaptive (the default), SLS, v0 = 10 m/s (simulate call)": w(lambda: vcor.simulate("sls", 10.0), calls),
        "direct, butyl-fc sweep v0 = 1..50 m/s (50 calls, default dt)": w(sweep("butyl-fc", method="direct"), sweeps),
        "direct, butyl-cerf sweep v0 = 1..50 m/s": w(sweep("butyl-cerf", method="direct"), sweeps),
        "direct, butyl-prony3 sweep v0 = 1..50 m/s": w(sweep("butyl-prony3", method="direct"), sweeps),
        "ive-numba, butyl-prony3 sweep v0 = 1..50 m/s": w(sweep("butyl-prony3", method="ive-numba"), sweeps),
        "adaptive (the default), butyl-fc sweep v0 = 1..50 m/s": w(sweep("butyl-fc"), sweeps),
        "ive (solve_ivp Radau, rtol 1e-10), SLS, v0 = 10 m/s":
            w(lambda: vcor.simulate("sls", 10.0, method="ive"), max(2, calls // 3)),
    }
    off = solver_time("sls", 10.0, calls, method="direct", dt=1e-6)
    on = solver_time("sls", 10.0, calls, method="direct", dt=1e-6, volterra=True)
    scaling = []  # cost against the number of steps N: direct is O(N^2) (the history sum), ive-numba O(N)
    for dt in DTS[:2] if args.quick else DTS:
        n = vcor.simulate("butyl-fc", 10.0, method="direct", dt=dt).steps
        scaling.append({"dt": dt, "N": n,
                        "direct": solver_time("butyl-fc", 10.0, sweeps, method="direct", dt=dt),
                        "ive": solver_time("butyl-prony3", 10.0, sweeps, method="ive-numba", dt=dt)})
    cold = {label: timing.cold_and_cached(options)
            for label, options in (("direct, dt = 1 µs", "method='direct', dt=1e-6"), ("adaptive", ""))}
    return {"rows": rows, "volterra": on / off, "scaling": scaling, "cold": cold, "calls": calls, "sweeps": sweeps}


def report(args, results):
    r0 = results[0]
    c = timing.cell
    warm = timing.table(["benchmark", "warm call [ms]"],
                        [[name, c(timing.column(results, "rows", name), 1e3, ".3f")] for name in r0["rows"]])
    ratio = timing.table(["ratio", "value"],
                         [["Volterra on / off (direct, SLS, dt = 1 µs, solver loop)",
                           c(timing.column(results, "volterra"))]])
    rows, prev = [], None
    for i, s in enumerate(r0["scaling"]):
        td = [r["scaling"][i]["direct"] for r in results]
        ti = [r["scaling"][i]["ive"] for r in results]
        ratios = ([c([a / b for a, b in zip(td, prev[0])]), c([a / b for a, b in zip(ti, prev[1])])] if prev
                  else ["", ""])
        rows.append([f"{s['dt'] * 1e6:.3f}", s["N"], c(td, 1e3, ".3f"), ratios[0], c(ti, 1e3, ".3f"), ratios[1]])
        prev = (td, ti)
    steps = timing.table(["dt [µs]", "N", "direct butyl-fc [ms]", "ratio to the previous N",
                          "ive-numba butyl-prony3 [ms]", "ratio to the previous N"], rows)
    cold = timing.table(
        ["first impact `simulate('sls', 10.0)`", "numba cache", "process wall [s]", "import + run inside [s]"],
        [[label, state, c([r["cold"][label][state][0] for r in results]),
          c([r["cold"][label][state][1] for r in results])]
         for label in r0["cold"] for state in ("empty", "filled")])
    return [f"Warm calls: median of {r0['calls']} calls (sweeps: {r0['sweeps']}) after one untimed call, in a "
            "fresh process with an empty numba cache per run; cells: median over runs (min–max).", warm, ratio,
            "Cost against the number of steps N (butyl-fc for N; v0 = 10 m/s; solver loop, warm, median of "
            f"{r0['sweeps']} calls): per doubling of N the ratio tends to 4 for O(N^2), 2 for O(N).", steps,
            "A fresh process's first impact: an empty numba cache (compiles), then a second fresh process with "
            "the cache the first one filled.", cold]


if __name__ == "__main__":
    timing.main(__doc__, measure, report, quick="3 calls per warm median, 2 per sweep, two step sizes")
