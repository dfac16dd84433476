"""Measured DMA data: vcor's fit against pyvisco 2.1.3 on pyvisco's raw example
(``data/pyvisco/freq_user_raw.csv``, 21 sets, T_ref = -5 deg C), and how mastercurves 0.2.3 shifts
the same sets.

Rows of the main table, each fitted in its own fresh process (``OPENBLAS_NUM_THREADS=1``, an empty
``NUMBA_CACHE_DIR``), ``--runs`` times:

* vcor ``method: spectrum`` with ``instrument_lag: true`` (the default config's fit) and without it:
  :func:`vcor.fitting.fits.run_fit` on the fit spec ``{model: prony, data: {file, T_ref: -5,
  instrument_lag?}}`` (the workflow's fit rule; with the lag, the master curve is the data with the
  fitted lag removed);
* pyvisco: ``master.get_aT`` (its own shifts), ``get_curve``, ``smooth(win=1)``,
  ``prony.discretize(window="round")`` and ``prony.fit(opt=False)``; and the same followed by
  ``opt.nprony(window="min", opt=1.5)``, run with ``/tmp/spec/venv/bin/python`` where it exists;
* mastercurves: shifts only (Gaussian-process superposition of ln E' against ln f).

Every fit is measured against its own master curve (its own shifts) by one function,
:func:`vcor.fitting.spectrum.model.fit_metrics`, in this process: rms relative errors of E', E'' and
tan delta over the master-curve points, and local extrema of the fitted tan delta on 2000
log-spaced frequencies over the data's reduced range. "fit" is the time from reading the file to the
Prony terms, measured inside the worker; "process" is the worker's wall time (imports included).
The tables below the first are computed once, in this process.

Run: python benchmarks/bench_dma.py [--runs 3] [--out docs/_generated/dma.md]
"""

from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

