"""Smooth relaxation spectra (vcor.fitting.spectrum): a smooth material reproduced without wiggles,
the lambda choices, joint E(t) data, mode merging with its reported change, shifts refined with the
spectrum, an instrument's time lag told from the material, and pyvisco's raw data meeting the fit
targets (docs/user-guide/dma.md)."""

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from synthetic_dma import SMOOTH, T_REF, TRUE, synthetic

from vcor.fitting import dma
from vcor.fitting import spectrum as spc
from vcor.materials.shift import wlf_log_aT

RAW = Path(__file__).resolve().parents[2] / "data/pyvisco/freq_user_raw.csv"


def _lognormal(n=40, noise=0.0, seed=0):
    """E', E'' of a smooth (log-normal) relaxation spectrum by dense quadrature, and the spectrum."""
    tau_q = np.logspace(-9, 5, 1400)
    Eq = 1e8 * np.exp(-0.5 * ((np.log10(tau_q) + 2) / 1.2) ** 2) * math.log(tau_q[1] / tau_q[0])
    f = np.geomspace(1e-3, 1e4, n)
    e = spc.complex_modulus(2 * np.pi * f, 1e6, Eq, tau_q)
    nz = 1 + noise * np.random.default_rng(seed).standard_normal((2, n))
    return f, e.real * nz[0], e.imag * nz[1], (1e6, Eq, tau_q)


def test_tau_grid_and_prony_limits():
    tau = spc.tau_grid(0.01, 100.0, per_decade=5, margin=1.5)
    assert tau[0] == pytest.approx(1 / (2 * math.pi * 100) / 10**1.5) and np.allclose(np.diff(np.log10(tau)), 0.2)
    e = spc.complex_modulus(np.array([1e-9, 1e9]), 0.5, np.array([1.0, 2.0]), np.array([1e-3, 1.0]))
    assert e.real == pytest.approx([0.5, 3.5], rel=1e-6)
    assert spc.count_extrema(np.sin(np.linspace(0, 4 * np.pi, 2000))) == 4 and spc.count_extrema([0, 1, 1, 0]) == 1


def test_smooth_material_is_reproduced_without_wiggles():
    f, es, el, (ei, Eq, tq) = _lognormal()
    fit = spc.fit_spectrum(f, es, el)
    fd = np.geomspace(f.min(), f.max(), 2000)
    et = spc.complex_modulus(2 * np.pi * fd, ei, Eq, tq)
    assert fit.metrics["E_stor_rms"] < 2e-3 and fit.metrics["E_loss_rms"] < 5e-3
    assert fit.metrics["tan_delta_extrema"] == spc.count_extrema(et.imag / et.real)
    assert np.all(fit.E > 0) and fit.E_inf >= 0
    # noise-free data: the one-standard-error choice is the grid's smallest lambda, and the note says what
    # that means of the data (no config key widens the grid, so it gives no advice to)
    assert fit.notes == ["lambda by gcv1se: 1e-05, the smallest of the scanned 1e+05..1e-05: the data ask for no "
                         "more smoothing than this (noise-free data, e.g. synthetic); the fit follows them that "
                         "closely"]


def test_lambda_choices_and_relaxation_data():
    f, es, el, (ei, Eq, tq) = _lognormal(noise=0.01, seed=1)
    gcv, se = spc.fit_spectrum(f, es, el, lam="gcv"), spc.fit_spectrum(f, es, el)
    assert se.notes == []  # 1 % noise: a lambda inside the grid
    assert se.lam >= gcv.lam and se.method == "gcv1se" and np.all(np.isfinite(gcv.scan["gcv"]))
    assert spc.fit_spectrum(f, es, el, lam=3.0).lam == 3.0
    with pytest.raises(ValueError, match="lam must be"):
        spc.fit_spectrum(f, es, el, lam="aic")
    t = np.geomspace(1e-4, 1e2, 10)
    both = spc.fit_spectrum(f, es, el, relaxation=(t, spc.relaxation_modulus(t, ei, Eq, tq)))
    assert both.metrics["E_relax_rms"] < 0.01


