"""The test suite as a user runs it: the README's test command, in a fresh clone of the commit, with
an empty numba cache, RUNS times.

The command is the one of the README's ``<!-- test-command: ... -->`` marker (the line .ci/run runs),
which must also be the line the README shows under it; ``--durations=15 -rfE`` is appended to its pytest
call, and a failed or erroring test is named in its run's row. Each run clones the commit afresh (``git
clone`` into a new temporary folder) and runs the command there in a new virtual environment that sees
the machine's installed packages, so that the command's editable install of vcor goes into that
environment and not over the machine's own; the wall time is that of the whole command (install and
tests), measured around it. The table gives each run's exit code, wall time, pytest's own time and
summary line, the median, and pytest's 15 slowest tests of the median run.

Run: python benchmarks/bench_suite.py [--runs 2] [--rev REV] [--pytest-args ARGS] [--quick] [--out FILE]
"""

from __future__ import annotations

import os
import re
import subprocess
import tempfile
from pathlib import Path

import timing

#: as .ci/run reads it: sed -n 's/^<!-- test-command: \(.*\) -->$/\1/p' README.md
MARKER = re.compile(r"^<!-- test-command: (.*) -->$", re.M)
QUICK_TESTS = "tests/test_architecture.py"
SLOWEST = 15
#: pytest's short summary lines (-rfE): FAILED / ERROR and the test's id
FAILED = re.compile(r"^(FAILED|ERROR) (\S+)", re.MULTILINE)
SUMMARY = re.compile(r"^=*\s*(\d+ (?:passed|failed|error|errors|skipped|deselected|xfailed|xpassed)\b.*?) in "
                     r"([\d.]+)s\b", re.M)
DURATION = re.compile(r"^([\d.]+)s (setup|call|teardown)\s+(\S.*)$", re.M)


def test_command(readme: Path) -> str:
    """The README's test command: its marker's, checked against the line shown under it."""
    text = readme.read_text(encoding="utf-8")
    m = MARKER.search(text)
    if not m:
        raise SystemExit(f"{readme}: no test-command marker (a line <!-- test-command: ... -->)")
    cmd = m.group(1).strip()
    below = text[m.end():].lstrip("\n").splitlines()[:2]
    if len(below) < 2 or not below[0].startswith("```") or below[1].strip() != cmd:
        raise SystemExit(f"{readme}: the block under the test-command marker does not show {cmd!r}")
    if "pytest" not in cmd.rsplit("&&", 1)[-1]:
        raise SystemExit(f"{readme}: the test command {cmd!r} does not end with its pytest call")
    return cmd


def one_run(rev: str, extra: str) -> dict:
    """Clone ``rev``, run the README's test command with ``extra`` appended in a new virtual environment
    and an empty numba cache: exit code, wall time (s), pytest's time and summary, its slowest tests."""
    with tempfile.TemporaryDirectory(prefix="vcor-suite-") as tmp:
        clone, venv = Path(tmp) / "vcor", Path(tmp) / "venv"
        subprocess.run(["git", "clone", "-q", str(timing.ROOT), str(clone)], check=True)
        subprocess.run(["git", "-C", str(clone), "checkout", "-q", rev], check=True)
        cmd = f"{test_command(clone / 'README.md')} {extra}"
        subprocess.run([timing.PYTHON, "-m", "venv", "--system-site-packages", str(venv)], check=True)
        env = {"PATH": f"{venv / 'bin'}{os.pathsep}{os.environ['PATH']}", "VIRTUAL_ENV": str(venv)}
        proc = timing.run_fresh(cmd, env=env, cwd=clone, check=False)
        where = subprocess.run([str(venv / "bin" / "python"), "-c", "import vcor; print(vcor.__file__)"], cwd=tmp,
                               capture_output=True, text=True, env=dict(os.environ, **env)).stdout.strip()
    if proc.returncode == 0 and not where.startswith(str(clone)):
        raise RuntimeError(f"the clone's environment imports vcor from {where or 'nowhere'}, not from {clone}")
    out = proc.stdout + proc.stderr
    summary = SUMMARY.findall(out)
    slowest = [[f"{float(t):.2f}", phase, test.strip()] for t, phase, test in DURATION.findall(out)][:SLOWEST]
    return {"command": cmd, "exit": proc.returncode, "wall": proc.wall,
            "pytest": float(summary[-1][1]) if summary else None,
            "summary": summary[-1][0] if summary else "no pytest summary: " + " ".join(out.split()[-40:]),
            "failed": FAILED.findall(out), "slowest": slowest}


def main():
    p = timing.parser(__doc__, quick=f"only {QUICK_TESTS}")
    p.add_argument("--rev", default="HEAD", help="the commit to clone (default HEAD: committed changes only)")
    p.add_argument("--pytest-args", default="", help="more arguments for pytest, e.g. \"-m slurm\"")
    args = p.parse_args()
    rev = timing.short_rev(args.rev)
    extra = " ".join(filter(None, [QUICK_TESTS if args.quick else "", args.pytest_args, f"--durations={SLOWEST}",
                                   "-rfE"]))
    runs = [one_run(rev, extra) for _ in range(args.runs)]
    c = timing.cell
    rows = [[i + 1, r["exit"], f"{r['wall']:.1f}", "-" if r["pytest"] is None else f"{r['pytest']:.1f}",
             r["summary"] + "".join(f"; {kind} {test}" for kind, test in r["failed"])]
            for i, r in enumerate(runs)]
    pytest_times = [r["pytest"] for r in runs if r["pytest"] is not None]
    rows.append(["median (min–max)", "", c(timing.column(runs, "wall"), 1.0, ".1f"), c(pytest_times, 1.0, ".1f"), ""])
    order = sorted(range(len(runs)), key=lambda i: runs[i]["wall"])
    mid = order[(len(runs) - 1) // 2]
    blocks = [f"The README's test command in a fresh clone of {rev} per run (new virtual environment seeing the "
              "machine's packages, empty numba cache), with pytest's slowest tests: "
              f"`{runs[0]['command']}`. Wall time: the whole command (install and tests); pytest: its own "
              "summary's time.",
              timing.table(["run", "exit", "wall [s]", "pytest [s]", "pytest summary"], rows),
              f"The {SLOWEST} slowest tests of run {mid + 1} (the median run):"]
    blocks.append(timing.table(["time [s]", "phase", "test"], runs[mid]["slowest"]) if runs[mid]["slowest"]
                  else "(pytest printed no durations)")
    timing.publish(args.out, args.runs, blocks, rev=rev)


if __name__ == "__main__":
    main()