import timing

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "data" / "pyvisco" / "freq_user_raw.csv"
SHIPPED = ROOT / "data" / "pyvisco" / "freq_user_master__shift_factors.csv"
T_REF = -5.0
VENV_PYTHON = Path("/tmp/spec/venv/bin/python")
PYVISCO = "pyvisco==2.1.3"
MASTERCURVES = "mastercurves==0.2.3"
#: method key -> (label, interpreter: "vcor" or "venv")
METHODS = {
    "spectrum-lag": ("vcor `method: spectrum`, `instrument_lag: true` (the default config's fit)", "vcor"),
    "spectrum": ("vcor `method: spectrum`, data as measured", "vcor"),
    "pyvisco-fit": ("pyvisco 2.1.3: `get_aT` + `prony.fit`", "venv"),
    "pyvisco-nprony": ("pyvisco 2.1.3: `get_aT` + `prony.fit` + `opt.nprony`", "venv"),
    "mastercurves": ("mastercurves 0.2.3 (E', `fixed_noise` 0.04)", "venv"),
}
THREAD_ENV = {"OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}


# --- workers (each prints one JSON line; the venv ones import neither vcor nor anything outside the venv)

def _worker_vcor(method):
    t_import = time.perf_counter()
    from vcor.fitting import fits

    t0 = time.perf_counter()
    lag = method == "spectrum-lag"
    result, data, _ = fits.run_fit({"model": "prony", "data": {"file": str(DATA), "T_ref": T_REF,
                                                                "instrument_lag": lag}})
    fit_time = time.perf_counter() - t0
    m = result.material
    return {"fit": fit_time, "import": t0 - t_import, "E_inf": m.E_inf, "E": list(m.E), "tau": [1 / b for b in m.beta],
            "f": (data.omega / (2 * math.pi)).tolist(), "E_stor": data.E_star.real.tolist(),
            "E_loss": data.E_star.imag.tolist()}


def _worker_pyvisco(nprony):
    import contextlib
    import io

    from pyvisco import load, master, opt, prony

    t0 = time.perf_counter()
    with contextlib.redirect_stdout(io.StringIO()):
        df_raw, _, _ = load.user_raw(load.file(str(DATA)), "freq", "E")
        df_aT, _ = master.get_aT(df_raw, T_REF)
        df_master = master.smooth(master.get_curve(df_raw, df_aT, T_REF), 1)
        p = prony.fit(prony.discretize(df_master, "round", 0), df_master, opt=False)[0]
        if nprony:
            fits_, n_opt, _ = opt.nprony(df_master, p, window="min", opt=1.5)
            p = fits_[n_opt]
    fit_time = time.perf_counter() - t0
    alpha, tau = p["df_terms"]["alpha_i"].values, p["df_terms"]["tau_i"].values
    E0 = float(p["E_0"])
    return {"fit": fit_time, "E_inf": E0 * (1 - float(alpha.sum())), "E": (E0 * alpha).tolist(), "tau": tau.tolist(),
            "f": df_master["f"].tolist(), "E_stor": df_master["E_stor"].tolist(),
            "E_loss": df_master["E_loss"].tolist(), "T": df_aT["T"].tolist(), "log_aT": df_aT["log_aT"].tolist()}


def _worker_mastercurves(sets_file, variants):
    import warnings

    import numpy as np

    warnings.filterwarnings("ignore")
    from mastercurves import MasterCurve
    from mastercurves.transforms import Multiply

    sets = json.loads(Path(sets_file).read_text())
    out = {}
    for variant in variants:
        quantity, noise = variant.split(":")
        mc = MasterCurve(fixed_noise=float(noise))
        y = [np.log(np.asarray(s["E_stor"])) if quantity == "E_stor"
             else np.log(np.asarray(s["E_loss"]) / np.asarray(s["E_stor"])) for s in sets]
        mc.add_data([np.log(np.asarray(s["f"])) for s in sets], y, [s["T"] for s in sets])
        # the default bounds (1e-2, 1) allow 2 decades per step; these data have steps of up to 2.4
        mc.add_htransform(Multiply(bounds=(1e-4, 1), scale="log"))
        t0 = time.perf_counter()
        mc.superpose()
        out[variant] = {"fit": time.perf_counter() - t0, "a": [float(v) for v in mc.hparams[0]],
                        "u": [float(v) for v in mc.huncertainties[0]]}
    return out


def _worker(argv):
    kind = argv[0]
    if kind in ("spectrum-lag", "spectrum"):
        return _worker_vcor(kind)
    if kind in ("pyvisco-fit", "pyvisco-nprony"):
        return _worker_pyvisco(kind == "pyvisco-nprony")
    if kind == "mastercurves":
        return _worker_mastercurves(argv[1], argv[2:])
    raise SystemExit(f"unknown worker {kind!r}")


# --- running the workers ---------------------------------------------------------------------------

def _interpreter(where):
    return sys.executable if where == "vcor" else (str(VENV_PYTHON) if VENV_PYTHON.exists() else None)


def run_worker(method, *args):
    """(JSON result, wall time of the process in s) of one fresh worker process."""
    python = _interpreter(METHODS[method][1])
    cmd = [python, str(Path(__file__).resolve()), "--worker", method, *args]
    env = dict(THREAD_ENV)
    if METHODS[method][1] == "vcor":
        env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT / "src"), os.environ.get("PYTHONPATH")]))
    p = timing.run_fresh(cmd, env=env, cwd=ROOT)
    return json.loads(p.stdout.strip().splitlines()[-1]), p.wall


# --- the report ------------------------------------------------------------------------------------

def _pct(x):
    return f"{100 * x:.2f} %"


def _metrics(r):
    import numpy as np

    from vcor.fitting import spectrum

    return spectrum.fit_metrics(r["E_inf"], np.asarray(r["E"]), np.asarray(r["tau"]), np.asarray(r["f"]),
                                np.asarray(r["E_stor"]), np.asarray(r["E_loss"]))


