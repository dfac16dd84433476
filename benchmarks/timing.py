"""Helpers shared by the benchmark scripts.

- Fresh processes: :func:`run_fresh` starts a command with ``NUMBA_CACHE_DIR`` set to a new, empty
  temporary folder (removed afterwards), so that compile time is counted where a user meets it;
  :func:`fresh_json` reads the JSON a worker prints on its last line; :func:`worker_runs` starts the
  calling script itself as such a worker, once per run.
- Warm calls: :func:`warm_median` times calls after one untimed call (compile, caches).
- Statistics: :func:`median`, :func:`cell` (median and, over two or more values, the spread min-max).
- Output: :func:`table` (Markdown), :func:`header` (one line: command, commit, date in UTC, machine,
  runs) and :func:`publish` (to stdout, or atomically to ``--out``: a temporary file, then a rename).
- :func:`parser` and :func:`main`: the common command line (``--out``, ``--runs``, ``--quick``, ``--calls``)
  and the usual flow (RUNS fresh workers, or RUNS per job, then one report from their results);
  :func:`calls` and :func:`quick_flags` read it back; :func:`short_rev` names a commit.

``python benchmarks/timing.py markdown --command CMD --runs N [--commit C] [--out PATH]`` turns
tab-separated lines on stdin (the first: column headers) into the same header and table, for the
shell benchmark.
"""

from __future__ import annotations

import argparse
import contextlib
import datetime as _dt
import json
import os
import shlex
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PYTHON = sys.executable
WORKER_FLAG = "--worker"


# --- fresh processes -------------------------------------------------------------------------------

@contextlib.contextmanager
def empty_numba_cache():
    """A new, empty folder for ``NUMBA_CACHE_DIR`` (removed on exit)."""
    d = tempfile.mkdtemp(prefix="vcor-numba-cache-")
    try:
        yield d
    finally:
        shutil.rmtree(d, ignore_errors=True)


@dataclass(frozen=True)
class Process:
    """A finished process: its wall time (s, measured around it), exit code and output."""

    wall: float
    returncode: int
    stdout: str
    stderr: str


def run_fresh(cmd, *, cache: str | None = None, env: dict | None = None, cwd=None, check: bool = True) -> Process:
    """Run ``cmd`` (a list; a string runs with bash) in a new process with ``NUMBA_CACHE_DIR`` = ``cache``,
    or a new empty folder when ``cache`` is None; ``env``: more environment variables."""
    with contextlib.ExitStack() as stack:
        folder = cache if cache is not None else stack.enter_context(empty_numba_cache())
        full_env = dict(os.environ, **(env or {}), NUMBA_CACHE_DIR=folder)
        argv = ["bash", "-c", cmd] if isinstance(cmd, str) else [str(c) for c in cmd]
        t = time.perf_counter()
        out = subprocess.run(argv, env=full_env, cwd=cwd, capture_output=True, text=True)
        wall = time.perf_counter() - t
    if check and out.returncode != 0:
        raise RuntimeError(f"{shlex.join(argv)} exited with {out.returncode}:\n{out.stderr[-4000:]}")
    return Process(wall, out.returncode, out.stdout, out.stderr)


def fresh_json(cmd, **kwargs):
    """The JSON value a fresh process (:func:`run_fresh`) prints on its last line of output."""
    return json.loads(run_fresh(cmd, **kwargs).stdout.strip().splitlines()[-1])


def worker_runs(runs: int, *worker_args, script=None, **kwargs) -> list:
    """Start ``script`` (default: the running one) ``runs`` times as ``python script --worker ARGS``,
    each in a fresh process with an empty numba cache; the JSON results of the runs, in order."""
    script = Path(script or sys.argv[0]).resolve()
    return [fresh_json([PYTHON, script, WORKER_FLAG, *worker_args], **kwargs) for _ in range(runs)]


def first_impact(options: str, cache: str) -> tuple[float, float]:
    """(wall time of a fresh Python process that imports vcor and runs ``vcor.simulate('sls', 10.0,
    <options>)``, the import + run time measured inside it), s, with ``NUMBA_CACHE_DIR`` = ``cache``."""
    code = ("import time; t = time.perf_counter(); import vcor; "
            f"vcor.simulate('sls', 10.0, {options}); print(time.perf_counter() - t)")
    p = run_fresh([PYTHON, "-c", code], cache=cache)
    return p.wall, float(p.stdout.strip())


