"""The adaptive method against direct: per impact, where the time of one impact goes, exponential
modes, a fresh process's first impact, cost against plate thickness, level-table builds, sweep
throughput inside one shard.

Every section runs in fresh processes with an empty numba cache, once per run; sections of warm calls
time them after one untimed call; cells give the median over runs (min–max).

Run: python benchmarks/bench_adaptive.py [section ...] [--runs 2] [--quick] [--out FILE]
     (default: all sections: per_impact breakdown mode_counts cold thickness table_builds throughput)
"""

from __future__ import annotations

import json
import sys
import time

import numpy as np

import timing
import vcor
from vcor.contact.impact import make_impact
from vcor.materials.expsums import soe
from vcor.solvers.adaptive import GRIDS, SMOOTH_GRIDS, run_adaptive
from vcor.solvers.adaptive_tables import level_tables
from vcor.solvers.options import solver_options
from vcor.study import runner, scene

MATERIALS = ("sls", "butyl-fc", "butyl-cerf", "butyl-prony3")
c = timing.cell


def _calls(args, full, quick):
    return quick if args.quick else full


# --- sections measured inside a fresh process (a worker): return JSON-able results -------------------

def measure_per_impact(args):
    calls = _calls(args, 101, 11)
    out = {}
    for name in MATERIALS:
        td, rd = timing.warm_timed(lambda n=name: vcor.simulate(n, 10.0, method="direct"), calls)
        ta, ra = timing.warm_timed(lambda n=name: vcor.simulate(n, 10.0, method="adaptive"), calls)
        out[name] = {"direct": td, "adaptive": ta, "steps": [rd.steps, ra.steps]}
    return {"calls": calls, "materials": out}


def measure_breakdown(args):
    calls = _calls(args, 200, 20)
    opts = vcor.SolverOptions(method="adaptive")
    kw = {"step_tol": opts.step_tol, "max_steps": opts.max_adaptive_steps, "tol": opts.soe_tol}
    out = {}
    for name in MATERIALS:
        imp = make_impact(name, 10.0, {})
        tc = imp.contact_time_estimate()
        w = timing.warm_median
        out[name] = {
            "simulate": w(lambda n=name: vcor.simulate(n, 10.0, options=opts), calls),
            "setup": w(lambda n=name: (solver_options(method="adaptive"),
                                       make_impact(n, 10.0, {}).contact_time_estimate()), calls),
            "three": w(lambda i=imp, t=tc: run_adaptive(i, t, extrapolate=True, **kw), calls),
            "one": w(lambda i=imp, t=tc: run_adaptive(i, t, **kw), calls),
            "steps": [run_adaptive(imp, tc, **kw).steps, run_adaptive(imp, tc, extrapolate=True, **kw).steps],
            "modes": soe(imp.material, tc * 2.0**-18, 256.0 * tc, opts.soe_tol).n_terms}
    return {"calls": calls, "materials": out}


def measure_mode_counts(args):
    tol = vcor.SolverOptions(method="adaptive").soe_tol
    out = {}
    for name in ("butyl-fc", "butyl-cerf"):
        imp = make_impact(name, 10.0, {})
        top = 2.0 ** np.floor(np.log2(imp.contact_time_estimate()))
        t_max = 256.0 * top
        rep = soe(imp.material, top * 2.0**-18, t_max, tol)
        live = level_tables(imp.material, float(imp.kappa), top * 2.0**-18, 22, t_max, tol).levels.live_modes
        out[name] = {"all": rep.n_terms, "slow": int(np.sum(np.asarray(rep.material.beta) * t_max < 1e-3)),
                     "short": soe(imp.material, top * 2.0**-18, 8.0 * top, tol).n_terms,
                     "live": [int(live[0]), int(live[-1])]}
    return out


def measure_thickness(args):
    calls = _calls(args, 5, 2)
    out = {"calls": calls,
           "standard": timing.warm_median(lambda: vcor.simulate("sls", 10.0, method="adaptive"), 9), "rows": []}
    for h in np.geomspace(1e-3, 1.0, 3 if args.quick else 7):
        ta, ra = timing.warm_timed(lambda hh=h: vcor.simulate("sls", 10.0, h=hh, method="adaptive"), calls)
        td, rd = timing.warm_timed(lambda hh=h: vcor.simulate("sls", 10.0, h=hh, method="direct"), 1)
        out["rows"].append({"h": h, "status": ra.status, "t0": ra.t0, "cor": ra.cor, "steps": ra.steps, "adaptive": ta,
                            "direct_status": rd.status, "direct": td})
    return out