def main_table(runs):
    """Rows of the comparison table and the per-method results of the first run."""
    rows, first = [], {}
    for method, (label, where) in METHODS.items():
        if _interpreter(where) is None:
            pkg = MASTERCURVES if method == "mastercurves" else PYVISCO
            rows.append([label, f"{pkg.split('==')[0]} not installed (pip install {pkg})", "", "", "", "", "", ""])
            continue
        extra = []
        if method == "mastercurves":
            extra = [str(SETS_FILE), "E_stor:0.04"]
        res = [run_worker(method, *extra) for _ in range(runs)]
        fit_times = [r["E_stor:0.04"]["fit"] if method == "mastercurves" else r["fit"] for r, _ in res]
        walls = [w for _, w in res]
        first[method] = res[0][0]
        if method == "mastercurves":
            rows.append([label, "shifts only (below)", "", "", "", "", timing.cell(fit_times), timing.cell(walls)])
            continue
        mets = [_metrics(r) for r, _ in res]
        same = all(m == mets[0] for m in mets)
        m = mets[0]
        rows.append([label, _pct(m["E_stor_rms"]), _pct(m["E_loss_rms"]), _pct(m["tan_delta_rms"]),
                     str(m["tan_delta_extrema"]) + ("" if same else " (runs differ)"), len(res[0][0]["E"]),
                     timing.cell(fit_times), timing.cell(walls)])
    return rows, first


