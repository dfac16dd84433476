"""Solver studies: work-precision (COR error against run time) and stability maps."""

from __future__ import annotations

import numpy as np

from .common import axis_label, plt, solver_label

__all__ = ["stability_map", "work_precision"]


def work_precision(conv, opts):
    """COR error against solver wall time, one line per solver, one panel per (material, v0)."""
    mats, v0s = conv["material"].values, conv["v0"].values
    fig, axes = plt.subplots(len(v0s), len(mats), figsize=(4 * len(mats), 3.3 * len(v0s)), layout="constrained",
                             squeeze=False)
    markers = "os^vDxP*"
    for i, v in enumerate(v0s):
        for j, m in enumerate(mats):
            ax = axes[i, j]
            d = conv.sel(material=m, v0=v)
            for k, s in enumerate(d["solver"].values):
                ds = d.sel(solver=s)
                ok = (ds["status"].values == 0) & (ds["err_cor"].values > 0)
                if ok.any():
                    ax.loglog(ds["wall_time"].values[ok], ds["err_cor"].values[ok], marker=markers[k % 8], ms=4,
                              color=f"C{k}", label=solver_label(str(s)))
            ax.axhline(1e-6, color="grey", lw=0.5, ls=":")
            ax.set_title(f"{m}, v0 = {v:g} m/s", fontsize=9)
            ax.set_xlabel("solver wall time [s]")
            ax.set_ylabel("COR error |COR - reference|")
            # decades only: the minor ticks of twelve log-log panels made up half of the drawing time
            ax.minorticks_off()
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=min(len(labels), 5), fontsize=7)
    fig.suptitle("Work-precision: COR error against run time (reference: Richardson-extrapolated direct; "
                 "dotted: 1e-6)")
    return fig


def stability_map(sweep, opts):
    """Status and Richardson error estimate over a stability grid (v0 against one other axis)."""
    axes_names = [d for d in sweep["cor"].dims if d != "material"]
    mats = sweep["material"].values
    fig, axs = plt.subplots(1, len(mats), figsize=(5.5 * len(mats), 4.5), layout="constrained", squeeze=False)
    codes = {int(v): n for v, n in zip(sweep["status"].attrs["flag_values"], sweep["status"].attrs["flag_meanings"].split())}
    for ax, m in zip(axs[0], mats):
        d = sweep.sel(material=m)
        err = d["cor_err"] if "cor_err" in d else d["energy_residual"]
        if len(axes_names) == 1:
            x = d[axes_names[0]].values
            ok = d["status"].values == 0
            ax.loglog(x[ok], np.maximum(err.values[ok], 1e-17), "o-", label="estimated COR error (ok points)")
            for xx, st in zip(x[~ok], d["status"].values[~ok]):
                ax.annotate(codes.get(int(st), "?"), (xx, 1e-4), color="red", fontsize=7, rotation=90)
            ax.axhline(1e-4, color="red", lw=0.5, ls=":")
            ax.set_xlabel(axis_label(d, axes_names[0]))
            ax.set_ylabel("estimated COR error")
        else:
            a, b = axes_names[0], axes_names[1]
            z = np.log10(np.maximum(err.transpose(a, b).values, 1e-17))
            st = d["status"].transpose(a, b).values
            z = np.where(st == 0, z, np.nan)
            im = ax.pcolormesh(np.arange(d.sizes[b] + 1), np.arange(d.sizes[a] + 1), z, vmin=-12, vmax=-3,
                               cmap="viridis")
            for ia in range(d.sizes[a]):
                for ib in range(d.sizes[b]):
                    if st[ia, ib] != 0:
                        ax.text(ib + 0.5, ia + 0.5, codes.get(int(st[ia, ib]), "?").replace("_", "\n"), ha="center",
                                va="center", fontsize=6, color="red")
            ax.set_xticks(np.arange(d.sizes[b]) + 0.5, [f"{x:.3g}" for x in d[b].values], rotation=45, fontsize=7)
            ax.set_yticks(np.arange(d.sizes[a]) + 0.5, [f"{x:.3g}" for x in d[a].values], fontsize=7)
            ax.set_xlabel(axis_label(d, b))
            ax.set_ylabel(axis_label(d, a))
            fig.colorbar(im, ax=ax, label="estimated COR error, log10 (ok points)")
        ax.set_title(str(m))
    fig.suptitle(opts["title"])
    return fig

