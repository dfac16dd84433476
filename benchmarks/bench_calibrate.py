"""Calibration benchmark (issue 13): wall time of calibrations from measured COR, medians of 3 calls
after one untimed call (numba compiled, caches warm). Run: python benchmarks/bench_calibrate.py

Cases: the acceptance case (3 free parameters, 20 data points with 0.5 % noise: an SLS's alpha with a
modulus scale and a time scale), the two-parameter SLS case of the coverage test (10 points), and the
ice g* fits (Bridges law, 21 log-spaced speeds 0.05..5 cm/s). Target: the 3-parameter case <= 10 s."""

import numpy as np
from timing import timed

import vcor
from vcor import calibrate as C
from vcor import materials as M


def main():
    sls = M.SLS(15e6, 300.0, 1200.0)
    rng = np.random.default_rng(0)
    v20 = np.geomspace(1.0, 30.0, 20)
    truth = C.scaled(sls, 1.3, -0.2)
    cor20 = np.array([vcor.simulate(truth, v, method="adaptive").cor for v in v20]) * (1 + 0.005 * rng.standard_normal(20))
    free3 = {"alpha": [30.0, 1000.0], "modulus_scale": [0.1, 10.0], "log_aT": [-2.0, 2.0]}
    v10 = np.geomspace(1.0, 30.0, 10)
    cor10 = np.array([vcor.simulate(sls, v, method="adaptive").cor for v in v10]) * (1 + 0.005 * rng.standard_normal(10))
    free2 = {"E_glassy": [1e6, 1e9], "beta": [400.0, 1e6]}
    g = np.geomspace(0.05, 5.0, 21)
    rows = []
    t, cal = timed(lambda: C.calibrate(C.CorData(v20, cor20), sls, free3), 3, warmup=True)
    rows.append(("SLS alpha + modulus_scale + log_aT, 20 points", t, cal.nfev))
    t, cal = timed(lambda: C.calibrate(C.CorData(v10, cor10), M.SLS(10e6, 300.0, 2000.0), free2), 3, warmup=True)
    rows.append(("SLS E_glassy + beta, 10 points", t, cal.nfev))
    for model, rule in (("numeric", "overlap"), ("numeric", "force"), ("pade", "overlap")):
        t, _ = timed(lambda model=model, rule=rule: C.fit_g_star(g, C.bridges_ice(g), model=model, rule=rule), 3,
                     warmup=True)
        rows.append((f"ice g*, {model}{' ' + rule if model == 'numeric' else ''}, 21 points", t, -1))
    print(f"{'calibration':50s} {'median':>9s} {'model runs':>11s}")
    for name, t, n in rows:
        print(f"{name:50s} {t:7.2f} s {n if n >= 0 else '-':>11}")
    print("target: the 3-parameter, 20-point calibration <= 10 s")


if __name__ == "__main__":
    main()