def detail_tables(first):
    """The tables computed once in this process: shifts, the instrument lag, shift functions, lambda,
    merging, weights, the tan delta excess by measured frequency, mastercurves."""
    import numpy as np

    from vcor.fitting import dma, spectrum

    table = dma.read_table(DATA)
    raw = table.columns
    sets = dma.split_sets(raw)
    T = np.array([s.T for s in sets])
    fit = dma.fit_dma(raw, T_REF, lag=True)          # the default config's fit
    fit0 = dma.fit_dma(raw, T_REF)                   # the data as measured
    s1 = fit.spline_shifts
    blocks = []

    def corrected(fx):
        """The master curve of a fit's shifts with its lag removed (dma.superpose)."""
        return dma.superpose(table, T_REF, log_aT=fx.log_aT, lag=fx.lag)

    def merged_metrics(fx):
        e_inf, e, beta = fx.prony_terms()
        mc_ = corrected(fx)
        return spectrum.fit_metrics(e_inf, e, 1 / beta, mc_.f_red, mc_.E_stor, mc_.E_loss)

    # shifts per set
    pv = first.get("pyvisco-fit")
    mc = _mastercurves_shifts(T, first.get("mastercurves"))
    head = ["T [°C]", "stage 1 (spline)", "final (joint, lag fitted)", "final (joint, data as measured)",
            "rms log10 E' of the set about the stage-1 curve", "pyvisco `get_aT`", "mastercurves"]
    rows = []
    for k in range(T.size):
        rows.append([f"{T[k]:.2f}", f"{s1.log_aT[k]:.2f} ± {s1.log_aT_std[k]:.2f}",
                     f"{fit.log_aT[k]:.2f} ± {fit.log_aT_std[k]:.2f}",
                     f"{fit0.log_aT[k]:.2f} ± {fit0.log_aT_std[k]:.2f}",
                     f"{s1.set_rms['E_stor'][k]:.4f}",
                     f"{pv['log_aT'][k]:.2f}" if pv else "-",
                     f"{mc['E_stor:0.04']['log_aT'][k]:.2f} ± {mc['E_stor:0.04']['std'][k]:.2f}" if mc else "-"])
    sup = {name: dma.superposition_rms(raw, la)["E_stor"] for name, la in
           [("stage 1", s1.log_aT), ("final, lag fitted", fit.log_aT), ("final, data as measured", fit0.log_aT)]
           + ([("pyvisco `get_aT`", np.asarray(pv["log_aT"]))] if pv else [])
           + ([("mastercurves", mc["E_stor:0.04"]["log_aT"])] if mc else [])}
    blocks += ["**Shift factors** log10 a_T (decades, 0 at T_ref = -5 °C; ± the standard error: the joint fit's "
               "sandwich covariance; mastercurves: its own error, accumulated from the reference set).",
               timing.table(head, rows),
               "How well each set of shifts superposes E' (rms of log10 E' about one P-spline through all sets, "
               "`superposition_rms`): " + ", ".join(f"{k} {v:.4f}" for k, v in sup.items()) + "."]

    # the instrument lag
    rows = []
    for label, fx in (("data as measured", fit0), ("lag fitted (default config)", fit)):
        m = merged_metrics(fx)
        rows.append([label, f"{1e6 * fx.lag:.1f} ± {1e6 * fx.lag_std:.1f}" if fx.lag else "-",
                     f"{2 * math.pi * 100 * fx.lag:.4f}" if fx.lag else "-", _pct(m["E_stor_rms"]),
                     _pct(m["E_loss_rms"]), _pct(m["tan_delta_rms"]), m["tan_delta_extrema"], fx.reduced.n_modes])
    blocks += ["**The instrument's time lag** (fitted with the shifts and the spectrum; merged series against its "
               "own master curve, with the lag removed from the data where it is fitted).",
               timing.table(["fit", "lag Δt [µs]", "phase at 100 Hz [rad]", "E' rms", "E'' rms", "tan δ rms",
                             "tan δ extrema", "modes"], rows)]

    # shift functions
    rows = [["WLF, all sets", f"C1 = {fit.wlf['C1']:.4g}, C2 = {fit.wlf['C2']:.4g} K", f"{fit.wlf['rms']:.2f}",
             f"{np.max(np.abs(fit.wlf['residual'])):.2f}"],
            ["Arrhenius, all sets", f"E_a = {fit.arrhenius['E_a'] / 1e3:.0f} kJ/mol", f"{fit.arrhenius['rms']:.2f}",
             f"{np.max(np.abs(fit.arrhenius['residual'])):.2f}"]]
    hot = T >= T_REF
    w_hot = dma.wlf_fit(T[hot], fit.log_aT[hot], T_REF, sigma=fit.log_aT_std[hot])
    rows.append([f"WLF, sets at T ≥ T_ref ({hot.sum()})", f"C1 = {w_hot['C1']:.4g}, C2 = {w_hot['C2']:.4g} K",
                 f"{w_hot['rms']:.2f}", f"{np.max(np.abs(w_hot['residual'])):.2f}"])
    blocks += ["**Shift functions fitted to the final shifts** (lag fitted; weighted by their standard errors; "
               "residuals in decades; C1 is bounded at 1e4 and C2 at 1e5 K).",
               timing.table(["function", "constants", "rms residual", "largest residual"], rows)]

    # lambda
    mcurve = corrected(fit)
    rows = []
    for lam in ("gcv1se", "gcv", "lcurve", 100.0):
        sp_ = spectrum.fit_spectrum(mcurve.f_red, mcurve.E_stor, mcurve.E_loss,
                                    components=(1.0, dma.LOSS_WEIGHT), lam=lam)
        m = sp_.metrics
        rows.append([f"`{lam}`" if isinstance(lam, str) else f"fixed {lam:g}", f"{sp_.lam:.3g}",
                     _pct(m["E_stor_rms"]), _pct(m["E_loss_rms"]), m["tan_delta_extrema"]])
    blocks += [f"**Choice of lambda** (the smooth spectrum at the final shifts, the lag removed from the data, "
               f"{spectrum.PER_DECADE:g} modes per decade, before merging).",
               timing.table(["lam", "lambda", "E' rms", "E'' rms", "tan δ extrema"], rows)]

    # merging, at the final shifts and at the shipped shift factors (given: the spectrum alone)
    shipped = dma.superpose(table, T_REF, dma.read_table(SHIPPED)).log_aT
    f_pv = dma.fit_dma(raw, T_REF, log_aT=shipped)
    rows = []
    for label, fx, densities in (("final (joint, lag fitted)", fit, (1.0, 1.5, 2.0, 3.0)),
                                 ("pyvisco's shipped", f_pv, (2.0, 3.0))):
        rows.append([label, "none (fine grid)", fx.spectrum.n_modes, "-", "-", "-",
                     fx.spectrum.metrics["tan_delta_extrema"]])
        for pd in densities:
            red = spectrum.reduce_modes(fx.spectrum, pd)
            c = red.change
            rows.append([label, f"{pd:g}", red.n_modes, _pct(c["E_stor_max"]), _pct(c["E_loss_max"]),
                         _pct(c["tan_delta_max"]), c["tan_delta_extrema"]])
    blocks += ["**Merging the fine spectrum** (`reduce_modes`, NNLS re-fit): largest change against the smooth "
               "fit over the data's reduced range, and the merged series' tan δ extrema (2000 points). The "
               "material is the 2 modes/decade series. Shipped shift factors: "
               "`data/pyvisco/freq_user_master__shift_factors.csv`, given (no shift fit).",
               timing.table(["shifts", "modes per decade", "modes", "E' change", "E'' change", "tan δ change",
                             "tan δ extrema"], rows)]

    # weights of E'', and shifts refined with the spectrum or not
    rows = []
    for shifts, kk in (("joint (final)", True), ("stage 1 only", False)):
        for label, comp in (("1/100 (default)", (1.0, dma.LOSS_WEIGHT)), ("1 (equal)", (1.0, 1.0))):
            f2 = fit if kk and comp[1] == dma.LOSS_WEIGHT else dma.fit_dma(raw, T_REF, components=comp,
                                                                                 kk_refine=kk, lag=True)
            m = merged_metrics(f2)
            rows.append([shifts, label, f"{1e6 * f2.lag:.1f}", _pct(m["E_stor_rms"]), _pct(m["E_loss_rms"]),
                         m["tan_delta_extrema"], len(f2.joint.at_bound) if kk else "-"])
    blocks += ["**Shifts refined with the spectrum, and the weight a'' of the relative E'' residuals** (whole "
               "chain with the lag fitted, merged series, each against its own master curve; stage 1 only: the "
               "spectrum and the lag fitted at the spline shifts, `kk_refine=False`).",
               timing.table(["shifts", "a''", "lag [µs]", "E' rms", "E'' rms", "tan δ extrema",
                             "joint steps at the overlap bound"], rows)]

    # tan delta excess by measured frequency
    freqs = np.unique(np.round(np.concatenate([s.f for s in sets]), 6))
    excess = {(float(fq), which): [] for fq in freqs for which in (0, 1)}
    for which, fx in enumerate((fit0, fit)):
        e_inf, e, beta = fx.prony_terms()
        for s, la in zip(sets, fx.log_aT, strict=True):
            model = spectrum.complex_modulus(2 * math.pi * s.f * 10**la, e_inf, e, 1 / beta)
            model = model * np.exp(2j * math.pi * s.f * fx.lag)        # as the instrument measures it
            for fq, d in zip(np.round(s.f, 6), s.E_loss / s.E_stor - model.imag / model.real, strict=True):
                excess[float(fq), which].append(d)
    rows = [[f"{fq:.3g}"] + [f"{statistics.median(excess[fq, w]):+.4f} ({min(excess[fq, w]):+.4f} .. "
                             f"{max(excess[fq, w]):+.4f})" for w in (0, 1)] for fq in map(float, freqs)]
    blocks += ["**Measured tan δ minus the fitted one, by measured frequency** (over the 21 sets: median (range)). "
               "With the lag fitted, the fit is compared as the instrument measures it (its E* times "
               "exp(i 2π f Δt)).",
               timing.table(["measured f [Hz]", "data as measured", "lag fitted"], rows)]

    # mastercurves
    if mc:
        ref = s1.log_aT
        rows = []
        for variant, v in mc.items():
            dev = np.abs(v["log_aT"] - ref)
            warm = T >= -12.5
            bound = int(np.sum(np.isclose(np.abs(np.diff(v["log_aT"])), 4.0, atol=1e-3)))
            rows.append([variant.replace("E_stor", "E'").replace("tan_delta", "tan δ").replace(":", ", noise "),
                         f"{v['fit']:.1f}", f"{np.max(dev[warm]):.2f}", f"{np.max(dev):.2f}",
                         f"{v['std'][0]:.2f}", f"{int(np.sum(~np.isfinite(v['std'])))}", str(bound),
                         f"{dma.superposition_rms(raw, v['log_aT'])['E_stor']:.4f}"])
        a, b = mc["E_stor:0.04"]["std"][0], mc["E_stor:0.01"]["std"][0]
        blocks += ["**mastercurves 0.2.3** (`Multiply(bounds=(1e-4, 1), scale=\"log\")`, states cold to hot, "
                   "anchored at T_ref like vcor's) against vcor's stage-1 shifts.",
                   timing.table(["run", "time [s]", "largest difference from -12 °C up", "largest difference",
                                 f"error at {T[0]:.1f} °C", "NaN errors", "steps at the 4-decade bound",
                                 "rms log10 E' at its shifts"], rows),
                   f"Its error of the coldest shift moves {a / b:.1f}x between `fixed_noise` 0.04 and 0.01."]
    return blocks


