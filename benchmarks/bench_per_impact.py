"""Per-impact cost of the default method against another commit, in one run.

Each round starts one fresh process per implementation (this checkout's ``src``, and a clean checkout
of REV made with ``git worktree``), alternating, so that both meet the same machine load; each
process warms up (compile or cache load, first tables) and then times CALLS warm calls of
``vcor.simulate(material, 10.0, method="adaptive")`` per material. Printed: per material the median
over rounds of each implementation's median, and the ratio this/REV (< 1: this checkout is faster).

Run: python benchmarks/bench_per_impact.py REV [--rounds 5] [--calls 101] [--out FILE]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
MATERIALS = ("sls", "butyl-fc", "butyl-cerf", "butyl-prony3")

WORKER = """
import json, statistics, sys, time
import vcor
calls = int(sys.argv[1])
out = {}
for name in sys.argv[2:]:
    vcor.simulate(name, 10.0, method="adaptive")
    times = []
    for _ in range(calls):
        t = time.perf_counter()
        vcor.simulate(name, 10.0, method="adaptive")
        times.append(time.perf_counter() - t)
    out[name] = statistics.median(times)
print(json.dumps(out))
"""


def run_worker(src: Path, calls: int) -> dict:
    env = dict(os.environ, PYTHONPATH=str(src))
    out = subprocess.run([sys.executable, "-c", WORKER, str(calls), *MATERIALS], env=env, capture_output=True,
                         text=True, check=True)
    return json.loads(out.stdout)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("rev", help="the commit to compare with (e.g. HEAD~1)")
    p.add_argument("--rounds", type=int, default=5)
    p.add_argument("--calls", type=int, default=101)
    p.add_argument("--out", type=Path, default=None, help="also write the table (Markdown) to this file")
    args = p.parse_args(argv)
    rev = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", args.rev], capture_output=True, text=True,
                         check=True).stdout.strip()
    with tempfile.TemporaryDirectory() as tmp:
        tree = Path(tmp) / "tree"
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(tree), rev], capture_output=True,
                       check=True)
        try:
            os.environ["NUMBA_CACHE_DIR"] = str(Path(tmp) / "numba-cache")
            results = {"this": [], rev: []}
            for _ in range(args.rounds):
                results["this"].append(run_worker(ROOT / "src", args.calls))
                results[rev].append(run_worker(tree / "src", args.calls))
        finally:
            subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force", str(tree)], capture_output=True)
    lines = [f"Per impact, v0 = 10 m/s, method adaptive (whole simulate call): medians over {args.rounds} rounds of "
             f"{args.calls} warm calls, this checkout against {rev}",
             "", "| material | this [us] | " + rev + " [us] | this / " + rev + " |", "|---|---|---|---|"]
    for name in MATERIALS:
        this = statistics.median(r[name] for r in results["this"])
        other = statistics.median(r[name] for r in results[rev])
        ratios = statistics.median(a[name] / b[name] for a, b in zip(results["this"], results[rev]))
        lines.append(f"| {name} | {this * 1e6:.1f} | {other * 1e6:.1f} | {ratios:.3f} |")
    text = "\n".join(lines) + "\n"
    print(text)
    if args.out:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text(text)


if __name__ == "__main__":
    main()
