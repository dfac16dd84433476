"""The log of a workflow job: stderr goes to the job's log file; an error also reaches the terminal.

A job's error must never be lost: on a full disk the log cannot be written (and Python's exit would
fail to flush it, exit code 120, an empty log). :func:`job_log` writes the error to the log where it
can and always to the terminal's stderr, then exits with code 1.
"""

from __future__ import annotations

import contextlib
import sys
import traceback

__all__ = ["job_log"]


def _write(stream, text) -> None:
    if stream is None:
        return
    with contextlib.suppress(OSError, ValueError):
        stream.write(text)
        stream.flush()


@contextlib.contextmanager
def job_log(smk):
    """``with job_log(snakemake): ...``: stderr to ``snakemake.log[0]`` for the block (module docstring)."""
    terminal = sys.stderr
    path = smk.log[0] if smk.log else None
    log = None
    if path:
        try:
            log = open(path, "w", buffering=1)  # noqa: SIM115 (closed in finally)
        except OSError as exc:
            _write(terminal, f"vcor: cannot write the job log {path}: {exc}\n")
    sys.stderr = log or terminal
    try:
        yield
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
