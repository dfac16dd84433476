"""Calibration benchmark: wall time of calibrations from measured COR, with the number of model runs
each needed.

Cases: three free parameters on 20 data points with 0.5 % noise (an SLS's alpha with a modulus scale
and a time scale), the two-parameter SLS case of the coverage test (10 points), and the ice g* fits
(Bridges law, 21 log-spaced speeds 0.05..5 cm/s).

Each run is a fresh process with an empty numba cache; each time is the median of CALLS warm calls
after one untimed call; cells give the median over runs (min–max).

Run: python benchmarks/bench_calibrate.py [--runs 2] [--calls 3] [--quick] [--out FILE]
"""

from __future__ import annotations

import numpy as np

import timing
import vcor
from vcor.fitting import calibrate as cal
from vcor.fitting import g_star
from vcor.materials import SLS

ICE_FITS = (("numeric", "overlap"), ("numeric", "force"), ("pade", "overlap"))


def noisy_cor(material, v0, rng):
    """COR of ``material`` at speeds ``v0`` (default method) with 0.5 % relative noise."""
    return np.array([vcor.simulate(material, v).cor for v in v0]) * (1 + 0.005 * rng.standard_normal(len(v0)))


def measure(args):
    sls = SLS(15e6, 300.0, 1200.0)
    rng = np.random.default_rng(0)
    v20, v10 = np.geomspace(1.0, 30.0, 20), np.geomspace(1.0, 30.0, 10)
    cor20 = noisy_cor(cal.scaled(sls, 1.3, -0.2), v20, rng)
    cor10 = noisy_cor(sls, v10, rng)
    free3 = {"alpha": [30.0, 1000.0], "modulus_scale": [0.1, 10.0], "log_aT": [-2.0, 2.0]}
    free2 = {"E_glassy": [1e6, 1e9], "beta": [400.0, 1e6]}
    cases = [("SLS alpha + modulus_scale + log_aT, 20 points",
              lambda: cal.calibrate(cal.CorData(v20, cor20), sls, free3)),
             ("SLS E_glassy + beta, 10 points",
              lambda: cal.calibrate(cal.CorData(v10, cor10), SLS(10e6, 300.0, 2000.0), free2))]
    g = np.geomspace(0.05, 5.0, 21)
    if args.quick:
        cases = cases[1:]
    for model, rule in (("pade", "overlap"),) if args.quick else ICE_FITS:
        label = f"ice g*, {model}{' ' + rule if model == 'numeric' else ''}, 21 points"
        ice = g_star.bridges_ice(g)
        cases.append((label, lambda model=model, rule=rule, ice=ice: g_star.fit_g_star(g, ice, model=model, rule=rule)))
    out = {}
    for name, fn in cases:
        t, res = timing.warm_timed(fn, timing.calls(args))
        out[name] = {"time": t, "model_runs": getattr(res, "nfev", None)}
    return out


def report(args, results):
    rows = [[name, timing.cell(timing.column(results, name, "time"), 1.0, ".3f"), info["model_runs"] or "-"]
            for name, info in results[0].items()]
    return [f"Calibrations: median of {timing.calls(args)} warm call(s) after one untimed call, one fresh "
            "process with an empty numba cache per run; cells: median over runs (min–max).",
            timing.table(["calibration", "time [s]", "model runs"], rows)]


if __name__ == "__main__":
    timing.main(__doc__, measure, report, calls=3,
                quick="one warm call per case; the two-parameter SLS case and the Padé ice fit only")
