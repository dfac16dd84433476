"""The cost of a ``dem:`` entry: vcor's collisions at 25 speeds (0.1..10 m/s, log-spaced) and the fit
of every DEM law to them, for the paper's SLS and the 3-term Prony Butyl (``butyl-prony3``), each as a
sphere pair (a 5 mm sphere hitting its twin) and as a sphere on a rigid wall, as the config's ``dem:``
entries run them (vcor.dem.fit.collision, then vcor.dem.fit.fit_laws, default solver options).

Every case runs in its own fresh process with an empty numba cache, once per run, as the workflow's
dem job meets it: the import of vcor.dem.fit, the first collision and the first fit (cold: compile
included), then CALLS warm calls of each after one untimed call (their median); cells give the median
over runs (min–max).

Run: python benchmarks/bench_dem.py [case ...] [--runs 2] [--calls 5] [--quick] [--out FILE]
     (cases: sls-pair sls-wall butyl-prony3-pair butyl-prony3-wall; default: all)
"""

from __future__ import annotations

import time

import numpy as np

import timing

MATERIALS = ("sls", "butyl-prony3")
TARGETS = {"pair": {"sphere": {}}, "wall": "rigid"}
CASES = [f"{m}-{t}" for m in MATERIALS for t in TARGETS]
SPHERE = {"r": 0.005}  # m; density and Poisson ratio: the material's
SPEEDS, QUICK_SPEEDS = 25, 5
QUICK_CASES = ("sls-pair", "butyl-prony3-wall")  # --quick: each material and each target once


def speeds(args) -> np.ndarray:
    return np.geomspace(0.1, 10.0, QUICK_SPEEDS if args.quick else SPEEDS)


def measure(args):
    """In a worker: ``args.cases`` is the one case."""
    (case,) = args.cases
    material, target = case.rsplit("-", 1)
    v0 = speeds(args)
    t = time.perf_counter()
    from vcor.dem import fit

    out = {"import": time.perf_counter() - t}

    def collide():
        return fit.collision(material, v0, sphere=SPHERE, target=TARGETS[target])

    t = time.perf_counter()
    col = collide()
    out["collision_cold"] = time.perf_counter() - t
    t = time.perf_counter()
    fitted = fit.fit_laws(col)
    out["fit_cold"] = time.perf_counter() - t
    n = timing.calls(args)
    out["collision_warm"] = timing.warm_median(collide, n)
    out["fit_warm"] = timing.warm_median(lambda: fit.fit_laws(col), n)
    out.update(calls=n, speeds=len(v0), ok=int(np.isfinite(col.cor).sum()), laws=len(fitted))
    return out


def jobs(args):
    unknown = sorted(set(args.cases) - set(CASES))
    if unknown:
        raise SystemExit(f"unknown case(s) {unknown}; choose from {CASES}")
    for case in args.cases or (QUICK_CASES if args.quick else CASES):
        yield case, [case, "--calls", str(args.calls), *timing.quick_flags(args)]


def report(args, results):
    c = timing.cell
    rows = []
    for case, runs in results.items():
        col = timing.column(runs, "collision_cold")
        fits = timing.column(runs, "fit_cold")
        first = [r["import"] + r["collision_cold"] + r["fit_cold"] for r in runs]
        rows.append([case, f"{runs[0]['ok']}/{runs[0]['speeds']}", runs[0]["laws"], c(timing.column(runs, "import")),
                     c(col), c(fits), c(first), c(timing.column(runs, "collision_warm"), 1e3, ".1f"),
                     c(timing.column(runs, "fit_warm"), 1e3, ".1f")])
    r0 = next(iter(results.values()))[0]
    calls = f"{r0['calls']} call{'s' if r0['calls'] != 1 else ''}"
    return [f"One dem: entry's work, a {SPHERE['r'] * 1e3:g} mm sphere, {r0['speeds']} speeds 0.1..10 m/s "
            "log-spaced, default solver options: per case a fresh process with an empty numba cache per run; "
            "cold = the first call in the process (compile included); warm = median of "
            f"{calls} after one untimed call; first entry = import + cold collision + cold fit; cells: "
            "median over runs (min–max).",
            timing.table(["case", "speeds ok", "laws", "import [s]", "collisions, cold [s]", "fit laws, cold [s]",
                          "first entry [s]", "collisions, warm [ms]", "fit laws, warm [ms]"], rows)]


def configure(p):
    p.add_argument("cases", nargs="*", metavar="case", help=f"any of {' '.join(CASES)} (default: all)")


if __name__ == "__main__":
    timing.main(__doc__, measure, report,
                quick=f"{QUICK_SPEEDS} speeds, one warm call, cases {' '.join(QUICK_CASES)} (default)", calls=5,
                configure=configure, jobs=jobs)