def cold_and_cached(options: str) -> dict:
    """First impact (:func:`first_impact`) of a fresh process with an empty numba cache, then of a second
    fresh process with the cache the first one filled: {"empty": (wall, inside), "filled": (...)}."""
    with empty_numba_cache() as d:
        return {"empty": first_impact(options, d), "filled": first_impact(options, d)}


# --- warm calls ------------------------------------------------------------------------------------

def call_times(fn, calls: int) -> tuple[list, object]:
    """(wall times of ``calls`` calls of ``fn()`` after one untimed call, the last call's result)."""
    out = fn()
    ts = []
    for _ in range(calls):
        t = time.perf_counter()
        out = fn()
        ts.append(time.perf_counter() - t)
    return ts, out


def warm_median(fn, calls: int) -> float:
    """Median wall time (s) of ``calls`` calls of ``fn()`` after one untimed call (compile, caches)."""
    return statistics.median(call_times(fn, calls)[0])


def warm_timed(fn, calls: int) -> tuple[float, object]:
    """(:func:`warm_median`, the last call's result)."""
    ts, out = call_times(fn, calls)
    return statistics.median(ts), out


# --- statistics ------------------------------------------------------------------------------------

def median(values) -> float:
    return statistics.median(list(values))


def cell(values, scale: float = 1.0, fmt: str = ".2f") -> str:
    """``median (min–max)`` of ``values`` times ``scale`` (only the value where there is one)."""
    v = [float(x) * scale for x in values]
    if not v:
        return "-"
    if len(v) == 1:
        return format(v[0], fmt)
    return f"{format(statistics.median(v), fmt)} ({format(min(v), fmt)}–{format(max(v), fmt)})"


def column(results, *keys) -> list:
    """``[r[k1][k2]... for r in results]``: one measured quantity over the runs."""
    out = []
    for r in results:
        for k in keys:
            r = r[k]
        out.append(r)
    return out


# --- output ----------------------------------------------------------------------------------------

def table(headers, rows) -> str:
    """A Markdown table (cells as given, converted with str)."""
    lines = ["| " + " | ".join(map(str, headers)) + " |", "|" + "---|" * len(headers)]
    lines += ["| " + " | ".join(map(str, r)) + " |" for r in rows]
    return "\n".join(lines)


def _git(*args) -> str:
    return subprocess.run(["git", "-C", str(ROOT), *args], capture_output=True, text=True, check=True).stdout.strip()


def short_rev(rev: str = "HEAD") -> str:
    """``git rev-parse --short REV`` in this repository."""
    return _git("rev-parse", "--short", rev)


def commit() -> str:
    """``git rev-parse --short HEAD``, with ``+changes`` when the working tree differs from it (the
    benchmark tables under docs/_generated, which the benchmarks write, do not count)."""
    return short_rev() + ("+changes" if _git("status", "--porcelain", "--", ".", ":!docs/_generated") else "")


def machine() -> str:
    """``<n> cores, <CPU model>`` (cores this process may use; the model from /proc/cpuinfo)."""
    model = "unknown CPU"
    with contextlib.suppress(OSError):
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    return f"{len(os.sched_getaffinity(0))} cores, {model}"


def invocation() -> str:
    """The command that runs this script, with its path relative to the repository."""
    script = Path(sys.argv[0]).resolve()
    with contextlib.suppress(ValueError):
        script = script.relative_to(ROOT)
    return "python " + shlex.join([str(script), *sys.argv[1:]])


def header(runs: int, *, command: str | None = None, rev: str | None = None) -> str:
    """The line above every table: command, commit, date (UTC), machine, number of runs."""
    date = _dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d %H:%M UTC")
    return (f"`{command or invocation()}` · commit {rev or commit()} · {date} · {machine()} · "
            f"{runs} run{'s' if runs != 1 else ''}")


