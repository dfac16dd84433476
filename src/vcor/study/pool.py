"""Solving many grid points on the local machine's cores: worker processes, work ordered by estimate,
kernels compiled once, Ctrl-C honoured at once.

:func:`solve` is what :func:`vcor.sweep` and the workflow's sweep jobs solve points with (a workflow
job solves its shard with one worker; Snakemake runs the jobs side by side).

* **Order.** The points are grouped as :func:`vcor.study.runner.solving_order` groups them (points that
  differ only in speed together, so that a material's tables are built once), then sorted by their
  estimated work (:func:`vcor.study.cost.point_cost`), largest first, and cut into chunks of about
  equal estimated work: the largest chunks start first and the last ones, small, fill the cores' gaps.
* **Processes.** ``workers`` processes: the calling one and ``workers - 1`` workers (``fork`` where the
  platform has it), each worker a copy of the calling process with the numba kernels it has loaded
  (:func:`vcor.solvers.backend.load_kernels` runs once, before the workers start), so no kernel is
  compiled or loaded again; where only ``spawn`` exists a worker loads them from numba's cache once.
  Every process takes the next chunk from a shared counter until none is left; the workers' rows come
  back through a queue and are put in their points' places. The calling process solving too spares a
  process start and its own idle waiting, which a sweep of a few seconds would feel.
* **The same numbers.** A point's result is a pure function of the point, the settings and the
  material (the solvers keep no state between points that could change a number), so the rows equal
  those of one process, whatever the number of processes or the order (``tests/study/test_sweep.py``).
* **Ctrl-C.** The worker processes ignore SIGINT; the calling process receives it (between two points
  of its own chunk, or while it waits), terminates them (SIGTERM, then it waits for them: none is left
  behind) and raises KeyboardInterrupt, within a second.
"""

from __future__ import annotations

import math
import multiprocessing
import numbers
import os
import queue
import signal
from collections.abc import Callable, Sequence

from ..materials.catalogue import Catalogue
from .cost import point_cost
from .runner import solve_rows, solving_order

__all__ = ["CHUNK_SECONDS", "CHUNKS_PER_WORKER", "available_cores", "check_workers", "chunks_of", "solve"]

#: estimated work of a chunk at most (s): progress and Ctrl-C are seen at least this often per process
CHUNK_SECONDS = 0.25
#: the calling process checks this often (s) that no worker has died while it waits for their chunks
WAIT_SECONDS = 1.0
#: chunks per worker at least (when there are points enough): the last chunks even out the cores' loads
CHUNKS_PER_WORKER = 8


def available_cores() -> int:
    """The cores this process may run on (its CPU affinity where the platform says, else the count)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not on Linux
        return os.cpu_count() or 1


def check_workers(workers) -> int:
    """``workers`` as a number of processes: None -> :func:`available_cores`; otherwise an integer >= 1,
    else ValueError naming the argument."""
    if workers is None:
        return available_cores()
    if isinstance(workers, bool) or not isinstance(workers, numbers.Integral) or workers < 1:
        raise ValueError(f"workers must be an integer >= 1 (processes; None: the {available_cores()} cores "
                         f"available), got {workers!r}")
    return int(workers)


def chunks_of(points: Sequence[dict], settings: dict, workers: int,
              from_data: frozenset | set = frozenset()) -> list[list[int]]:
    """Indices of ``points`` in chunks, in the order they are handed out (module docstring)."""
    cost = point_cost(settings, from_data)
    order = solving_order(points)
    costs = {i: cost(points[i]) for i in order}
    order.sort(key=lambda i: -costs[i])  # stable: the solving order's groups stay together
    total = math.fsum(costs.values())
    n = max(1, min(len(order), max(workers * CHUNKS_PER_WORKER, math.ceil(total / CHUNK_SECONDS))))
    chunks: list[list[int]] = []
    current: list[int] = []
    done = 0.0
    for i in order:
        if current and done + costs[i] / 2 > total * (len(chunks) + 1) / n:
            chunks.append(current)
            current = []
        current.append(i)
        done += costs[i]
    return [*chunks, current] if current else chunks


# -- the worker processes ------------------------------------------------------------------------------
class _Board:
    """What the processes of one solve share: the next chunk to take (a counter under a lock) and the
    queue of solved chunks ``(k, rows)``; every process takes chunks until none is left."""

    def __init__(self, ctx, chunks: list[list[int]]):
        self.chunks = chunks
        self.next = ctx.Value("l", 0)
        self.done = ctx.Queue()

    def take(self) -> int | None:
        with self.next.get_lock():
            k = self.next.value
            self.next.value = k + 1
        return k if k < len(self.chunks) else None


def _work(board: _Board, job: tuple, method: str, spawned: bool) -> None:
    """A worker process: ignore SIGINT (the caller stops the workers), where it was spawned (not forked)
    load the kernels from numba's cache, then solve chunks until none is left."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if spawned:  # pragma: no cover - fork is used where it exists
        from ..solvers.backend import load_kernels

        load_kernels([method])
    points, settings, catalogue = job
    while (k := board.take()) is not None:
        board.done.put((k, solve_rows([points[i] for i in board.chunks[k]], settings, catalogue, ordered=True)))
    board.done.close()
    board.done.join_thread()


