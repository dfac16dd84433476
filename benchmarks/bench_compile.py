"""Compile cost of every solver path: a fresh process with an empty numba cache runs every method and
path once (one-call and general adaptive path, histories, a thin plate, every preset kind); the
table gives its wall time per run and the median, and the kernels that numba compiled more than once
(none is expected; tests/solvers/test_adaptive.py::test_each_kernel_is_compiled_once checks the same workload).

Run: python benchmarks/bench_compile.py [--runs 2] [--quick] [--out FILE]
     python benchmarks/bench_compile.py --workload [--quick]   (one in-process run: prints every kernel
     with more than one type signature, nothing if there is none)
To measure another commit: PYTHONPATH=<its src> python benchmarks/bench_compile.py
"""

from __future__ import annotations

import contextlib
import os
import sys

import timing

METHODS = ({"method": "direct"}, {}, {"richardson": False}, {"method": "soe"}, {"method": "ive-numba"},
           {"history": True}, {"method": "direct", "history": True}, {"method": "direct", "form": "b"},
           {"method": "paper"}, {"method": "direct", "volterra": True})
MATERIALS = ("butyl-prony3", "butyl-fc", "butyl-cerf", "kelvin-voigt", "sls", "elastic")
#: --quick: the default method and direct on sls (and the thin plate)
QUICK_METHODS, QUICK_MATERIALS = ({}, {"method": "direct"}), ("sls",)


def workload(quick: bool = False):
    """Every method on every preset kind, and the thin-plate (general adaptive) path; then print the
    kernels with more than one type signature."""
    import vcor
    from vcor.solvers.backend import compiled_signatures

    for material in QUICK_MATERIALS if quick else MATERIALS:
        for kw in QUICK_METHODS if quick else METHODS:
            with contextlib.suppress(ValueError):  # a method that does not apply to this material
                vcor.simulate(material, 10.0, **kw)
    vcor.simulate("sls", 10.0, h=0.001)
    for name, signatures in compiled_signatures().items():
        if len(signatures) > 1:
            print(name, len(signatures))


def main():
    p = timing.parser(__doc__, quick="the default method and direct on sls, and the thin plate")
    p.add_argument("--workload", action="store_true", help="one in-process run of the workload")
    args = p.parse_args()
    if args.workload:
        workload(args.quick)
        return
    runs = args.runs
    rows, walls = [], []
    for i in range(runs):
        proc = timing.run_fresh([timing.PYTHON, __file__, "--workload", *timing.quick_flags(args)])
        twice = ", ".join(f"{line.split()[0]} ({line.split()[1]})" for line in proc.stdout.splitlines()) or "none"
        walls.append(proc.wall)
        rows.append([i + 1, f"{proc.wall:.2f}", twice])
    rows.append(["median (min–max)", timing.cell(walls), ""])
    other = os.environ.get("PYTHONPATH")
    timing.publish(args.out, runs, [
        "A fresh process with an empty numba cache per run (import vcor, "
        + ("--quick: the default method and direct on sls, and the thin plate" if args.quick
           else "every method and path once") + "); "
        "kernels compiled more than once with their number of signatures."
        + (f" Package measured: PYTHONPATH={other} (not necessarily the commit above)." if other else ""),
        timing.table(["run", "wall time [s]", "kernels compiled more than once"], rows)])


if __name__ == "__main__":
    sys.exit(main())
