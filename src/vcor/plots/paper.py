"""The paper's figures (Green 2026, Figs. 1-9) and the Prony-terms study: one function per figure,
datasets in, Figure out."""

from __future__ import annotations

import math

import numpy as np

from .common import (
    Drawn,
    cor_line,
    fixed_axes,
    flag_legend,
    flag_reasons,
    json_materials,
    plt,
    point,
    run_label,
    status_name,
    sweep_line,
    v0_line,
    validity_of,
)

__all__ = ["fig1", "fig2", "fig3", "fig4", "fig5", "fig6", "fig7", "fig8", "fig9", "prony_terms"]


def moduli_axes(fig, mod, materials, marks, inset_tmax=None):
    """E(t) left; storage (solid), loss (dashed) and tan delta (dotted, right axis) right.
    One colour per material."""
    ax_t, ax_w = fig.subplots(1, 2)
    ax_tan = ax_w.twinx()
    for i, m in enumerate(materials):
        c = f"C{i}"
        ax_t.loglog(mod["t"], mod["relaxation_modulus"].sel(material=m), color=c, label=m)
        ax_w.loglog(mod["omega"], mod["storage_modulus"].sel(material=m), "-", color=c, label=f"{m}: E'")
        ax_w.loglog(mod["omega"], mod["loss_modulus"].sel(material=m), "--", color=c, label=f"{m}: E''")
        ax_tan.semilogx(mod["omega"], mod["tan_delta"].sel(material=m), ":", color=c, label=f"{m}: tan δ")
    ax_t.set_xlabel("t [s]")
    ax_t.set_ylabel("E(t) [Pa]")
    ax_w.set_xlabel(r"$\omega$ [rad/s]")
    ax_w.set_ylabel("storage E' (solid), loss E'' (dashed) [Pa]")
    ax_tan.set_ylabel(r"tan $\delta$ (dotted) [-]")
    for t0, wmin, lab in marks:
        if math.isfinite(t0):
            ax_t.axvline(t0, color="k", lw=0.8)
            ax_t.annotate(f"t0 = {t0 * 1e3:.3g} ms\n({lab})", (t0, 0.02), xycoords=("data", "axes fraction"),
                          fontsize=7, xytext=(3, 0), textcoords="offset points")
            ax_w.axvline(wmin, color="k", lw=0.8)
            ax_w.annotate(f"ω_min = {wmin:.4g} rad/s", (wmin, 0.02), xycoords=("data", "axes fraction"),
                          fontsize=7, xytext=(3, 0), textcoords="offset points")
    if inset_tmax:
        ins = ax_t.inset_axes([0.52, 0.55, 0.45, 0.42])
        for i, m in enumerate(materials):
            sel = mod["t"] <= inset_tmax
            ins.plot(mod["t"][sel] * 1e3, mod["relaxation_modulus"].sel(material=m)[sel] / 1e6, color=f"C{i}")
        ins.set_xlabel("t [ms]", fontsize=7)
        ins.set_ylabel("E [MPa]", fontsize=7)
        ins.set_yscale("log")
        ins.tick_params(labelsize=6)
    ax_t.legend(fontsize=7, loc="lower left")
    h1, l1 = ax_w.get_legend_handles_labels()
    h2, l2 = ax_tan.get_legend_handles_labels()
    ax_w.legend(h1 + h2, l1 + l2, fontsize=6, loc="upper left")
    return ax_t, ax_w


def fig1(sweep, moduli, opts):
    """SLS moduli in time and frequency with t0 and omega_min of the v0 = 10 m/s impact."""
    mat = opts["material"]
    p = point(sweep, mat, opts["v0"], beta=opts["beta"])
    fig = plt.figure(figsize=(10, 4), layout="constrained")
    moduli_axes(fig, moduli, [mat], [(float(p["t0"]), float(p["omega_min"]), f"v0={float(p['v0']):g} m/s")])
    fig.suptitle(f"Fig. 1: relaxation and dynamic moduli of {mat}" + _marked_note(p))
    return fig


def _run_flag(h) -> str:
    """"; outside the model's range (reasons)" for an ok history run with validity flags (histories
    datasets that carry ``validity``), else ""."""
    flags = int(validity_of(h))
    return f"; outside the model's range ({flag_reasons(flags)})" if flags else ""


