"""Scaling benchmark: a 1e4-point sweep through the workflow with -j2 against the in-process cost.

Run: python benchmarks/bench_scaling.py [--points-per-job 2500]
Prints a table: in-process cost per point, workflow wall time, per-point cost in the workflow
(wall x cores / points), their ratio, points per second per core, and the cores a 1e6-point sweep
needs to finish in one hour.
"""

import argparse
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import yaml

from vcor import runner, scene

ROOT = Path(__file__).resolve().parents[1]
SCENE = {
    "materials": ["sls"],
    "grid": {"v0": {"start": 1, "stop": 100, "step": 1}, "beta": {"start": 100, "stop": 1.0e5, "num": 100, "log": True}},
    "tie": {"alpha": {"to": "beta", "ratio": 0.25}},
}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--points-per-job", type=int, default=2500)
    ap.add_argument("--cores", type=int, default=2)
    args = ap.parse_args()
    points = scene.scene_points(SCENE)
    n = len(points)
    settings = scene.settings_of(SCENE)
    runner.run_points(points[:5], settings)  # JIT / cache load
    sample = points[:: max(1, n // 500)]
    times = []
    for _ in range(3):
        t = time.perf_counter()
        runner.run_points(sample, settings)
        times.append((time.perf_counter() - t) / len(sample))
    per_point = statistics.median(times)
    with tempfile.TemporaryDirectory() as d:
        d = Path(d)
        shutil.copy(ROOT / "Snakefile", d / "Snakefile")
        shutil.copytree(ROOT / "workflow", d / "workflow")
        cfg = {"shard_size": args.points_per_job, "material_dir": "results/materials", "scenes": {"scaling": SCENE}}
        (d / "config.yaml").write_text(yaml.safe_dump(cfg))
        t = time.perf_counter()
        subprocess.run([sys.executable, "-m", "snakemake", "-j", str(args.cores), "-q"], cwd=d, check=True,
                       capture_output=True)
        wall = time.perf_counter() - t
        jobs = sorted((d / "results/scaling/benchmarks/shards").glob("*.tsv"))
        job_s = sum(float(p.read_text().splitlines()[1].split("\t")[0]) for p in jobs)
    wf_point = wall * args.cores / n
    rate = 1.0 / wf_point
    print(f"{'quantity':58s} {'value':>14s}")
    print(f"{'grid points':58s} {n:14d}")
    print(f"{'shard jobs (points per job)':58s} {len(jobs):8d} ({args.points_per_job})")
    print(f"{'in-process cost per point (runner.run_points, median)':58s} {per_point * 1e3:11.2f} ms")
    print(f"{'workflow wall time, -j' + str(args.cores) + ' (DAG, shards, aggregation)':58s} {wall:12.1f} s")
    print(f"{'shard jobs, summed job wall time':58s} {job_s:12.1f} s")
    print(f"{'workflow cost per point (wall x cores / points)':58s} {wf_point * 1e3:11.2f} ms")
    print(f"{'ratio workflow / in-process (target <= 2)':58s} {wf_point / per_point:14.2f}")
    print(f"{'points per second per core (workflow)':58s} {rate:14.0f}")
    print(f"{'cores for 1e6 points in one hour':58s} {1e6 / (rate * 3600):14.1f}")


if __name__ == "__main__":
    main()
