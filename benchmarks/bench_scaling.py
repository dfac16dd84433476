"""Scaling benchmark: a 1e4-point SLS sweep (v0 x beta) through the workflow against the in-process
cost of the same points.

Per run: a worker (a fresh process with an empty numba cache) times study.runner.run_points on a
sample of the points, warm (medians of 3 passes after a 5-point untimed call), and the workflow runs
in a new temporary project (Snakefile, workflow/, profiles/ and a config.yaml of this one scene) with
an empty numba cache: ``python -m snakemake -j CORES``. The table: in-process cost per point, workflow
wall time, the summed wall time of the shard jobs (their Snakemake ``benchmark:`` files), the
workflow's cost per point per core (wall x cores / points) and its ratio to the in-process cost,
points per second per core, and the cores a 1e6-point sweep needs to finish in one hour. Cells give
the median over runs (min–max).

Run: python benchmarks/bench_scaling.py [--points-per-job 2500] [--cores 2] [--runs 2] [--quick] [--out FILE]
"""

from __future__ import annotations

import json
import shutil
import sys
import tempfile
from pathlib import Path

import timing
import yaml

from vcor.study import runner, scene

ROOT = timing.ROOT
SCENE = {
    "materials": ["sls"],
    "grid": {"v0": {"start": 1, "stop": 100, "step": 1}, "beta": {"start": 100, "stop": 1.0e5, "num": 100, "log": True}},
    "tie": {"alpha": {"to": "beta", "ratio": 0.25}},
}
#: --quick: 400 points in 4 jobs of 100
QUICK_SCENE = {**SCENE, "grid": {"v0": {"start": 1, "stop": 40, "step": 1},
                                 "beta": {"start": 100, "stop": 1.0e5, "num": 10, "log": True}}}
QUICK_POINTS_PER_JOB = 100


def in_process(sc) -> float:
    """Warm cost per point (s) of run_points: median of 3 passes over a sample after a 5-point call."""
    points = scene.scene_points(sc)
    settings = scene.settings_of(sc)
    sample = points[:: max(1, len(points) // 500)]
    return timing.warm_median(lambda: runner.run_points(sample, settings), 3) / len(sample) if sample else 0.0


def workflow(sc, points_per_job: int, cores: int) -> dict:
    """Wall time (s) of the workflow over ``sc`` in a new project, with its shard jobs' summed wall time."""
    with tempfile.TemporaryDirectory() as d:
        d = Path(d)
        shutil.copy(ROOT / "Snakefile", d / "Snakefile")
        for folder in ("workflow", "profiles"):
            shutil.copytree(ROOT / folder, d / folder)
        cfg = {"shard_size": points_per_job, "material_dir": "results/materials", "scenes": {"scaling": sc}}
        (d / "config.yaml").write_text(yaml.safe_dump(cfg))
        proc = timing.run_fresh([sys.executable, "-m", "snakemake", "-j", str(cores), "-q"], cwd=d)
        jobs = sorted((d / "results/scaling/benchmarks/shards").glob("*.tsv"))
        job_s = sum(float(p.read_text().splitlines()[1].split("\t")[0]) for p in jobs)
    return {"wall": proc.wall, "jobs": len(jobs), "job_s": job_s}


def main():
    p = timing.parser(__doc__, quick=f"400 points (v0 1..40 x 10 beta) in jobs of {QUICK_POINTS_PER_JOB}")
    p.add_argument("--points-per-job", type=int, default=2500)
    p.add_argument("--cores", type=int, default=2)
    args = p.parse_args()
    sc = QUICK_SCENE if args.quick else SCENE
    if args.worker:
        print(json.dumps(in_process(sc)))
        return
    per_job = QUICK_POINTS_PER_JOB if args.quick else args.points_per_job
    n = scene.point_count(sc)
    per_point, runs = [], []
    for _ in range(args.runs):
        per_point.append(timing.fresh_json([sys.executable, __file__, timing.WORKER_FLAG, *timing.quick_flags(args)]))
        runs.append(workflow(sc, per_job, args.cores))
    c = timing.cell
    wall = timing.column(runs, "wall")
    wf_point = [w * args.cores / n for w in wall]
    rows = [["grid points", n], ["shard jobs (points per job)", f"{runs[0]['jobs']} ({per_job})"],
            ["in-process cost per point (run_points, warm) [ms]", c(per_point, 1e3)],
            [f"workflow wall time, -j{args.cores} (DAG, shards, aggregation) [s]", c(wall, 1.0, ".1f")],
            ["shard jobs, summed job wall time [s]", c(timing.column(runs, "job_s"), 1.0, ".1f")],
            ["workflow cost per point (wall x cores / points) [ms]", c(wf_point, 1e3)],
            ["ratio workflow / in-process", c([w / q for w, q in zip(wf_point, per_point)])],
            ["points per second per core (workflow)", c([1.0 / w for w in wf_point], 1.0, ".0f")],
            ["cores for 1e6 points in one hour", c([1e6 * w / 3600.0 for w in wf_point], 1.0, ".1f")]]
    timing.publish(args.out, args.runs, [
        "An SLS sweep (v0 x beta, alpha = beta / 4) through the workflow in a new project with an empty numba "
        "cache per run, against the warm in-process cost of the same points; cells: median over runs (min–max).",
        timing.table(["quantity", "value"], rows)])


if __name__ == "__main__":
    main()
