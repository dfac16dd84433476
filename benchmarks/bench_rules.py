"""Where a workflow run's time goes, by rule: jobs, summed job time, the start-up share, and the work
itself (the floor: the same work done in one process would cost about that).

Every job's log ends with ``job <rule>: start-up S s, work W s`` (:mod:`vcor.io.joblog`): start-up is
the time from the job's process start to its work (Python, imports), work the rest (loading or
compiling numba kernels, solving, writing). This script reads those lines from the logs of one or more
finished projects (e.g. the runs of ``benchmarks/bench_reproduction.sh``, which calls it) and prints
the medians over the projects per rule; the rules made one per scene or per DEM entry count as one row
each (``figures_*``, ``dem_entry_*``, ``fit_family_*``).

Run: python benchmarks/bench_rules.py PROJECT [PROJECT ...] [--out FILE] [--command TEXT]
"""

from __future__ import annotations

import argparse
import re
import statistics
from collections import defaultdict
from pathlib import Path

import timing

#: prefixes of the rules the workflow makes one per scene (figures), DEM entry or fit family: one row each
GROUPED = ("figures_", "dem_entry_", "fit_family_")
LINE = re.compile(r"^job (\S+): start-up ([\d.]+) s, work ([\d.]+) s$", re.M)


def by_rule(project: Path) -> dict[str, list[tuple[float, float]]]:
    """{rule: [(start-up, work) per job]} of one finished project (from its job logs)."""
    out = defaultdict(list)
    for log in sorted((project / "results").rglob("*.log")):
        for rule, startup, work in LINE.findall(log.read_text(errors="replace")):
            rule = next((f"{p}*" for p in GROUPED if rule.startswith(p)), rule)
            out[rule].append((float(startup), float(work)))
    return out


def rows(projects: list[Path]) -> list[list]:
    """One row per rule (most summed time first) and a total row: medians over the projects."""
    runs = [by_rule(p) for p in projects]
    rules = sorted({r for run in runs for r in run})

    def med(rule, part):
        return statistics.median(sum(j[part] for j in run.get(rule, [])) for run in runs)

    table = []
    for rule in rules:
        jobs = statistics.median(len(run.get(rule, [])) for run in runs)
        start, work = med(rule, 0), med(rule, 1)
        table.append([rule, f"{jobs:g}", start + work, start, work])
    table.sort(key=lambda r: -r[2])
    total = [sum(r[i] for r in table) for i in (2, 3, 4)]
    jobs = sum(float(r[1]) for r in table)
    table.append(["all rules", f"{jobs:g}", *total])
    return [[r[0], r[1], f"{r[2]:.1f}", f"{r[3]:.1f}", f"{100 * r[3] / r[2]:.0f} %" if r[2] else "-", f"{r[4]:.1f}"]
            for r in table]


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("projects", nargs="+", type=Path, help="finished project folders (with results/)")
    p.add_argument("--out", help="write the table there (atomically) instead of printing it")
    p.add_argument("--command", default=None, help="the command line to name in the header")
    p.add_argument("--commit", default=None, help="the commit to name in the header (default: this checkout's)")
    args = p.parse_args()
    headers = ["rule", "jobs", "job time [s]", "start-up [s]", "start-up share", "work [s]"]
    body = timing.table(headers, rows(args.projects))
    note = ("Summed over each rule's jobs, median over the runs; start-up: process start to the job's work "
            "(Python, imports); work: the rest (kernels, solving, writing), about what the same work costs "
            "in one process.")
    timing.publish(args.out, len(args.projects), [body, note], command=args.command, rev=args.commit)


if __name__ == "__main__":
    main()