#: marker of the i-th history run drawn with markers (the first valid run is a plain solid line)
_RUN_MARKERS = ("o", "s", "^")


def _run_style(i: int, flagged: bool, n: int) -> dict:
    """``ax.plot`` keywords of history run ``i`` with ``n`` samples before separation. The first run is a
    solid line, further runs open markers on top (overlaid solutions stay visible); a run outside the
    model's range (``flagged``) is a dashed line with open markers, as flagged points are in every figure
    (:data:`vcor.plots.common.FLAGGED_STYLE`)."""
    every = max(1, n // 25)
    if not flagged:
        if i == 0:
            return {"ls": "-"}
        return {"ls": "none", "marker": _RUN_MARKERS[(i - 1) % 3], "mfc": "none", "ms": 4,
                "markevery": slice(i, None, every)}
    return {"ls": "--", "marker": _RUN_MARKERS[i % 3], "mfc": "none", "ms": 4, "markevery": slice(i, None, every)}


def _flagged_suffix(flags: int) -> str:
    return " [outside range]" if flags else ""


def responses(hist, runs, title):
    """Normalised s/s_max, -s'/v0 and F/F_max against time for ``runs`` (first solid, further runs as open
    markers on top, so that overlaid solutions stay visible; a run outside the model's range dashed with
    open markers and a legend entry naming the reasons; dotted: the ghost part after t0). The legend and
    each run's t0, COR and residual interference sit below the axes, off the curves."""
    fig, (ax, below) = plt.subplots(2, 1, figsize=(7.5, 5.8), height_ratios=[4, 1.15], layout="constrained")
    below.axis("off")
    notes, failed, union = [], False, 0
    v0 = hist.attrs["v0"]
    for i, run in enumerate(runs):
        h = hist.sel(run=run)
        name = run_label(run)
        if int(h["status"]) != 0:
            notes.append(f"{name}: {status_name(h['status'])}: {h['message'].values}")
            failed = True
            continue
        flags = int(validity_of(h))
        union |= flags
        t = h["t"].values * 1e3
        ghost = h["ghost"].values.astype(bool)
        curves = {
            "s/s_max": h["s"].values / float(h["s_max"]),
            "-s'/v0": -h["sdot"].values / v0,
            "F/F_max": h["F"].values / float(h["f_max"]),
        }
        style = _run_style(i, bool(flags), int((~ghost).sum()))
        for (label, y), color in zip(curves.items(), ["C0", "C1", "C2"]):
            ax.plot(t[~ghost], y[~ghost], color=color, label=f"{label}, {name}{_flagged_suffix(flags)}", **style)
            ax.plot(t[ghost], y[ghost], ":", color=color, alpha=0.6)
        t0 = float(h["t0"]) * 1e3
        ax.axvline(t0, color="k", lw=0.8, ls="-" if i == 0 else ":")
        notes.append(f"{name}: t0 = {t0:.4g} ms, COR = {float(h['cor']):.4f}, residual interference "
                     f"s/s_max = {float(h['s_residual'] / h['s_max']):.4f}" + _run_flag(h))
    ax.axhline(0, color="grey", lw=0.5)
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("normalised response")
    ax.set_title(f"{title} at v0 = {v0:g} m/s\n(vertical lines: separation t0; dotted: solution after separation)",
                 fontsize=10)
    flag_legend(ax, union)
    handles, labels = ax.get_legend_handles_labels()
    if handles:
        below.legend(handles, labels, loc="upper left", fontsize=7, ncol=2, frameon=False)
    below.text(0.0, 0.0, "\n".join(notes), transform=below.transAxes, fontsize=7, va="bottom",
               color="red" if failed else "black")
    return fig


def runs(hist, opts, default_materials):
    if "runs" in opts:
        return list(opts["runs"])
    return [str(r) for r in hist["run"].values if str(r).split("/")[0] in default_materials]


def fig2(hist, opts):
    """Responses of the SLS, two solvers overlaid."""
    chosen = runs(hist, opts, ["sls"])
    return responses(hist, chosen, "Fig. 2: responses, " + ", ".join(run_label(r) for r in chosen))


def fig3(hist, opts):
    """Hysteresis loops F(s) up to separation with W_h (a run outside the model's range dashed with open
    markers, and a legend entry naming the reasons)."""
    fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
    union = 0
    for i, run in enumerate(runs(hist, opts, ["sls", "butyl-fc"])):
        h = hist.sel(run=run)
        if int(h["status"]) != 0:
            ax.text(0.02, 0.95 - 0.05 * i, f"{run_label(run)}: {status_name(h['status'])} ({h['message'].values})",
                    color="red", transform=ax.transAxes, fontsize=7)
            continue
        ghost = h["ghost"].values.astype(bool)
        flags = int(validity_of(h))
        union |= flags
        style = {"ls": "-"} if not flags else _run_style(0, True, int((~ghost).sum()))
        ax.plot(h["s"].values[~ghost] * 1e3, h["F"].values[~ghost],
                label=f"{run_label(run)}: F_max = {float(h['f_max']):.1f} N, s_max = {float(h['s_max']) * 1e3:.3g} mm, "
                      f"W_h = {float(h['w_h']):.3f} J" + _run_flag(h), **style)
    flag_legend(ax, union)
    ax.set_xlabel("s [mm]")
    ax.set_ylabel("F [N]")
    ax.set_title(f"Fig. 3: hysteresis loops up to separation, v0 = {hist.attrs['v0']:g} m/s")
    ax.legend(fontsize=7)
    return fig


def fig4(sweep, opts):
    """COR vs v0 with the SLS decay rate beta as a parameter."""
    fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
    mat = opts.get("material", str(sweep["material"].values[0]))
    ds = sweep.sel(material=mat)
    drawn = Drawn.total(cor_line(ax, ds.sel(beta=b), f"β = {b:g} 1/s") for b in ds["beta"].values)
    ax.set_title(f"Fig. 4: COR against impact speed, {mat}, a line per decay rate β" + drawn.note(True), fontsize=10)
    flag_legend(ax, drawn.flags)
    ax.legend(fontsize=7)
    return fig


def fig5(sweep, moduli, opts):
    """Butyl B252 moduli: fractional law, CERF and Prony sets."""
    ref = opts["reference"]
    mats = [str(m) for m in moduli["material"].values]
    p = point(sweep, ref, opts["v0"])
    fig = plt.figure(figsize=(11, 4.5), layout="constrained")
    inset = 4e-4
    moduli_axes(fig, moduli, mats, [(float(p["t0"]), float(p["omega_min"]), ref)], inset_tmax=inset)
    fig.suptitle(f"Fig. 5: moduli of {', '.join(mats)} (inset: t <= {inset * 1e3:g} ms)" + _marked_note(p))
    return fig


def fig6(hist, opts):
    """Responses of the fractional law and the CERF set (the runs the options name)."""
    chosen = runs(hist, opts, ["butyl-fc", "butyl-cerf"])
    return responses(hist, chosen, "Fig. 6: responses, " + ", ".join(run_label(r) for r in chosen))


def fig7(hist, opts):
    """Responses of the 3-term Prony set, two solvers overlaid."""
    chosen = runs(hist, opts, ["butyl-prony3"])
    return responses(hist, chosen, "Fig. 7: responses, " + ", ".join(run_label(r) for r in chosen))


def fig8(sweep, opts):
    """COR vs v0 for the Butyl models."""
    fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
    mats = [str(m) for m in sweep["material"].values]
    drawn = Drawn.total(cor_line(ax, v0_line(sweep, m), m) for m in mats)
    held = fixed_axes(sweep, {}, ("material", "v0"))[1]  # the values v0_line holds the other axes at
    ax.set_title("Fig. 8: COR against impact speed, " + ", ".join(mats) + held + drawn.note(True), fontsize=10)
    flag_legend(ax, drawn.flags)
    ax.legend(fontsize=8)
    return fig


def fig9(sweep, opts):
    """t0, omega_min, s_max, F_max and W_h vs v0 for one material (default: the fractional law)."""
    mat = opts["material"]
    d = v0_line(sweep, mat)
    fig, axes = plt.subplots(1, 5, figsize=(16, 3.5), layout="constrained")
    specs = [("t0", 1e3, "t0 [ms]"), ("omega_min", 1.0, "ω_min [rad/s]"), ("s_max", 1e3, "s_max [mm]"),
             ("f_max", 1.0, "F_max [N]"), ("w_h", 1.0, "W_h [J]")]
    for ax, (var, scale, lab) in zip(axes, specs):
        drawn = sweep_line(ax, d["v0"].values, d[var].values * scale, d["status"].values, validity_of(d),
                           color="C0")
        ax.set_xlabel("v0 [m/s]")
        ax.set_ylabel(lab)
    if drawn.flags or drawn.not_ok:
        flag_legend(axes[0], drawn.flags)
        fig.legend(*axes[0].get_legend_handles_labels(), loc="outside lower center", fontsize=8, frameon=False)
    held = fixed_axes(sweep, {}, ("material", "v0"))[1]  # the values v0_line holds the other axes at
    fig.suptitle(f"Fig. 9: effect of the impact speed, {mat}" + held + drawn.note())
    return fig


def _flag_note(p) -> str:
    """", outside the model's range" for an ok point ``p`` with validity flags, else ""."""
    return ", outside the model's range" if int(validity_of(p)) and int(p["status"]) == 0 else ""


def _marked_note(p) -> str:
    """A title line saying that the impact whose t0 and omega_min are marked is outside the model's range
    (and why), when it is; else ""."""
    if not _flag_note(p):
        return ""
    return (f"\nthe marked impact (v0 = {float(p['v0']):g} m/s) is outside the model's range: "
            f"{flag_reasons(int(validity_of(p)))}")


def prony_terms(sweep, opts):
    """COR at v0 (default 10 m/s) against the number of Prony terms N, beside the reference law;
    right: COR(v0) for the reference, a few N, the paper's 3-term set and the automatic fit."""
    import re

    ref = opts["reference"]
    v0 = float(opts["v0"])
    pat = re.compile("^" + re.escape(opts["pattern"]).replace(r"\{n\}", r"(\d+)") + "$")
    mats = [str(m) for m in sweep["material"].values]
    ns = sorted((int(pat.match(m).group(1)), m) for m in mats if pat.match(m))
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12, 4.5), layout="constrained")
    at = {m: point(sweep, m, v0) for m in [ref, *mats]}
    c_ref = float(at[ref]["cor"])
    cors = [float(at[m]["cor"]) for _, m in ns]
    drawn = [sweep_line(ax, [n for n, _ in ns], cors, [int(at[m]["status"]) for _, m in ns],
                        [int(validity_of(at[m])) for _, m in ns], label="Prony fit with N terms")]
    ax.axhline(c_ref, color="k", label=f"{ref} (solved directly): {c_ref:.4f}" + _flag_note(at[ref]))
    for other, style in (("butyl-prony3", "s"), ("butyl-prony-fit", "D")):
        if other in mats:
            n_other = len(json_materials(sweep)[other]["material"]["E"])
            ax.plot([n_other], [float(at[other]["cor"])], style, ms=8, mfc="none" if validity_of(at[other]) else None,
                    label=f"{other} (N = {n_other})" + _flag_note(at[other]))
    for other, style in (("butyl-cerf", "--"), ("butyl-cerf-fit", ":")):
        if other in mats:
            ax.axhline(float(at[other]["cor"]), ls=style, color="grey", label=other + _flag_note(at[other]))
    flags = int(np.bitwise_or.reduce([int(validity_of(at[m])) for m in at if int(at[m]["status"]) == 0]))
    flag_legend(ax, flags)
    ax.set_xlabel("number of Prony terms N")
    ax.set_ylabel(f"COR at v0 = {v0:g} m/s [-]")
    ax.legend(fontsize=7, loc="lower right")
    ax_in = ax.inset_axes([0.33, 0.6, 0.3, 0.32])
    ax_in.semilogy([n for n, _ in ns], np.abs(np.array(cors) / c_ref - 1), "o-")
    ax_in.set_title("|COR/COR_ref - 1|", fontsize=7)
    ax_in.tick_params(labelsize=6)
    show = [ref] + [m for m in ("butyl-prony3", "butyl-prony-fit") if m in mats] + [m for n, m in ns if n in (3, 12)]
    drawn += [cor_line(ax2, v0_line(sweep, m), m) for m in show]
    flag_legend(ax2, Drawn.total(drawn[1:]).flags)
    ax2.legend(fontsize=7)
    fig.suptitle("Prony class or 3-term fit? COR against the number of Prony terms")
    return fig

