"""A calibration from measured COR: data, the calibrated curve with its band, residuals."""

from __future__ import annotations

import json

import numpy as np

from .common import FLAGGED_STYLE, Drawn, flagged_label, plt, unit_label

__all__ = ["calibration"]


def calibration(cal):
    """A calibration's data (error bars: cor_std), the calibrated model with its 95 % band, and the residuals.
    Data points where the calibrated model's result is outside the model's stated range (``validity`` not 0)
    are drawn open, with a legend entry naming the reasons and a count in the title, as in the sweep figures;
    a speed axis over more than a factor 5 is logarithmic, labelled with plain numbers
    (:func:`vcor.plots.ticks.plain_log_labels`). The title gives the estimates with their standard errors
    and units, or says that a parameter is not identified."""
    from .ticks import plain_log_labels  # imports matplotlib: the registry is read without it

    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(6.5, 6.0), layout="constrained", sharex=True,
                                   gridspec_kw={"height_ratios": [3, 1]})
    v0 = cal["v0"].values
    err = cal["cor_std"].values if "cor_std" in cal else None
    flags = np.asarray(cal["validity"].values, np.int64) if "validity" in cal else np.zeros(v0.size, np.int64)
    _points(ax1, v0, cal["cor"].values, err, flags, label="data")
    ax1.fill_between(cal["v0_curve"].values, cal["cor_lower95"].values, cal["cor_upper95"].values, color="C0",
                     alpha=0.3, label="95 % band (parameters)")
    ax1.plot(cal["v0_curve"].values, cal["cor_curve"].values, "C0-", label="calibrated model")
    ax1.set_ylabel("COR")
    ax1.legend(fontsize=8)
    ax2.axhline(0.0, color="0.5", lw=0.8)
    _points(ax2, v0, cal["residual"].values, err, flags)
    ax2.set_ylabel("data - model")
    ax2.set_xlabel("v0 [m/s]")
    if v0.max() / v0.min() > 5:
        ax2.set_xscale("log")
        plain_log_labels(ax2.xaxis)
    flagged = Drawn(color="k", not_ok=0, flagged=int(np.count_nonzero(flags)),
                    flags=int(np.bitwise_or.reduce(flags, initial=0)))
    ax1.set_title(_title(cal) + flagged.note(), fontsize=8)
    return fig


def _points(ax, x, y, err, flags, label=None):
    """``y`` against ``x`` as black markers with error bars ``err``: filled where ``flags`` is 0, open
    (:data:`~vcor.plots.common.FLAGGED_STYLE`) elsewhere; with ``label``, the filled ones carry it and the open
    ones the reasons of their flags (:func:`~vcor.plots.common.flagged_label`)."""
    flagged = flags != 0
    open_label = label and flagged_label(int(np.bitwise_or.reduce(flags, initial=0)))
    for pick, text, mfc in ((~flagged, label, None), (flagged, open_label, FLAGGED_STYLE["mfc"])):
        if pick.any():
            ax.errorbar(x[pick], y[pick], yerr=None if err is None else err[pick], ls="none",
                        marker=FLAGGED_STYLE["marker"], mfc=mfc, ms=4, color="k", label=text)


def _unit_text(units: str) -> str:
    """A parameter's unit as the figures write units (:func:`~vcor.plots.common.unit_label`; "" for
    dimensionless), followed by the description the dataset gives in parentheses ("(log10 of a_T)")."""
    base, _, described = units.partition(" (")
    return " ".join(t for t in (unit_label(base), f"({described}" if described else "") if t)


def _title(cal) -> str:
    """One line per free parameter, "name = estimate ± stderr unit" or "name = estimate unit: NOT
    IDENTIFIED" (also for a standard error that is not finite), then chi2 and the degrees of freedom."""
    units = json.loads(cal["estimate"].attrs.get("units_by_parameter", "{}"))
    parts = []
    for p in cal["parameter"].values:
        e, s = float(cal["estimate"].sel(parameter=p)), float(cal["stderr"].sel(parameter=p))
        ok = int(cal["identified"].sel(parameter=p)) == 1 and np.isfinite(s)
        unit = _unit_text(units.get(str(p), ""))
        text = f"{p} = {e:.4g}" + (f" ± {s:.2g}" if ok else "") + (f" {unit}" if unit else "")
        parts.append(text if ok else f"{text}: NOT IDENTIFIED")
    return "\n".join(parts) + f"\nchi2 = {cal.attrs.get('chi2', float('nan')):.3g}, dof = {cal.attrs.get('dof', '?')}"
