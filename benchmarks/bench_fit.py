"""Fit benchmark: the time of each fit of the Bagley–Torvik data (automatic Prony, CERF, Prony with
N = 3, 7, 9, 12) and of the default config's fit of pyvisco's raw DMA example (``fits.pyvisco-polymer``:
global shifts and the instrument lag refined with a smooth spectrum, merged to two Prony terms per
decade, WLF and Arrhenius fitted to the shifts), with each fit's worst relative error.

Each run is a fresh process with an empty numba cache; each time is the median of CALLS warm calls
after one untimed call; cells give the median over runs (min–max).

Run: python benchmarks/bench_fit.py [--runs 2] [--calls 3] [--quick] [--out FILE]
"""

from __future__ import annotations

import timing
from vcor.fitting import fits, prony
from vcor.io.yamlfile import load_yaml


def measure(args):
    calls = timing.calls(args)
    data = prony.bagley_torvik_data()
    cases = [("Prony, automatic N, tol 1 %", lambda: prony.fit_prony(data, None, tol=0.01)),
             ("CERF", lambda: prony.fit_cerf(data))]
    terms = (3, 7) if args.quick else (3, 7, 9, 12)
    cases += [(f"Prony, N = {n}", lambda n=n: prony.fit_prony(data, n)) for n in terms]
    spec = load_yaml(timing.ROOT / "config.yaml")["fits"]["pyvisco-polymer"]
    cases.append(("pyvisco raw DMA (`fits.pyvisco-polymer`): shifts + lag + spectrum",
                  lambda: fits.run_fit(spec, timing.ROOT)[0]))
    out = {}
    for name, fn in cases:
        t, res = timing.warm_timed(fn, calls)
        out[name] = {"time": t, "error": res.max_error, "n_terms": res.n_terms}
    out["calls"] = calls
    return out


def report(args, results):
    r0 = results[0]
    names = [k for k in r0 if k != "calls"]
    rows = [[name, r0[name]["n_terms"] or "-", timing.cell(timing.column(results, name, "time"), 1e3, ".1f"),
             f"{r0[name]['error']:.3e}"] for name in names]
    stage = [r[names[0]]["time"] + r[names[1]]["time"] for r in results]
    rows.append(["material stage (automatic Prony + CERF)", "", timing.cell(stage, 1e3, ".1f"), ""])
    return [f"Fits: median of {r0['calls']} warm call(s) after one untimed call, one fresh process with an empty "
            "numba cache per run; cells: median over runs (min–max).",
            timing.table(["fit", "terms N", "time [ms]", "worst relative error"], rows)]


if __name__ == "__main__":
    timing.main(__doc__, measure, report, quick="one call per fit, N = 3 and 7 only", calls=3)
