"""vcor.sweep on a 3000-point SLS sweep (v0 = 1..30 m/s x 100 relaxation rates beta, alpha = beta / 4):
workers=2 against workers=1, and workers=1 per point against a bare loop over vcor.simulate in one process
(the loop a notebook user writes: one material per beta, every speed of it); and the machine's own bound for
two processes, the bare loop split in two forked processes side by side against the whole loop in one (on a
2-vCPU VM two busy vCPUs are each slower than one alone, so this ratio is above 0.5, and no workers=2 call,
which also checks, forks and builds its dataset, can go below it).

Each run is a fresh process with an empty numba cache; inside it, after one untimed call of each (compile,
caches), the four are timed interleaved (CALLS rounds) and each ratio is the median of its rounds'
ratios, so that a busy machine slows all four alike. Cells give the median over runs (min–max).

Run: python benchmarks/bench_sweep.py [--runs 2] [--calls 5] [--quick] [--out docs/_generated/sweep.md]
"""

from __future__ import annotations

import multiprocessing
import time

import numpy as np

import timing
import vcor

V0 = np.arange(1.0, 31.0)                       # m/s
BETA = np.geomspace(600.0, 4800.0, 100)         # 1/s
SCENE = {"materials": ["sls"], "grid": {"v0": V0, "beta": BETA}, "tie": {"alpha": {"to": "beta", "ratio": 0.25}}}
E_GLASSY = vcor.materials.get("sls").E_glassy   # Pa


def bare_loop(betas=BETA):
    for beta in betas:
        material = vcor.materials.SLS(E_GLASSY, 0.25 * beta, beta)
        for v in V0:
            vcor.simulate(material, float(v))


def bare_halves():
    """The bare loop split in two forked processes (every other beta each), side by side: what two workers
    could do with no work outside solving, on this machine (two busy vCPUs are each slower than one)."""
    ctx = multiprocessing.get_context("fork")
    procs = [ctx.Process(target=bare_loop, args=(BETA[i::2],)) for i in range(2)]
    for p in procs:
        p.start()
    for p in procs:
        p.join()
        if p.exitcode != 0:
            raise RuntimeError(f"a bare-loop process ended with exit code {p.exitcode}")


def _timed(fn):
    t = time.perf_counter()
    fn()
    return time.perf_counter() - t


def measure(args):
    calls = {"bare": bare_loop, "one": lambda: vcor.sweep(SCENE, workers=1, progress=False),
             "two": lambda: vcor.sweep(SCENE, workers=2, progress=False), "halves": bare_halves}
    for fn in calls.values():
        fn()  # compile, load, caches
    rounds = [{k: _timed(fn) for k, fn in calls.items()} for _ in range(timing.calls(args, 2))]
    n = V0.size * BETA.size
    return {"points": n, "bare": timing.median([r["bare"] / n for r in rounds]),
            "one": timing.median([r["one"] / n for r in rounds]), "two": timing.median([r["two"] / n for r in rounds]),
            "two_over_one": timing.median([r["two"] / r["one"] for r in rounds]),
            "one_over_bare": timing.median([r["one"] / r["bare"] for r in rounds]),
            "halves_over_bare": timing.median([r["halves"] / r["bare"] for r in rounds])}


def report(args, results):
    c = timing.cell
    rows = [[str(results[0]["points"]), c([r["bare"] for r in results], 1e3, ".3f"),
             c([r["one"] for r in results], 1e3, ".3f"), c([r["two"] for r in results], 1e3, ".3f"),
             c([r["two_over_one"] for r in results]), c([r["one_over_bare"] for r in results]),
             c([r["halves_over_bare"] for r in results])]]
    return [f"A 3000-point SLS sweep (v0 1..30 m/s x 100 values of beta, 600..4800 1/s, alpha = beta / 4), "
            f"adaptive method: time per point of a bare loop over vcor.simulate in one process, of vcor.sweep with "
            f"workers=1 and workers=2 (whole call: checks, solving, dataset), and the ratios; the last column is "
            f"the machine's bound for two processes: the bare loop split in two forked processes side by side "
            f"(every other beta each) against the whole loop in one; {timing.calls(args, 2)} "
            "interleaved rounds after one untimed call of each, ratios the median of the rounds' ratios; one "
            "fresh process with an empty numba cache per run; cells: median over runs (min–max).",
            timing.table(["points", "bare loop [ms/point]", "workers=1 [ms/point]", "workers=2 [ms/point]",
                          "workers=2 / workers=1", "workers=1 / bare loop", "two bare halves / bare loop"], rows)]


if __name__ == "__main__":
    timing.main(__doc__, measure, report, quick="2 rounds", calls=5)
