"""Scaling benchmark: SLS sweeps (v0 x beta) through the workflow against the in-process cost of the same
points, at two sizes: 1e4 points (about a second of solver work) and 2e5 points (about half a minute).

Per run: a worker (a fresh process with an empty numba cache) times study.runner.run_points on all
the points of each size in one call, in the grid's order, warm (after a 5-point untimed call; the
median of 3 passes for the smaller size, one pass for the larger), and for each size the workflow
runs in a new temporary project (Snakefile, workflow/, profiles/ and a config.yaml of this one scene,
its axes in the order written here, jobs sized by the config's defaults: vcor.study.cost) with an empty numba cache:
``python -m snakemake -j CORES``. The table, per size: the jobs planned, the estimated cost per point
(vcor.study.cost.point_seconds) beside the measured in-process cost, workflow wall time, the summed
wall time of the shard jobs (their Snakemake ``benchmark:`` files), the workflow's cost per point per
core (wall x cores / points) and its ratio to the in-process cost, points per second per core, and the
cores a 1e6-point sweep needs to finish in one hour. Cells give the median over runs (min–max).

Run: python benchmarks/bench_scaling.py [--points-per-job N] [--cores 2] [--runs 2] [--quick] [--out FILE]
"""

from __future__ import annotations

import json
import shutil
import statistics
import sys
import tempfile
import time
from pathlib import Path

import yaml

import timing
from vcor.study import cost, runner, scene

ROOT = timing.ROOT
SCENE = {
    "materials": ["sls"],
    "grid": {"v0": {"start": 1, "stop": 100, "step": 1},
             "beta": {"start": 100, "stop": 1.0e5, "num": 100, "log": True}},
    "tie": {"alpha": {"to": "beta", "ratio": 0.25}},
}
#: about half a minute of one core's solver work (0.13 ms per point): a run's fixed costs (Snakemake,
#: the compile, the aggregate) weigh less
LARGE_SCENE = {**SCENE, "grid": {"v0": {"start": 1, "stop": 200, "step": 1},
                                 "beta": {"start": 100, "stop": 1.0e5, "num": 1000, "log": True}}}
#: --quick: 400 points, one size
QUICK_SCENE = {**SCENE, "grid": {"v0": {"start": 1, "stop": 40, "step": 1},
                                 "beta": {"start": 100, "stop": 1.0e5, "num": 10, "log": True}}}


def in_process(sc, passes: int) -> float:
    """Warm cost per point (s) of run_points over all the scene's points in one call (the median of
    ``passes`` after a 5-point call). All of them, not a sample: a strided sample of a grid meets few
    values of its inner axis, and points that share a material share its tables (runner.solving_order)."""
    points = scene.scene_points(sc)
    settings = scene.settings_of(sc)
    runner.run_points(points[:5], settings)
    walls = []
    for _ in range(passes):
        t = time.perf_counter()
        runner.run_points(points, settings)
        walls.append(time.perf_counter() - t)
    return statistics.median(walls) / len(points)


def workflow(sc, points_per_job: int | None, cores: int) -> dict:
    """Wall time (s) of the workflow over ``sc`` in a new project, with its shard jobs' summed wall time."""
    with tempfile.TemporaryDirectory() as d:
        d = Path(d)
        shutil.copy(ROOT / "Snakefile", d / "Snakefile")
        for folder in ("workflow", "profiles"):
            shutil.copytree(ROOT / folder, d / folder)
        cfg = {"material_dir": "results/materials", "scenes": {"scaling": sc}}
        if points_per_job:
            cfg["shard_size"] = points_per_job
        (d / "config.yaml").write_text(yaml.safe_dump(cfg, sort_keys=False))  # the axes in the order written
        proc = timing.run_fresh([sys.executable, "-m", "snakemake", "-j", str(cores), "-q"], cwd=d)
        jobs = sorted((d / "results/scaling/benchmarks/shards").glob("*.tsv"))
        job_s = sum(float(p.read_text().splitlines()[1].split("\t")[0]) for p in jobs)
    return {"wall": proc.wall, "jobs": len(jobs), "job_s": job_s}


def main():
    p = timing.parser(__doc__, quick="400 points, one size")
    p.add_argument("--points-per-job", type=int, default=None, help="cap the points per job (default: none)")
    p.add_argument("--cores", type=int, default=2)
    args = p.parse_args()
    sizes = [QUICK_SCENE] if args.quick else [SCENE, LARGE_SCENE]
    if args.worker:
        print(json.dumps([in_process(sc, 3 if k == 0 else 1) for k, sc in enumerate(sizes)]))
        return
    per_point, runs = [], []
    for _ in range(args.runs):
        per_point.append(timing.fresh_json([sys.executable, __file__, timing.WORKER_FLAG, *timing.quick_flags(args)]))
        runs.append([workflow(sc, args.points_per_job, args.cores) for sc in sizes])
    c = timing.cell
    estimate = cost.point_seconds({"material": "sls"}, scene.settings_of(SCENE))
    columns = []
    for k, sc in enumerate(sizes):
        n = scene.point_count(sc)
        wall = [r[k]["wall"] for r in runs]
        wf_point = [w * args.cores / n for w in wall]
        columns.append([n, runs[0][k]["jobs"], f"{estimate * 1e3:.2f}", c([q[k] for q in per_point], 1e3),
                        c(wall, 1.0, ".1f"),
                        c([r[k]["job_s"] for r in runs], 1.0, ".1f"), c(wf_point, 1e3),
                        c([w / q[k] for w, q in zip(wf_point, per_point)]), c([1.0 / w for w in wf_point], 1.0, ".0f"),
                        c([1e6 * w / 3600.0 for w in wf_point], 1.0, ".1f")])
    names = ["grid points", "shard jobs (sized by estimated work)", "estimated cost per point (vcor.study.cost) [ms]",
             "in-process cost per point (run_points, warm) [ms]",
             f"workflow wall time, -j{args.cores} (DAG, shards, aggregation) [s]",
             "shard jobs, summed job wall time [s]", "workflow cost per point (wall x cores / points) [ms]",
             "ratio workflow / in-process", "points per second per core (workflow)",
             "cores for 1e6 points in one hour"]
    rows = [[name, *(col[i] for col in columns)] for i, name in enumerate(names)]
    headers = ["quantity", *(f"{scene.point_count(sc):.0e} points".replace("e+0", "e") for sc in sizes)]
    timing.publish(args.out, args.runs, [
        "SLS sweeps (v0 x beta, alpha = beta / 4) through the workflow in a new project with an empty numba "
        "cache per run, against the warm in-process cost of the same points (run_points over all of them in one "
        "process, in the grid's order); cells: median over runs (min–max).",
        timing.table(headers, rows)])


if __name__ == "__main__":
    main()
