"""Running points (vcor.study.runner): the solving order groups a material's points, and neither the
results nor the dataset's order depend on the order of the grid's axes."""

import numpy as np

from vcor.solvers import adaptive
from vcor.study import runner, scene

BETAS = {"start": 100, "stop": 1.0e5, "num": 70, "log": True}  # more materials than level_tables keeps
SPEEDS = [1.0, 1.01, 1.02]


def _scene(grid):
    return {"materials": ["sls"], "grid": grid, "tie": {"alpha": {"to": "beta", "ratio": 0.25}}}


def _solved(grid):
    sc = _scene(grid)
    adaptive.level_tables.cache_clear()
    adaptive.impact_tables.cache_clear()
    ds = runner.run_points(scene.scene_points(sc), scene.settings_of(sc))
    return ds, adaptive.impact_tables.cache_info().misses


def test_solving_order_groups_points_that_differ_only_in_speed():
    points = [{"index": i, "material": m, "v0": v, "beta": b}
              for i, (v, m, b) in enumerate((v, m, b) for v in (1.0, 2.0) for m in ("a", "b") for b in (10.0, 20.0))]
    order = runner.solving_order(points)
    assert sorted(order) == list(range(len(points)))
    groups = [(points[i]["material"], points[i]["beta"]) for i in order]
    assert groups == [("a", 10.0)] * 2 + [("a", 20.0)] * 2 + [("b", 10.0)] * 2 + [("b", 20.0)] * 2
    assert [points[i]["v0"] for i in order] == [1.0, 2.0] * 4  # the grid's order within a group


def test_results_and_table_builds_do_not_depend_on_the_axis_order():
    speed_outer, builds_a = _solved({"v0": SPEEDS, "beta": BETAS})
    beta_outer, builds_b = _solved({"beta": BETAS, "v0": SPEEDS})
    # each material's tables built as often in either order (without grouping, the speed-outer grid
    # rebuilt them for every point: more materials than the cache holds)
    assert builds_a == builds_b < speed_outer.sizes["point"]
    a = speed_outer.set_index(point=["v0", "beta"]).sortby(["v0", "beta"])
    b = beta_outer.set_index(point=["v0", "beta"]).sortby(["v0", "beta"])
    for v in a.data_vars:
        if v != "wall_time":
            np.testing.assert_array_equal(a[v].values, b[v].values, err_msg=v)
    # the dataset keeps the order of the points it was given
    assert list(speed_outer["v0"].values[:3]) == [SPEEDS[0]] * 3
