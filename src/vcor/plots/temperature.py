"""Temperature: COR against T, COR against v0 at several T, and measured-data master curves."""

from __future__ import annotations

import json

import numpy as np

from .common import Drawn, fixed_axes, flag_legend, plt, sweep_line, validity_of

__all__ = ["cor_temperature", "cor_v0_temperature", "master_curve"]


def _band(ax, d, x, ok, color):
    """The bootstrap band (``cor_lo`` .. ``cor_hi``) of the ok points, shaded, when the sweep has one."""
    if "cor_lo" in d:
        ax.fill_between(d[x].values[ok], d["cor_lo"].values[ok], d["cor_hi"].values[ok], color=color, alpha=0.2,
                        lw=0)


def _band_note(sweep) -> str:
    """The title's line on the band: its probability and the number of samples ('' without a band)."""
    if "cor_lo" not in sweep:
        return ""
    level = float(sweep.attrs.get("uncertainty_level", 0.95))
    return (f"\nlines: median; shaded: {100 * level:g} % band over {sweep.sizes['sample']} bootstrap samples "
            f"of the DMA data")


def cor_temperature(sweep, opts):
    """COR against temperature T (deg C), one line per material and impact speed v0; any other
    axis at the value the options name (e.g. ``nu: 0.5``) or its first; points not ok as red crosses, ok
    points outside the model's range open on dashed segments (:func:`~vcor.plots.common.sweep_line`)."""
    if "T" not in sweep.dims:
        raise ValueError("figure cor_temperature needs a sweep with a temperature axis T (deg C)")
    fig, ax = plt.subplots(figsize=(6.5, 4.5), layout="constrained")
    drawn = []
    sel, fixed = fixed_axes(sweep, opts, ("material", "T", "v0"))
    v0s = opts.get("v0s", list(sweep["v0"].values))
    for m in sweep["material"].values:
        for v0 in v0s:
            d = sweep.sel(material=m, v0=v0, **sel)
            drawn.append(sweep_line(ax, d["T"].values, d["cor"].values, d["status"].values, validity_of(d),
                                    label=f"{m}, v0 = {v0:g} m/s"))
            _band(ax, d, "T", d["status"].values == 0, drawn[-1].color)
    total = Drawn.total(drawn)
    ax.set_xlabel("temperature T [°C]")
    ax.set_ylabel("COR")
    ax.set_title("COR against temperature" + fixed + total.note(True) + _band_note(sweep), fontsize=9)
    flag_legend(ax, total.flags)
    ax.legend(fontsize=7)
    return fig


def cor_v0_temperature(sweep, opts):
    """COR against v0 (m/s), one line per temperature (option ``T``: a list of values on the
    sweep's T axis; default: five spread over it), one panel per material; other axes as in
    :func:`cor_temperature`."""
    if "T" not in sweep.dims:
        raise ValueError("figure cor_v0_temperature needs a sweep with a temperature axis T (deg C)")
    temps = sweep["T"].values
    spread = np.unique(np.linspace(0, temps.size - 1, min(5, temps.size)).round().astype(int))  # five, evenly spaced
    chosen = opts.get("T", list(temps[spread]))
    missing = [t for t in chosen if t not in temps]
    if missing:
        raise ValueError(f"figure option T: {missing} not on the sweep's T axis {list(temps)}")
    sel, fixed = fixed_axes(sweep, {k: v for k, v in opts.items() if k != "T"}, ("material", "T", "v0"))
    mats = sweep["material"].values
    fig, axes = plt.subplots(1, len(mats), figsize=(5.0 * len(mats), 4.2), layout="constrained", squeeze=False)
    colors = plt.cm.coolwarm(np.linspace(0, 1, len(chosen)))
    for ax, m in zip(axes[0], mats):
        drawn = []
        for c, t in zip(colors, chosen):
            d = sweep.sel(material=m, T=t, **sel)
            drawn.append(sweep_line(ax, d["v0"].values, d["cor"].values, d["status"].values, validity_of(d),
                                    label=f"T = {t:g} °C", color=c))
            _band(ax, d, "v0", d["status"].values == 0, c)
        total = Drawn.total(drawn)
        ax.set_xscale("log")
        ax.set_xlabel("impact speed v0 [m/s]")
        ax.set_ylabel("COR")
        ax.set_title(f"{m}" + total.note(), fontsize=9)
        flag_legend(ax, total.flags)
        ax.legend(fontsize=7)
    fig.suptitle("COR against impact speed at several temperatures" + fixed + _band_note(sweep), fontsize=10)
    return fig