def measure_table_builds(args):
    n_ranges = _calls(args, 20, 5)
    out = {"ranges": n_ranges, "materials": {}}
    for name in MATERIALS:
        imp = make_impact(name, 10.0, {})
        ts = []
        for k in range(8, 9 + n_ranges):  # a different range each time: nothing cached; the first untimed
            top = 2.0**-k
            t = time.perf_counter()
            level_tables(imp.material, float(imp.kappa), top * 2.0**-18, 22, 256.0 * top, 1e-10)
            ts.append(time.perf_counter() - t)
        out["materials"][name] = float(np.median(ts[1:]))
    return out


def _throughput_scenes(quick):
    scenes = {}
    for n_v0, n_b in ((30, 50),) if quick else ((30, 50), (250, 334)):
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
    s2 = {**_throughput_scenes(False)[label], "solver": {"method": method}}
    pts = scene.scene_points(s2)
    settings = scene.settings_of(s2)
    runner.run_points(pts[:3], settings)  # JIT
    built = level_tables.cache_info().misses
    t = time.perf_counter()
    runner.run_points(pts, settings)
    return {"points": len(pts), "wall": time.perf_counter() - t, "built": level_tables.cache_info().misses - built}


MEASURE = {"per_impact": measure_per_impact, "breakdown": measure_breakdown, "mode_counts": measure_mode_counts,
           "thickness": measure_thickness, "table_builds": measure_table_builds}


# --- the sections' tables --------------------------------------------------------------------------

def by_material(args, section):
    """(the section's results over RUNS fresh workers, {material: its results over the runs})."""
    res = timing.worker_runs(args.runs, section, *args.flags)
    return res, {name: timing.column(res, "materials", name) for name in MATERIALS}


def per_impact(args):
    res, by = by_material(args, "per_impact")
    rows = []
    for name, runs in by.items():
        td, ta = [r["direct"] for r in runs], [r["adaptive"] for r in runs]
        rows.append([name, c(td, 1e3, ".3f"), c(ta, 1e3, ".3f"), c([a / d for a, d in zip(ta, td)], 1.0, ".3f"),
                     "/".join(map(str, runs[0]["steps"]))])
    opts = vcor.SolverOptions()
    return [f"Per impact at default settings, v0 = 10 m/s, whole simulate call, warm: median of {res[0]['calls']} "
            "calls after one untimed call (direct: 2000 steps per contact-time estimate; adaptive: its defaults, "
            f"step_tol {opts.step_tol:g} with Richardson extrapolation from {GRIDS} grids, {SMOOTH_GRIDS} where the "
            "kernel is an exact exponential sum resolved on the grid: sls).",
            timing.table(["material", "direct [ms]", "adaptive [ms]", "adaptive / direct", "steps direct/adaptive"],
                         rows)]


def breakdown(args):
    res, by = by_material(args, "breakdown")
    rows = []
    for name, runs in by.items():
        rows.append([name] + [c([r[k] for r in runs], 1e6, ".0f") for k in ("simulate", "setup", "three", "one")]
                    + ["/".join(map(str, runs[0]["steps"])), runs[0]["modes"]])
    return [f"Where the time of one adaptive impact goes (v0 = 10 m/s, warm: median of {res[0]['calls']} calls after "
            "one untimed call): set-up = options, impact and contact-time estimate; one march = run_adaptive "
            "without extrapolation; all marches = run_adaptive as simulate calls it (the grid and its "
            f"{SMOOTH_GRIDS - 1} or {GRIDS - 1} replays, extrapolation); modes: terms of the exponential sum on "
            "[t_c / 2^18, 256 t_c].",
            timing.table(["material", "simulate [µs]", "set-up [µs]", "all marches [µs]", "one march [µs]",
                          "steps (grid/all)", "modes"], rows)]


def mode_counts(args):
    res = timing.worker_runs(1, "mode_counts", *args.flags)[0]  # counts, not timings: one run
    rows = [[name, r["all"], r["slow"], r["short"], "/".join(map(str, r["live"]))] for name, r in res.items()]
    return ["Modes of the exponential sums (v0 = 10 m/s; counts, not timings): all = on the range of the one-call "
            "path's tables, [t_c 2^-18, 256 t_c] in powers of two; slow = of those, beta t_max < 1e-3; a sum ending "
            "at 8 t_c instead; live = modes a step touches on the finest / coarsest level (rows 0 and last of the "
            "tables).",
            timing.table(["material", "all", "slow", "to 8 t_c", "live finest/coarsest"], rows)]


