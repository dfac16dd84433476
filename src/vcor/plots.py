"""Figures of Green 2026 (Figs. 1-9). One function per figure: datasets in, Figure out.

``FIGURES[name] = (function, needs)`` where ``needs`` names the datasets the function takes
(``sweep``, ``moduli``, ``histories``), so the workflow builds only those. Every function takes
``opts`` (the scene's figure options). Points whose status is not ok are drawn as red crosses on
the axis and counted in the title, never silently dropped.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["FIGURES", "draw", "needs", "save"]


class _Pyplot:
    """``matplotlib.pyplot`` (Agg backend), imported on first use: the workflow's Snakefile imports
    this module for ``FIGURES`` and ``needs`` only, and importing pyplot cost ~0.5 s of every
    ``snakemake`` start (also of a no-op re-run)."""

    def __getattr__(self, name):
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot

        return getattr(matplotlib.pyplot, name)


plt = _Pyplot()


def _mark_failed(ax, x, ok, label="not ok"):
    bad = ~ok
    if np.any(bad):
        ax.plot(x[bad], np.zeros(bad.sum()), "x", color="red", ms=7, clip_on=False, transform=ax.get_xaxis_transform(),
                label=f"{label} ({bad.sum()})")
    return int(bad.sum())


def _status_name(var) -> str:
    """Status name of a scalar status variable (CF flag_meanings)."""
    codes = dict(zip(var.attrs["flag_values"].tolist(), var.attrs["flag_meanings"].split()))
    return codes.get(int(var), "unknown").replace("_", "-")


def _v0_line(sweep, material):
    """The sweep along v0 for one material (first value of any other axis)."""
    d = sweep.sel(material=material)
    for extra in [k for k in d.dims if k != "v0"]:
        d = d.isel({extra: 0})
    return d


def _cor_line(ax, d, label):
    """COR against v0 for the ok points; the others as red crosses. Returns how many were not ok."""
    ok = d["status"].values == 0
    ax.plot(d["v0"].values[ok], d["cor"].values[ok], "o-", ms=3, label=label)
    ax.set_xlabel("v0 [m/s]")
    ax.set_ylabel("COR [-]")
    return _mark_failed(ax, d["v0"].values, ok)


def _point(sweep, material, v0, **sel):
    """Scalars at the grid point nearest to v0 (and the given other coordinates)."""
    ds = sweep.sel(material=material)
    for k, v in sel.items():
        if k in ds.dims:
            ds = ds.sel({k: v}, method="nearest")
    ds = ds.sel(v0=v0, method="nearest")
    for d in list(ds.dims):
        ds = ds.isel({d: 0})
    return ds


def _moduli_axes(fig, mod, materials, marks, inset_tmax=None):
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
    mat = opts.get("material", "sls")
    p = _point(sweep, mat, opts.get("v0", 10.0), beta=opts.get("beta", 1200.0))
    fig = plt.figure(figsize=(10, 4), layout="constrained")
    _moduli_axes(fig, moduli, [mat], [(float(p["t0"]), float(p["omega_min"]), f"v0={float(p['v0']):g} m/s")])
    fig.suptitle(f"Fig. 1: {mat} relaxation and dynamic moduli")
    return fig


def _responses(hist, runs, title):
    fig, ax = plt.subplots(figsize=(7, 4.5), layout="constrained")
    for i, run in enumerate(runs):
        h = hist.sel(run=run)
        if int(h["status"]) != 0:
            ax.text(0.02, 0.02 + 0.05 * i, f"{run}: {_status_name(h['status'])} ({h['message'].values})", color="red",
                    transform=ax.transAxes, fontsize=7)
            continue
        t = h["t"].values * 1e3
        ghost = h["ghost"].values.astype(bool)
        v0 = hist.attrs["v0"]
        curves = {
            "s/s_max": h["s"].values / float(h["s_max"]),
            "-s'/v0": -h["sdot"].values / v0,
            "F/F_max": h["F"].values / float(h["f_max"]),
        }
        for (name, y), color in zip(curves.items(), ["C0", "C1", "C2"]):
            if i == 0:  # first run: solid line
                ax.plot(t[~ghost], y[~ghost], "-", color=color, label=f"{name} {run}")
            else:  # further runs: open markers on top, so that overlaid solutions stay visible
                every = max(1, int((~ghost).sum()) // 25)
                ax.plot(t[~ghost][i::every], y[~ghost][i::every], ["o", "s", "^"][(i - 1) % 3], mfc="none",
                        color=color, ms=4, label=f"{name} {run}")
            ax.plot(t[ghost], y[ghost], "--", color=color, alpha=0.6)
        t0 = float(h["t0"]) * 1e3
        ax.axvline(t0, color="k", lw=0.8)
        ax.annotate(f"{run}: t0={t0:.4g} ms, COR={float(h['cor']):.4f},\nresidual s/s_max={float(h['s_residual'] / h['s_max']):.4f}",
                    (t0, 0.9 - 0.15 * i), fontsize=7, xytext=(5, 0), textcoords="offset points")
    ax.axhline(0, color="grey", lw=0.5)
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("normalised response [-]")
    ax.set_title(title + "\n(dashed: ghost solution after separation)", fontsize=10)
    ax.legend(fontsize=6, ncol=2, loc="lower left")
    return fig


def _runs(hist, opts, default_materials):
    if "runs" in opts:
        return list(opts["runs"])
    return [str(r) for r in hist["run"].values if str(r).split("/")[0] in default_materials]


def fig2(hist, opts):
    """SLS responses, direct and IVE overlaid."""
    return _responses(hist, _runs(hist, opts, ["sls"]), "Fig. 2: SLS responses, direct and IVE")


def fig3(hist, opts):
    """Hysteresis loops F(s) up to separation with W_h."""
    fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
    for i, run in enumerate(_runs(hist, opts, ["sls", "butyl-fc"])):
        h = hist.sel(run=run)
        if int(h["status"]) != 0:
            ax.text(0.02, 0.95 - 0.05 * i, f"{run}: {_status_name(h['status'])} ({h['message'].values})",
                    color="red", transform=ax.transAxes, fontsize=7)
            continue
        ghost = h["ghost"].values.astype(bool)
        ax.plot(h["s"].values[~ghost] * 1e3, h["F"].values[~ghost],
                label=f"{run}: F_max={float(h['f_max']):.1f} N, s_max={float(h['s_max']) * 1e3:.3g} mm, "
                      f"W_h={float(h['w_h']):.3f} J")
    ax.set_xlabel("s [mm]")
    ax.set_ylabel("F [N]")
    ax.set_title("Fig. 3: hysteresis loops")
    ax.legend(fontsize=7)
    return fig


def fig4(sweep, opts):
    """COR vs v0 with the SLS decay rate beta as a parameter."""
    fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
    mat = opts.get("material", str(sweep["material"].values[0]))
    ds = sweep.sel(material=mat)
    nbad = 0
    for b in ds["beta"].values:
        nbad += _cor_line(ax, ds.sel(beta=b), f"β = {b:g} 1/s")
    ax.set_title("Fig. 4: COR vs impact speed, SLS, α/β fixed" + (f" ({nbad} points not ok)" if nbad else ""))
    ax.legend(fontsize=7)
    return fig


def fig5(sweep, moduli, opts):
    """Butyl B252 moduli: fractional law, CERF and Prony sets."""
    ref = opts.get("reference", "butyl-fc")
    mats = [str(m) for m in moduli["material"].values]
    p = _point(sweep, ref, opts.get("v0", 10.0))
    fig = plt.figure(figsize=(11, 4.5), layout="constrained")
    _moduli_axes(fig, moduli, mats, [(float(p["t0"]), float(p["omega_min"]), ref)], inset_tmax=4e-4)
    fig.suptitle("Fig. 5: Butyl B252 moduli (inset: t <= 0.4 ms)")
    return fig


def fig6(hist, opts):
    return _responses(hist, _runs(hist, opts, ["butyl-fc", "butyl-cerf"]), "Fig. 6: Butyl, fractional law and CERF")


def fig7(hist, opts):
    return _responses(hist, _runs(hist, opts, ["butyl-prony3"]), "Fig. 7: Butyl, 3-term Prony, direct and IVE")


def fig8(sweep, opts):
    """COR vs v0 for the Butyl models."""
    fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
    nbad = 0
    for m in sweep["material"].values:
        nbad += _cor_line(ax, _v0_line(sweep, m), str(m))
    ax.set_title("Fig. 8: COR vs impact speed, Butyl B252 models" + (f" ({nbad} not ok)" if nbad else ""))
    ax.legend(fontsize=8)
    return fig


def fig9(sweep, opts):
    """t0, omega_min, s_max, F_max and W_h vs v0 for one material (default: the fractional law)."""
    mat = opts.get("material", "butyl-fc")
    d = _v0_line(sweep, mat)
    ok = d["status"].values == 0
    fig, axes = plt.subplots(1, 5, figsize=(16, 3.5), layout="constrained")
    specs = [("t0", 1e3, "t0 [ms]"), ("omega_min", 1.0, "ω_min [rad/s]"), ("s_max", 1e3, "s_max [mm]"),
             ("f_max", 1.0, "F_max [N]"), ("w_h", 1.0, "W_h [J]")]
    for ax, (var, scale, lab) in zip(axes, specs):
        ax.plot(d["v0"].values[ok], d[var].values[ok] * scale, "o-", ms=3)
        _mark_failed(ax, d["v0"].values, ok)
        ax.set_xlabel("v0 [m/s]")
        ax.set_ylabel(lab)
    fig.suptitle(f"Fig. 9: effect of impact speed, {mat}")
    return fig


def prony_terms(sweep, opts):
    """COR at v0 (default 10 m/s) against the number of Prony terms N, beside the reference law;
    right: COR(v0) for the reference, a few N, the paper's 3-term set and the automatic fit."""
    import re

    ref = opts.get("reference", "butyl-fc")
    v0 = float(opts.get("v0", 10.0))
    pat = re.compile("^" + re.escape(opts.get("pattern", "butyl-prony-n{n}")).replace(r"\{n\}", r"(\d+)") + "$")
    mats = [str(m) for m in sweep["material"].values]
    ns = sorted((int(pat.match(m).group(1)), m) for m in mats if pat.match(m))
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12, 4.5), layout="constrained")
    c_ref = float(_point(sweep, ref, v0)["cor"])
    cors = [float(_point(sweep, m, v0)["cor"]) for _, m in ns]
    ax.plot([n for n, _ in ns], cors, "o-", label="Prony fit with N terms")
    ax.axhline(c_ref, color="k", label=f"{ref} (solved directly): {c_ref:.4f}")
    for other, style in (("butyl-prony3", "s"), ("butyl-prony-fit", "D")):
        if other in mats:
            n_other = len(json_materials(sweep)[other]["E"])
            ax.plot([n_other], [float(_point(sweep, other, v0)["cor"])], style, ms=8, label=f"{other} (N = {n_other})")
    for other, style in (("butyl-cerf", "--"), ("butyl-cerf-fit", ":")):
        if other in mats:
            ax.axhline(float(_point(sweep, other, v0)["cor"]), ls=style, color="grey", label=other)
    ax.set_xlabel("number of Prony terms N")
    ax.set_ylabel(f"COR at v0 = {v0:g} m/s [-]")
    ax.legend(fontsize=7, loc="lower right")
    ax_in = ax.inset_axes([0.33, 0.6, 0.3, 0.32])
    ax_in.semilogy([n for n, _ in ns], np.abs(np.array(cors) / c_ref - 1), "o-")
    ax_in.set_title("|COR/COR_ref - 1|", fontsize=7)
    ax_in.tick_params(labelsize=6)
    show = [ref] + [m for m in ("butyl-prony3", "butyl-prony-fit") if m in mats] + [m for n, m in ns if n in (3, 12)]
    for m in show:
        _cor_line(ax2, _v0_line(sweep, m), m)
    ax2.legend(fontsize=7)
    fig.suptitle("Prony class or 3-term fit? COR against the number of Prony terms")
    return fig


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
            ax2.loglog(b, np.abs(sph["eps_numeric"].sel(rule=rule) / sph[ref] - 1), label=f"|numerical/{ref} - 1|, {rule}")
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
    (issue 13) the curves with g* fitted to the law (numerical eps per rule, and the Pade)."""
    from . import spheres as S

    gs = float(opts.get("g_star_cm_s", 0.32))
    g = np.linspace(float(opts.get("g_min_cm_s", 0.05)), float(opts.get("g_max_cm_s", 5.0)), 200)
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
                              color=f"C{k}", label=str(s))
            ax.axhline(1e-6, color="grey", lw=0.5, ls=":")
            ax.set_title(f"{m}, v0 = {v:g} m/s", fontsize=9)
            ax.set_xlabel("solver wall time [s]")
            ax.set_ylabel("|COR - reference|")
            # decades only: the minor ticks of twelve log-log panels made up half of the drawing time
            ax.minorticks_off()
    axes[0, 0].legend(fontsize=6)
    fig.suptitle("Work-precision: COR error against run time (reference: Richardson-extrapolated direct)")
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
            ax.loglog(x[ok], np.maximum(err.values[ok], 1e-17), "o-", label="cor_err (ok points)")
            for xx, st in zip(x[~ok], d["status"].values[~ok]):
                ax.annotate(codes.get(int(st), "?"), (xx, 1e-4), color="red", fontsize=7, rotation=90)
            ax.axhline(1e-4, color="red", lw=0.5, ls=":")
            ax.set_xlabel(axes_names[0])
            ax.set_ylabel("Richardson estimate of the COR error")
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
            ax.set_xlabel(f"{b} [{d[b].attrs.get('units', '')}]")
            ax.set_ylabel(f"{a} [{d[a].attrs.get('units', '')}]")
            fig.colorbar(im, ax=ax, label="log10 cor_err (ok points)")
        ax.set_title(str(m))
    fig.suptitle(opts.get("title", "Stability map: status and estimated COR error"))
    return fig


def json_materials(ds) -> dict:
    """The material parameter dicts stored in a sweep dataset's attributes."""
    import json

    return json.loads(ds.attrs["materials"])


