"""A DEM entry: vcor's COR against each DEM law's, and the error each law makes."""

from __future__ import annotations

import json

import numpy as np

from .common import flag_legend, plt, sweep_line, validity_of

__all__ = ["dem"]

#: the three Brilliantov laws share one curve; drawn once, with their names
_BRILLIANTOV = ("lammps-viscoelastic", "mercurydpm-bshp", "yade-mindlin")
_STYLE = {"brilliantov": ("C0", "-"), "lammps-coeff-restitution": ("C1", "--"), "lammps-hereditary": ("C3", "-.")}


def _columns(ds):
    if "T" not in ds.dims:
        return [None]
    n = ds.sizes["T"]
    return sorted({int(i) for i in np.linspace(0, n - 1, min(4, n)).round()})


def _trend_note(sel, models) -> str:
    """A note naming the laws whose COR changes with speed the other way from vcor's (the dataset's
    ``opposite_trend``); empty when there is none."""
    if "opposite_trend" not in sel:
        return ""
    bad = [m for m in models if int(sel["opposite_trend"].sel(model=m)) == 1]
    if not bad:
        return ""
    route = ("vcor's own law in LAMMPS\n(lammps-hereditary) or the COR table" if "lammps-hereditary" in models
             else "the COR table\n(table.csv; Aspherix cor_lookup)")
    return ("\nno fitted law follows this curve:\n" + ", ".join(bad) + "\nchange with speed the other way: "
            f"use {route}")


def dem(ds):
    """vcor's COR (black) and each DEM law's curve against v0 (top), law minus vcor (bottom), one
    column per temperature (up to four); the titles give each law's largest error, and a note names
    the laws whose COR changes with speed the other way from vcor's."""
    cols = _columns(ds)
    fig, axes = plt.subplots(2, len(cols), figsize=(4.2 * len(cols) + 1.0, 6.0), layout="constrained",
                             sharex=True, squeeze=False, gridspec_kw={"height_ratios": [3, 2]})
    models = [str(m) for m in ds["model"].values]
    v0 = ds["v0"].values
    flags = 0
    for j, it in enumerate(cols):
        sel = ds if it is None else ds.isel(T=it)
        top, bottom = axes[0, j], axes[1, j]
        vcor_line = sweep_line(top, v0, sel["cor"].values, sel["status"].values, validity_of(sel),
                               label="vcor (hereditary)", color="k")
        flags |= vcor_line.flags
        bottom.axhspan(-0.01, 0.01, color="0.9")
        bottom.axhline(0.0, color="0.5", lw=0.8)
        drawn = set()
        for m in models:
            if m == "table":
                continue
            key = "brilliantov" if m in _BRILLIANTOV else m
            if key in drawn:
                continue
            drawn.add(key)
            colour, ls = _STYLE.get(key, ("C2", ":"))
            names = ", ".join(x for x in _BRILLIANTOV if x in models) if key == "brilliantov" else m
            err = float(sel["max_abs_error"].sel(model=m))
            top.plot(v0, sel["cor_model"].sel(model=m).values, color=colour, ls=ls,
                     label=f"{names} (max error {err:.2g})")
            bottom.plot(v0, sel["error"].sel(model=m).values, color=colour, ls=ls)
        top.set_ylabel("COR")
        bottom.set_ylabel("law - vcor")
        bottom.set_xlabel("impact speed v0 [m/s]")
        if v0.max() / v0.min() > 5:
            bottom.set_xscale("log")
        note = _trend_note(sel, models)
        top.set_title((f"T = {float(ds['T'].values[it]):g} °C" if it is not None else ds.attrs.get("dem", "")) + note,
                      fontsize=8 if note else 9, color="C3" if note else "black")
    flag_legend(axes[0, 0], flags)  # the reasons of every column's flagged points, once
    axes[0, 0].legend(fontsize=7, loc="lower left")
    contact = json.loads(ds.attrs.get("contact", "{}"))
    fig.suptitle(f"DEM entry {ds.attrs.get('dem', '')}: {contact.get('kind', '')}, "
                 f"m_eff = {contact.get('m_eff_kg', float('nan')):.3g} kg, "
                 f"R_eff = {contact.get('r_eff_m', float('nan')):.3g} m",
                 fontsize=10)
    return fig
