"""The adaptive method against direct (issue 11's benchmark table): per impact, thin plates, cost
against plate thickness, sweep throughput inside one shard.

Prints tables of medians (this machine is shared: read ratios). Run: python benchmarks/bench_adaptive.py
[section ...] (default: all; sections per_impact breakdown mode_counts cold thickness table_builds throughput)
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import time

import numpy as np
from timing import cold_process, median_time

import vcor
from vcor import runner, scene
from vcor.options import solver_options
from vcor.soe import soe
from vcor.solvers.adaptive import level_tables, run_adaptive
from vcor.solvers.simulate import make_impact

#: calls per median in the per-impact table (15 before 2026-11-23: too few on a shared machine)
PER_IMPACT_CALLS = 101


def per_impact():
    print("per impact at default settings, v0 = 10 m/s, whole simulate call (direct: 2000 steps per contact-time "
          "estimate; adaptive: its defaults, step_tol 3e-4 with Richardson extrapolation from three grids)")
    print(f"{'material':14s} {'direct [ms]':>12s} {'adaptive [ms]':>14s} {'adaptive/direct':>16s} {'steps d/a':>12s}")
    for name in ("sls", "butyl-fc", "butyl-cerf", "butyl-prony3"):
        td = median_time(lambda n=name: vcor.simulate(n, 10.0), PER_IMPACT_CALLS)
        ta = median_time(lambda n=name: vcor.simulate(n, 10.0, method="adaptive"), PER_IMPACT_CALLS)
        sd, sa = vcor.simulate(name, 10.0).steps, vcor.simulate(name, 10.0, method="adaptive").steps
        print(f"{name:14s} {td * 1e3:12.3f} {ta * 1e3:14.3f} {ta / td:16.3f} {sd:>6d}/{sa:<6d}")
    print()


def breakdown():
    print("where the time of one adaptive impact goes (v0 = 10 m/s, warm, medians of 200 calls): set-up = options,")
    print("impact and contact-time estimate; one march = run_adaptive without extrapolation (the accepted grid and")
    print("its result); three marches = run_adaptive as simulate calls it (grid, halved, quartered, extrapolation)")
    print(f"{'material':14s} {'simulate [us]':>14s} {'set-up [us]':>12s} {'three marches [us]':>19s} "
          f"{'one march [us]':>15s} {'steps (grid/all)':>17s} {'modes':>6s}")
    print("(modes: terms of the exponential sum on [t_c / 2^18, 256 t_c], about the range the march uses)")
    opts = vcor.SolverOptions(method="adaptive")
    for name in ("sls", "butyl-fc", "butyl-cerf", "butyl-prony3"):
        imp = make_impact(name, 10.0, {})
        tc = imp.contact_time_estimate()
        kw = {"step_tol": opts.step_tol, "max_steps": opts.max_adaptive_steps, "tol": opts.soe_tol}
        whole = median_time(lambda n=name: vcor.simulate(n, 10.0, options=opts), 200)
        setup = median_time(lambda n=name: (solver_options(method="adaptive"),
                                            make_impact(n, 10.0, {}).contact_time_estimate()), 200)
        three = median_time(lambda i=imp, t=tc, k=kw: run_adaptive(i, t, extrapolate=True, **k), 200)
        one = median_time(lambda i=imp, t=tc, k=kw: run_adaptive(i, t, **k), 200)
        steps = (run_adaptive(imp, tc, **kw).steps, run_adaptive(imp, tc, extrapolate=True, **kw).steps)
        modes = soe(imp.material, tc * 2.0**-18, 256.0 * tc, opts.soe_tol).n_terms
        print(f"{name:14s} {whole * 1e6:14.0f} {setup * 1e6:12.0f} {three * 1e6:19.0f} {one * 1e6:15.0f} "
              f"{steps[0]:>8d}/{steps[1]:<8d} {modes:6d}")
    print()


def mode_counts():
    print("modes of the exponential sums (v0 = 10 m/s): all = on the range of the one-call path's tables,")
    print("[h_base / 4, 2 x horizon] = [t_c 2^-18, 256 t_c] in powers of two; slow = of those, beta t_max < 1e-3")
    print("(nearly constant over the whole horizon); a sum ending at 8 t_c instead; live = modes a step")
    print("touches on the coarsest / finest level (rows 0 and last of the tables)")
    print(f"{'material':14s} {'all':>5s} {'slow':>5s} {'to 8 t_c':>9s} {'live finest/coarsest':>21s}")
    opts = vcor.SolverOptions(method="adaptive")
    for name in ("butyl-fc", "butyl-cerf"):
        imp = make_impact(name, 10.0, {})
        top = 2.0 ** np.floor(np.log2(imp.contact_time_estimate()))
        t_max = 256.0 * top
        rep = soe(imp.material, top * 2.0**-18, t_max, opts.soe_tol)
        slow = int(np.sum(np.asarray(rep.material.beta) * t_max < 1e-3))
        short = soe(imp.material, top * 2.0**-18, 8.0 * top, opts.soe_tol).n_terms
        tab = level_tables(imp.material, float(imp.kappa), top * 2.0**-18, 22, t_max, opts.soe_tol)
        print(f"{name:14s} {rep.n_terms:5d} {slow:5d} {short:9d} {tab['live'][0]:>10d}/{tab['live'][-1]:<10d}")
    print()


def cold():
    print("fresh process (import vcor, one simulate('sls', 10.0)), numba cache empty (compiles) / filled:")
    for label, options in (("direct", "dt=1e-6"), ("adaptive", "method='adaptive'")):
        with tempfile.TemporaryDirectory() as d:
            empty = cold_process({"NUMBA_CACHE_DIR": d}, options)[0]
            filled = cold_process({"NUMBA_CACHE_DIR": d}, options)[0]
        print(f"{label:10s} {empty:6.2f} s / {filled:5.2f} s")
    print()


def thickness():
    print("cost against plate half-thickness h (sls, v0 = 10 m/s): adaptive; direct for comparison")
    print(f"{'h [mm]':>8s} {'status':>7s} {'t0 [s]':>10s} {'COR':>10s} {'steps':>7s} {'adaptive [s]':>13s} "
          f"{'direct status':>14s} {'direct [s]':>11s}")
    standard = median_time(lambda: vcor.simulate("sls", 10.0, method="adaptive"), 9)
    for h in np.geomspace(1e-3, 1.0, 7):
        ra = vcor.simulate("sls", 10.0, h=h, method="adaptive")
        ta = median_time(lambda hh=h: vcor.simulate("sls", 10.0, h=hh, method="adaptive"), 5)
        t = time.perf_counter()
        rd = vcor.simulate("sls", 10.0, h=h)
        td = time.perf_counter() - t
        print(f"{h * 1e3:8.2f} {ra.status:>7s} {ra.t0:10.4g} {ra.cor:10.3e} {ra.steps:7d} {ta:13.4f} {rd.status:>14s} "
              f"{td:11.4f}")
    thin = median_time(lambda: vcor.simulate("sls", 10.0, h=1e-3, method="adaptive"), 5)
    print(f"thin plate h = 1 mm / standard impact (h = 2 r = 20 mm), adaptive: {thin / standard:.1f}x "
          f"({thin * 1e3:.2f} ms / {standard * 1e3:.3f} ms)")
    print()


def _throughput_scenes():
    scenes = {}
    for n_v0, n_b in ((30, 50), (250, 334)):
        scenes[f"sls, v0 1..30 ({n_v0}) x beta (4)"] = {
            "materials": ["sls"], "grid": {"v0": list(np.linspace(1.0, 30.0, n_v0)), "beta": [600, 1200, 2400, 4800]},
            "tie": {"alpha": {"to": "beta", "ratio": 0.25}}}
        scenes[f"butyl (3 materials), v0 1..50 ({n_b})"] = {
            "materials": ["butyl-fc", "butyl-cerf", "butyl-prony3"], "grid": {"v0": list(np.linspace(1.0, 50.0, n_b))}}
    return scenes


def shard_wall(label, method):
    """(points, wall time [s], level tables built) of run_points over the scene ``label`` in this
    process, after a 3-point warm-up (compiles; the other materials' and step ranges' tables are
    built in the run)."""
    s2 = {**_throughput_scenes()[label], "solver": {"method": method}}
    pts = scene.scene_points(s2)
    settings = scene.settings_of(s2)
    runner.run_points(pts[:3], settings)  # JIT
    built = level_tables.cache_info().misses
    t = time.perf_counter()
    runner.run_points(pts, settings)
    return len(pts), time.perf_counter() - t, level_tables.cache_info().misses - built


def table_builds():
    print("level tables of one (material, step range) pair, as a sweep point on a new power of two of t_c")
    print("builds them (exponential sum with its check, per-level weights): medians over 20 ranges")
    print(f"{'material':14s} {'build [ms]':>11s}")
    for name in ("sls", "butyl-fc", "butyl-cerf", "butyl-prony3"):
        imp = make_impact(name, 10.0, {})
        ts = []
        for k in range(8, 28):  # a different range each time: nothing cached
            top = 2.0**-k
            t = time.perf_counter()
            level_tables(imp.material, float(imp.kappa), top * 2.0**-18, 22, 256.0 * top, 1e-10)
            ts.append(time.perf_counter() - t)
        print(f"{name:14s} {np.median(ts) * 1e3:11.2f}")
    print()


def throughput():
    print("sweep throughput inside one shard (runner.run_points: validation, solve, dataset; each in a fresh")
    print("process after a 3-point warm-up that compiles: the tables of the other materials and step ranges")
    print("are built inside the timed run, as in a shard); 1000 points is config.yaml's shard_size")
    print(f"{'scene':36s} {'points':>7s} {'method':>9s} {'wall [s]':>9s} {'points/s':>9s} {'tables built':>13s}")
    for label in _throughput_scenes():
        for method in ("adaptive", "direct"):
            out = subprocess.run([sys.executable, __file__, "--shard", label, method], capture_output=True,
                                 text=True, check=True)
            n, wall, built = out.stdout.split()
            print(f"{label:36s} {int(n):7d} {method:>9s} {float(wall):9.3f} {int(n) / float(wall):9.0f} "
                  f"{int(built):13d}")
    print()


if __name__ == "__main__":
    if sys.argv[1:2] == ["--shard"]:
        print(*shard_wall(sys.argv[2], sys.argv[3]))
        sys.exit(0)
    sections = (per_impact, breakdown, mode_counts, cold, thickness, table_builds, throughput)
    chosen = sys.argv[1:] or [f.__name__ for f in sections]  # e.g. bench_adaptive.py per_impact breakdown
    unknown = set(chosen) - {f.__name__ for f in sections}
    if unknown:
        sys.exit(f"unknown section(s) {sorted(unknown)}; choose from {[f.__name__ for f in sections]}")
    for f in sections:
        if f.__name__ in chosen:
            f()
