"""Figures mark ok points outside the model's stated range: open markers on dashed segments and a legend
entry naming the reasons; an all-valid sweep draws neither. Synthetic sweeps (no solver run)."""

from __future__ import annotations

import numpy as np
import pytest

# vcor.plots imports matplotlib, so the imports below follow the skips
# ruff: noqa: E402
xr = pytest.importorskip("xarray")
pytest.importorskip("matplotlib")

from vcor import plots, status
from vcor.plots import common
from vcor.solvers import validity

LARGE = validity.FLAGS["large_indentation"]
FAST = validity.FLAGS["fast_impact"]


def _sweep(flags, codes=None, *, materials=("sls", "butyl-fc"), extra=None):
    """A sweep dataset shaped like the aggregate's: dims (material, v0[, extra axis]), COR falling with
    v0, the given validity flags and status codes (broadcast over the materials and any extra axis)."""
    v0 = np.geomspace(0.5, 50.0, len(flags))
    shape = (len(materials), v0.size) + ((len(extra[1]),) if extra else ())
    dims = ("material", "v0") + ((extra[0],) if extra else ())
    codes = np.zeros(v0.size, np.int8) if codes is None else np.asarray(codes, np.int8)

    def spread(row):
        row = np.asarray(row)
        return np.broadcast_to(row.reshape((1, -1) + (1,) * bool(extra)), shape).copy()

    cor = spread(np.linspace(0.9, 0.3, v0.size))
    data = {"cor": (dims, cor, {"units": "1", "long_name": "coefficient of restitution"}),
            "status": (dims, spread(codes), status.cf_attrs()),
            "validity": (dims, spread(np.asarray(flags, np.int8)), validity.cf_attrs())}
    for name in ("t0", "omega_min", "s_max", "f_max", "w_h", "energy_residual"):
        data[name] = (dims, spread(np.linspace(1.0, 2.0, v0.size)), {"units": "1"})
    coords = {"material": list(materials), "v0": ("v0", v0, {"units": "m s-1", "long_name": "impact speed"})}
    if extra:
        coords[extra[0]] = (extra[0], np.asarray(extra[1], float), {"units": "1"})
    return xr.Dataset(data, coords=coords)


def _flagged_artists(fig):
    """The lines of ``fig`` drawn in the flagged style: open markers, or dashed segments."""
    open_markers, dashed = [], []
    for ax in fig.axes:
        for line in ax.get_lines():
            if line.get_marker() not in ("None", "", None) and str(line.get_markerfacecolor()) == "none":
                open_markers.append(line)
            if line.get_linestyle() == "--":
                dashed.append(line)
    return open_markers, dashed


def _legend_texts(fig):
    legends = [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None] + list(fig.legends)
    return [t.get_text() for legend in legends for t in legend.get_texts()]


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    common.plt.close("all")


@pytest.mark.parametrize("name", ["fig8", "fig9"])
def test_flagged_points_are_drawn_open_and_dashed_with_a_legend_entry(name):
    flags = [0, 0, 0, LARGE, LARGE | FAST, LARGE | FAST]
    fig = plots.draw(name, {"sweep": _sweep(flags)}, {"material": "sls"} if name == "fig9" else {})
    open_markers, dashed = _flagged_artists(fig)
    # the data's open markers sit exactly on the flagged points (the legend's proxy line is empty)
    drawn_open = np.concatenate([line.get_xdata() for line in open_markers if len(line.get_xdata())])
    v0 = _sweep(flags)["v0"].values
    assert set(np.round(drawn_open, 12)) == set(np.round(v0[3:], 12))
    # dashed segments span from the last valid point over the flagged range
    drawn_dashed = np.concatenate([np.asarray(line.get_xdata(), float) for line in dashed if len(line.get_xdata())])
    assert np.nanmin(drawn_dashed) == pytest.approx(v0[2]) and np.nanmax(drawn_dashed) == pytest.approx(v0[-1])
    texts = _legend_texts(fig)
    entry = [t for t in texts if t.startswith("outside the model's range")]
    assert len(entry) == 1, texts
    assert f"s_max/r > {validity.MAX_INDENTATION:g}" in entry[0] and "fast impact" in entry[0]
    assert "energy" not in entry[0]  # only the reasons the drawn points carry


