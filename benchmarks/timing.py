"""Timing helper shared by the benchmark scripts."""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
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


def cold_process(env_extra, options):
    """(wall time of a fresh Python process that imports vcor and runs ``vcor.simulate('sls', 10.0,
    <options>)``, the import + run time measured inside it), with ``env_extra`` in its environment."""
    code = ("import time; t=time.perf_counter(); import vcor; "
            f"vcor.simulate('sls', 10.0, {options}); print(time.perf_counter()-t)")
    env = dict(os.environ, **env_extra)
    t = time.perf_counter()
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    return time.perf_counter() - t, float(out.stdout.strip())