def _fixed_axes(sweep, opts, free):
    """Selection of the axes a line figure does not draw: an option naming the axis picks its value
    (e.g. ``nu: 0.5``), else the first value. Returns (selection dict, label suffix)."""
    sel = {}
    for d in sweep["cor"].dims:
        if d in free:
            continue
        if d in opts:
            values = sweep[d].values
            if opts[d] not in values:
                raise ValueError(f"figure option {d}: {opts[d]!r} is not on the sweep's {d} axis {list(values)}")
            sel[d] = opts[d]
        else:
            sel[d] = sweep[d].values[0]
    units = {d: sweep[d].attrs.get("units", "") for d in sel}
    text = ", ".join(f"{d} = {v:g} {units[d] if units[d] != '1' else ''}".rstrip() for d, v in sel.items())
    return sel, (f" ({text})" if text else "")


def cor_temperature(sweep, opts):
    """Issue 12: COR against temperature T (deg C), one line per material and impact speed v0; any other
    axis at the value the options name (e.g. ``nu: 0.5``) or its first; points not ok as red crosses."""
    if "T" not in sweep.dims:
        raise ValueError("figure cor_temperature needs a sweep with a temperature axis T (deg C)")
    fig, ax = plt.subplots(figsize=(6.5, 4.5), layout="constrained")
    nbad = 0
    sel, fixed = _fixed_axes(sweep, opts, ("material", "T", "v0"))
    v0s = opts.get("v0s", list(sweep["v0"].values))
    for m in sweep["material"].values:
        for v0 in v0s:
            d = sweep.sel(material=m, v0=v0, **sel)
            ok = d["status"].values == 0
            ax.plot(d["T"].values[ok], d["cor"].values[ok], "o-", ms=3, label=f"{m}, v0 = {v0:g} m/s")
            nbad += _mark_failed(ax, d["T"].values, ok)
    ax.set_xlabel("T [deg C]")
    ax.set_ylabel("COR")
    ax.set_title("COR against temperature" + fixed + (f", {nbad} not ok" if nbad else ""), fontsize=9)
    ax.legend(fontsize=7)
    return fig