def test_valid_points_stay_filled_on_a_solid_line():
    flags = [0, 0, 0, LARGE, LARGE | FAST, LARGE | FAST]
    fig = plots.draw("fig8", {"sweep": _sweep(flags)}, {})
    ax = fig.axes[0]
    solid = [line for line in ax.get_lines() if line.get_linestyle() == "-" and line.get_label() == "sls"]
    assert len(solid) == 1
    y = np.asarray(solid[0].get_ydata(), float)
    assert np.isfinite(y[:3]).all() and np.isnan(y[3:]).all()  # the solid line stops at the flagged range
    assert str(solid[0].get_markerfacecolor()) != "none"


def test_an_all_valid_sweep_draws_no_flagged_style_or_entry():
    fig = plots.draw("fig8", {"sweep": _sweep([0] * 6)}, {})
    open_markers, dashed = _flagged_artists(fig)
    assert open_markers == [] and dashed == []
    assert not any("outside the model's range" in t for t in _legend_texts(fig))
    assert "outside the model's range" not in fig.axes[0].get_title()


def test_a_dataset_without_validity_draws_as_all_valid():
    fig = plots.draw("fig8", {"sweep": _sweep([LARGE] * 6).drop_vars("validity")}, {})
    assert _flagged_artists(fig) == ([], [])


def test_points_not_ok_keep_their_red_crosses_and_are_never_drawn_flagged():
    codes = [0, 0, status.code("diverged"), 0, 0, 0]
    flags = [0, 0, LARGE, 0, FAST, 0]  # the diverged point's flag is ignored: only ok points carry one
    fig = plots.draw("fig8", {"sweep": _sweep(flags, codes, materials=("sls",))}, {})
    ax = fig.axes[0]
    crosses = [line for line in ax.get_lines() if line.get_marker() == "x"]
    assert len(crosses) == 1 and len(crosses[0].get_xdata()) == 1
    open_markers, _ = _flagged_artists(fig)
    v0 = _sweep(flags)["v0"].values
    drawn_open = np.concatenate([line.get_xdata() for line in open_markers if len(line.get_xdata())])
    assert list(drawn_open) == pytest.approx([v0[4]])
    entry = [t for t in _legend_texts(fig) if t.startswith("outside the model's range")]
    assert entry and "s_max/r" not in entry[0] and "fast impact" in entry[0]
    assert "1 not ok, 1 outside the model's range" in ax.get_title()


@pytest.mark.parametrize("name", ["fig4", "cor_temperature", "cor_v0_temperature", "stability_map"])
def test_every_sweep_figure_shows_the_flag_legend(name):
    axis = {"fig4": ("beta", [300.0, 1200.0]), "cor_temperature": ("T", [0.0, 20.0, 40.0]),
            "cor_v0_temperature": ("T", [0.0, 20.0, 40.0]), "stability_map": None}[name]
    sweep = _sweep([0, 0, LARGE, LARGE], materials=("sls",), extra=axis)
    opts = {"title": "stability"} if name == "stability_map" else {}
    fig = plots.draw(name, {"sweep": sweep}, opts)
    open_markers, _ = _flagged_artists(fig)
    assert any(len(line.get_xdata()) for line in open_markers)
    assert any(t.startswith("outside the model's range") and "(s_max/r" in t for t in _legend_texts(fig))


def test_a_stability_map_rings_the_flagged_cells():
    sweep = _sweep([0, 0, LARGE, LARGE], materials=("sls",), extra=("beta", [300.0, 1200.0, 4800.0]))
    fig = plots.draw("stability_map", {"sweep": sweep}, {"title": "stability"})
    rings = [line for line in fig.axes[0].get_lines() if str(line.get_markerfacecolor()) == "none"]
    assert len(rings) == 1 and len(rings[0].get_xdata()) == 2 * 3  # two flagged v0 rows, three beta columns
    assert any(t.startswith("outside the model's range") and "(s_max/r" in t for t in _legend_texts(fig))


