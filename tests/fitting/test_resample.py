"""Bootstrap of measured-data fits (vcor.fitting.resample): resampling schemes (the wild bootstrap and
its leverages, the pairs schemes), the samples dataset (the contract of a study's uncertainty band) and
the plausibility of the shifts' bootstrap spread."""

import json

import numpy as np
import pytest
from synthetic_dma import SMOOTH, T_REF, TEMPS, TRUE, synthetic, write_csv

from vcor.fitting import dma, resample
from vcor.fitting.samples import sample_materials
from vcor.io.netcdf import scalar_dataset_check
from vcor.materials.files import from_file
from vcor.materials.shift import shift_from_file


def test_resample_schemes():
    data = synthetic(0)
    rng = np.random.default_rng(4)
    b = resample.resample(data, rng)
    assert b["f"].size == data["f"].size and np.all(b["weight"] > 0)
    assert b["weight"].mean() == pytest.approx(1.0, rel=1e-12)
    for _ in range(10):
        c = resample.resample(data, rng, T_ref=T_REF, mode="classical")
        kept = np.unique(c["Set"])
        assert 2 in kept and kept.size >= 2 and np.all(c["weight"] >= 1)  # the set at T_ref is always kept
    with pytest.raises(ValueError, match="mode must be one of"):
        resample.resample(data, rng, mode="jackknife")
    with pytest.raises(ValueError, match="two or more temperatures"):
        resample.resample({k: v[:10] for k, v in data.items()}, rng)


@pytest.fixture(scope="module")
def fitted():

    data = synthetic(0)
    return data, dma.fit_dma(data, T_REF)


