"""The stability scenes of config.yaml (``stability-*``, error estimates included) solved with each
named method: statuses per scene, the largest error estimate over the ok points, the wall time, and
the flagged points of the last method.

Each (scene, method) runs in fresh processes with an empty numba cache, once per run; the wall time is
that of study.runner.run_points over the scene's points, the first call in the process (compile
included, as a user meets one scene); cells give the median over runs (min–max).

Run: python benchmarks/bench_stability_methods.py [method ...] [--scene NAME ...] [--runs 2] [--quick]
     [--out FILE]   (default methods: direct soe adaptive)
"""

from __future__ import annotations

import collections
import time

import numpy as np

import timing
from vcor import status
from vcor.io.yamlfile import load_yaml
from vcor.study import runner, scene

CONFIG = timing.ROOT / "config.yaml"
QUICK_STRIDE = 4  # --quick: every 4th grid point
METHODS = ("direct", "soe", "adaptive")
QUICK_SCENE, QUICK_METHODS = "stability-ratio", ("direct", "adaptive")  # --quick, unless named


def stability_scenes() -> dict:
    return {k: v for k, v in load_yaml(CONFIG)["scenes"].items() if k.startswith("stability-")}


def measure(args):
    """In a worker: ``args.methods`` is [scene, method]."""
    name, method = args.methods
    sc = stability_scenes()[name]
    s2 = {**sc, "solver": {**sc.get("solver", {}), "method": method}}
    points = scene.scene_points(s2)[:: QUICK_STRIDE if args.quick else 1]
    t = time.perf_counter()
    ds = runner.run_points(points, scene.settings_of(s2))
    wall = time.perf_counter() - t
    names = [status.STATUS_NAMES[int(code)] for code in ds["status"].values]
    ok = ds["status"].values == status.code("ok")
    axes = [a for a in ds.coords if a not in ("point", "material", "material_id")]
    flagged = [f"{names[i]}: {ds['material'].values[i]}, "
               + ", ".join(f"{a} = {float(ds[a].values[i]):g}" for a in axes)
               for i in np.where(~ok)[0]]
    err = float(np.nanmax(ds["cor_err"].values[ok])) if ok.any() else float("nan")
    return {"points": len(points), "statuses": dict(collections.Counter(names)), "max_cor_err": err, "wall": wall,
            "flagged": flagged}


def configure(p):
    p.add_argument("methods", nargs="*", metavar="method", help="methods (default: direct soe adaptive)")
    p.add_argument("--scene", action="append", help="only this stability scene (repeatable; default: all)")


def methods_of(args) -> list:
    return args.methods or list(QUICK_METHODS if args.quick else METHODS)


def jobs(args):
    """(scene, method): one set of RUNS fresh workers each."""
    for name in args.scene or ([QUICK_SCENE] if args.quick else list(stability_scenes())):
        for method in methods_of(args):
            yield (name, method), [name, method, *timing.quick_flags(args)]


def report(args, results):
    last_method = methods_of(args)[-1]
    rows, flagged = [], []
    for (name, method), res in results.items():
        last = res[-1]
        statuses = ", ".join(f"{k} {v}" for k, v in sorted(last["statuses"].items()))
        rows.append([name, method, last["points"], statuses, f"{last['max_cor_err']:.2e}",
                     timing.cell(timing.column(res, "wall"), 1.0, ".1f")])
        if method == last_method:
            flagged += [f"- {name}: {line}" for line in last["flagged"]]
    quick = f" (--quick: every {QUICK_STRIDE}th point)" if args.quick else ""
    blocks = [f"Stability scenes by method{quick}: "
              "statuses and the largest cor_err over the ok points (of the last run), and the wall time of "
              "run_points in a fresh process with an empty numba cache (compile included).",
              timing.table(["scene", "method", "points", "statuses", "max cor_err", "wall [s]"], rows),
              f"Points not ok with {last_method}:" + ("" if flagged else " none")]
    if flagged:
        blocks.append("\n".join(flagged))
    return blocks


if __name__ == "__main__":
    timing.main(__doc__, measure, report, configure=configure, jobs=jobs,
                quick=f"every {QUICK_STRIDE}th grid point; unless named, the scene {QUICK_SCENE} with "
                      f"{' and '.join(QUICK_METHODS)} only")
