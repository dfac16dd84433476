"""The calibration figure (vcor.plots.calibration): plain log-axis labels that do not collide, units in the
title as the other figures write them, and data points outside the model's range drawn open with a legend
entry, as in the sweep figures. Synthetic calibration datasets shaped like
vcor.fitting.calibrate.calibration_dataset's (no solver run)."""

from __future__ import annotations

import json

import numpy as np
import pytest

# vcor.plots imports matplotlib, so the imports below follow the skips
# ruff: noqa: E402
xr = pytest.importorskip("xarray")
pytest.importorskip("matplotlib")

from vcor import plots
from vcor.plots import common
from vcor.plots.ticks import minor_ticks_in_view
from vcor.solvers import validity

LARGE = validity.FLAGS["large_indentation"]

#: name -> (estimate, stderr, identified, UDUNITS unit), as calibration_dataset writes them
PARAMETERS = {"modulus_scale": (0.1371, 0.012, 1, "1"), "log_aT": (0.03723, 0.21, 1, "1 (log10 of a_T)"),
              "beta": (1234.5, 56.0, 1, "s-1"), "E_glassy": (1.5e7, np.inf, 0, "Pa")}


def _calibration(v0, flags=None, parameters=None):
    """A calibration dataset over the speeds ``v0`` (m/s), with the per-point validity ``flags`` and the
    free ``parameters`` (name -> estimate, stderr, identified, unit)."""
    v0 = np.asarray(v0, float)
    flags = np.zeros(v0.size, np.int8) if flags is None else np.asarray(flags, np.int8)
    parameters = PARAMETERS if parameters is None else parameters
    names = list(parameters)
    est, err, ident, units = (list(c) for c in zip(*parameters.values()))
    by_name = {"units_by_parameter": json.dumps(dict(zip(names, units)))}
    cor = np.linspace(0.265, 0.228, v0.size)
    curve = np.geomspace(v0.min(), v0.max(), 40)
    cor_curve = np.interp(np.log(curve), np.log(v0), cor)
    return xr.Dataset(
        {"estimate": ("parameter", np.array(est, float), by_name),
         "stderr": ("parameter", np.array(err, float), by_name),
         "identified": ("parameter", np.array(ident, np.int8)), "note": ("parameter", np.array([""] * len(names))),
         "v0": ("point", v0, {"units": "m s-1"}), "cor": ("point", cor, {"units": "1"}),
         "cor_fit": ("point", cor, {"units": "1"}), "residual": ("point", np.linspace(0.008, -0.008, v0.size)),
         "validity": ("point", flags, validity.cf_attrs()),
         "cor_curve": ("v0_curve", cor_curve), "cor_lower95": ("v0_curve", cor_curve - 0.01),
         "cor_upper95": ("v0_curve", cor_curve + 0.01)},
        coords={"parameter": names, "point": np.arange(v0.size), "v0_curve": curve},
        attrs={"chi2": 0.000214, "dof": 3})


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    common.plt.close("all")


def _speed_labels(fig):
    """The shown labels of the speed axis (text, extent in display units), left to right, as drawn when the
    figure is saved (plots.save gives log axes the InView minor locator first)."""
    minor_ticks_in_view(fig)
    fig.draw_without_rendering()
    renderer = fig.canvas.get_renderer()
    ax = fig.axes[1]
    lo, hi = sorted(ax.get_xlim())
    ticks = ax.xaxis.get_major_ticks() + ax.xaxis.get_minor_ticks()
    shown = [t.label1 for t in ticks if t.label1.get_visible() and t.label1.get_text()
             and lo <= t.get_loc() <= hi]
    return sorted(((t.get_text(), t.get_window_extent(renderer)) for t in shown), key=lambda item: item[1].x0)


@pytest.mark.parametrize("v0", [[0.2, 0.5, 1.0, 2.0, 3.5], [0.02, 0.05, 0.1, 0.2, 0.35], [2.0, 5.0, 15.0],
                                [1.0, 3.0, 10.0, 30.0], [0.0013, 0.004, 0.012]])
