"""When the adaptive method's Richardson extrapolation is trusted: its grids' spread and difference ratios
against the true error, on the impacts that set ``vcor.solvers.extrapolation``'s checks.

Impacts: six presets (sls, butyl-prony3, butyl-fc, butyl-cerf, elastic, kelvin-voigt) at 40 log-spaced
speeds 1e-3..300 m/s on the default plate and a rigid target; the points of the ``stability-*`` scenes of
``config.yaml`` but their plates of 3.2 mm and thinner (``ive`` takes seconds to minutes there, and most
of them leave below ``COR_FLOOR``); 32 Kelvin-Voigt gels on a rigid target (E 1e5 and 1e6 Pa, tau 1e-3..1 s,
v0 0.01 and 1 m/s, r 0.1 and 10 mm). References: ``ive`` (scipy Radau) at rtol 1e-12 for Prony-type kernels;
``adaptive`` at step_tol 1.5e-5 for the fractional and CERF laws (its own error against ``direct``'s
Richardson references is below 3e-9). For every impact ``vcor.simulate`` runs at its defaults and the rows
of the grids it extrapolates are recorded (a wrapper around ``vcor.solvers.extrapolation.extrapolate``, the
one function that receives them); the error is max(|COR / ref - 1|, |t0 / ref - 1|).

Printed: per family, the impacts whose grids it extrapolates, how many of them are within 1e-7, the
largest t0 spread (finest against coarse grid, relative, in units of step_tol) among those, and how many of
those have a t0 difference ratio outside RICHARDSON_T0_RATIO with a spread above RICHARDSON_T0_GAP (the
checks' false alarms); then every impact more than 1e-7 off with its spread, ratios and the flag it
carries. The numbers do not depend on the machine: one process computes them.

Run: python benchmarks/bench_extrapolation.py [--quick] [--out FILE]
"""

from __future__ import annotations

import itertools
from pathlib import Path

import numpy as np
import yaml

import timing

PRESETS = ("sls", "butyl-prony3", "butyl-fc", "butyl-cerf", "elastic", "kelvin-voigt")
TARGETS = ("plate", "rigid")
#: stability points on plates this thin or thinner are left out (module docstring)
THIN = 3.2e-3
ACCURACY = 1e-7
CONFIG = Path(__file__).resolve().parents[1] / "config.yaml"


def cases(quick: bool):
    """(family, label, material, v0, simulate keywords) of every impact."""
    from vcor.study import scene

    speeds = np.geomspace(1e-3, 300.0, 8 if quick else 40)
    for name, target, v0 in itertools.product(PRESETS, TARGETS, speeds):
        yield "presets", f"{name} {target} {v0:.4g} m/s", name, float(v0), {"target": target}
    scenes = yaml.safe_load(CONFIG.read_text())["scenes"]
    for name, sc in scenes.items():
        if not name.startswith("stability-"):
            continue
        settings = scene.settings_of(sc)
        for p in scene.scene_points(sc)[:: 6 if quick else 1]:
            material, v0, geometry = scene.build_point(p, settings, None, {})
            if geometry.get("h", 1.0) > THIN:
                yield "stability", f"{name} {p}", material, v0, geometry
    for E, tau, v0, r in itertools.product((1e5, 1e6), (1e-3, 1e-2, 0.1, 1.0), (0.01, 1.0), (1e-4, 1e-2)):
        if not quick or (tau, r) == (0.01, 1e-4):
            yield ("kelvin-voigt gels", f"E {E:g} Pa, tau {tau:g} s, {v0:g} m/s, r {r:g} m",
                   {"model": "kelvin-voigt", "E": E, "tau": tau}, v0, {"target": "rigid", "r": r})


def _material(material):
    """The Material object of a preset name, a spec or a Material."""
    from vcor.materials import get
    from vcor.materials.specs import from_spec

    if isinstance(material, str):
        return get(material)
    return from_spec(material) if isinstance(material, dict) else material