def test_merging_keeps_the_curve_and_reports_the_change():
    f, es, el, _ = _lognormal()
    fit = spc.fit_spectrum(f, es, el)
    r2, r05 = spc.reduce_modes(fit, 2.0), spc.reduce_modes(fit, 0.5)
    assert r2.n_modes < fit.n_modes and r2.change["E_stor_max"] < 0.01 and r2.change["E_loss_max"] < 0.02
    assert r05.change["E_loss_max"] > r2.change["E_loss_max"]  # fewer modes, more ripple
    assert set(r2.change) >= {"E_stor_rms", "E_loss_rms", "tan_delta_max", "tan_delta_extrema"}


def test_joint_refinement_keeps_synthetic_shifts_and_a_noise_free_set_is_recovered():
    for seed, noise, tol in ((0, 0.0, 0.02),):
        fit = dma.fit_dma(synthetic(seed, noise), T_REF, components=(1.0, 1.0))
        print(f"\nnoise {noise}: worst shift error {np.max(np.abs(fit.log_aT - TRUE)):.4f} decade, "
              f"E' rms {fit.spectrum.metrics['E_stor_rms']:.4f}")
        assert np.max(np.abs(fit.log_aT - TRUE)) < tol
        assert fit.joint.at_bound == [] and fit.spectrum.metrics["E_stor_rms"] < 0.02


def test_joint_refinement_is_start_independent():
    """Stage 2 starts from stage 1, which takes no start: any start given to stage 1 ends at the same fit."""
    data = synthetic(3)
    base = dma.global_shifts(data, T_REF)
    other = dma.global_shifts(data, T_REF, start=np.zeros(5))
    sets = dma.split_sets(data)
    a = dma.fit_with_shifts(sets, T_REF, base.log_aT, lam=1e-3, final_lam=1e-3)
    b = dma.fit_with_shifts(sets, T_REF, other.log_aT, lam=1e-3, final_lam=1e-3)
    assert np.max(np.abs(a.log_aT - b.log_aT)) < 1e-6


def test_an_instrument_lag_is_told_from_the_material():
    """A time lag between force and displacement adds 2 pi f dt to every measured loss angle, f the
    measured frequency. Fitted with the shifts and the spectrum (lag=True), it is recovered: noise-free
    data of a smooth material (five sets) give 30 us within 1 us and 0 within 1 us, the shifts within 0.01
    decade; with 0.5 % noise (eleven sets, four seeds) every estimate lies within 3.5 of its standard
    errors of the truth and their mean within 2 standard errors of the mean. A material whose tan delta
    ripples between five sparse modes (which the smooth fit cannot follow) biases the lag: the printed
    bias stays within 3 of its standard errors."""
    for lag in (0.0, 30e-6):
        fit = dma.fit_dma(synthetic(0, 0.0, material=SMOOTH, lag=lag), T_REF, lag=True)
        print(f"\nsmooth, noise-free, lag {1e6 * lag:g} us: fitted {1e6 * fit.lag:.2f} +- {1e6 * fit.lag_std:.2f} us, "
              f"worst shift error {np.max(np.abs(fit.log_aT - TRUE)):.4f} decade")
        assert abs(fit.lag - lag) < 1e-6 and np.max(np.abs(fit.log_aT - TRUE)) < 0.01
    temps = np.linspace(-10, 50, 11)
    got = [dma.fit_dma(synthetic(seed, 0.005, temps=temps, material=SMOOTH, lag=30e-6), T_REF, lag=True)
           for seed in range(4)]
    lags, stds = np.array([g.lag for g in got]), np.array([g.lag_std for g in got])
    print("0.5 % noise, 11 sets, lag 30 us: "
          + ", ".join(f"{1e6 * a:.1f} +- {1e6 * b:.1f}" for a, b in zip(lags, stds)))
    assert np.all(np.abs(lags - 30e-6) < 3.5 * stds)
    assert abs(lags.mean() - 30e-6) < 2 * np.sqrt(np.sum(stds**2)) / lags.size
    for g in got:
        assert np.max(np.abs(g.log_aT - wlf_log_aT(temps, T_REF, 8.86, 101.6))) < 0.1
    sparse = dma.fit_dma(synthetic(0, 0.0), T_REF, lag=True)
    print(f"sparse five modes, noise-free, no lag: fitted {1e6 * sparse.lag:.1f} +- {1e6 * sparse.lag_std:.1f} us")
    assert abs(sparse.lag) < 3 * sparse.lag_std


