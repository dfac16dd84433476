"""Solver studies: work-precision (COR error against run time) and stability maps."""

from __future__ import annotations

import numpy as np

from .common import Drawn, axis_label, flag_legend, flagged_label, plt, solver_label, sweep_line, validity_of

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
            floor = float(d["err_cor_floor"]) if "err_cor_floor" in d else np.nan
            if np.isfinite(floor) and floor > 0:  # below it an error measures the reference as much as the solver
                ax.axhspan(floor * 1e-3, floor, color="grey", alpha=0.12, lw=0)
            ax.set_title(f"{m}, v0 = {v:g} m/s", fontsize=9)
            ax.set_xlabel("solver wall time [s]")
            ax.set_ylabel("COR error |COR - reference|")
            # decades only: the minor ticks of twelve log-log panels made up half of the drawing time
            ax.minorticks_off()
    # one entry per solver drawn in any panel: a solver may not apply to the first panel's material (ive on
    # a fractional law), and its line elsewhere still needs its name
    drawn = {}
    for ax in axes.flat:
        for handle, label in zip(*ax.get_legend_handles_labels()):
            drawn.setdefault(label, handle)
    labels = [lab for lab in dict.fromkeys(solver_label(str(s)) for s in conv["solver"].values) if lab in drawn]
    fig.legend([drawn[lab] for lab in labels], labels, loc="outside lower center", ncol=min(len(labels), 5),
               fontsize=7)
    fig.suptitle("Work-precision: COR error against run time (reference: Richardson-extrapolated direct; "
                 "dotted: 1e-6; grey band: errors that measure the reference as much as the solver)")
    return fig


def _flag_rings(ax, cols, rows, label=None):
    """Open rings (white, outlined black: visible on any colour of the map) at the map cells of ok
    points outside the model's range."""
    from matplotlib import patheffects

    ax.plot(cols, rows, ls="none", marker="o", mfc="none", mec="w", mew=1.2, ms=9, label=label,
            path_effects=[patheffects.withStroke(linewidth=2.6, foreground="k")])


def _stability_line(ax, d, name, codes):
    """The estimated COR error along one axis: ok points (flagged ones open, dashed), the others
    named in red at their abscissa. Returns what was drawn."""
    err = d["cor_err"] if "cor_err" in d else d["energy_residual"]
    x, st = d[name].values, d["status"].values
    ok = st == 0
    drawn = sweep_line(ax, x[ok], np.maximum(err.values[ok], 1e-17), st[ok], validity_of(d)[ok],
                       label="estimated COR error (ok points)")
    for xx, code in zip(x[~ok], st[~ok]):
        ax.annotate(codes.get(int(code), "?"), (xx, 1e-4), color="red", fontsize=7, rotation=90)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.axhline(1e-4, color="red", lw=0.5, ls=":")
    ax.set_xlabel(axis_label(d, name))
    ax.set_ylabel("estimated COR error")
    flag_legend(ax, drawn.flags)
    ax.legend(fontsize=7)
    return Drawn(color=drawn.color, not_ok=int((~ok).sum()), flagged=drawn.flagged, flags=drawn.flags)


def _stability_grid(fig, ax, d, a, b, codes):
    """The estimated COR error over two axes as a map: points not ok named in red in their cell, ok
    points outside the model's range ringed. Returns what was drawn."""
    err = d["cor_err"] if "cor_err" in d else d["energy_residual"]
    z = np.log10(np.maximum(err.transpose(a, b).values, 1e-17))
    st = d["status"].transpose(a, b).values
    flags = np.where(st == 0, validity_of(d.transpose(a, b)), 0)
    z = np.where(st == 0, z, np.nan)
    im = ax.pcolormesh(np.arange(d.sizes[b] + 1), np.arange(d.sizes[a] + 1), z, vmin=-12, vmax=-3, cmap="viridis")
    for ia, ib in zip(*np.nonzero(st != 0)):
        ax.text(ib + 0.5, ia + 0.5, codes.get(int(st[ia, ib]), "?").replace("_", "\n"), ha="center", va="center",
                fontsize=6, color="red")
    union = int(np.bitwise_or.reduce(flags.ravel(), initial=0))
    if union:
        rows, cols = np.nonzero(flags)
        _flag_rings(ax, cols + 0.5, rows + 0.5, label=flagged_label(union))
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.22), fontsize=7, frameon=False)
    ax.set_xticks(np.arange(d.sizes[b]) + 0.5, [f"{x:.3g}" for x in d[b].values], rotation=45, fontsize=7)
    ax.set_yticks(np.arange(d.sizes[a]) + 0.5, [f"{x:.3g}" for x in d[a].values], fontsize=7)
    ax.set_xlabel(axis_label(d, b))
    ax.set_ylabel(axis_label(d, a))
    fig.colorbar(im, ax=ax, label="estimated COR error, log10 (ok points)")
    return Drawn(color="", not_ok=int((st != 0).sum()), flagged=int((flags != 0).sum()), flags=union)


def stability_map(sweep, opts):
    """Status and Richardson error estimate over a stability grid (v0 against one other axis); ok points
    outside the model's range open (a line) or ringed (a map)."""
    axes_names = [d for d in sweep["cor"].dims if d != "material"]
    mats = sweep["material"].values
    fig, axs = plt.subplots(1, len(mats), figsize=(5.5 * len(mats), 4.5), layout="constrained", squeeze=False)
    flags = sweep["status"].attrs
    codes = {int(v): n for v, n in zip(flags["flag_values"], flags["flag_meanings"].split())}
    for ax, m in zip(axs[0], mats):
        d = sweep.sel(material=m)
        if len(axes_names) == 1:
            drawn = _stability_line(ax, d, axes_names[0], codes)
        else:
            drawn = _stability_grid(fig, ax, d, axes_names[0], axes_names[1], codes)
        ax.set_title(str(m) + drawn.note(), fontsize=9)
    fig.suptitle(opts["title"])
    return fig
