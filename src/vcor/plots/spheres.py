"""Viscoelastic spheres (Ramirez et al. 1999): eps(b), the ice figure, the hereditary extension."""

from __future__ import annotations

import numpy as np

from .common import plt

__all__ = ["spheres_eps", "spheres_hereditary", "spheres_ice"]


def spheres_eps(sph, opts):
    """eps(b): numerics (both separation rules), series orders 1..4, both Pade approximants."""
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12, 4.5), layout="constrained")
    b = sph["b"].values
    for rule, style in zip(sph["rule"].values, ("-", "--")):
        ax.semilogx(b, sph["eps_numeric"].sel(rule=rule), style, color="k", lw=2, label=f"numerical, {rule} rule")
    for k in sph["order"].values:
        ax.semilogx(b, sph["eps_series"].sel(order=k), ":", label=f"series, order {k}")
    ax.semilogx(b, sph["eps_pade"], "-.", color="C5", label="Pade [1/4] (Ramirez Eq. 35)")
    ax.semilogx(b, sph["eps_pade_force"], "-.", color="C6", label="Pade, Mueller & Poeschel 2011 (force)")
    ax.set_ylim(-0.05, 1.05)
    ax.set_xlabel("b = 3/2 A (ρ/m_eff)^(2/5) g^(1/5)")
    ax.set_ylabel("ε [-]")
    ax.legend(fontsize=7)
    ax.set_title("Viscoelastic spheres: ε(b)")
    for rule, ref in (("overlap", "eps_pade"), ("force", "eps_pade_force")):
        if rule in sph["rule"].values:
            ax2.loglog(b, np.abs(sph["eps_numeric"].sel(rule=rule) / sph[ref] - 1),
                       label=f"|numerical/{ref} - 1|, {rule}")
    if "overlap" in sph["rule"].values:
        ax2.loglog(b, np.abs(sph["eps_numeric"].sel(rule="overlap") - sph["eps_series"].sel(order=4)),
                   label="|numerical - series(4)|, overlap")
    ax2.set_xlabel("b")
    ax2.set_ylabel("deviation")
    ax2.legend(fontsize=7)
    return fig


def spheres_ice(sph, opts):
    """Ramirez Fig. 1: ice, experimental fit eps = 0.32 g^-0.234 (g in cm/s, Bridges et al. 1984),
    the Pade with g* = 0.32 cm/s and the numerical curve with the same g*; with the dataset's ice fits
    the curves with g* fitted to the law (numerical eps per rule, and the Pade)."""
    from .. import (
        spheres as S,  # the series coefficients (imported here: figure jobs need no solver)
    )

    gs = float(opts["g_star_cm_s"])
    g = np.linspace(float(opts["g_min_cm_s"]), float(opts["g_max_cm_s"]), 200)
    fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
    ax.plot(g, np.minimum(0.32 * g**-0.234, 1.0), "k-", label="experiment fit 0.32 g^-0.234 (Bridges et al.)")
    b_of_g = (g / gs) ** 0.2 / abs(S.C[0])
    ax.plot(g, S.cor_pade(b_of_g), "--", label=f"Pade, g* = {gs:g} cm/s")
    if "overlap" in sph["rule"].values:
        num = np.interp(np.log(b_of_g), np.log(sph["b"].values), sph["eps_numeric"].sel(rule="overlap").values)
        ax.plot(g, num, ":", lw=2, label="numerical (overlap rule), same g*")
    if "ice_g_star" in sph:
        for m in sph["ice_model"].values:
            gs_fit = float(sph["ice_g_star"].sel(ice_model=m))
            se = float(sph["ice_g_star_stderr"].sel(ice_model=m))
            ax.plot(sph["ice_g"].values, sph["ice_eps_fit"].sel(ice_model=m).values, "-", lw=1,
                    label=f"{m} fitted: g* = {gs_fit:.3f} +- {se:.3f} cm/s")
    ax.set_xlabel("g [cm/s]")
    ax.set_ylabel("ε [-]")
    ax.set_ylim(0, 1.05)
    ax.legend(fontsize=7)
    ax.set_title("Ramirez et al. Fig. 1: ice")
    return fig


def spheres_hereditary(sph, opts):
    """eps(b) for an SLS pair with the Kelvin-Voigt viscosity, several relaxation times."""
    fig, ax = plt.subplots(figsize=(7, 4.5), layout="constrained")
    b = sph["b"].values
    for rule, style in zip(sph["rule"].values, ("-", "--")):
        ax.semilogx(b, sph["eps_numeric"].sel(rule=rule), style, color="k", lw=2, label=f"Kelvin-Voigt, {rule}")
        for i, tr in enumerate(sph["tau_ratio"].values):
            y = sph["eps_sls"].sel(tau_ratio=tr, rule=rule)
            ax.semilogx(b, y, style, color=f"C{i}", label=f"SLS τ = {tr:g} t_c, {rule}")
            bad = ~np.isfinite(y.values)
            if bad.any():
                ax.plot(b[bad], np.zeros(bad.sum()), "x", color="red", label=f"failed ({bad.sum()})")
    ax.set_xlabel("b")
    ax.set_ylabel("ε [-]")
    ax.set_title("Hereditary spheres: SLS vs its Kelvin-Voigt limit")
    ax.legend(fontsize=6, ncol=2)
    return fig

