"""Accuracy and cost of the adaptive method's settings against independent references, and the cost of
direct at equal accuracy.

References (not computed by adaptive), per preset at v0 = 0.001, 1, 10, 50, 300 m/s:

* Prony-type kernels (sls, butyl-prony3, elastic, kelvin-voigt): ``ive`` (scipy Radau) at rtol 1e-12;
* the fractional and CERF laws: ``direct`` at 4000, 8000 and 16000 steps per contact-time estimate,
  Richardson-extrapolated (errors h^2 and h^2.5 eliminated); the same from 2000, 4000, 8000 steps gives
  the spread printed beside the table.

Sections:

* ``accuracy``: per setting (rows: the default; four grids for every kernel (RESOLVED_DECAY 0); step_tol;
  soe_tol; no extrapolation; the separation located on a step 8 times finer (the constant SEP_STEPS, not
  an option); other Richardson exponents everywhere: four grids eliminating h^2, h^3, h^4, and three
  grids eliminating h^2, h^4, set through the module constants), the largest relative error of the COR
  and of t0 per preset over the speeds, the steps per impact, and the time per impact (warm median of
  ``vcor.simulate`` at 10 m/s, mean over sls, butyl-fc, butyl-cerf, butyl-prony3);
* ``equal_accuracy``: per preset at 10 m/s, adaptive's COR error and time, and the time of ``direct``
  (numba, O(N^2)) at the steps that give the same COR error: plain (error ~ N^-2, N from two runs, then
  run), and Richardson-extrapolated from N, 2N, 4N steps (h^2 and h^2.5 eliminated; its N the smallest
  power-of-two multiple of 125 steps per contact time that reaches the error); the ratios adaptive / direct.

Every run is a fresh process with an empty numba cache; timings are warm medians; cells give the median
over runs (min–max); errors are the same in every run.

Run: python benchmarks/bench_accuracy.py [--runs 2] [--quick] [--out FILE]
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import tempfile
from pathlib import Path

import numpy as np

import timing

PRESETS = ("sls", "butyl-prony3", "butyl-fc", "butyl-cerf", "elastic", "kelvin-voigt")
TIMED = ("sls", "butyl-fc", "butyl-cerf", "butyl-prony3")
SPEEDS = (0.001, 1.0, 10.0, 50.0, 300.0)
#: rows of the accuracy table: label, simulate keywords, module constants to set (name: value)
SETTINGS = (
    ("default (four grids h^2, h^3.5, h^4, three grids h^2, h^4 where resolved; step_tol 4e-4)", {}, {}),
    ("four grids everywhere (RESOLVED_DECAY 0)", {}, {"RESOLVED_DECAY": 0.0}),
    ("step_tol 8e-4", {"step_tol": 8e-4}, {}),
    ("step_tol 1.5e-3", {"step_tol": 1.5e-3}, {}),
    ("step_tol 1e-3", {"step_tol": 1e-3}, {}),
    ("step_tol 6e-4", {"step_tol": 6e-4}, {}),
    ("step_tol 3e-4", {"step_tol": 3e-4}, {}),
    ("step_tol 1e-4", {"step_tol": 1e-4}, {}),
    ("soe_tol 1e-8", {"soe_tol": 1e-8}, {}),
    ("soe_tol 1e-12", {"soe_tol": 1e-12}, {}),
    ("separation step 8x finer", {}, {"SEP_STEPS": 8192}),
    ("no extrapolation (one grid)", {"richardson": False}, {}),
    ("four grids (h^2, h^3, h^4)", {}, {"exponents": (2.0, 3.0, 4.0)}),
    ("four grids (h^2, h^3, h^4), step_tol 1e-3", {"step_tol": 1e-3}, {"exponents": (2.0, 3.0, 4.0)}),
    ("three grids (h^2, h^4), step_tol 3e-4", {"step_tol": 3e-4}, {"exponents": (2.0, 4.0)}),
    ("three grids (h^2, h^4), step_tol 1.5e-4", {"step_tol": 1.5e-4}, {"exponents": (2.0, 4.0)}),
)


def references(quick: bool) -> dict:
    """{"name@v0": (cor, t0, spread of the COR)} (module docstring)."""
    import vcor

    out = {}
    for name in PRESETS:
        for v0 in SPEEDS[1:3] if quick else SPEEDS:
            if vcor.materials.get(name).is_prony:
                r = vcor.simulate(name, v0, method="ive", rtol=1e-12)
                spread = abs(vcor.simulate(name, v0, method="ive", rtol=1e-11).cor / r.cor - 1)
                out[f"{name}@{v0}"] = (r.cor, r.t0, spread)
            else:
                fine, coarse = (_richardson_direct(name, v0, base) for base in (4000, 2000))
                out[f"{name}@{v0}"] = (*fine, abs(coarse[0] / fine[0] - 1))
    return out


def _richardson_direct(name, v0, base):
    """(COR, t0) of direct at base, 2 base, 4 base steps per contact time, extrapolated (h^2, h^2.5)."""
    import vcor

    runs = [vcor.simulate(name, v0, method="direct", steps_per_contact=base * k, max_steps=10**7) for k in (1, 2, 4)]
    w = _weights((2.0, 2.5))
    return float(sum(wj * r.cor for wj, r in zip(w, runs))), float(sum(wj * r.t0 for wj, r in zip(w, runs)))


def _weights(exponents):
    n = len(exponents) + 1
    rows = np.array([[1.0] + [2.0 ** (-p * j) for p in exponents] for j in range(n)])
    return np.linalg.solve(rows.T, np.eye(n)[0])


def _set_constants(constants: dict):
    """Set the adaptive module's constants for a row; returns the previous values."""
    from vcor.solvers import adaptive

    old = {k: getattr(adaptive, k) for k in ("SEP_STEPS", "SPLIT_LEVELS", "GRIDS", "RICHARDSON_WEIGHTS",
                                              "RESOLVED_DECAY")}
    for name in ("SEP_STEPS", "RESOLVED_DECAY"):
        if name in constants:
            setattr(adaptive, name, constants[name])
    if "exponents" in constants:
        # these grids everywhere: no smaller set where the kernel is resolved
        grids = len(constants["exponents"]) + 1
        adaptive.SPLIT_LEVELS, adaptive.GRIDS, adaptive.RESOLVED_DECAY = grids - 1, grids, 0.0
        adaptive.RICHARDSON_WEIGHTS = tuple(float(w) for w in _weights(constants["exponents"]))
    return old


