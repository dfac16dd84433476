"""The end of a Snakemake run (vcor.study.run_end): the scheduler's pending timers are cancelled, no
other timer is touched."""

import threading

from vcor.study import run_end


class JobScheduler:
    """Stands for snakemake.scheduling.job_scheduler.JobScheduler: the same qualified names."""

    def _schedule_reevalutation(self, delay):
        timer = threading.Timer(delay, lambda: None)
        timer.start()
        return timer


def test_only_the_schedulers_timers_are_cancelled():
    ours = JobScheduler()._schedule_reevalutation(60.0)
    other = threading.Timer(60.0, lambda: None)
    other.start()
    try:
        assert run_end.cancel_rescheduling_timers() == 1
        ours.join(5.0)
        assert not ours.is_alive()  # cancelled: the thread ends at once instead of in 60 s
        assert other.is_alive()
    finally:
        other.cancel()


def test_the_name_is_snakemakes():
    from snakemake.scheduling.job_scheduler import JobScheduler as Real

    assert Real._schedule_reevalutation.__qualname__ + ".<locals>." == run_end.SCHEDULER_TIMER
