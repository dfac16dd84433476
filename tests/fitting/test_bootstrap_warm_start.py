"""Bootstrap refits start from the full-data fit (vcor.fitting.resample.refit): a warm start converges to
the optimum a start from scratch reaches, the joint solve's geodesic acceleration reaches the plain solver's
optimum on pyvisco's data in fewer iterations, the full-data fit read back from its material file is the fit
itself, and samples split over jobs are the samples one job fits."""

import json
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from synthetic_dma import SMOOTH, T_REF, synthetic, write_csv

from vcor.fitting import dma, fits, resample, samples
from vcor.fitting.dma import joint as joint_module
from vcor.fitting.dma.joint import TOL, JointStart, fit_with_shifts
from vcor.fitting.spectrum import lm
from vcor.fitting.spectrum.smooth import log_spectrum

#: an instrument lag in the synthetic data, s (the pyvisco fit's is about 40 us)
LAG = 20e-6
RAW = Path(__file__).resolve().parents[2] / "data/pyvisco/freq_user_raw.csv"
#: pyvisco's wild samples (seed 0) whose warm refits took the plain solver longest (250-450 iterations)
SLOW_SAMPLES = (35, 49)


@pytest.fixture(scope="module")
def lagged():
    """Synthetic sets with an instrument lag and their full-data fit (shifts, lag and spectrum fitted)."""
    data = synthetic(3, 0.01, material=SMOOTH, lag=LAG)
    return data, dma.fit_dma(data, T_REF, lag=True)


def _cold_start(sets, full):
    """The start a refit without the full-data optimum takes, on the full-data joint grid (so that both
    solves minimise the same objective): start-free spline shifts of the sample, the full-data final
    spectrum carried onto the grid, no lag."""
    tau = full.joint.solution.tau
    ln_e_inf, H = log_spectrum(full.spectrum, tau, float(max(s.E_stor.max() for s in sets)))
    return dma.global_shifts(sets, T_REF).log_aT, JointStart(tau=tau, E_inf=float(np.exp(ln_e_inf)), E=np.exp(H))


def test_warm_start_converges_to_the_cold_optimum(lagged):
    """Three wild samples: from the full-data optimum the joint solve stops at the optimum of a start from
    scratch on the same problem (same grid, same lambda): the same objective within 1e-8 (relative; each solve
    stops where a Gauss-Newton step predicts a decrease below TOL = 1e-10 of it, and 1e-8 leaves room for the
    objective not being quadratic), shifts within 1e-3 decades and lags within 1e-8 s (the full-data standard
    errors are ~1e-2 decades and ~1e-7 s). The iterations are printed: on these synthetic data the start from
    scratch (spline shifts, the full-data spectrum) is already close, and the warm start saves none.
    """
    data, full = lagged
    j = full.joint
    res = resample.residuals(data, full)
    rng = np.random.default_rng(11)
    for _ in range(3):
        sets = resample.wild_sample(res, rng)
        warm = resample.refit(sets, full).joint
        shifts, start = _cold_start(sets, full)
        cold = fit_with_shifts(sets, T_REF, shifts, lam=j.lam_joint, final_lam=full.spectrum.lam,
                               start_spectrum=full.spectrum, start=start, lag=True)
        print(f"\nwarm: {warm.nfev} iterations, objective {warm.objective:.12e}; cold: {cold.nfev} iterations, "
              f"objective {cold.objective:.12e}; full-data: {j.nfev} iterations")
        assert not warm.notes and not cold.notes            # both converged (TOL)
        assert warm.objective == pytest.approx(cold.objective, rel=1e-8)
        assert np.abs(warm.log_aT - cold.log_aT).max() < 1e-3 and abs(warm.lag - cold.lag) < 1e-8
        assert np.array_equal(warm.solution.tau, j.solution.tau)   # the refit keeps the full-data grid
    assert TOL == 1e-10


def _plain_solver(monkeypatch):
    """Make the joint solve take plain Levenberg-Marquardt steps (the same solver, no geodesic acceleration)."""
    def plain(cost, normal, x0, **kw):
        return lm.levenberg_marquardt(cost, normal, x0, **{k: v for k, v in kw.items() if k != "curvature"})
    monkeypatch.setattr(joint_module, "levenberg_marquardt", plain)