def measure_accuracy(args, refs):
    import vcor
    from vcor.solvers import adaptive

    calls = 3 if args.quick else 31
    rows = []
    for label, kw, constants in SETTINGS:
        old = _set_constants(constants)
        try:
            errors, steps = {}, []
            for key, (cor, t0, _) in refs.items():
                name, v0 = key.split("@")
                r = vcor.simulate(name, float(v0), **kw)
                errors[key] = (abs(r.cor / cor - 1), abs(r.t0 / t0 - 1)) if r.ok else (math.inf, math.inf)
                steps.append(r.steps)
            times = [timing.warm_median(lambda n=n, k=kw: vcor.simulate(n, 10.0, **k), calls) for n in TIMED]
        finally:
            for k, v in old.items():
                setattr(adaptive, k, v)
        rows.append({"label": label, "errors": errors, "steps": float(np.mean(steps)), "time": float(np.mean(times))})
    return rows


def _equal_direct_steps(name, v0, target, ref_cor):
    """Steps per contact time at which plain direct's COR error is ``target`` (error ~ N^-2)."""
    import vcor

    n1, n2 = 1000, 4000
    e1, e2 = (abs(vcor.simulate(name, v0, method="direct", steps_per_contact=n).cor / ref_cor - 1) for n in (n1, n2))
    order = math.log(e1 / e2) / math.log(n2 / n1) if e2 > 0 and e1 > e2 else 2.0
    return max(10, round(n2 * (e2 / target) ** (1.0 / order)))