def test_given_shifts_hold_while_the_lag_is_fitted():
    """With shift factors given, lag=True fits the spectrum and the lag at those shifts, which stay."""
    fit = dma.fit_dma(synthetic(0, 0.0, material=SMOOTH, lag=20e-6), T_REF, log_aT=TRUE, lag=True)
    assert np.array_equal(fit.log_aT, TRUE) and np.all(fit.log_aT_std == 0)
    assert abs(fit.lag - 20e-6) < 1e-6


def test_too_few_points_for_the_modes_are_refused():
    data = synthetic(0, 0.0, temps=np.array([-10.0, 5.0, 20.0]), f=np.geomspace(0.1, 100, 3))
    with pytest.raises(ValueError, match="9 frequency points are fewer than the .* modes"):
        dma.fit_dma(data, T_REF, log_aT=TRUE[:3])


_WORKER = """
import json, sys, time
from vcor.fitting import fits
t = time.perf_counter()
result, _, attrs = fits.run_fit(json.loads(sys.argv[1]))
sup = json.loads(attrs["superposition"])
print(json.dumps({"metrics": result.metrics, "terms": len(result.material.E), "time": time.perf_counter() - t,
                  "shift": json.loads(attrs["shift"])["model"], "lag": sup["instrument_lag_s"],
                  "lag_std": sup["instrument_lag_std_s"]}))
"""


@pytest.mark.skipif(not RAW.is_file(), reason="pyvisco's raw data not present")
def test_pyvisco_raw_data_meet_the_targets():
    """The default config's fit of pyvisco's raw data (``fits.pyvisco-polymer``: shifts found from the
    data, the instrument lag fitted): E' rms <= 2 %, E'' rms <= 18 % (against the lag-corrected master
    curve), at most 3 tan delta extrema on 2000 points over the reduced range, shifts + spectrum within
    20 s (a fresh process, OPENBLAS_NUM_THREADS=1: docs/user-guide/dma.md); the lag lies 10 standard
    errors or more above 0 (the tan delta excess at the top of every set, docs/user-guide/dma.md)."""
    import yaml

    spec = yaml.safe_load((RAW.parents[2] / "config.yaml").read_text())["fits"]["pyvisco-polymer"]
    spec = {**spec, "data": {**spec["data"], "file": str(RAW)}}
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    out = subprocess.run([sys.executable, "-c", _WORKER, json.dumps(spec)], env=env, capture_output=True, text=True,
                         check=True)
    r = json.loads(out.stdout.strip().splitlines()[-1])
    m = r["metrics"]
    print(f"\npyvisco raw: E' rms {m['storage_rms']:.4f}, E'' rms {m['loss_rms']:.4f}, tan delta rms "
          f"{m['tan_delta_rms']:.4f}, extrema {m['tan_delta_extrema']}, {r['terms']} terms, {r['time']:.2f} s, "
          f"instrument lag {1e6 * r['lag']:.1f} +- {1e6 * r['lag_std']:.1f} us")
    assert m["storage_rms"] <= 0.02 and m["loss_rms"] <= 0.18 and m["tan_delta_extrema"] <= 3, m
    assert r["time"] <= 20.0 and r["shift"] == "table"
    assert spec["data"]["instrument_lag"] and r["lag"] > 10 * r["lag_std"]