def _same_optimum(a, b):
    """Both joint solves converged (TOL) to one optimum: objectives within 1e-8 (relative), shifts within
    1e-3 decades, lags within 1e-8 s (pyvisco's standard errors: ~1e-2 decades and ~1e-6 s)."""
    assert not a.notes and not b.notes
    assert a.objective == pytest.approx(b.objective, rel=1e-8)
    assert np.abs(a.log_aT - b.log_aT).max() < 1e-3 and abs(a.lag - b.lag) < 1e-8


@pytest.mark.slow  # four joint solves of pyvisco's data, two from scratch: ~10 s
@pytest.mark.skipif(not RAW.is_file(), reason="pyvisco's raw data not present")
def test_geodesic_acceleration_reaches_the_plain_optimum_on_pyvisco_data(monkeypatch):
    """The config's fit of pyvisco's raw data (T_ref -5 deg C, shifts and instrument lag fitted) and the warm
    refits of its two slowest wild samples: with geodesic acceleration each joint solve converges on the same
    criterion (TOL) to the plain solver's optimum, in fewer iterations."""
    raw = dma.read_table(RAW)
    full = dma.fit_dma(raw, -5.0, lag=True)
    res = resample.residuals(raw, full)
    rng = np.random.default_rng(0)
    draws = [resample.wild_sample(res, rng) for _ in range(max(SLOW_SAMPLES) + 1)]
    fast = [full.joint] + [resample.refit(draws[i], full).joint for i in SLOW_SAMPLES]
    with monkeypatch.context() as m:
        _plain_solver(m)
        plain = [dma.fit_dma(raw, -5.0, lag=True).joint] + [resample.refit(draws[i], full).joint for i in SLOW_SAMPLES]
    for a, b in zip(fast, plain):
        print(f"\ngeodesic {a.nfev} iterations, objective {a.objective:.12e}; plain {b.nfev}, {b.objective:.12e}")
        _same_optimum(a, b)
        assert a.nfev < b.nfev


def test_the_full_data_optimum_is_its_own_refit(lagged):
    """Refitting the full data from their own optimum takes no iteration and gives the fit back."""
    data, full = lagged
    again = resample.refit(data, full)
    assert again.joint.nfev <= 1
    assert np.abs(again.log_aT - full.log_aT).max() < 1e-9 and again.lag == pytest.approx(full.lag, rel=1e-9)


def test_the_material_file_records_the_full_data_fit(lagged, tmp_path):
    """The record of a fit (attribute bootstrap_start, :func:`vcor.fitting.fits.full_fit_record`) reads back
    from a netCDF file as the fit the bootstrap needs: the same shifts, lag, spectrum, joint optimum and merged
    material bit for bit, so residuals and refits are those of the fit itself; the fit rule writes it beside
    the material it records."""
    data, full = lagged
    xr.Dataset(attrs={fits.START_ATTR: json.dumps(fits.full_fit_record(full))}).to_netcdf(tmp_path / "fit.nc")
    back = fits.full_fit_from_file(tmp_path / "fit.nc")
    assert np.array_equal(back.log_aT, full.log_aT) and back.lag == full.lag and back.T_ref == full.T_ref
    assert np.array_equal(back.spectrum.E, full.spectrum.E) and back.spectrum.lam == full.spectrum.lam
    assert np.array_equal(back.joint.solution.E, full.joint.solution.E) and back.joint.lam_joint == full.joint.lam_joint
    assert back.material().to_dict() == full.material().to_dict()
    a, b = resample.residuals(data, full), resample.residuals(data, back)
    assert all(np.array_equal(x, y) for x, y in zip(a.rho_loss, b.rho_loss))
    sample = resample.wild_sample(a, np.random.default_rng(0))
    assert np.array_equal(resample.refit(sample, back).log_aT, resample.refit(sample, full).log_aT)
    # the fit rule's attributes: the record of the material they describe
    path = write_csv(tmp_path / "dma.csv", data)
    spec = {"model": "prony", "data": {"file": str(path), "T_ref": T_REF, "instrument_lag": True}}
    result, _, attrs = fits.run_fit(spec)
    record = fits.full_fit_from_record(json.loads(attrs[fits.START_ATTR]))
    assert record.material().to_dict() == result.material.to_dict() and record.joint.lag_fitted
    xr.Dataset(attrs={"material": "{}"}).to_netcdf(tmp_path / "old.nc")
    with pytest.raises(ValueError, match="no attribute 'bootstrap_start'"):
        fits.full_fit_from_file(tmp_path / "old.nc")