def cold(args):
    labels = (("direct, dt = 1 µs", "method='direct', dt=1e-6"), ("adaptive", "method='adaptive'"))
    res = [{label: timing.cold_and_cached(options) for label, options in labels} for _ in range(args.runs)]
    rows = [[label, state, c([r[label][state][0] for r in res]), c([r[label][state][1] for r in res])]
            for label, _ in labels for state in ("empty", "filled")]
    return ["A fresh process's first impact (import vcor, one simulate('sls', 10.0)): an empty numba cache "
            "(compiles), then a second fresh process with the cache the first one filled.",
            timing.table(["method", "numba cache", "process wall [s]", "import + run inside [s]"], rows)]


def thickness(args):
    res = timing.worker_runs(args.runs, "thickness", *args.flags)
    rows = []
    for i, r in enumerate(res[0]["rows"]):
        runs = [x["rows"][i] for x in res]
        rows.append([f"{r['h'] * 1e3:.2f}", r["status"], f"{r['t0']:.4g}", f"{r['cor']:.3e}", r["steps"],
                     c([x["adaptive"] for x in runs], 1e3, ".2f"), r["direct_status"],
                     c([x["direct"] for x in runs], 1e3, ".1f")])
    thin = [x["rows"][0]["adaptive"] / x["standard"] for x in res]
    return [f"Cost against plate half-thickness h (sls, v0 = 10 m/s), warm: adaptive the median of {res[0]['calls']} "
            "calls, direct one call, each after one untimed call.",
            timing.table(["h [mm]", "status", "t0 [s]", "COR", "steps", "adaptive [ms]", "direct status",
                          "direct [ms]"], rows),
            f"Thin plate h = 1 mm against the standard impact (h = 2 r = 20 mm), adaptive: {c(thin, 1.0, '.1f')} times "
            f"({c(timing.column(res, 'standard'), 1e3, '.3f')} ms for the standard impact, median of 9 warm calls)."]


def table_builds(args):
    res = timing.worker_runs(args.runs, "table_builds", *args.flags)
    rows = [[name, c(timing.column(res, "materials", name), 1e3, ".2f")] for name in MATERIALS]
    return [f"Level tables of one (material, step range) pair, as a sweep point on a new power of two of t_c builds "
            f"them (exponential sum with its check, per-level weights): median over {res[0]['ranges']} new ranges "
            "after one untimed build.", timing.table(["material", "build [ms]"], rows)]


def throughput(args):
    rows = []
    for label in _throughput_scenes(args.quick):
        for method in ("adaptive", "direct"):
            res = [timing.fresh_json([timing.PYTHON, __file__, "--shard", label, method]) for _ in range(args.runs)]
            walls = timing.column(res, "wall")
            rows.append([label, res[0]["points"], method, c(walls, 1.0, ".3f"),
                         c([res[0]["points"] / w for w in walls], 1.0, ".0f"), res[0]["built"]])
    return ["Sweep throughput inside one shard (study.runner.run_points: validation, solve, dataset), each in a fresh "
            "process with an empty numba cache after a 3-point warm-up that compiles (the tables of the other "
            "materials and step ranges are built inside the timed run, as in a shard).",
            timing.table(["scene", "points", "method", "wall [s]", "points/s", "tables built"], rows)]


SECTIONS = (per_impact, breakdown, mode_counts, cold, thickness, table_builds, throughput)


def main():
    names = [f.__name__ for f in SECTIONS]
    p = timing.parser(__doc__, quick="fewer calls, sizes and scenes in every section")
    p.add_argument("sections", nargs="*", metavar="section", help=f"any of {' '.join(names)} (default: all)")
    args = p.parse_args()
    unknown = set(args.sections) - set(names)
    if unknown:
        p.error(f"unknown section(s) {sorted(unknown)}; choose from {names}")
    if args.worker:
        print(json.dumps(MEASURE[args.sections[0]](args)))
        return
    args.flags = timing.quick_flags(args)
    blocks = []
    for f in SECTIONS:
        if f.__name__ in (args.sections or names):
            blocks += [f"**{f.__name__}**", *f(args)]
    timing.publish(args.out, args.runs, blocks)


if __name__ == "__main__":
    if sys.argv[1:2] == ["--shard"]:
        print(json.dumps(shard_wall(sys.argv[2], sys.argv[3])))
    else:
        main()
