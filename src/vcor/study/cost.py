"""Sizing sweep jobs by work: an estimate of each grid point's solve time, and the split of a scene's
new points into jobs of about equal estimated work.

A sweep job pays a fixed start-up (a Python process, imports, loading the numba cache, reading the
materials: about a second per sweep job; ``benchmarks/bench_rules.py`` measures it per rule) before it solves
anything. Jobs are therefore sized by the *work* they hold, not by their number of points: a scene
whose points are estimated at less than ``job_seconds`` of solver work runs in one job; a larger one is
cut into ``ceil(work / job_seconds)`` jobs of equal estimated work, so that a job's work dwarfs its
start-up and a large scene still spreads over the cores.

The estimate is deliberately coarse (within a factor of about two of the measured cost, which
``benchmarks/bench_scaling.py`` prints beside it): the cost of one solve by method, measured on the
reference machine for the presets, including the runner's own work per point (building the point's
material, recording its row); more for a material fitted to measured data (tens of Prony modes) with
the methods whose cost grows with the number of modes; more for a bootstrap sample (its material is
built at the point's temperature from the samples file); and a factor for the error estimate (a
second, finer run). Planning is deterministic: the same points give the same jobs on every machine.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

__all__ = [
    "DATA_FIT_FACTOR",
    "DATA_FIT_FACTOR_OTHERS",
    "ERROR_ESTIMATE_FACTOR",
    "JOB_SECONDS",
    "POINT_SECONDS",
    "SAMPLE_SECONDS",
    "point_cost",
    "point_seconds",
    "split_by_work",
]

#: target estimated solver work per sweep job (s): about ten times a job's start-up, and a scene of a
#: minute of work still splits into four jobs for the cores
JOB_SECONDS = 15.0
#: estimated seconds per point by method for a preset material, runner included (measured with
#: ``vcor.simulate`` and ``vcor.study.runner.run_points`` on the reference machine, rounded up; for
#: ``adaptive``, four Richardson grids (three for a resolved exponential kernel: less): 0.13-0.25 ms per
#: point over the presets,
#: ``benchmarks/bench_scaling.py`` prints the estimate beside the measured SLS cost)
POINT_SECONDS = {
    "adaptive": 2.5e-4,
    "direct": 1.5e-3,
    "paper": 1.5e-3,
    "soe": 8e-4,
    "ive-numba": 6e-4,
    "ive": 0.25,
}
#: a material fitted to measured data has tens of Prony modes: the fixed-step and ``ive-numba``
#: methods' cost grows with them (about 5x at 64 modes); the adaptive method's about 2x (the pyvisco
#: fit: 0.15-0.28 ms per point)
DATA_FIT_FACTOR = {"adaptive": 2.0}
DATA_FIT_FACTOR_OTHERS = 5.0
#: building a bootstrap sample's material at the point's temperature (s per point; a sweep's points of
#: one sample and temperature share it: ``benchmarks/bench_uncertainty.py cost`` prints the estimated
#: work of the pyvisco scene beside its sweep jobs' measured work)
SAMPLE_SECONDS = 1e-4
#: the error estimate solves every point again, finer (dt/2, rtol/100 or step_tol/16)
ERROR_ESTIMATE_FACTOR = 3.0


def point_seconds(point: dict, settings: dict, from_data: frozenset | set = frozenset()) -> float:
    """Estimated solve time (s) of one grid point (``point``: its material name and axis values) with the
    scene's ``settings``; ``from_data``: the names of materials fitted to measured data."""
    method = settings["solver"]["method"]
    seconds = POINT_SECONDS.get(method, max(POINT_SECONDS.values()))
    if point.get("material") in from_data:
        seconds *= DATA_FIT_FACTOR.get(method, DATA_FIT_FACTOR_OTHERS)
    if settings.get("error_estimate"):
        seconds *= ERROR_ESTIMATE_FACTOR
    if "sample" in point:
        seconds += SAMPLE_SECONDS
    return seconds


def point_cost(settings: dict, from_data: frozenset | set = frozenset()) -> Callable[[dict], float]:
    """:func:`point_seconds` as a function of the point alone, computed once per material and
    presence of a bootstrap sample (all it depends on; a plan of 2e5 points calls it for each)."""
    known: dict[tuple, float] = {}

    def cost(point: dict) -> float:
        key = (point.get("material"), "sample" in point)
        if key not in known:
            known[key] = point_seconds(point, settings, from_data)
        return known[key]

    return cost


def split_by_work(points: Sequence, cost: Callable[[dict], float], job_seconds: float | None,
                  max_points: int | None = None) -> list[list]:
    """``points`` in order, cut into contiguous jobs of about equal estimated work (``cost(point)``,
    seconds): ``ceil(work / job_seconds)`` of them, at least one, and at least as many as ``max_points``
    points per job need; a job still above ``max_points`` (uneven costs) is cut further. ``job_seconds``
    None: only ``max_points`` cuts, in runs of ``max_points`` points."""
    points = list(points)
    if not points:
        return []
    if job_seconds is not None and not job_seconds > 0:
        raise ValueError(f"job_seconds must be > 0 s, got {job_seconds}")
    if max_points is not None and max_points < 1:
        raise ValueError(f"shard_size must be >= 1 point, got {max_points}")
    costs = [float(cost(p)) for p in points] if job_seconds is not None else [1.0] * len(points)
    total = math.fsum(costs)
    n = 1 if job_seconds is None else max(1, math.ceil(total / job_seconds))
    if max_points is not None and job_seconds is not None:
        n = max(n, math.ceil(len(points) / max_points))
    jobs, current, done = [], [], 0.0
    for p, c in zip(points, costs):
        # a job ends where the cumulative work passes its share of the total
        if current and done + c / 2 > total * (len(jobs) + 1) / n:
            jobs.append(current)
            current = []
        current.append(p)
        done += c
    jobs.append(current)
    if max_points is None:
        return jobs
    return [job[i : i + max_points] for job in jobs for i in range(0, len(job), max_points)]