def _mastercurves_shifts(T, timed):
    """The mastercurves runs as log10 a_T anchored at T_ref and errors from the reference set."""
    import numpy as np

    from vcor.fitting import dma

    if timed is None:
        return None
    runs = dict(timed)
    runs.update(run_worker("mastercurves", str(SETS_FILE), "E_stor:0.01", "tan_delta:0.04")[0])
    A = dma.anchor_matrix(T, T_REF)
    k = int(np.argmin(np.abs(T - T_REF)))
    out = {}
    for variant, r in runs.items():
        a, u = np.asarray(r["a"]), np.asarray(r["u"])
        std = u / (a * math.log(10))                   # accumulated from the coldest state
        pair = np.concatenate([[0.0], np.sqrt(np.maximum(np.diff(std**2), 0))])
        with np.errstate(invalid="ignore"):
            std_ref = np.array([math.sqrt(np.sum(pair[min(i, k) + 1:max(i, k) + 1] ** 2)) for i in range(T.size)])
        out[variant] = {"fit": r["fit"], "log_aT": A @ np.log10(a), "std": std_ref}
    return out


SETS_FILE = None


def main():
    global SETS_FILE
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", type=Path, help="write the tables (Markdown) to this file, atomically")
    p.add_argument("--runs", type=int, default=3, help="fresh processes per method (default 3)")
    p.add_argument("--worker", nargs="+", help=argparse.SUPPRESS)
    args = p.parse_args()
    if args.worker:
        print(json.dumps(_worker(args.worker)))
        return
    if args.runs < 1:
        p.error("--runs must be >= 1")
    sys.path.insert(0, str(ROOT / "src"))
    from vcor.fitting import dma

    with tempfile.TemporaryDirectory(prefix="vcor-bench-dma-") as tmp:
        SETS_FILE = Path(tmp) / "sets.json"
        SETS_FILE.write_text(json.dumps([{"T": s.T, "f": s.f.tolist(), "E_stor": s.E_stor.tolist(),
                                          "E_loss": s.E_loss.tolist()}
                                         for s in dma.split_sets(dma.read_table(DATA))]))
        rows, first = main_table(args.runs)
        details = detail_tables(first)
    command = timing.invocation()
    versions = [f"numpy {_version('numpy')}, scipy {_version('scipy')}"]
    if VENV_PYTHON.exists():
        versions.append(f"pyvisco and mastercurves from {VENV_PYTHON}")
    text = "\n\n".join([
        timing.header(args.runs, command=command),
        f"pyvisco's raw example (`data/pyvisco/freq_user_raw.csv`, 21 sets), T_ref = {T_REF:g} °C. Each row is "
        f"fitted in its own fresh process ({', '.join(f'{k}=1' for k in THREAD_ENV)}, an empty NUMBA_CACHE_DIR), "
        f"{args.runs} times; times: median (min–max). Errors: rms of fit/data − 1 over each fit's own master "
        f"curve; tan δ extrema: local extrema of the fitted tan δ on 2000 log-spaced frequencies over the data's "
        f"reduced range ({'; '.join(versions)}).",
        timing.table(["fit", "E' rms", "E'' rms", "tan δ rms", "tan δ extrema", "modes", "fit [s]", "process [s]"],
                     rows),
        *details])
    text += "\n"
    if args.out:
        timing.write_atomic(args.out, text)
        os.chmod(args.out, 0o644)          # the temporary file's 0600 would stay with the rename
        print(f"wrote {args.out}")
    else:
        print(text, end="")


def _version(name):
    import importlib.metadata

    return importlib.metadata.version(name)


if __name__ == "__main__":
    main()