def cor_v0_temperature(sweep, opts):
    """Issue 12: COR against v0 (m/s), one line per temperature (option ``T``: a list of values on the
    sweep's T axis; default: five spread over it), one panel per material; other axes as in
    :func:`cor_temperature`."""
    if "T" not in sweep.dims:
        raise ValueError("figure cor_v0_temperature needs a sweep with a temperature axis T (deg C)")
    temps = sweep["T"].values
    chosen = opts.get("T", list(temps[np.unique(np.linspace(0, temps.size - 1, min(5, temps.size)).round().astype(int))]))
    missing = [t for t in chosen if t not in temps]
    if missing:
        raise ValueError(f"figure option T: {missing} not on the sweep's T axis {list(temps)}")
    sel, fixed = _fixed_axes(sweep, {k: v for k, v in opts.items() if k != "T"}, ("material", "T", "v0"))
    mats = sweep["material"].values
    fig, axes = plt.subplots(1, len(mats), figsize=(5.0 * len(mats), 4.2), layout="constrained", squeeze=False)
    colors = plt.cm.coolwarm(np.linspace(0, 1, len(chosen)))
    for ax, m in zip(axes[0], mats):
        nbad = 0
        for c, t in zip(colors, chosen):
            d = sweep.sel(material=m, T=t, **sel)
            ok = d["status"].values == 0
            ax.plot(d["v0"].values[ok], d["cor"].values[ok], "o-", ms=3, color=c, label=f"T = {t:g} deg C")
            nbad += _mark_failed(ax, d["v0"].values, ok)
        ax.set_xscale("log")
        ax.set_xlabel("v0 [m/s]")
        ax.set_ylabel("COR")
        ax.set_title(f"{m}" + (f" ({nbad} not ok)" if nbad else ""), fontsize=9)
        ax.legend(fontsize=7)
    fig.suptitle("COR against impact speed at several temperatures" + fixed, fontsize=10)
    return fig


