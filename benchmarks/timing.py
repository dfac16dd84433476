"""Timing helper shared by the benchmark scripts."""

from __future__ import annotations

import statistics
import time


def median_time(fn, repeat=15):
    """Median wall time of ``fn()`` over ``repeat`` calls, after one untimed call (JIT, caches)."""
    fn()
    ts = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t)
    return statistics.median(ts)


def timed(fn, repeat=5, warmup=False):
    """(median wall time of ``repeat`` calls, the last call's result); ``warmup``: one untimed call first."""
    out = fn() if warmup else None
    ts = []
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        ts.append(time.perf_counter() - t)
    return statistics.median(ts), out