@pytest.mark.parametrize("n, parts", [(2, 2), (5, 2), (7, 3), (50, 2), (4, 1)])
def test_the_parts_hold_every_sample_once(n, parts):
    got = np.concatenate([samples.part_indices(n, k, parts) for k in range(parts)])
    assert np.array_equal(got, np.arange(n))
    sizes = [samples.part_indices(n, k, parts).size for k in range(parts)]
    assert max(sizes) - min(sizes) <= 1


@pytest.mark.parametrize("args, words", [((3, 2, 2), "part 2 of 2"), ((1, 0, 2), "parts <= n"), ((3, -1, 2), "part:"),
                                         ((3, 0, 0), "parts:")])
def test_bad_parts_are_refused(args, words):
    with pytest.raises(ValueError, match=words):
        samples.part_indices(*args)


def test_a_sample_is_the_same_whichever_part_fits_it(lagged, tmp_path):
    """Four samples in one job and in two: the merged parts are the one job's dataset, value for value
    (each sample's data are its own draw of the seed's stream); a missing or doubled part is refused."""
    data, full = lagged
    path = write_csv(tmp_path / "dma.csv", data)
    spec = {"model": "prony", "data": {"file": str(path), "T_ref": T_REF, "instrument_lag": True}}
    one = resample.samples_dataset("syn", spec, 4, seed=5, full=full)
    parts = [resample.samples_dataset("syn", spec, 4, seed=5, full=full, indices=samples.part_indices(4, k, 2))
             for k in (1, 0)]
    assert [p["sample"].values.tolist() for p in parts] == [[2, 3], [0, 1]]
    xr.testing.assert_identical(samples.merge_samples(parts), one)
    with pytest.raises(ValueError, match="not each of 0..3 once"):
        samples.merge_samples(parts[:1])
    with pytest.raises(ValueError, match="not each of 0..3 once"):
        samples.merge_samples([parts[0], parts[0], parts[1]])
    other = resample.samples_dataset("syn", spec, 4, seed=6, full=full, indices=[0, 1])
    with pytest.raises(ValueError, match=r"different bootstraps .*'seed'"):
        samples.merge_samples([parts[0], other])


def test_a_refit_that_stops_short_of_convergence_is_named(lagged, tmp_path, monkeypatch):
    """A sample whose joint solve stopped at its iteration limit stays in the band, and the samples file names
    it (attribute not_converged: sample -> its note), in one job and merged from parts alike."""
    import dataclasses

    data, full = lagged
    path = write_csv(tmp_path / "dma.csv", data)
    spec = {"model": "prony", "data": {"file": str(path), "T_ref": T_REF, "instrument_lag": True}}
    real, calls = resample.refit, []
    note = "joint solve: not converged (stopped after 500 of at most 500 iterations)"

    def refit(sample, fit):
        calls.append(1)
        out = real(sample, fit)
        return dataclasses.replace(out, notes=[*out.notes, note]) if len(calls) % 2 == 0 else out

    monkeypatch.setattr(resample, "refit", refit)
    one = resample.samples_dataset("syn", spec, 4, seed=5, full=full)
    assert samples.not_converged(one) == {1: [note], 3: [note]}
    calls.clear()
    parts = [resample.samples_dataset("syn", spec, 4, seed=5, full=full, indices=samples.part_indices(4, k, 2))
             for k in (0, 1)]
    assert samples.not_converged(samples.merge_samples(parts)) == {1: [note], 3: [note]}
