"""A progress bar for a long solve: points done, ok / flagged / failed so far and the time left.

The bar is tqdm's (``tqdm.std`` on a terminal, ``tqdm.notebook``'s widget in Jupyter when ipywidgets is
installed, else the text bar, which Jupyter shows as well). tqdm is a small dependency with no
dependencies of its own that already solves what a hand-written bar would have to: the rate and the
time left from a smoothed rate, redrawing in place on a terminal of any width, a widget in Jupyter,
and a delay so that a short solve shows nothing. (rich would do the same with more: a console
library whose bars need its live-display machinery.)

When it shows (:func:`wanted`): ``progress=None`` (the default) shows it when standard error is a
terminal or the code runs in a Jupyter kernel, and only once the work has lasted :data:`DELAY`
seconds; ``progress=False`` never; ``progress=True`` always (on standard error, also when it is not
a terminal). A log file or a pipe therefore never receives bar lines unless asked for.
"""

from __future__ import annotations

import sys
from collections.abc import Iterable

from .. import status as _status

__all__ = ["DELAY", "Counts", "ProgressBar", "in_jupyter", "wanted"]

#: seconds of work before the bar appears: a solve shorter than that shows nothing
DELAY = 2.0
_OK = _status.code("ok")


def in_jupyter() -> bool:
    """True inside a Jupyter kernel (an IPython ZMQ shell)."""
    shell = sys.modules.get("IPython")
    get = getattr(shell, "get_ipython", None)
    return get is not None and type(get()).__name__ == "ZMQInteractiveShell"


def wanted(progress: bool | None) -> bool:
    """Whether to draw a bar (module docstring); ``progress`` must be None, True or False."""
    if progress is None:
        stream = sys.stderr
        return in_jupyter() or bool(stream is not None and hasattr(stream, "isatty") and stream.isatty())
    if not isinstance(progress, bool):
        raise ValueError(f"progress must be None (a bar on a terminal or in Jupyter), True or False, got {progress!r}")
    return progress


class Counts:
    """Outcome counts of the rows solved so far: ``ok`` (status ok, no validity flag), ``flagged``
    (status ok with a flag) and ``failed`` (any other status)."""

    def __init__(self) -> None:
        self.ok = self.flagged = self.failed = 0

    def add(self, rows: Iterable[dict]) -> None:
        for row in rows:
            if row["status"] != "ok":
                self.failed += 1
            elif row.get("validity", 0):
                self.flagged += 1
            else:
                self.ok += 1

    def text(self) -> str:
        return f"{self.ok} ok, {self.flagged} flagged, {self.failed} failed"


def _bar_class(notebook: bool):
    from tqdm import std

    cls = std.tqdm
    if notebook:
        from tqdm import notebook as nb

        if getattr(nb, "IProgress", None) is not None:  # None without ipywidgets: then the text bar
            cls = nb.tqdm

    class Bar(cls):  # type: ignore[valid-type,misc]
        # no monitor thread: a sweep forks its worker processes, and a thread of the parent's would be
        # a needless risk for them (the bar is redrawn on every update anyway)
        monitor_interval = 0

    return Bar


class ProgressBar:
    """A bar over ``total`` points (``enabled``: :func:`wanted`); :meth:`advance` with each batch of
    rows solved. A disabled bar only counts. Use as a context manager."""

    def __init__(self, total: int, *, enabled: bool, description: str = "vcor.sweep") -> None:
        self.counts = Counts()
        self._bar = None
        if enabled and total > 0:
            cls = _bar_class(in_jupyter())
            self._bar = cls(total=total, desc=description, unit="point", delay=DELAY, file=sys.stderr,
                            dynamic_ncols=True, smoothing=0.1)

    def advance(self, rows: list[dict]) -> None:
        self.counts.add(rows)
        if self._bar is not None:
            self._bar.set_postfix_str(self.counts.text(), refresh=False)
            self._bar.update(len(rows))

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None

    def __enter__(self) -> ProgressBar:
        return self

    def __exit__(self, *exc) -> None:
        self.close()
