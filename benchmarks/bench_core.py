"""Core solver benchmark: prints a table of medians and ratios (machine is shared: read ratios).

Run: python benchmarks/bench_core.py
"""

from __future__ import annotations

import statistics
import tempfile

from timing import cold_process, median_time

import vcor


def solver_time(material, v0, repeat=15, **kw):
    vcor.simulate(material, v0, **kw)
    return statistics.median(vcor.simulate(material, v0, **kw).wall_time for _ in range(repeat))


def main():
    rows = []
    t_sls = median_time(lambda: vcor.simulate("sls", 10.0, dt=1e-6))
    rows.append(("direct, SLS, v0=10, dt=1 us, Volterra off (simulate call)", t_sls, "<= 2 ms"))
    rows.append(("  same, solver loop only (Result.wall_time)", solver_time("sls", 10.0, dt=1e-6), ""))

    def sweep():
        for v in range(1, 51):
            vcor.simulate("butyl-fc", float(v))

    rows.append(("Butyl fractional sweep v0=1..50 (50 runs, default dt)", median_time(sweep, 5), "<= 0.1 s"))
    for name in ("butyl-cerf", "butyl-prony3"):
        rows.append((f"{name} sweep v0=1..50", median_time(lambda n=name: [vcor.simulate(n, float(v)) for v in range(1, 51)], 5), ""))
    rows.append(("ive-numba, butyl-prony3 sweep v0=1..50",
                 median_time(lambda: [vcor.simulate("butyl-prony3", float(v), method="ive-numba") for v in range(1, 51)], 5), ""))
    rows.append(("ive (solve_ivp Radau, rtol 1e-10), SLS v0=10", median_time(lambda: vcor.simulate("sls", 10.0, method="ive"), 5), ""))

    off = solver_time("sls", 10.0, dt=1e-6)
    on = solver_time("sls", 10.0, dt=1e-6, volterra=True)
    # cost against the number of steps N: direct is O(N^2) (the history sum), ive-numba O(N)
    scaling = []
    for dt in (1e-6, 0.5e-6, 0.25e-6, 0.125e-6):
        n = vcor.simulate("butyl-fc", 10.0, dt=dt).steps
        t_direct = solver_time("butyl-fc", 10.0, repeat=5, dt=dt)
        t_ive = solver_time("butyl-prony3", 10.0, repeat=5, dt=dt, method="ive-numba")
        scaling.append((dt, n, t_direct, t_ive))
    print(f"{'benchmark':62s} {'median':>12s}  target")
    for name, t, target in rows:
        print(f"{name:62s} {t * 1e3:9.3f} ms  {target}")
    print()
    print(f"{'ratio':62s} {'value':>12s}  target")
    print(f"{'Volterra on / off (SLS, dt = 1 us)':62s} {on / off:12.2f}  <= 20")
    print()
    print("cost against steps N (v0 = 10): the ratio per doubling of N tends to 4 for O(N^2), 2 for O(N)")
    print(f"{'dt [us]':>8s} {'N':>6s} {'direct butyl-fc [ms]':>21s} {'ratio':>6s} {'ive-numba prony3 [ms]':>22s} {'ratio':>6s}")
    prev = None
    for dt, n, td, ti in scaling:
        rd = f"{td / prev[2]:6.2f}" if prev else f"{'':6s}"
        ri = f"{ti / prev[3]:6.2f}" if prev else f"{'':6s}"
        print(f"{dt * 1e6:8.3f} {n:6d} {td * 1e3:21.3f} {rd} {ti * 1e3:22.3f} {ri}")
        prev = (dt, n, td, ti)
    print()
    with tempfile.TemporaryDirectory() as d:
        total, inner = cold_process({"NUMBA_CACHE_DIR": d}, "dt=1e-6")
        print(f"{'fresh process, empty numba cache (compiles)':62s} {total:9.3f} s   (import+run {inner:.3f} s)")
        total, inner = cold_process({"NUMBA_CACHE_DIR": d}, "dt=1e-6")
        print(f"{'fresh process, numba cache filled (no compile)':62s} {total:9.3f} s   (import+run {inner:.3f} s)")
    print(f"{'warm (same process) SLS dt=1 us':62s} {t_sls:9.6f} s")


if __name__ == "__main__":
    main()