def _context():
    methods = multiprocessing.get_all_start_methods()
    return multiprocessing.get_context("fork" if "fork" in methods else "spawn")


def _in_processes(points, settings, catalogue, chunks, processes, put) -> None:
    """Solve ``chunks`` in this process and ``processes - 1`` workers side by side; ``put(k, rows)`` for each
    solved chunk, in this process. On any exception (KeyboardInterrupt too) the workers are terminated and
    waited for before it propagates."""
    ctx = _context()
    board = _Board(ctx, chunks)
    method = settings["solver"]["method"]
    workers = [ctx.Process(target=_work, args=(board, (points, settings, catalogue), method,
                                               ctx.get_start_method() != "fork"), daemon=True)
               for _ in range(processes - 1)]
    received = 0
    try:
        for w in workers:
            w.start()
        while (k := board.take()) is not None:  # this process takes its share too
            put(k, solve_rows([points[i] for i in chunks[k]], settings, catalogue, ordered=True))
            received += 1
            while not board.done.empty() and received < len(chunks):
                put(*board.done.get())
                received += 1
        while received < len(chunks):
            try:
                put(*board.done.get(timeout=WAIT_SECONDS))
            except queue.Empty:
                _check_alive(workers)
                continue
            received += 1
    except BaseException:
        for w in workers:
            w.terminate()
        raise
    finally:
        for w in workers:
            w.join()
        board.done.close()


def _check_alive(workers) -> None:
    """RuntimeError when a worker has ended before its chunks came back (killed, or out of memory): its
    chunk would never come."""
    if any(w.exitcode not in (None, 0) for w in workers):
        raise RuntimeError(f"a worker process ended with exit code {[w.exitcode for w in workers]} before its "
                           f"points were solved")


def solve(points: Sequence[dict], settings: dict, catalogue: Catalogue | None = None, *, workers: int = 1,
          on_rows: Callable[[list[dict]], None] | None = None, from_data: frozenset | set = frozenset()) -> list[dict]:
    """The rows of ``points`` (:func:`vcor.study.runner.solve_rows`, in the order of ``points``), solved in
    ``workers`` processes, this one among them (module docstring); ``on_rows(rows)`` after each chunk (a
    progress bar)."""
    from ..solvers.backend import load_kernels

    catalogue = catalogue or Catalogue()
    points = list(points)
    chunks = chunks_of(points, settings, workers, from_data)
    rows: list = [None] * len(points)
    report = on_rows or (lambda done: None)

    def put(k, solved):
        for i, row in zip(chunks[k], solved):
            rows[i] = row
        report(solved)

    load_kernels([settings["solver"]["method"]])  # here, once: forked workers inherit them
    processes = min(workers, len(chunks))
    if processes <= 1:
        for k, chunk in enumerate(chunks):
            put(k, solve_rows([points[i] for i in chunk], settings, catalogue, ordered=True))
    else:
        _in_processes(points, settings, catalogue, chunks, processes, put)
    return rows
