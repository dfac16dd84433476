"""The figure registry loads without matplotlib (the workflow reads it at parse time), and
:func:`vcor.plots.save` writes the same pictures as matplotlib's own ``savefig`` while drawing each file once."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

# ruff: noqa: E402
pytest.importorskip("matplotlib")

from vcor import plots
from vcor.plots import common

#: modules the workflow's main process must not pay for when it reads the figure registry
HEAVY = ("matplotlib", "xarray", "scipy")


def test_importing_the_registry_loads_no_plotting_or_data_library():
    code = ("import sys, vcor.plots\n"
            "assert vcor.plots.FIGURES and vcor.plots.needs(['fig1']) == {'sweep', 'moduli'}\n"
            f"print(sorted({{m.split('.')[0] for m in sys.modules}} & set({HEAVY!r})))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]", out.stdout


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    common.plt.close("all")


def _figure():
    """A constrained-layout figure with the costly parts of the real ones: log axes over many decades and
    within one decade (labelled minor ticks), an inverted one, log axes shared by two panels, a twin axis,
    a colorbar, a legend, a suptitle."""
    fig, axes = common.plt.subplots(2, 3, figsize=(10, 5), layout="constrained", sharex="col")
    (ax, ax2, ax3), (ax4, ax5, ax6) = axes
    x = np.geomspace(1e-3, 3e2, 9)
    ax.loglog(x, 1e-8 * (1 + x), "o-", label="a line")
    ax.set_xlabel("impact speed v0 [m/s]")
    ax.set_ylabel("estimated COR error")
    ax.legend(fontsize=7)
    ax4.loglog(x, 1e-3 / x)
    ax4.twinx().semilogx(x, np.log(x), ":")
    im = ax2.pcolormesh(np.arange(5), np.arange(4), np.arange(12.0).reshape(3, 4))
    fig.colorbar(im, ax=ax2, label="a colorbar")
    ax5.semilogy([0.0, 1.0], [2.2e4, 7.5e4])
    ax3.loglog([3.0, 40.0], [0.5, 0.55])
    ax3.invert_xaxis()
    ax6.loglog([5.0, 8.0], [1e-6, 1e2])
    fig.suptitle("a title")
    return fig


def _png(path):
    from matplotlib.image import imread

    return imread(path)


def test_save_writes_what_savefig_writes(tmp_path):
    plots.save(_figure(), tmp_path / "a.png", tmp_path / "a.pdf")
    reference = _figure()
    reference.savefig(tmp_path / "b.png", dpi=common.PNG_DPI, format="png")
    reference.set_layout_engine("none")
    reference.savefig(tmp_path / "b.pdf", metadata={"CreationDate": None}, format="pdf")
    assert np.array_equal(_png(tmp_path / "a.png"), _png(tmp_path / "b.png"))
    assert (tmp_path / "a.pdf").read_bytes() == (tmp_path / "b.pdf").read_bytes()


def test_log_axes_keep_their_minor_ticks_in_view_and_compute_fewer(tmp_path):
    from matplotlib import ticker

    from vcor.plots.ticks import InView, minor_ticks_in_view

    fig = _figure()
    fig.draw_without_rendering()
    before = {id(a): (a.get_minor_locator(), np.asarray(a.get_minor_locator()()), sorted(a.get_view_interval()))
              for ax in fig.axes for a in (ax.xaxis, ax.yaxis) if a.get_scale() == "log"}
    minor_ticks_in_view(fig)
    fewer = 0
    for ax in fig.axes:
        for a in (ax.xaxis, ax.yaxis):
            if id(a) not in before:
                continue
            base, locs, (lo, hi) = before[id(a)]
            kept = np.asarray(a.get_minor_locator()())
            assert isinstance(a.get_minor_locator(), InView) and isinstance(base, ticker.LogLocator)
            assert np.array_equal(kept, locs[(locs >= lo * (1 - 1e-9)) & (locs <= hi * (1 + 1e-9))])
            fewer += kept.size < locs.size
    assert fewer >= 3


def test_save_draws_each_file_once(tmp_path):
    fig = _figure()
    draws = []
    fig.canvas.mpl_connect("draw_event", lambda event: draws.append(event))
    plots.save(fig, tmp_path / "a.png", tmp_path / "a.pdf")
    assert len(draws) == 2
    assert (tmp_path / "a.png").stat().st_size > 0 and (tmp_path / "a.pdf").stat().st_size > 0