def write_atomic(path, text: str) -> None:
    """Write ``text`` to ``path`` through a temporary file in the same folder and a rename."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w") as f:
            f.write(text)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes it 0600: the table is for everyone to read
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def publish(out, runs: int, blocks, **header_kw) -> None:
    """The header and ``blocks`` (Markdown paragraphs and tables), to stdout or atomically to ``out``."""
    text = "\n\n".join([header(runs, **header_kw), *blocks]) + "\n"
    if out:
        write_atomic(out, text)
        print(f"wrote {out}")
    else:
        print(text, end="")


# --- the command line ------------------------------------------------------------------------------

def at_least_two(text: str) -> int:
    n = int(text)
    if n < 2:
        raise argparse.ArgumentTypeError("at least two runs")
    return n


def parser(doc: str, *, runs: int = 2, quick: str | None = None, calls: int | None = None) -> argparse.ArgumentParser:
    """``--out PATH``, ``--runs N`` (>= 2), where ``quick`` says what it does ``--quick``, and where
    ``calls`` is given ``--calls N`` (warm calls per median, default ``calls``)."""
    p = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", type=Path, help="write the table (Markdown) to this file instead of stdout")
    p.add_argument("--runs", type=at_least_two, default=runs,
                   help=f"fresh processes (empty numba cache each) per measurement (default {runs})")
    if quick:
        p.add_argument("--quick", action="store_true", help=quick)
    if calls:
        p.add_argument("--calls", type=int, default=calls, help=f"warm calls per median (default {calls})")
    p.add_argument(WORKER_FLAG, action="store_true", help=argparse.SUPPRESS)
    return p


def calls(args, quick: int = 1) -> int:
    """Warm calls per median: ``quick`` with ``--quick``, else ``--calls``."""
    return quick if getattr(args, "quick", False) else args.calls


def quick_flags(args) -> list:
    """``["--quick"]`` when the command line has it (to pass on to workers), else ``[]``."""
    return ["--quick"] if getattr(args, "quick", False) else []


def main(doc: str, measure, report, *, quick: str | None = None, calls: int | None = None, configure=None,
         jobs=None) -> None:
    """The usual flow: parse the command line (:func:`parser`, then ``configure(parser)``); as a worker,
    print ``measure(args)`` as JSON; otherwise start RUNS workers (:func:`worker_runs`, with this
    command line) and publish ``report(args, results)`` (a list of Markdown blocks).

    ``jobs(args)``, where given, splits the work: it yields (key, worker arguments) and every key gets
    its own RUNS workers; ``results`` is then {key: the JSON results of its runs}."""
    p = parser(doc, quick=quick, calls=calls)
    if configure:
        configure(p)
    args = p.parse_args()
    if args.worker:
        print(json.dumps(measure(args)))
        return
    if jobs:
        results = {key: worker_runs(args.runs, *wargs) for key, wargs in jobs(args)}
    else:
        results = worker_runs(args.runs, *sys.argv[1:])
    publish(args.out, args.runs, report(args, results))


def one_process_main(doc: str, measure, report, *, quick: str) -> None:
    """Tables that do not depend on the machine (errors, not timings): one process computes them. ``--out PATH``
    and ``--quick`` (``quick`` says what it does); publishes ``report(measure(quick))``."""
    p = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", type=Path, help="write the tables (Markdown) to this file instead of stdout")
    p.add_argument("--quick", action="store_true", help=quick)
    args = p.parse_args()
    publish(args.out, 1, report(measure(args.quick)))


def _markdown_main(argv=None) -> None:
    p = argparse.ArgumentParser(description="tab-separated rows on stdin (first line: headers) -> header "
                                "and Markdown table")
    p.add_argument("markdown")
    p.add_argument("--command", required=True)
    p.add_argument("--runs", type=int, required=True)
    p.add_argument("--commit", default=None, help="default: this checkout's (git rev-parse --short HEAD)")
    p.add_argument("--note", action="append", default=[], help="a paragraph below the table (repeatable)")
    p.add_argument("--out", type=Path)
    args = p.parse_args(argv)
    lines = [line.split("\t") for line in sys.stdin.read().splitlines() if line.strip()]
    publish(args.out, args.runs, [table(lines[0], lines[1:]), *args.note], command=args.command, rev=args.commit)


if __name__ == "__main__":
    _markdown_main()