def measure_equal_accuracy(args, refs):
    import vcor
    from vcor.contact.impact import make_impact
    from vcor.solvers import direct

    calls = 3 if args.quick else 21
    out = {}
    for name in TIMED:
        cor_ref = refs[f"{name}@10.0"][0]
        t_a, res = timing.warm_timed(lambda n=name: vcor.simulate(n, 10.0), calls)
        err = max(abs(res.cor / cor_ref - 1), 1e-12)
        impact = make_impact(name, 10.0, {})
        tc = impact.contact_time_estimate()

        def plain(spc, i=impact, t=tc):
            dt = t / spc
            return direct.run_direct(i, dt, math.ceil(1.5 * t / dt), max_steps=10**8)

        spc = _equal_direct_steps(name, 10.0, err, cor_ref)
        t_p, rp = timing.warm_timed(lambda s=spc: plain(s), max(3, calls // 5))
        w = _weights((2.0, 2.5))
        base = 125
        while True:
            runs = [plain(base * k) for k in (1, 2, 4)]
            e_r = abs(sum(wj * r.cor for wj, r in zip(w, runs)) / cor_ref - 1)
            if e_r <= err or base >= 64000:
                break
            base *= 2
        t_r = timing.warm_median(lambda b=base: [plain(b * k) for k in (1, 2, 4)], max(3, calls // 5))
        out[name] = {"err": err, "t_a": t_a, "spc": spc, "err_plain": abs(rp.cor / cor_ref - 1), "t_plain": t_p,
                     "base": base, "err_rich": e_r, "t_rich": t_r}
    return out


def measure(args):
    refs = json.loads(Path(args.refs).read_text())
    return {"accuracy": measure_accuracy(args, refs), "equal": measure_equal_accuracy(args, refs)}


def report(args, results, refs):
    c = timing.cell
    names = list(PRESETS)
    speeds = sorted({float(k.split("@")[1]) for k in refs})
    blocks = [f"Relative errors against independent references (ive Radau at rtol 1e-12 for the Prony-type "
              f"kernels; direct at 4000, 8000, 16000 steps per contact-time estimate, Richardson-extrapolated, for "
              f"butyl-fc and butyl-cerf), largest over v0 = {', '.join(f'{v:g}' for v in speeds)} m/s, per "
              f"preset: COR / t0. Steps: per impact, mean over these cases (all grids). Time: warm median of "
              f"vcor.simulate at 10 m/s, mean over {', '.join(TIMED)}; median over {args.runs} fresh processes "
              f"(min–max). The references' own spread (the same at rtol 1e-11, or from 2000 steps): largest "
              f"{max(v[2] for v in refs.values()):.1e}."]
    rows = []
    for i, first in enumerate(results[0]["accuracy"]):
        runs = [r["accuracy"][i] for r in results]
        cells = []
        for name in names:
            errs = [first["errors"][f"{name}@{v}"] for v in speeds if f"{name}@{v}" in first["errors"]]
            cells.append(f"{max(e[0] for e in errs):.1e} / {max(e[1] for e in errs):.1e}")
        worst = max(max(e) for e in first["errors"].values())
        rows.append([first["label"], *cells, f"{worst:.1e}", f"{first['steps']:.0f}",
                     c([r["time"] for r in runs], 1e6, ".0f")])
    blocks.append(timing.table(["setting", *names, "worst", "steps", "time [µs]"], rows))
    eq = [r["equal"] for r in results]
    rows = []
    for name in TIMED:
        e = eq[0][name]
        rows.append([name, f"{e['err']:.1e}", c([x[name]["t_a"] for x in eq], 1e3, ".3f"), e["spc"],
                     f"{e['err_plain']:.1e}", c([x[name]["t_plain"] for x in eq], 1e3, ".1f"),
                     c([x[name]["t_a"] / x[name]["t_plain"] for x in eq], 1.0, ".4f"), e["base"],
                     f"{e['err_rich']:.1e}", c([x[name]["t_rich"] for x in eq], 1e3, ".2f"),
                     c([x[name]["t_a"] / x[name]["t_rich"] for x in eq], 1.0, ".3f")])
    blocks.append("Equal accuracy, v0 = 10 m/s: adaptive at its defaults (whole simulate call) against direct's "
                  "numba O(N^2) march (vcor.solvers.direct.run_direct: weights and march) at the steps per "
                  "contact time that give the same COR error: plain (N from the measured order), and "
                  "Richardson-extrapolated from N, 2N, 4N (N: the smallest of 125 x 2^k reaching the error).")
    blocks.append(timing.table(["material", "adaptive error", "adaptive [ms]", "plain N", "plain error",
                                "plain [ms]", "adaptive / plain", "Richardson N", "Richardson error",
                                "Richardson [ms]", "adaptive / Richardson"], rows))
    return blocks


def main():
    p = timing.parser(__doc__, quick="two speeds, a few calls")
    p.add_argument("--refs", help=argparse.SUPPRESS)  # a worker's references (JSON file)
    args = p.parse_args()
    if args.worker:
        if args.refs is None:
            print(json.dumps(references(args.quick)))
        else:
            print(json.dumps(measure(args)))
        return
    flags = timing.quick_flags(args)
    refs = timing.fresh_json([timing.PYTHON, __file__, timing.WORKER_FLAG, *flags])
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "refs.json"
        path.write_text(json.dumps(refs))
        results = timing.worker_runs(args.runs, "--refs", str(path), *flags)
    timing.publish(args.out, args.runs, report(args, results, refs))


if __name__ == "__main__":
    sys.exit(main())