def test_a_log_speed_axis_is_labelled_with_plain_numbers_that_do_not_collide(v0):
    """Over less than two decades, matplotlib labels minor ticks in scientific notation ("3×10⁻¹") and they
    overlap; the figure's labels are plain numbers, at least two, and no two overlap."""
    fig = plots.calibration(_calibration(v0))
    assert fig.axes[1].get_xscale() == "log"
    labels = _speed_labels(fig)
    texts = [text for text, _ in labels]
    assert len(texts) >= 2, texts
    for (a, box_a), (b, box_b) in zip(labels, labels[1:]):
        assert box_a.x1 < box_b.x0, f"{a!r} and {b!r} overlap in {texts}"
    assert all(float(text) > 0 for text in texts), texts  # plain numbers, no mathtext


def test_the_title_writes_units_as_the_figures_do_and_names_unidentified_parameters():
    """A dimensionless unit ("1") is not printed, a unit with a description keeps the description, other
    units are written as in the axis labels (s-1 as 1/s), and a parameter that is not identified (infinite
    standard error) shows its estimate and unit and says so, without an infinite error."""
    title = plots.calibration(_calibration([0.2, 0.5, 1.0, 2.0, 3.5])).axes[0].get_title().splitlines()
    assert title[:4] == ["modulus_scale = 0.1371 ± 0.012", "log_aT = 0.03723 ± 0.21 (log10 of a_T)",
                         "beta = 1234 ± 56 1/s", "E_glassy = 1.5e+07 Pa: NOT IDENTIFIED"]
    assert title[4] == "chi2 = 0.000214, dof = 3"


def test_an_identified_parameter_with_an_infinite_standard_error_reads_as_not_identified():
    parameters = {"log_aT": (0.5, np.inf, 1, "1 (log10 of a_T)")}
    title = plots.calibration(_calibration([1.0, 2.0], parameters=parameters)).axes[0].get_title()
    assert title.splitlines()[0] == "log_aT = 0.5 (log10 of a_T): NOT IDENTIFIED" and "inf" not in title


def _open_markers(ax):
    """x of the markers of ``ax`` drawn open (face colour none)."""
    lines = [line for line in ax.get_lines() if line.get_marker() not in ("None", "", None)
             and str(line.get_markerfacecolor()) == "none" and len(line.get_xdata())]
    return sorted(np.concatenate([line.get_xdata() for line in lines])) if lines else []


def test_points_outside_the_models_range_are_drawn_open_with_a_legend_entry_and_a_count():
    v0 = [0.2, 0.5, 1.0, 2.0, 3.5]
    fig = plots.calibration(_calibration(v0, flags=[0, 0, LARGE, LARGE, LARGE]))
    data, residuals = fig.axes
    for ax in (data, residuals):
        assert _open_markers(ax) == pytest.approx(v0[2:])
    filled = [line for line in data.get_lines() if line.get_marker() == "o"
              and str(line.get_markerfacecolor()) != "none"]
    assert len(filled) == 1 and list(filled[0].get_xdata()) == pytest.approx(v0[:2])
    texts = [t.get_text() for t in data.get_legend().get_texts()]
    entry = [t for t in texts if t.startswith("outside the model's range")]
    assert len(entry) == 1 and f"s_max/r > {validity.MAX_INDENTATION:g}" in entry[0], texts
    assert "data" in texts
    assert data.get_title().endswith("(3 outside the model's range)")


def test_valid_points_draw_no_open_markers_and_no_entry():
    fig = plots.calibration(_calibration([0.2, 0.5, 1.0, 2.0, 3.5]))
    assert all(_open_markers(ax) == [] for ax in fig.axes)
    assert not any("outside the model's range" in t.get_text() for t in fig.axes[0].get_legend().get_texts())
    assert "outside the model's range" not in fig.axes[0].get_title()
