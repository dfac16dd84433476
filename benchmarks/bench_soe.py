"""The fixed-step soe method against direct, per impact (the adaptive method, thin plates and cost
against plate thickness: bench_adaptive.py).

Prints tables of medians (this machine is shared: read ratios). Run: python benchmarks/bench_soe.py
"""

from __future__ import annotations

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


if __name__ == "__main__":
    main()
