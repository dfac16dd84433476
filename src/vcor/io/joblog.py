"""The log of a workflow job: stderr goes to the job's log file; an error also reaches the terminal.

``with job_log(snakemake) as log:`` gives a :class:`JobLog`; ``log.note(text)`` writes one line saying
what the job computed, with the time since the block began (``solved 120 points of scene sls: 118 ok,
2 flagged (large_indentation 2), 0 failed, in 1.3 s``), so that each job's log says what it did.

The last line of a finished job's log says where its time went, for the benchmark of the reproduction
by rule (``benchmarks/bench_rules.py``): ``job <rule>: start-up 1.21 s, work 3.40 s``, start-up being
the time from the process's start (Linux: ``/proc/self/stat``) to the block (Python, imports) and work
the block itself (loading kernels, solving, writing).

A job's error must never be lost: on a full disk the log cannot be written (and Python's exit would
fail to flush it, exit code 120, an empty log). :func:`job_log` writes the error to the log where it
can and always to the terminal's stderr, then exits with code 1.

The block is the job: in a workflow job (``snakemake`` is Snakemake's script object) the process ends
as soon as the block has succeeded, with exit code 0, after every stream is flushed and without
Python's teardown of numba, xarray and matplotlib, a fixed cost of every job that does nothing for it
(CHANGELOG: what it saved). Every workflow script ends with its ``with job_log(...)`` block
(tests/io/test_joblog.py); nothing after it would run. Outputs are closed by the functions that
write them (:mod:`vcor.io.netcdf`, :mod:`vcor.io.receipts`, :func:`vcor.plots.save`); a file a block
opens itself must be closed in the block (``with open(...)``): an unclosed file loses what is still
buffered.
"""

from __future__ import annotations

import contextlib
import logging
import numbers
import os
import sys
import time
import traceback

__all__ = ["JobLog", "brief", "count", "end_process", "is_workflow_job", "job_log", "process_age", "seconds"]


def seconds(t: float) -> str:
    """A duration for a log line: ``0.042 s``, ``1.3 s``, ``75 s`` (two significant digits below 10 s)."""
    return f"{t:.2g} s" if t < 10 else f"{t:.0f} s"


def brief(value, digits: int = 4) -> str:
    """A job's settings for a log line: numbers to ``digits`` significant digits (numpy scalars as plain
    numbers), mappings and sequences item by item, everything else as ``str``.

    Examples
    --------
    >>> from vcor.io.joblog import brief
    >>> brief({"lam": 48.69675251658631, "n": 3, "mu": {"E_stor": 3.1622776601683795}, "notes": []})
    '{lam: 48.7, n: 3, mu: {E_stor: 3.162}, notes: []}'
    """
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k}: {brief(v, digits)}" for k, v in value.items()) + "}"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(brief(v, digits) for v in value) + "]"
    if isinstance(value, bool) or value is None:
        return str(value)
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        return f"{float(value):.{digits}g}"
    return str(value)


def count(n: int, noun: str, plural: str | None = None) -> str:
    """``1 figure``, ``3 figures``; ``plural`` for a noun that does not take an s (``histories``)."""
    return f"{n} {noun if n == 1 else plural or noun + 's'}"


def process_age() -> float | None:
    """Seconds since this process started (Linux ``/proc``; None where that cannot be read)."""
    try:
        with open("/proc/self/stat") as fh:
            fields = fh.read().rsplit(")", 1)[1].split()
        with open("/proc/uptime") as fh:
            uptime = float(fh.read().split()[0])
        return uptime - int(fields[19]) / os.sysconf("SC_CLK_TCK")  # field 22: start time in clock ticks
    except (OSError, ValueError, IndexError):
        return None


class JobLog:
    """What a job writes to its log (module docstring); ``started`` is its :func:`time.perf_counter`."""

    def __init__(self) -> None:
        self.started = time.perf_counter()

    @property
    def elapsed(self) -> float:
        """Seconds since the job's block began."""
        return time.perf_counter() - self.started

    def note(self, text: str, *, timed: bool = True) -> None:
        """Write ``text`` (with ``, in <elapsed> s`` when ``timed``) as one line to the job's log."""
        _write(sys.stderr, f"{text}, in {seconds(self.elapsed)}\n" if timed else f"{text}\n")


def _write(stream, text) -> None:
    if stream is None:
        return
    with contextlib.suppress(OSError, ValueError):
        stream.write(text)
        stream.flush()


def is_workflow_job(smk) -> bool:
    """Whether ``smk`` is the ``snakemake`` object Snakemake gives a script job (not a stand-in of a test)."""
    kind = type(smk)  # snakemake.iocontainers.Snakemake (Snakemake 9), snakemake.script.Snakemake before
    return kind.__name__ == "Snakemake" and kind.__module__.startswith("snakemake.")


def end_process() -> None:
    """End this process now with exit code 0 (120 when standard output cannot be flushed, as Python's
    own exit): flush the logging handlers and Python's and the C library's output streams, then
    ``os._exit``, skipping the interpreter's teardown (atexit handlers, module finalisation). For the
    end of a successful workflow job only (module docstring)."""
    logging.shutdown()
    code = 0
    for stream in (sys.stdout, sys.__stdout__, sys.stderr, sys.__stderr__):
        try:
            stream.flush()
        except OSError:
            if stream in (sys.stdout, sys.__stdout__):
                code = 120
        except (AttributeError, ValueError):  # no stream, or one the job closed
            pass
    with contextlib.suppress(OSError, AttributeError):
        import ctypes

        ctypes.CDLL(None).fflush(None)  # output that C libraries (HDF5, netCDF) buffered
    os._exit(code)


@contextlib.contextmanager
def job_log(smk, *, end: bool | None = None):
    """``with job_log(snakemake) as log: ...``: stderr to ``snakemake.log[0]`` for the block, ``log`` a
    :class:`JobLog` (module docstring). ``end``: after a successful block, end the process
    (:func:`end_process`); default: in a workflow job (:func:`is_workflow_job`), never in-process."""
    end = is_workflow_job(smk) if end is None else end
    terminal = sys.stderr
    path = smk.log[0] if smk.log else None
    log = None
    if path:
        try:
            log = open(path, "w", buffering=1)  # noqa: SIM115 (closed in finally)
        except OSError as exc:
            _write(terminal, f"vcor: cannot write the job log {path}: {exc}\n")
    sys.stderr = log or terminal
    startup = process_age()
    try:
        job = JobLog()
        yield job
        rule = getattr(smk, "rule", None) or "job"
        if startup is not None:
            job.note(f"job {rule}: start-up {startup:.2f} s, work {job.elapsed:.2f} s", timed=False)
    except BaseException as exc:
        if isinstance(exc, SystemExit) and exc.code in (0, None):
            raise
        text = f"vcor: job failed: {type(exc).__name__}: {exc}\n{traceback.format_exc()}"
        _write(log, text)
        _write(terminal, text)
        sys.stderr = terminal
        raise SystemExit(1) from None
    finally:
        sys.stderr = terminal
        if log is not None:
            with contextlib.suppress(OSError, ValueError):
                log.close()
    if end:
        end_process()
