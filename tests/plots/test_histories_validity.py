"""Histories datasets carry each run's validity flags, and the history figures (Figs. 2, 3, 6, 7) draw a
run outside the model's stated range dashed with open markers, with a legend entry naming the reason.

At v0 = 2 m/s the SLS preset indents past a tenth of the sphere's radius (s_max/r = 0.13 > 0.1) while
the fractional butyl law stays inside (it reaches the limit near 5 m/s): one dataset, one run of each."""

from __future__ import annotations

import pytest

# vcor.plots imports matplotlib, so the imports below follow the skips
# ruff: noqa: E402
xr = pytest.importorskip("xarray")
pytest.importorskip("matplotlib")

from vcor import plots
from vcor.io import netcdf
from vcor.solvers import validity
from vcor.study import datasets, summary

FLAGGED, VALID = "sls/adaptive", "butyl-fc/adaptive"
LARGE = validity.FLAGS["large_indentation"]


@pytest.fixture(scope="module")
def hist():
    return datasets.histories_dataset([("sls", "adaptive"), ("butyl-fc", "adaptive")], 2.0)


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plots.common.plt.close("all")


def test_the_dataset_stores_each_runs_flags_and_their_reason(hist, tmp_path):
    var = hist["validity"]
    assert var.dims == ("run",) and var.attrs["flag_meanings"].split() == list(validity.FLAGS)
    assert list(var.attrs["flag_masks"]) == list(validity.FLAGS.values())
    assert int(var.sel(run=FLAGGED)) == LARGE and int(var.sel(run=VALID)) == 0
    assert str(hist["validity_message"].sel(run=FLAGGED).values).startswith("s_max / r = ")
    assert str(hist["validity_message"].sel(run=VALID).values) == ""
    assert "flagged" in summary.outcome_of(hist).text()
    path = tmp_path / "histories.nc"
    netcdf.write_dataset(hist, path, title="test histories")
    with netcdf.read_dataset(path) as back:
        assert back["validity"].values.tolist() == [LARGE, 0]
        assert back["validity"].attrs["flag_meanings"] == var.attrs["flag_meanings"]


def _labelled_lines(fig):
    """{legend label: Line2D} of every labelled line of ``fig``."""
    return {line.get_label(): line for ax in fig.axes for line in ax.get_lines()
            if not line.get_label().startswith("_")}


def _legend_texts(fig):
    return [t.get_text() for ax in fig.axes if ax.get_legend() is not None for t in ax.get_legend().get_texts()]


def _is_flagged_style(line):
    return line.get_linestyle() == "--" and str(line.get_markerfacecolor()) == "none"


@pytest.mark.parametrize("name", ["fig2", "fig3", "fig6", "fig7"])
@pytest.mark.parametrize("order", [(FLAGGED, VALID), (VALID, FLAGGED)])
def test_a_flagged_run_is_dashed_with_open_markers_and_a_legend_entry(hist, name, order):
    fig = plots.draw(name, {"histories": hist}, {"runs": list(order)})
    lines = _labelled_lines(fig)
    flagged = [line for label, line in lines.items() if label.split(":")[0].split(", ")[-1].startswith("sls")]
    valid = [line for label, line in lines.items() if "butyl-fc" in label]
    assert flagged and valid
    assert all(_is_flagged_style(line) for line in flagged), [(x.get_linestyle(), x.get_markerfacecolor())
                                                             for x in flagged]
    assert not any(_is_flagged_style(line) or line.get_linestyle() == "--" for line in valid)
    entries = [t for t in _legend_texts(fig) if t.startswith("outside the model's range")]
    assert len(entries) == 1 and "s_max/r > 0.1" in entries[0], _legend_texts(fig)


@pytest.mark.parametrize("name", ["fig2", "fig3"])
def test_all_valid_runs_draw_no_flagged_style_or_entry(hist, name):
    fig = plots.draw(name, {"histories": hist}, {"runs": [VALID]})
    assert not any(_is_flagged_style(line) for line in _labelled_lines(fig).values())
    assert not any("outside the model's range" in t for t in _legend_texts(fig))


def test_the_captions_say_how_a_flagged_run_is_drawn():
    from pathlib import Path

    report = Path(__file__).resolve().parents[2] / "workflow" / "report" / "figures"
    for name in ("fig2", "fig3", "fig6", "fig7"):
        text = " ".join((report / f"{name}.rst").read_text().split())
        assert "outside the model's stated range" in text and "dashed with open markers" in text, name
