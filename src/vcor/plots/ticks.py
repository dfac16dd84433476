"""Ticks of log axes: minor ticks without the ones outside the view, and labels as plain numbers that do not
collide.

matplotlib's ``LogLocator`` returns the minor ticks of every decade the view touches, whole: on the
figures' log axes a quarter to half of them lie outside the view. matplotlib builds a tick object for each,
positions and labels it on every layout pass and draw, then drops it because it is not in view.
:class:`InView` hands on only the ticks inside the view (with a margin, so that matplotlib's own filter
still decides at the edges): the same ticks are drawn, fewer are computed.

matplotlib labels a log axis that spans less than about two decades at some minor ticks too, in scientific
notation ("3×10⁻¹"), and neighbouring labels overlap. :func:`plain_log_labels` labels such an axis with plain
numbers (0.2, 0.5, 1, 2) at only as many ticks per decade as the view leaves room for (:class:`PlainLog`).

Imported when a figure is drawn or saved (it imports matplotlib)."""

from __future__ import annotations

import numpy as np
from matplotlib import ticker

__all__ = ["InView", "PlainLog", "minor_ticks_in_view", "plain_log_labels"]

#: margin kept on each side of the view, as a fraction of its length in the axis' scale (matplotlib keeps
#: ticks within 1e-10 of it)
MARGIN = 1e-6


class InView(ticker.Locator):
    """The ticks of ``base`` that lie inside the axis' view interval (widened by :data:`MARGIN` of its length
    in the axis' scale). Everything else (tick values for given limits, view limits) is ``base``'s, and
    ``base`` keeps the axis it was made for (shared axes share one locator)."""

    def __init__(self, base: ticker.Locator):
        self.base = base

    def __call__(self):
        locs = np.asarray(self.base(), dtype=float)
        if self.axis is None or locs.size == 0:
            return locs
        transform = self.axis.get_transform()
        lo, hi = np.sort(transform.transform(np.asarray(self.axis.get_view_interval(), dtype=float)))
        pad = MARGIN * (hi - lo)
        with np.errstate(divide="ignore", invalid="ignore"):
            at = transform.transform(locs)
        return locs[np.isfinite(at) & (at >= lo - pad) & (at <= hi + pad)]

    def tick_values(self, vmin, vmax):
        return self.base.tick_values(vmin, vmax)

    def nonsingular(self, v0, v1):
        return self.base.nonsingular(v0, v1)

    def view_limits(self, vmin, vmax):
        return self.base.view_limits(vmin, vmax)


def minor_ticks_in_view(fig) -> None:
    """Give every log axis of ``fig`` whose minor ticks come from a ``LogLocator`` the :class:`InView` form of
    it. Call it when the figure is drawn in full (its view limits then are final)."""
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            locator = axis.get_minor_locator()
            if isinstance(locator, ticker.LogLocator):
                axis.set_minor_locator(InView(locator))


#: the mantissas labelled between decades, by the most decades the view spans: every tick within 0.4 decade,
#: 2, 3 and 5 within one, 2 and 5 within two, only the decades beyond (no two labels of the calibration
#: figure's speed axis overlap: tests/plots/test_calibration_figure.py)
LABELLED = ((0.4, frozenset(range(1, 10))), (1.0, frozenset({1, 2, 3, 5})), (2.0, frozenset({1, 2, 5})))


class PlainLog(ticker.Formatter):
    """Labels of a base-10 log axis as plain numbers (``f"{x:g}"``: 0.2, 3, 40): every decade, and the ticks
    between decades whose mantissa :data:`LABELLED` keeps for the decades in view; the other ticks unlabelled."""

    def __call__(self, x, pos=None):
        if not np.isfinite(x) or x <= 0:
            return ""
        lo, hi = sorted(abs(float(v)) for v in self.axis.get_view_interval())
        decades = np.log10(hi / lo) if lo > 0 else np.inf
        mantissa = x / 10.0 ** np.floor(np.log10(x) + 1e-9)
        whole = round(mantissa)
        keep = next((m for limit, m in LABELLED if decades <= limit), frozenset({1}))
        return f"{x:g}" if abs(mantissa - whole) < 1e-6 and whole in keep else ""


def plain_log_labels(axis) -> None:
    """Label the log axis ``axis`` (an ``ax.xaxis`` or ``ax.yaxis``) with :class:`PlainLog` at its major and
    minor ticks (axes that share it share its labels)."""
    axis.set_major_formatter(PlainLog())
    axis.set_minor_formatter(PlainLog())