def test_leverage_is_the_fits_response_to_its_own_point(fitted):
    """h of a point = d(fitted value)/d(data value), both relative, at fixed lambda: nudge one E' value by
    1e-3 (relative), refit from the solution, and the fitted E' there moves by h * 1e-3, within 3 %, for h
    with the residuals' curvature (``curvature=True``; what is left is the response's own nonlinearity
    and the factor (2 r_i + 1) / (r_i + 1) of a relative residual r_i ~ 1 %). The Gauss-Newton h that the
    wild bootstrap uses lies in [0, 1) and is printed beside: up to about 18 % off at the ends of the
    data."""
    from vcor.fitting import spectrum

    data, full = fitted
    sp = full.spectrum
    sets = resample.residuals(data, full).sets
    fr = np.concatenate([s.f * 10.0 ** la for s, la in zip(sets, full.log_aT)])
    es, el = np.concatenate([s.E_stor for s in sets]), np.concatenate([s.E_loss for s in sets])
    hs, _ = spectrum.leverage(sp, fr, es, el, components=(1.0, 0.01), curvature=True)
    gs, gl = spectrum.leverage(sp, fr, es, el, components=(1.0, 0.01))
    assert np.all((gs >= 0) & (gs < 1) & (gl >= 0) & (gl < 1))
    base = spectrum.fit_spectrum(fr, es, el, lam=sp.lam, components=(1.0, 0.01), start=sp)
    for i in (int(np.argmax(hs)), 0, fr.size // 2, 7):
        nudged = es.copy()
        nudged[i] *= 1 + 1e-3
        moved = spectrum.fit_spectrum(fr, nudged, el, lam=sp.lam, components=(1.0, 0.01), start=base)
        w = 2 * np.pi * fr[i]
        response = (moved.complex_modulus(w).real / base.complex_modulus(w).real - 1) / 1e-3
        print(f"point {i}: response {response:.3f}, h with curvature {hs[i]:.3f}, Gauss-Newton h {gs[i]:.3f}")
        assert response == pytest.approx(hs[i], rel=0.03)


def test_fitted_shifts_and_lag_add_their_leverage():
    """The shifts and the instrument lag a fit refines are parameters: with them in the hat matrix every
    point's leverage grows, and the leverages' sum (the fit's degrees of freedom) grows by their number,
    four shifts (the set nearest T_ref is held) and one lag, within 0.15."""
    from vcor.fitting import spectrum

    data = synthetic(0, 0.01, material=SMOOTH, lag=20e-6)
    full = dma.fit_dma(data, T_REF, lag=True)
    sets = dma.split_sets(data)
    fr = np.concatenate([s.f * 10.0 ** la for s, la in zip(sets, full.log_aT)])
    es, el = np.concatenate([s.E_stor for s in sets]), np.concatenate([s.E_loss for s in sets])
    f_meas = np.concatenate([s.f for s in sets])
    index = np.concatenate([np.full(s.f.size, [0, 1, -1, 2, 3][k]) for k, s in enumerate(sets)])
    alone = spectrum.leverage(full.spectrum, fr, es, el, components=(1.0, 0.01), lag=(f_meas, full.lag, False))
    both = spectrum.leverage(full.spectrum, fr, es, el, components=(1.0, 0.01), lag=(f_meas, full.lag, True),
                             shift_index=index)
    for a, b in zip(alone, both):
        assert np.all(b >= a - 1e-9) and np.all(b < 1)
    added = sum(b.sum() - a.sum() for a, b in zip(alone, both))
    print(f"\nleverage sum: spectrum alone {sum(a.sum() for a in alone):.2f}, with 4 shifts and the lag +{added:.2f}")
    assert abs(added - 5) < 0.15


def test_wild_sample_keeps_the_design_and_the_residuals_second_moment(fitted):
    """Same frequencies, temperatures and sets, positive moduli; over many draws the mean square of
    ln(E*/fit) at each point is the set-mean part squared plus the point part squared (weights of
    variance 1), and a fit without residuals gives back the fit."""
    data, full = fitted
    res = resample.residuals(data, full)
    rng = np.random.default_rng(3)
    draws = [resample.wild_sample(res, rng) for _ in range(4000)]
    for k, s in enumerate(res.sets):
        one = draws[0][k]
        assert np.array_equal(one.f, s.f) and one.T == s.T and one.label == s.label
        assert np.all(one.E_stor > 0) and np.all(one.E_loss > 0)
        got = np.mean([np.log(d[k].E_stor / res.fit_stor[k]) ** 2 for d in draws], axis=0)
        m = res.rho_stor[k].mean()
        want = m**2 + (res.rho_stor[k] - m) ** 2
        assert got == pytest.approx(want, rel=0.12)
    clean = resample.Residuals(sets=res.sets, fit_stor=res.fit_stor, fit_loss=res.fit_loss,
                               rho_stor=[0 * r for r in res.rho_stor], rho_loss=[0 * r for r in res.rho_loss])
    again = resample.wild_sample(clean, rng)
    assert all(np.array_equal(a.E_stor, b) for a, b in zip(again, res.fit_stor))


@pytest.fixture(scope="module")
def samples(tmp_path_factory):
    path = write_csv(tmp_path_factory.mktemp("boot") / "dma.csv", synthetic(1))
    spec = {"model": "prony", "data": {"file": str(path), "T_ref": T_REF}}
    return resample.samples_dataset("syn", spec, 3, seed=7), spec


def test_samples_dataset_layout_and_materials(samples, tmp_path):
    ds, spec = samples
    assert dict(ds.sizes)["sample"] == 3 and list(ds["sample"].values) == [0, 1, 2]
    assert np.allclose(ds["T_set"].values, TEMPS)
    scalar_dataset_check(ds)
    assert json.loads(ds.attrs["spec"]) == spec and ds.attrs["n"] == 3 and ds.attrs["seed"] == 7
    n = ds["n_modes"].values
    for i in range(3):  # padding: E = 0 and beta = NaN after the sample's own terms
        assert np.all(ds["E"].values[i, n[i]:] == 0) and np.all(np.isnan(ds["beta"].values[i, n[i]:]))
        assert np.all(np.isfinite(ds["beta"].values[i, :n[i]]))
    pairs = sample_materials(ds)
    assert len(pairs) == 3
    for (mat, shift), row in zip(pairs, ds["log_aT"].values):
        assert shift.model == "table" and shift.log_aT(float(TEMPS[0])) == pytest.approx(row[0])
        assert mat.kind == "prony" and len(mat.E) <= ds.sizes["mode"]
    # written like a fit's material file: the full-data material and shift read back
    from vcor.io.netcdf import write_dataset

    path = write_dataset(ds, tmp_path / "syn.nc", title="bootstrap", timestamp=False, command="test")
    assert from_file(path).kind == "prony" and shift_from_file(path).model == "table"


def test_bootstrap_spread_of_the_shifts_is_plausible(samples):
    """The full-data shifts lie within 0.1 decade of the truth (1 % noise), every sample's within 0.3, and
    the samples' spread is below 0.1 decade and within 1/10..20 times the linearised standard errors (the
    linearised errors assume independent residuals; three samples make a rough spread)."""
    ds, _ = samples
    assert np.abs(ds["log_aT_full"].values - TRUE).max() < 0.1
    assert np.abs(ds["log_aT"].values - TRUE).max() < 0.3
    spread = ds["log_aT"].std("sample").values
    std = ds["log_aT_std"].values
    free = std > 0
    ratio = spread[free] / std[free]
    print(f"\nbootstrap sd / linearised sd: {np.round(ratio, 2)}")
    assert np.all((ratio > 0.1) & (ratio < 20.0)) and spread.max() < 0.1


def test_refusals_name_the_fit(tmp_path):
    one = write_csv(tmp_path / "one.csv", synthetic(0, temps=np.array([20.0])))
    with pytest.raises(ValueError, match="two or more temperatures"):
        resample.samples_dataset("x", {"model": "prony", "data": {"file": str(one), "T_ref": 20}}, 2)
    two = write_csv(tmp_path / "two.csv", synthetic(0))
    with pytest.raises(ValueError, match="fits.x.method"):
        resample.samples_dataset("x", {"model": "prony", "method": "free", "data": {"file": str(two), "T_ref": 20}}, 2)
