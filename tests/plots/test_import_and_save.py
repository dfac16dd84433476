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
    """A constrained-layout figure with the costly parts of the real ones: log axes over many decades, a
    colorbar, a legend, a suptitle."""
    fig, (ax, ax2) = common.plt.subplots(1, 2, figsize=(7, 3), layout="constrained")
    x = np.geomspace(1e-3, 3e2, 9)
    ax.loglog(x, 1e-8 * (1 + x), "o-", label="a line")
    ax.set_xlabel("impact speed v0 [m/s]")
    ax.set_ylabel("estimated COR error")
    ax.legend(fontsize=7)
    im = ax2.pcolormesh(np.arange(5), np.arange(4), np.arange(12.0).reshape(3, 4))
    fig.colorbar(im, ax=ax2, label="a colorbar")
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


def test_save_draws_each_file_once(tmp_path):
    fig = _figure()
    draws = []
    fig.canvas.mpl_connect("draw_event", lambda event: draws.append(event))
    plots.save(fig, tmp_path / "a.png", tmp_path / "a.pdf")
    assert len(draws) == 2
    assert (tmp_path / "a.png").stat().st_size > 0 and (tmp_path / "a.pdf").stat().st_size > 0