def master_curve(fits, opts):
    """Issue 12: measured-data fits' master curves at T_ref, a column per fit: the shifted data (E', E''
    coloured by the temperature of their set) and the Prony fit, and tan delta, against reduced
    frequency f a_T (Hz); the title gives the fit's rms relative errors of E', E'' and tan delta."""
    import json

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
            fig.colorbar(sc, ax=ax1, label="T of the set [deg C]")
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
        name = json.loads(fit.attrs.get("fit_spec", "{}")).get("data", {}).get("shift_file", "shifts from the data")
        title = f"{fit.attrs.get('data', '')}\nT_ref = {shift.get('T_ref', '?')} deg C; {name}"
        title += "\nrms relative error: " + ", ".join(
            f"{lab} {100 * met[k]:.1f} %" for lab, k in (("E'", "storage_rms"), ("E''", "loss_rms"),
                                                        ("tan delta", "tan_delta_rms")) if k in met)
        ax1.set_title(title, fontsize=8)
    return fig


FIGURES = {
    "cor_temperature": (cor_temperature, ("sweep",)),
    "cor_v0_temperature": (cor_v0_temperature, ("sweep",)),
    "master_curve": (master_curve, ("material_fit",)),
    "fig1": (fig1, ("sweep", "moduli")),
    "fig2": (fig2, ("histories",)),
    "fig3": (fig3, ("histories",)),
    "fig4": (fig4, ("sweep",)),
    "fig5": (fig5, ("sweep", "moduli")),
    "fig6": (fig6, ("histories",)),
    "fig7": (fig7, ("histories",)),
    "fig8": (fig8, ("sweep",)),
    "fig9": (fig9, ("sweep",)),
    "prony_terms": (prony_terms, ("sweep",)),
    "spheres_eps": (spheres_eps, ("spheres",)),
    "spheres_ice": (spheres_ice, ("spheres",)),
    "spheres_hereditary": (spheres_hereditary, ("spheres",)),
    "work_precision": (work_precision, ("convergence",)),
    "stability_map": (stability_map, ("sweep",)),
}


