"""The end of a Snakemake run: the workflow's ``onsuccess`` and ``onerror`` handlers call
:func:`cancel_rescheduling_timers` last, so that the process ends with its last job.

Snakemake's job scheduler arms a ``threading.Timer`` for its job-rate limiter
(``--max-jobs-per-timespan``, by default 100 jobs per 1 s) on every pass. The timer is not a daemon
thread, so Python waits for the last one before it exits: every run ended about a second after its
last job. When the handlers run, nothing is left to schedule; cancelling those timers changes nothing
but the exit. Only timers whose function is that scheduler's are touched.
"""

from __future__ import annotations

import threading

__all__ = ["SCHEDULER_TIMER", "cancel_rescheduling_timers"]

#: the qualified name of the function of Snakemake's rescheduling timers (snakemake.scheduling.job_scheduler)
SCHEDULER_TIMER = "JobScheduler._schedule_reevalutation.<locals>."


def cancel_rescheduling_timers() -> int:
    """Cancel the pending rescheduling timers of Snakemake's job scheduler; how many were pending."""
    pending = [t for t in threading.enumerate()
               if isinstance(t, threading.Timer) and SCHEDULER_TIMER in getattr(t.function, "__qualname__", "")]
    for timer in pending:
        timer.cancel()
    return len(pending)