def measure(quick: bool) -> list:
    import vcor
    from vcor.solvers import adaptive, extrapolation

    recorded = []
    plain = extrapolation.extrapolate

    def recording(runs, weights, **kw):
        recorded.append(runs.tolist() if isinstance(runs, np.ndarray) else list(runs))
        return plain(runs, weights, **kw)

    adaptive.extrapolate = recording  # the name richardson_outcome calls
    step_tol = vcor.SolverOptions(method="adaptive").step_tol
    out = []
    try:
        for family, label, material, v0, kw in cases(quick):
            recorded.clear()
            res = vcor.simulate(material, v0, **kw)
            if not (res.ok and recorded):
                continue
            rows = recorded[-1]
            prony = _material(material).is_prony
            ref = (vcor.simulate(material, v0, method="ive", rtol=1e-12, **kw) if prony
                   else vcor.simulate(material, v0, step_tol=1.5e-5, **kw))
            t0 = np.array([r[extrapolation.OUTCOME.index("t0")] for r in rows])
            d = np.diff(t0)
            error = max(abs(res.cor / ref.cor - 1), abs(res.t0 / ref.t0 - 1))
            out.append({"family": family, "label": label, "error": error,
                        "gap": abs(t0[-1] - t0[0]) / t0[-1] / step_tol, "gap_rel": abs(t0[-1] - t0[0]) / t0[-1],
                        "ratios": [float(a / b) if b else float("inf") for a, b in zip(d[:-1], d[1:])],
                        "flags": [f for f in ("grids_disagree", "uncertain_extrapolation")
                                  if res.validity & vcor.solvers.validity.FLAGS[f]]})
    finally:
        adaptive.extrapolate = plain
    return out


def report(results) -> list:
    from vcor.solvers import extrapolation as X

    lo, hi = X.RICHARDSON_T0_RATIO
    rows = []
    for family in dict.fromkeys(r["family"] for r in results):
        mine = [r for r in results if r["family"] == family]
        good = [r for r in mine if r["error"] <= ACCURACY]
        alarms = [r for r in good if r["gap_rel"] > X.RICHARDSON_T0_GAP and not lo <= r["ratios"][-1] <= hi]
        flagged = [r for r in good if r["flags"]]
        largest = max((r["gap"] for r in good), default=float("nan"))
        rows.append([family, str(len(mine)), str(len(good)), f"{largest:.2g}", str(len(alarms)), str(len(flagged))])
    bad = sorted((r for r in results if r["error"] > ACCURACY), key=lambda r: -r["error"])
    listed = [[r["label"], f"{r['error']:.1e}", f"{r['gap_rel']:.1e} ({r['gap']:.3g})",
               ", ".join(f"{x:.3g}" for x in r["ratios"]), " ".join(r["flags"]) or "-"] for r in bad]
    return [f"Impacts whose grids `vcor.simulate` extrapolates (or checks), against references (module docstring): "
            f"error = max(|COR / ref - 1|, |t0 / ref - 1|); spread = |t0 finest - t0 coarse| / t0, in units of the "
            f"default step_tol in parentheses; a false alarm: within {ACCURACY:g} but a t0 ratio outside "
            f"{X.RICHARDSON_T0_RATIO} with a spread above {X.RICHARDSON_T0_GAP:g}.",
            timing.table(["family", "impacts", f"within {ACCURACY:g}", "their largest spread [step_tol]",
                          "false alarms (t0 ratio)", "flagged though within"], rows),
            f"Every impact more than {ACCURACY:g} off, with the flag it carries (uncertain_extrapolation: a t0 "
            f"spread above {X.RICHARDSON_MAX_GAP_STEPS:g} step_tol or a t0 ratio outside {X.RICHARDSON_T0_RATIO}; "
            f"grids_disagree: not in the asymptotic range, the finest grid's values):",
            timing.table(["impact", "error", "t0 spread (step_tol)", "t0 difference ratios", "flag"], listed)]


def main():
    timing.one_process_main(__doc__, measure, report, quick="a few impacts per family")


if __name__ == "__main__":
    main()
