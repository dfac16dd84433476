"""Compile cost of every solver path: a fresh process with an empty numba cache runs every method
and path once (one-call and general adaptive, histories, a thin plate, every preset kind) and prints
its wall time and the kernels that numba compiled more than once.

Run: python benchmarks/bench_compile.py [runs]   (default 2; medians quoted, this machine is shared)
     python benchmarks/bench_compile.py --workload   (one in-process run: prints every kernel with
     more than one type signature, nothing if there is none; tests/test_adaptive.py uses it)
To compare with another commit: PYTHONPATH=<its src> python benchmarks/bench_compile.py
"""

from __future__ import annotations

import contextlib
import os
import statistics
import subprocess
import sys
import tempfile
import time

METHODS = ({"method": "direct"}, {}, {"richardson": False}, {"method": "soe"}, {"method": "ive-numba"},
           {"history": True}, {"method": "direct", "history": True}, {"method": "direct", "form": "b"},
           {"method": "paper"}, {"method": "direct", "volterra": True})
MATERIALS = ("butyl-prony3", "butyl-fc", "butyl-cerf", "kelvin-voigt", "sls", "elastic")


def workload():
    """Every method on every preset kind, and the thin-plate (general adaptive) path; then print the
    kernels with more than one type signature."""
    from vcor.solvers import simulate
    from vcor.solvers.backend import compiled_signatures

    for material in MATERIALS:
        for kw in METHODS:
            with contextlib.suppress(ValueError):  # a method that does not apply to this material
                simulate(material, 10.0, **kw)
    simulate("sls", 10.0, h=0.001)
    for name, signatures in compiled_signatures().items():
        if len(signatures) > 1:
            print(name, signatures)


def cold_run():
    """(wall time [s], names of the kernels compiled more than once) of a fresh process with an empty
    numba cache."""
    with tempfile.TemporaryDirectory() as d:
        env = dict(os.environ, NUMBA_CACHE_DIR=d)
        t = time.perf_counter()
        out = subprocess.run([sys.executable, __file__, "--workload"], env=env, capture_output=True,
                             text=True, check=True)
        wall = time.perf_counter() - t
    return wall, " ".join(line.split()[0] for line in out.stdout.splitlines())


if __name__ == "__main__":
    if sys.argv[1:] == ["--workload"]:
        workload()
        sys.exit(0)
    runs = int(sys.argv[1]) if len(sys.argv) > 1 else 2
    print("fresh process, empty numba cache: import vcor, every method and path once")
    walls = []
    for i in range(runs):
        wall, twice = cold_run()
        walls.append(wall)
        print(f"run {i + 1}: {wall:6.2f} s   kernels compiled more than once: {twice or 'none'}")
    print(f"median {statistics.median(walls):.2f} s over {runs} runs")
