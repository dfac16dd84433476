"""The work-precision figure: every solver drawn in any panel is named in the legend, also one that does
not apply to the first panel's material. Synthetic cases (no solver run)."""

from __future__ import annotations

import numpy as np
import pytest

# vcor.plots imports matplotlib, so the imports below follow the skips
# ruff: noqa: E402
xr = pytest.importorskip("xarray")
pytest.importorskip("matplotlib")

from vcor import status
from vcor.plots import common
from vcor.plots.studies import work_precision
from vcor.study import convergence


def _case(solvers):
    """One (material, v0) case as convergence.study returns it: errors falling as steps^-2, all ok."""
    steps = np.array([250.0, 500.0, 1000.0])
    shape = (len(solvers), steps.size)
    err = np.broadcast_to(steps ** -2.0, shape).copy()
    return xr.Dataset(
        {"err_cor": (("solver", "level"), err), "wall_time": (("solver", "level"), err ** -0.5 * 1e-6),
         "param": (("solver", "level"), np.broadcast_to(steps, shape).copy()),
         "status": (("solver", "level"), np.zeros(shape, np.int8), status.cf_attrs()),
         "message": (("solver", "level"), np.full(shape, ""), {"long_name": "solver message"})},
        coords={"solver": list(solvers), "level": np.arange(steps.size)})


def test_the_legend_names_solvers_missing_from_the_first_panel():
    # a fractional law first (no internal-variable methods), then an SLS that has them
    cases = {("butyl-fc", 0): _case(["direct-a", "adaptive"]), ("sls", 0): _case(["direct-a", "ive-Radau", "adaptive"])}
    ds = convergence.combine(cases, ["butyl-fc", "sls"], [10.0])
    fig = work_precision(ds, {})
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert labels == [common.solver_label(s) for s in ("direct-a", "adaptive", "ive-Radau")]
