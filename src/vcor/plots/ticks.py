"""Minor ticks of log axes without the ones outside the view.

matplotlib's ``LogLocator`` returns the minor ticks of every decade the view touches, whole: on the
figures' log axes a quarter to half of them lie outside the view. matplotlib builds a tick object for each,
positions and labels it on every layout pass and draw, then drops it because it is not in view.
:class:`InView` hands on only the ticks inside the view (with a margin, so that matplotlib's own filter
still decides at the edges): the same ticks are drawn, fewer are computed. Imported when a figure is saved
(it imports matplotlib)."""

from __future__ import annotations

import numpy as np
from matplotlib import ticker

__all__ = ["InView", "minor_ticks_in_view"]

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
