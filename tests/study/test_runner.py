"""Running points (vcor.study.runner): the solving order groups a material's points, and neither the
results nor the dataset's order depend on the order of the grid's axes."""

import functools

import numpy as np

from vcor.solvers import adaptive, adaptive_tables
from vcor.study import runner, scene

BETAS = {"start": 100, "stop": 1.0e5, "num": 70, "log": True}
SPEEDS = [1.0, 1.01, 1.02]
#: the impact tables' cache in these tests: fewer entries than the sweep has materials (70), so that a
#: speed-outer order without the grouping would evict every material's tables before its next speed
SMALL_CACHE = 64


def _scene(grid):
    return {"materials": ["sls"], "grid": grid, "tie": {"alpha": {"to": "beta", "ratio": 0.25}}}


def _solved(grid, monkeypatch):
    sc = _scene(grid)
    small = functools.lru_cache(maxsize=SMALL_CACHE)(adaptive.impact_tables.__wrapped__)
    monkeypatch.setattr(adaptive, "impact_tables", small)
    adaptive_tables.level_tables.cache_clear()
    ds = runner.run_points(scene.scene_points(sc), scene.settings_of(sc))
    return ds, small.cache_info().misses


def test_solving_order_groups_points_that_differ_only_in_speed():
    points = [{"index": i, "material": m, "v0": v, "beta": b}
              for i, (v, m, b) in enumerate((v, m, b) for v in (1.0, 2.0) for m in ("a", "b") for b in (10.0, 20.0))]
    order = runner.solving_order(points)
    assert sorted(order) == list(range(len(points)))
    groups = [(points[i]["material"], points[i]["beta"]) for i in order]
    assert groups == [("a", 10.0)] * 2 + [("a", 20.0)] * 2 + [("b", 10.0)] * 2 + [("b", 20.0)] * 2
    assert [points[i]["v0"] for i in order] == [1.0, 2.0] * 4  # the grid's order within a group


def test_results_and_table_builds_do_not_depend_on_the_axis_order(monkeypatch):
    speed_outer, builds_a = _solved({"v0": SPEEDS, "beta": BETAS}, monkeypatch)
    beta_outer, builds_b = _solved({"beta": BETAS, "v0": SPEEDS}, monkeypatch)
    # each material's tables built once in either order (without the grouping, the speed-outer grid would
    # build them for every point: more materials than SMALL_CACHE)
    assert builds_a == builds_b == 70 < speed_outer.sizes["point"]
    a = speed_outer.set_index(point=["v0", "beta"]).sortby(["v0", "beta"])
    b = beta_outer.set_index(point=["v0", "beta"]).sortby(["v0", "beta"])
    for v in a.data_vars:
        if v != "wall_time":
            np.testing.assert_array_equal(a[v].values, b[v].values, err_msg=v)
    # the dataset keeps the order of the points it was given
    assert list(speed_outer["v0"].values[:3]) == [SPEEDS[0]] * 3