def test_prony_terms_marks_flagged_points_in_both_panels():
    sweep = _sweep([0, 0, LARGE, LARGE], materials=("butyl-fc", "butyl-prony-n2", "butyl-prony-n3"))
    fig = plots.draw("prony_terms", {"sweep": sweep}, {"v0": 50.0})
    for ax in fig.axes[:2]:
        texts = [t.get_text() for t in ax.get_legend().get_texts()]
        assert any(t.startswith("outside the model's range") and "(s_max/r" in t for t in texts), texts
    left_open = [line for line in fig.axes[0].get_lines()
                 if str(line.get_markerfacecolor()) == "none" and len(line.get_xdata())]
    assert sorted(np.concatenate([line.get_xdata() for line in left_open])) == [2, 3]


def _histories(flags):
    """A histories dataset shaped like vcor.study.datasets.histories_dataset's, one run per flag, with a
    ``validity`` variable per run."""
    n = 50
    t = np.linspace(0.0, 1e-3, n)
    runs = [f"sls/method{i}" for i in range(len(flags))]
    shape = (len(runs), n)
    wave = np.sin(np.pi * t / t[-1])
    data = {"t": (("run", "sample"), np.broadcast_to(t, shape)), "s": (("run", "sample"), np.broadcast_to(wave, shape)),
            "sdot": (("run", "sample"), np.broadcast_to(np.cos(np.pi * t / t[-1]), shape)),
            "F": (("run", "sample"), np.broadcast_to(wave, shape)),
            "ghost": (("run", "sample"), np.zeros(shape, np.int8)),
            "status": ("run", np.zeros(len(runs), np.int8), status.cf_attrs()),
            "validity": ("run", np.asarray(flags, np.int8), validity.cf_attrs())}
    for name, value in (("cor", 0.5), ("t0", 1e-3), ("s_max", 1.0), ("f_max", 1.0), ("s_residual", 0.0), ("w_h", 1.0)):
        data[name] = ("run", np.full(len(runs), value))
    return xr.Dataset(data, coords={"run": runs}, attrs={"v0": 10.0})


def test_history_figures_name_a_flagged_run_and_its_reason():
    hist = _histories([0, LARGE])
    runs = {"runs": list(hist["run"].values)}
    notes = " ".join(t.get_text() for ax in plots.draw("fig2", {"histories": hist}, runs).axes for t in ax.texts)
    flagged = [line for line in notes.splitlines() if "outside the model's range (s_max/r" in line]
    assert len(flagged) == 1 and flagged[0].startswith("sls (method1)")
    labels = _legend_texts(plots.draw("fig3", {"histories": hist}, runs))
    # the two runs' entries (only the flagged one names the reasons), then the flagged style's own entry
    assert [("outside the model's range" in t) for t in labels] == [False, True, True]
    assert labels[2].startswith("outside the model's range")


def test_the_dem_figure_marks_flagged_speeds_of_vcors_curve():
    """The DEM figure draws vcor's COR in the same style: a collision fast enough to leave Hertz's
    range (s_max/r > 0.1) shows open markers and the legend entry."""
    from vcor.dem import export, fit
    from vcor.plots.dem import dem as dem_figure

    col = fit.collision("sls", [0.1, 1.0, 10.0, 40.0], sphere={"r": 0.005}, target="rigid")
    ds = export.dem_dataset("t", [col], [fit.fit_laws(col)])
    flagged = (ds["status"].values == 0) & (ds["validity"].values != 0)
    assert flagged.any() and not flagged.all()
    fig = dem_figure(ds)
    opened, _ = _flagged_artists(fig)
    assert opened
    assert any("outside the model's range" in t for t in _legend_texts(fig))


def test_v0_figures_name_the_values_they_hold_other_axes_at():
    """fig8 and fig9 draw COR (and the scalars) along v0: on a grid with another axis they draw its first
    value, and their titles say so; on a v0-only grid the title names nothing more."""
    sweep = _sweep([0, 0, 0], extra=("h", [0.005, 0.02]))
    sweep["h"].attrs["units"] = "m"
    fig8 = plots.draw("fig8", {"sweep": sweep}, {})
    assert "(h = 0.005 m)" in fig8.axes[0].get_title()
    fig9 = plots.draw("fig9", {"sweep": sweep}, {"material": "sls"})
    assert "(h = 0.005 m)" in fig9.get_suptitle()
    plain = plots.draw("fig8", {"sweep": _sweep([0, 0, 0])}, {})
    assert "=" not in plain.axes[0].get_title()
    for fig in (fig8, fig9, plain):
        common.plt.close(fig)