def calibration(cal):
    """Issue 13: a calibration's data (error bars: cor_std), the calibrated model with its 95 % band,
    and the residuals; the title gives the estimates, their standard errors and identifiability."""
    import json

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
    ax1.set_title("\n".join(parts) + f"\nchi2 = {cal.attrs.get('chi2', float('nan')):.3g}, dof = {cal.attrs.get('dof', '?')}",
                  fontsize=8)
    return fig


def save(fig, png, pdf) -> None:
    """Write ``fig`` as PNG (130 dpi, for the report) and PDF (for print), then close it. The PDF
    reuses the layout computed for the PNG (the layout engine is switched off after the first save):
    constrained layout costs up to a second per save on the many log axes of work_precision."""
    fig.savefig(png, dpi=130)
    fig.set_layout_engine("none")
    fig.savefig(pdf, metadata={"CreationDate": None})
    plt.close(fig)


def draw(name, data, opts):
    """Figure ``name`` from its datasets ``data`` (a dict: need -> Dataset, or list of Datasets for
    ``material_fit``) and the scene's options for it."""
    fn, need = FIGURES[name]
    return fn(*(data[n] for n in need), dict(opts or {}))


#: figures that need a grid axis besides v0
NEEDS_AXIS = {"cor_temperature": "T", "cor_v0_temperature": "T"}


def needs(figures) -> set[str]:
    """Datasets the given figures need."""
    out = set()
    for f in figures:
        if f not in FIGURES:
            raise ValueError(f"unknown figure {f!r}; allowed: {sorted(FIGURES)}")
        out.update(FIGURES[f][1])
    return out