def _spectrum_band(ax1, ax2, samples, f, level=0.95):
    """The band of the bootstrap samples' E', E'' and tan delta at T_ref over [min f, max f] (Hz), shaded."""
    from vcor.fitting.samples import sample_materials

    fd = np.geomspace(f.min(), f.max(), 200)
    e = np.array([m.complex_modulus(2 * np.pi * fd) for m, _ in sample_materials(samples)])
    q = [(1 - level) / 2, (1 + level) / 2]
    for y, ax in ((e.real, ax1), (e.imag, ax1), (e.imag / e.real, ax2)):
        lo, hi = np.quantile(y, q, axis=0)
        ax.fill_between(fd, lo, hi, color="0.6", alpha=0.4, lw=0)
    return f"\nshaded: {100 * level:g} % band over {samples.sizes['sample']} bootstrap samples"


def master_curve(fits, samples, opts):
    """Measured-data fits' master curves at T_ref, a column per fit: the shifted data (E', E''
    coloured by the temperature of their set) and the Prony fit, and tan delta, against reduced
    frequency f a_T (Hz); the title gives the fit's rms relative errors of E', E'' and tan delta, and a
    fitted instrument lag (the data are then shown with it removed, as fitted).
    ``samples``: bootstrap samples datasets (vcor.fitting.resample.samples_dataset) of some of the
    fits (matched by name; empty without an uncertainty band): their central band of probability
    ``opts["level"]`` (the scene's uncertainty level, set by the workflow; default 0.95) is shaded."""
    banded = {d.attrs.get("fit_name"): d for d in samples}
    fig, axes = plt.subplots(2, len(fits), figsize=(5.5 * len(fits), 7.0), layout="constrained", sharex="col",
                             squeeze=False)
    for (ax1, ax2), fit in zip(axes.T, fits):
        f = fit["omega"].values / (2 * np.pi)
        shift = json.loads(fit.attrs.get("shift", "{}"))
        c = fit["T_set"].values if "T_set" in fit else np.zeros(f.size)
        for var, marker, sym, style in (("storage", "o", "E'", "k-"), ("loss", "s", "E''", "k--")):
            sc = ax1.scatter(f, fit[f"{var}_data"].values, c=c, cmap="coolwarm", s=5, marker=marker,
                             label=f"{sym} data")
            ax1.plot(f, fit[f"{var}_fit"].values, style, lw=1, label=f"{sym} Prony fit")
        if "T_set" in fit:
            fig.colorbar(sc, ax=ax1, label="temperature of the measured set [°C]")
        ax1.set_xscale("log")
        ax1.set_yscale("log")
        ax1.set_ylabel("modulus [Pa]")
        ax1.legend(fontsize=7)
        ax2.scatter(f, fit["loss_data"].values / fit["storage_data"].values, c=c, cmap="coolwarm", s=5,
                    label="tan delta data")
        ax2.plot(f, fit["loss_fit"].values / fit["storage_fit"].values, "k-", lw=1, label="tan delta fit")
        ax2.set_yscale("log")
        ax2.set_xlabel("reduced frequency f a_T [Hz]")
        ax2.set_ylabel("tan delta")
        ax2.legend(fontsize=7)
        met = json.loads(fit.attrs.get("metrics", "{}"))
        spec = json.loads(fit.attrs.get("fit_spec", "{}")).get("data", {})
        shifts = "shift factors given with the data" if "shift_file" in spec else "shift factors found from the data"
        title = f"{fit.attrs.get('material_name', 'fit')}: {shifts}, T_ref = {shift.get('T_ref', '?')} °C"
        lag = json.loads(fit.attrs.get("fit_settings", "{}")).get("instrument_lag")
        if lag:
            title += f"\ndata shown with the fitted instrument lag {1e6 * lag['lag_s']:.1f} µs removed"
        title += "\nrms relative error: " + ", ".join(
            f"{lab} {100 * met[k]:.1f} %" for lab, k in (("E'", "storage_rms"), ("E''", "loss_rms"),
                                                        ("tan delta", "tan_delta_rms")) if k in met)
        name = fit.attrs.get("material_name")
        if name in banded:
            title += _spectrum_band(ax1, ax2, banded[name], f, opts.get("level", 0.95))
        ax1.set_title(title, fontsize=8)
    return fig

