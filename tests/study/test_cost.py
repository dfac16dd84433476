"""Sweep jobs sized by work (vcor.study.cost): the estimate, the split into jobs of equal estimated
work, and the plan of a scene: small scenes in one job, large ones over several, extensions reuse."""

import math

import pytest

from vcor.study import cost, shards
from vcor.study.scene import settings_of

SETTINGS = settings_of({"grid": {"v0": [1.0]}})


def test_the_estimate_grows_with_method_data_fits_samples_and_error_estimate():
    p = {"material": "sls", "v0": 1.0}
    base = cost.point_seconds(p, SETTINGS)
    assert base == cost.POINT_SECONDS["adaptive"]
    assert cost.point_seconds(p, SETTINGS, from_data={"sls"}) > base
    assert cost.point_seconds({**p, "sample": 3.0}, SETTINGS) == pytest.approx(base + cost.SAMPLE_SECONDS)
    assert cost.point_seconds(p, {**SETTINGS, "error_estimate": True}) == pytest.approx(3 * base)
    direct = {**SETTINGS, "solver": {**SETTINGS["solver"], "method": "direct"}}
    assert cost.point_seconds(p, direct) > base


@pytest.mark.parametrize("n, each, job, cap, jobs", [
    (10, 1.0, 100.0, None, 1),  # less than a job's work: one job
    (100, 1.0, 30.0, None, 4),  # ceil(100 / 30)
    (100, 1.0, 30.0, 10, 10),  # the cap cuts further
    (7, 1.0, None, 3, 3),  # no work target: the cap alone (the points-per-job plan)
])
def test_split_by_work_counts_and_order(n, each, job, cap, jobs):
    points = list(range(n))
    split = cost.split_by_work(points, lambda p: each, job, cap)
    assert len(split) == jobs
    assert [p for chunk in split for p in chunk] == points  # contiguous, in order, each point once
    if cap:
        assert max(map(len, split)) <= cap


def test_split_by_work_balances_uneven_costs():
    costs = [5.0] * 10 + [0.5] * 100  # 50 s of expensive points, then 50 s of cheap ones
    split = cost.split_by_work(list(range(110)), lambda i: costs[i], 40.0)
    work = [sum(costs[i] for i in chunk) for chunk in split]
    assert len(split) == math.ceil(100 / 40)
    assert max(work) - min(work) <= 5.0  # equal within one point's cost


@pytest.mark.parametrize("bad, words", [({"job_seconds": 0.0}, "job_seconds"), ({"max_points": 0}, "shard_size")])
def test_split_by_work_refuses_bad_sizes(bad, words):
    kw = {"job_seconds": 1.0, "max_points": None} | bad
    with pytest.raises(ValueError, match=words):
        cost.split_by_work([1, 2], lambda p: 1.0, kw["job_seconds"], kw["max_points"])


SCENE = {"materials": ["sls"], "grid": {"v0": {"start": 1, "stop": 400, "step": 1}}}
IDS = {"sls": "id-sls"}


def test_a_small_scene_is_one_job_and_a_large_one_spreads(tmp_path):
    assert len(shards.plan_shards(SCENE, tmp_path, None, IDS, job_seconds=15.0)) == 1
    # 400 points x 2.5e-4 s = 0.1 s: at 0.04 s per job, three jobs of about equal work
    plan = shards.plan_shards(SCENE, tmp_path, None, IDS, job_seconds=0.04)
    assert len(plan) == 3 and {len(s.points) for s in plan.values()} <= {133, 134}


def test_planning_is_deterministic(tmp_path):
    a = shards.plan_shards(SCENE, tmp_path, None, IDS, job_seconds=0.05)
    b = shards.plan_shards(SCENE, tmp_path, None, IDS, job_seconds=0.05)
    assert list(a) == list(b)


def test_the_default_config_plans_one_job_per_scene(root, tmp_path):
    """The numbers the docs quote (Scenes, "Jobs"): one job per scene, two for pyvisco (31 000 points of a
    material fitted to data, estimated at 2.5e-4 s x 2 each: 15.5 s, over the 15 s of a job)."""
    import yaml

    from vcor.study.config import load_project

    project = load_project(yaml.safe_load((root / "config.yaml").read_text()), root)
    jobs = {}
    for name, sc in project.scenes.items():
        if sc.grid is None:
            continue
        ids = {m: project.catalogue.identity(m) for m in sc.materials}
        jobs[name] = len(shards.plan_shards(sc.config, tmp_path, sc.shard_size, ids, grid=sc.grid,
                                            settings=sc.settings, job_seconds=sc.job_seconds,
                                            from_data=project.fitted_to_data))
    assert project.scenes["pyvisco"].grid.size == 31_000
    assert jobs.pop("pyvisco") == 2 and set(jobs.values()) == {1}


def test_all_points_at_once_equal_one_by_one():
    """Grid.points builds every point at once; each equals Grid.point(i), keys in the same order (the
    shard index files and the point names depend on it)."""
    from vcor.study.grid import Grid

    grid = Grid.from_scene({"materials": ["sls", "butyl-fc"], "grid": {"v0": [1, 2, 3], "T": [0, 20], "h": [0.01]}},
                           samples=4)
    assert [list(p.items()) for p in grid.points()] == [list(grid.point(i).items()) for i in range(grid.size)]


def test_point_cost_is_point_seconds_per_point():
    data = {"fitted"}
    settings = {**SETTINGS, "error_estimate": True}
    fn = cost.point_cost(settings, data)
    for p in ({"material": "sls", "v0": 1.0}, {"material": "fitted", "v0": 2.0},
              {"material": "fitted", "v0": 2.0, "sample": 3.0}, {"material": "sls", "v0": 5.0, "sample": 0.0}):
        assert fn(p) == cost.point_seconds(p, settings, data)


def test_a_shard_index_reads_back_as_written(tmp_path):
    import json

    points = [{"index": i, "material": "sls", "v0": 1.0 + i / 3, "beta": 1e3} for i in range(5)]
    settings = {"solver": {"method": "adaptive"}, "tie": {}}
    text = shards.index_text(points, settings)
    assert json.loads(text) == {"points": points, "settings": settings}
    assert len(text.splitlines()) >= len(points)  # one point per line
    assert json.loads(shards.index_text([], settings)) == {"points": [], "settings": settings}
