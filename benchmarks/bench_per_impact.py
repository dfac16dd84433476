"""Per-impact cost of the default method against another commit, in one run.

Each round starts one fresh process per implementation (this checkout's ``src``, and a clean checkout
of REV made with ``git worktree``), each with an empty numba cache, alternating which goes first, so
that both meet the same machine load; each process warms up (one untimed call: compile, first tables)
and then times CALLS warm calls of ``vcor.simulate(material, 10.0, method=<this checkout's default
method>)`` per material. The table gives per material the median over rounds of each implementation's
median (min–max over rounds) and the median of the per-round ratios this/REV (< 1: this checkout is
faster).

Run: python benchmarks/bench_per_impact.py REV [--rounds 5] [--calls 101] [--quick] [--out FILE]
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import timing

MATERIALS = ("sls", "butyl-fc", "butyl-cerf", "butyl-prony3")


def worker(calls: int, method: str) -> dict:
    """In a process whose PYTHONPATH names the implementation: per material the median of ``calls``
    warm calls (s), and where vcor was imported from."""
    import vcor

    out = {name: timing.warm_median(lambda n=name: vcor.simulate(n, 10.0, method=method), calls)
           for name in MATERIALS}
    return {"times": out, "vcor": str(Path(vcor.__file__).resolve().parent)}


def run_worker(src: Path, calls: int, method: str) -> dict:
    out = timing.fresh_json([timing.PYTHON, __file__, timing.WORKER_FLAG, str(calls), method],
                            env={"PYTHONPATH": str(src)})
    if Path(out["vcor"]) != (src / "vcor").resolve():
        raise RuntimeError(f"the worker for {src} imported vcor from {out['vcor']}")
    return out["times"]


def main():
    p = timing.parser(__doc__, runs=5, quick="2 rounds of 11 calls", calls=101)
    p.add_argument("rev", help="the commit to compare with (e.g. HEAD~1)")
    p.add_argument("--rounds", dest="runs", type=timing.at_least_two, default=argparse.SUPPRESS,
                   help="the same as --runs: rounds (default 5)")
    args = p.parse_args()
    from vcor.solvers.options import DEFAULT_METHOD

    rounds, calls = (2, 11) if args.quick else (args.runs, args.calls)
    rev = timing.short_rev(args.rev)
    results = {"this": [], rev: []}
    with tempfile.TemporaryDirectory() as tmp:
        tree = Path(tmp) / "tree"
        subprocess.run(["git", "-C", str(timing.ROOT), "worktree", "add", "--detach", str(tree), rev],
                       capture_output=True, check=True)
        try:
            sources = {"this": timing.ROOT / "src", rev: tree / "src"}
            for i in range(rounds):
                for key in (("this", rev) if i % 2 == 0 else (rev, "this")):
                    results[key].append(run_worker(sources[key], calls, DEFAULT_METHOD))
        finally:
            subprocess.run(["git", "-C", str(timing.ROOT), "worktree", "remove", "--force", str(tree)],
                           capture_output=True)
    rows = []
    for name in MATERIALS:
        this, other = timing.column(results["this"], name), timing.column(results[rev], name)
        rows.append([name, timing.cell(this, 1e6, ".1f"), timing.cell(other, 1e6, ".1f"),
                     f"{timing.median(a / b for a, b in zip(this, other)):.3f}"])
    timing.publish(args.out, rounds, [
        f"Per impact, v0 = 10 m/s, method {DEFAULT_METHOD} (this checkout's default), whole simulate call: per "
        f"round one fresh process per implementation (empty numba cache, one untimed call, then the median of "
        f"{calls} warm calls); cells: median over {rounds} rounds (min–max); ratio: median of the per-round "
        f"ratios; this checkout against {rev}.",
        timing.table(["material", "this [µs]", f"{rev} [µs]", f"this / {rev}"], rows)])


if __name__ == "__main__":
    if sys.argv[1:2] == [timing.WORKER_FLAG]:  # run_worker: --worker CALLS METHOD
        print(json.dumps(worker(int(sys.argv[2]), sys.argv[3])))
    else:
        main()
