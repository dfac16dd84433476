"""The soe method against direct: per impact, thin plates, cost against plate thickness.

Prints tables of medians (this machine is shared: read ratios). Run: python benchmarks/bench_soe.py
"""

from __future__ import annotations

import time

import numpy as np
from timing import median_time

import vcor


def main():
    print("per impact at default settings (2000 steps per contact-time estimate), v0 = 10 m/s, whole simulate call")
    print(f"{'material':14s} {'direct [ms]':>12s} {'soe [ms]':>10s} {'soe/direct':>11s} {'ive-numba [ms]':>15s} "
          f"{'|COR soe - direct|':>19s}")
    for name in ("sls", "butyl-fc", "butyl-cerf", "butyl-prony3"):
        td = median_time(lambda n=name: vcor.simulate(n, 10.0), 15)
        ts = median_time(lambda n=name: vcor.simulate(n, 10.0, method="soe"), 15)
        prony = name in ("sls", "butyl-prony3")
        ti = median_time(lambda n=name: vcor.simulate(n, 10.0, method="ive-numba"), 15) if prony else float("nan")
        gap = abs(vcor.simulate(name, 10.0, method="soe").cor - vcor.simulate(name, 10.0).cor)
        print(f"{name:14s} {td * 1e3:12.3f} {ts * 1e3:10.3f} {ts / td:11.2f} {ti * 1e3:15.3f} {gap:19.1e}")
    print()
    print("cost against plate half-thickness h (sls, v0 = 10 m/s, soe; direct for comparison)")
    print(f"{'h [mm]':>8s} {'soe status':>11s} {'t0 [s]':>10s} {'COR':>10s} {'steps':>9s} {'soe [s]':>9s} "
          f"{'direct status':>14s} {'direct [s]':>11s}")
    standard = median_time(lambda: vcor.simulate("sls", 10.0, method="soe"), 5)
    for h in np.geomspace(1e-3, 1.0, 7):
        rs = vcor.simulate("sls", 10.0, h=h, method="soe")
        ts = median_time(lambda hh=h: vcor.simulate("sls", 10.0, h=hh, method="soe"), 3)
        t = time.perf_counter()
        rd = vcor.simulate("sls", 10.0, h=h)
        td = time.perf_counter() - t
        print(f"{h * 1e3:8.2f} {rs.status:>11s} {rs.t0:10.4g} {rs.cor:10.3e} {rs.steps:9d} {ts:9.4f} {rd.status:>14s} "
              f"{td:11.4f}")
    thin = median_time(lambda: vcor.simulate("sls", 10.0, h=1e-3, method="soe"), 3)
    print(f"\nthin plate h = 1 mm / standard impact (h = 20 mm), soe: {thin / standard:.0f}x "
          f"({thin:.3f} s / {standard * 1e3:.3f} ms)")


if __name__ == "__main__":
    main()
