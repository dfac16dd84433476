"""The stability scenes of config.yaml solved with each method: statuses, largest Richardson
estimate over the ok points, wall time, and the flagged points of the last method.

Run: python benchmarks/bench_stability_methods.py [method ...]   (default: direct soe)
"""

from __future__ import annotations

import collections
import sys
import time
from pathlib import Path

import numpy as np
import yaml

from vcor import runner, scene, status

CONFIG = Path(__file__).resolve().parents[1] / "config.yaml"


def main(methods):
    cfg = yaml.safe_load(CONFIG.read_text())
    print(f"{'scene':22s} {'method':8s} {'statuses':40s} {'max cor_err':>12s} {'wall [s]':>9s}")
    for name, sc in cfg["scenes"].items():
        if not name.startswith("stability-"):
            continue
        for method in methods:
            s2 = {**sc, "solver": {**sc.get("solver", {}), "method": method}}
            t = time.perf_counter()
            ds = runner.run_points(scene.scene_points(s2), scene.settings_of(s2))
            wall = time.perf_counter() - t
            names = [status.STATUS_NAMES[int(c)] for c in ds["status"].values]
            ok = ds["status"].values == status.code("ok")
            print(f"{name:22s} {method:8s} {dict(collections.Counter(names))!s:40s} "
                  f"{np.nanmax(ds['cor_err'].values[ok]):12.2e} {wall:9.1f}")
            if method == methods[-1]:
                axes = [a for a in ds.coords if a not in ("point", "material", "material_id")]
                for i in np.where(~ok)[0]:
                    where = ", ".join(f"{a} = {float(ds[a].values[i]):g}" for a in axes)
                    print(f"    {names[i]}: {ds['material'].values[i]}, {where}")


if __name__ == "__main__":
    main(sys.argv[1:] or ["direct", "soe"])
