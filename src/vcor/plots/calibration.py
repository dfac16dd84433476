"""A calibration from measured COR: data, the calibrated curve with its band, residuals."""

from __future__ import annotations

import json

from .common import plt

__all__ = ["calibration"]


def calibration(cal):
    """A calibration's data (error bars: cor_std), the calibrated model with its 95 % band,
    and the residuals; the title gives the estimates, their standard errors and identifiability."""
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(6.5, 6.0), layout="constrained", sharex=True,
                                   gridspec_kw={"height_ratios": [3, 1]})
    v0, cor = cal["v0"].values, cal["cor"].values
    err = cal["cor_std"].values if "cor_std" in cal else None
    ax1.errorbar(v0, cor, yerr=err, fmt="o", ms=4, color="k", label="data")
    ax1.fill_between(cal["v0_curve"].values, cal["cor_lower95"].values, cal["cor_upper95"].values, color="C0",
                     alpha=0.3, label="95 % band (parameters)")
    ax1.plot(cal["v0_curve"].values, cal["cor_curve"].values, "C0-", label="calibrated model")
    ax1.set_ylabel("COR")
    ax1.legend(fontsize=8)
    ax2.axhline(0.0, color="0.5", lw=0.8)
    ax2.errorbar(v0, cal["residual"].values, yerr=err, fmt="o", ms=4, color="k")
    ax2.set_ylabel("data - model")
    ax2.set_xlabel("v0 [m/s]")
    if v0.max() / v0.min() > 5:
        ax2.set_xscale("log")
    units = json.loads(cal["estimate"].attrs.get("units_by_parameter", "{}"))
    parts = []
    for p in cal["parameter"].values:
        e, s = float(cal["estimate"].sel(parameter=p)), float(cal["stderr"].sel(parameter=p))
        ok = int(cal["identified"].sel(parameter=p)) == 1
        parts.append(f"{p} = {e:.4g} +- {s:.2g} {units.get(p, '')}" if ok else f"{p} = {e:.4g}: NOT IDENTIFIED")
    ax1.set_title("\n".join(parts)
                  + f"\nchi2 = {cal.attrs.get('chi2', float('nan')):.3g}, dof = {cal.attrs.get('dof', '?')}",
                  fontsize=8)
    return fig

