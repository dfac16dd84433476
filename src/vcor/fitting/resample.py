r"""Bootstrap of a measured-data fit: resampled DMA data, refitted shifts and spectrum per sample.

Default resampling (:func:`wild_sample`, ``mode="wild"``): a two-level wild bootstrap of the
full-data fit's residuals. Every point keeps its frequency and its set; its moduli become

.. math:: E^{*}_{ki} = \hat E_{ki}\, \exp\!\big(v_k\, \bar\rho_k + v_{ki}\,(\rho_{ki} - \bar\rho_k)\big),
          \qquad \rho_{ki} = \frac{\ln(E_{ki} / \hat E_{ki})}{1 - h_{ki}},

separately for E' and E'' (:math:`\hat E` the full-data spectrum at the point's reduced frequency, as
the instrument measures it when the fit has an instrument lag,
:math:`h` its leverage in that fit, with the fitted shifts and lag among the parameters,
:func:`vcor.fitting.spectrum.leverage.leverage`; :math:`\bar\rho_k` the
set's mean, a per-set modulus scale error such as a geometry or clamping error), with independent
weights :math:`v_k` per set and :math:`v_{ki}` per point, drawn from Webb's six-point distribution
(:math:`\pm\sqrt{1/2}, \pm 1, \pm\sqrt{3/2}`, mean 0, variance 1; Webb 2016, for few clusters; the
same :math:`v` for a point's E' and E''). So both levels of the data's scatter, the points within a
set and the sets, are resampled, the design (frequencies, temperatures) stays that of the data, and
no overlap between sets can break. Dividing by :math:`1 - h` (the HC3 correction of MacKinnon &
White 1985, as Davidson & Flachaire 2008 use in the wild bootstrap) undoes the shrinking of the
residuals where few points decide the fit: without it, on synthetic data (``python
benchmarks/bench_uncertainty.py coverage``) the samples' spread at the end of the data's reduced
range is half the fit's actual error.

``mode="bayesian"`` (:func:`resample`): the two-stage Bayesian bootstrap (Rubin 1981) of the points,
set k weighted :math:`g_k \sim \mathrm{Exp}(1)` and each of its points :math:`p_{ki} \sim \mathrm{Exp}(1)`,
multiplicity :math:`g_k p_{ki}`. ``mode="classical"``: sets drawn with replacement and then points
within sets, as integer multiplicities (it drops sets: on pyvisco's example 149 of 200 such draws
leave two neighbours with no common E', E'' or tan delta range). Both resample the pairs
(point, value) and understate the scatter where leverage is high, as above.

Every sample is refitted from the full-data fit (:func:`refit`, a *warm start*): the joint solve of
shifts, lag and spectrum (:func:`vcor.fitting.dma.joint.fit_with_shifts`) starts at the full-data
fit's optimum (its shifts, lag, and spectrum on its relaxation-time grid) with its smoothing held
fixed (joint and final lambda), and stops on the same criterion as the full-data fit
(:data:`vcor.fitting.dma.joint.TOL`); with given shifts and no lag, the smooth spectrum is refitted from
the full-data one. This is the usual way to bootstrap an iterative estimator: a sample differs from the
data by a resampled residual of the data's own size, so its optimum lies about a standard error from
the full-data one, well inside the region where Levenberg-Marquardt converges fast; a cold start
(start-free shifts, a spectrum from E'') would repeat the path the full-data fit has already taken.
Davidson & MacKinnon (1999, Bootstrap testing in nonlinear models, Int. Econ. Rev. 40, 487) and
Andrews (2002, Higher-order improvements of a computationally attractive k-step bootstrap for extremum
estimators, Econometrica 70, 119) go further and take only k Newton steps from the original estimate.
What the warm start can change: where the objective is flat along some direction
(a valley the data do not inform, such as the spectrum beyond the data's range or a shift traded
against the lag), a solve stops once the predicted decrease falls below the tolerance, and from the
full-data optimum that point may lie nearer to it than a cold start's end point would: the samples'
spread along such a direction can shrink. Whether the band's statistics moved is checked by the
coverage and spread benchmarks (``python benchmarks/bench_uncertainty.py coverage spread``).

The spread of the samples is the data's: it does not cover the model's own error (linear
viscoelasticity, horizontal-only shifts, a smooth spectrum) nor a Poisson-ratio choice downstream.

Sample i's data are the i-th draw of the seed's one random stream (``numpy.random.default_rng(seed)``,
drawn in sample order), whichever samples a job fits: the samples can be split over jobs
(:func:`vcor.fitting.samples.part_indices`) and merged (:func:`vcor.fitting.samples.merge_samples`)
into the dataset one job would write. A sample whose data cannot be superposed is drawn again from a
stream of its own, ``default_rng([seed, i, attempt])``, at most :data:`MAX_REDRAWS` times.

:func:`samples_dataset` fits ``n`` samples (or some of them) of a measured-data fit spec into one dataset
with a ``sample`` dimension, from the full-data fit's material file (:func:`vcor.fitting.fits.full_fit_from_file`)
or fitting the full data itself; :func:`vcor.fitting.samples.sample_materials` turns it back into
(material, shift function) pairs.
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..threads import one_blas_thread
from . import dma, fits
from .dma.joint import fit_with_shifts
from .dma.laws import arrhenius_fit, wlf_fit
from .dma.pipeline import MODES_PER_DECADE
from .spec import SHIFT_MODELS, check_fit_spec
from .spectrum.leverage import leverage
from .spectrum.modes import reduce_modes

__all__ = ["MAX_REDRAWS", "MODES", "WEBB", "Residuals", "bootstrap", "refit", "resample", "residuals",
           "samples_dataset", "wild_sample"]

#: resampling schemes (the first is the default)
MODES = ("wild", "bayesian", "classical")
#: Webb's six-point distribution of the wild weights (mean 0, variance 1)
WEBB = np.array([-math.sqrt(1.5), -1.0, -math.sqrt(0.5), math.sqrt(0.5), 1.0, math.sqrt(1.5)])
#: draws of one sample whose data cannot be superposed before the bootstrap gives up (a wild sample keeps the
#: design, so its sets always overlap; a pairs sample that drops sets may not)
MAX_REDRAWS = 20


@dataclass(frozen=True, kw_only=True)
class Residuals:
    """What :func:`wild_sample` needs of the full-data fit, per set (ascending temperature).

    Attributes
    ----------
    sets : list of DMASet
        The data.
    fit_stor, fit_loss : list of ndarray
        The full-data spectrum's E', E'' at every point, Pa.
    rho_stor, rho_loss : list of ndarray
        Leverage-corrected log residuals ln(E / fit) / (1 - h) (module docstring).
    """

    sets: list
    fit_stor: list
    fit_loss: list
    rho_stor: list
    rho_loss: list


def residuals(raw, full) -> Residuals:
    """The full-data fit's leverage-corrected log residuals at every raw point (module docstring).

    Parameters
    ----------
    raw : mapping, object with ``.columns`` or list of DMASet
    full : DMAFit
        The fit of ``raw`` (:func:`vcor.fitting.dma.pipeline.fit_dma`).
    """
    sets = dma.split_sets(raw)
    fr = np.concatenate([s.f * 10.0 ** la for s, la in zip(sets, full.log_aT)])
    es = np.concatenate([s.E_stor for s in sets])
    el = np.concatenate([s.E_loss for s in sets])
    w = np.concatenate([np.ones(s.f.size) if s.weight is None else s.weight for s in sets])
    f_meas = np.concatenate([s.f for s in sets])
    e = full.spectrum.complex_modulus(2 * math.pi * fr) * np.exp(2j * math.pi * f_meas * full.lag)  # as measured
    joint = full.joint
    shift_index = None
    if joint is not None and joint.free_shifts:
        # the fitted shifts are parameters too: every set's but the one held during the solve
        k_held = joint.held_set
        index = np.array([k - (k > k_held) if k != k_held else -1 for k in range(len(sets))])
        shift_index = np.concatenate([np.full(s.f.size, index[k]) for k, s in enumerate(sets)])
    lag = (f_meas, full.lag, True) if joint is not None and joint.lag_fitted else None
    hs, hl = leverage(full.spectrum, fr, es, el, weight=w, components=(1.0, dma.LOSS_WEIGHT), lag=lag,
                      shift_index=shift_index)
    rs, rl = np.log(es / e.real) / (1 - hs), np.log(el / e.imag) / (1 - hl)
    cut = np.cumsum([s.f.size for s in sets])[:-1]
    return Residuals(sets=sets, fit_stor=np.split(e.real, cut), fit_loss=np.split(e.imag, cut),
                     rho_stor=np.split(rs, cut), rho_loss=np.split(rl, cut))


def wild_sample(res: Residuals, rng) -> list:
    """One two-level wild-bootstrap sample (module docstring): the sets with resampled moduli."""
    out = []
    for s, fs, fl, rs, rl in zip(res.sets, res.fit_stor, res.fit_loss, res.rho_stor, res.rho_loss):
        vk, v = rng.choice(WEBB), rng.choice(WEBB, s.f.size)
        w = np.ones(s.f.size) if s.weight is None else s.weight
        ms, ml = np.average(rs, weights=w), np.average(rl, weights=w)
        out.append(dma.DMASet(T=s.T, f=s.f, E_stor=fs * np.exp(vk * ms + v * (rs - ms)),
                              E_loss=fl * np.exp(vk * ml + v * (rl - ml)), label=s.label, weight=s.weight))
    return out


def resample(raw, rng, *, T_ref=None, mode="bayesian", min_sets=2):
    """One pairs-bootstrap sample of raw multi-temperature data, as point weights (module docstring;
    the default resampling is :func:`wild_sample`).

    Parameters
    ----------
    raw : mapping or object with ``.columns``
        Columns f [Hz], E_stor, E_loss [Pa], T [deg C], Set, optional ``weight``.
    rng : numpy.random.Generator
    T_ref : float, optional
        Reference temperature, deg C (``mode="classical"``: that set is always kept).
    mode : "bayesian" or "classical"
        ``"classical"``: sets drawn with replacement (at least ``min_sets`` distinct, the set nearest
        T_ref always), points within a kept set drawn with replacement (at least three distinct
        frequencies), as integer multiplicities.
    min_sets : int
        Classical mode: distinct sets to keep.

    Returns
    -------
    dict
        Columns f, E_stor, E_loss, T, Set of the kept points and ``weight`` (> 0).
    """
    c = raw.columns if hasattr(raw, "columns") else raw
    sid = np.asarray(c["Set"])
    base = np.asarray(c["weight"], float) if "weight" in c else np.ones(sid.size)
    labels = np.unique(sid)
    K = labels.size
    if K < 2:
        raise ValueError(f"resampling needs sets at two or more temperatures (superposition), got {K}")
    f = np.asarray(c["f"], float)
    weight = np.zeros(sid.size)
    if mode == "bayesian":
        g = rng.exponential(1.0, K)
        g *= K / g.sum()
        for k, s in enumerate(labels):
            rows = np.flatnonzero(sid == s)
            p = rng.exponential(1.0, rows.size)
            weight[rows] = g[k] * p * rows.size / p.sum()
    elif mode == "classical":
        Tm = np.array([np.mean(np.asarray(c["T"], float)[sid == s]) for s in labels])
        k_ref = int(np.argmin(np.abs(Tm - T_ref))) if T_ref is not None else None
        for _ in range(100):
            count = np.bincount(rng.integers(0, K, K), minlength=K)
            if k_ref is not None:
                count[k_ref] = max(count[k_ref], 1)
            if np.count_nonzero(count) >= min(min_sets, K):
                break
        for k, s in enumerate(labels):
            rows = np.flatnonzero(sid == s)
            for _ in range(count[k]):
                for _ in range(100):
                    w = np.bincount(rng.integers(0, rows.size, rows.size), minlength=rows.size)
                    if np.unique(f[rows][w > 0]).size >= 3:
                        break
                weight[rows] += w
    else:
        raise ValueError(f"mode must be one of {list(MODES[1:])} (pairs; 'wild': wild_sample), got {mode!r}")
    weight *= base
    keep = weight > 0
    out = {k: np.asarray(c[k])[keep] for k in ("f", "E_stor", "E_loss", "T", "Set")}
    out["weight"] = weight[keep]
    return out


def _size_check(sets, reduced) -> None:
    n_points = sum(s.f.size for s in sets)
    if n_points < reduced.n_modes:
        raise ValueError(f"measured data: {n_points} frequency points are fewer than the {reduced.n_modes} modes of "
                         f"the merged Prony series: too few data to fit (or resample) a spectrum")


@one_blas_thread()
def refit(data, full):
    """Resampled data fitted again from the full-data fit (module docstring: warm start).

    Parameters
    ----------
    data : mapping, object with ``.columns`` or list of DMASet
        The resampled sets (:func:`wild_sample`, :func:`resample`).
    full : DMAFit
        The full-data fit (:func:`vcor.fitting.dma.pipeline.fit_dma`, or
        :func:`vcor.fitting.fits.full_fit_from_file`): with a joint solve, the refit starts at its optimum
        (shifts, lag, spectrum and grid), with its lambdas and its choice of free shifts and lag; without
        one (given shifts, no lag) the smooth spectrum is refitted at the full-data shifts from the full-data
        spectrum (shifts found without a joint solve are found again).

    Returns
    -------
    DMAFit
    """
    if full.joint is None:
        given = full.log_aT if full.spline_shifts is None else None
        return dma.fit_dma(data, full.T_ref, log_aT=given, kk_refine=False, smoothing=full.smoothing, start=full)
    t0 = time.perf_counter()
    sets, j = dma.split_sets(data), full.joint
    joint = fit_with_shifts(sets, full.T_ref, full.log_aT, lam=j.lam_joint, final_lam=full.spectrum.lam,
                            start_spectrum=full.spectrum, start=j.solution, lag=j.lag_fitted, free_shifts=j.free_shifts)
    reduced = reduce_modes(joint.spectrum, MODES_PER_DECADE)
    _size_check(sets, reduced)
    T, log_aT, std = joint.T, joint.log_aT, joint.log_aT_std
    return dma.DMAFit(T=T, log_aT=log_aT, log_aT_std=std, T_ref=full.T_ref, joint=joint, spectrum=joint.spectrum,
                      reduced=reduced, wlf=wlf_fit(T, log_aT, full.T_ref, sigma=std),
                      arrhenius=arrhenius_fit(T, log_aT, full.T_ref, sigma=std),
                      times={"joint": joint.time, "total": time.perf_counter() - t0},
                      notes=joint.notes + joint.spectrum.notes, lag=joint.lag, lag_std=joint.lag_std)


def _checked_indices(n, indices) -> np.ndarray:
    if not (isinstance(n, (int, np.integer)) and not isinstance(n, bool) and n >= 1):
        raise ValueError(f"the number of bootstrap samples must be an integer >= 1, got {n!r}")
    if indices is None:
        return np.arange(n)
    idx = np.asarray(indices)
    if not (idx.ndim == 1 and idx.size and np.issubdtype(idx.dtype, np.integer) and idx.min() >= 0 and idx.max() < n
            and np.unique(idx).size == idx.size):
        raise ValueError(f"indices: distinct sample numbers in 0..{n - 1}, got {indices!r}")
    return idx


@one_blas_thread()
def bootstrap(raw, T_ref, n, seed=0, *, mode="wild", log_aT=None, lag=False, full=None, indices=None,
              max_redraws=MAX_REDRAWS):
    """The full-data fit and refits of resampled data (module docstring).

    Parameters
    ----------
    raw : mapping or object with ``.columns``
        Raw sets (:func:`vcor.fitting.dma.sets.split_sets`).
    T_ref : float
        Reference temperature, deg C.
    n : int
        Number of samples of the bootstrap, >= 1.
    seed : int
        Seed of ``numpy.random.default_rng``.
    mode : "wild", "bayesian" or "classical"
        :func:`wild_sample` or :func:`resample`.
    log_aT : array_like, optional
        Given shift factors per set (decades): only the spectrum is refitted (without ``full``).
    lag : bool
        Fit the instrument's time lag in the full-data fit and in every sample (without ``full``;
        :func:`vcor.fitting.dma.pipeline.fit_dma`).
    full : DMAFit, optional
        The full-data fit of ``raw`` (e.g. :func:`vcor.fitting.fits.full_fit_from_file`); default: fitted here.
    indices : array_like of int, optional
        The samples to fit (distinct, in 0..n-1; :func:`vcor.fitting.samples.part_indices`); default all.
        Sample i is the same whichever others are fitted beside it.
    max_redraws : int
        Draws of a sample that cannot be superposed before the error is raised.

    Returns
    -------
    full : DMAFit
    samples : list of DMAFit
        In the order of ``indices``.
    info : dict
        ``failures`` ("sample i: reason" of every redrawn sample), ``time_per_sample`` (s), ``indices``.
    """
    idx = _checked_indices(n, indices)
    if mode not in MODES:
        raise ValueError(f"mode must be one of {list(MODES)}, got {mode!r}")
    full = dma.fit_dma(raw, T_ref, log_aT=log_aT, lag=lag) if full is None else full
    res = residuals(raw, full) if mode == "wild" else None

    def draw(rng):
        return wild_sample(res, rng) if res is not None else resample(raw, rng, T_ref=T_ref, mode=mode)

    stream = np.random.default_rng(seed)
    first = [draw(stream) for _ in range(int(idx.max()) + 1)]
    samples, fails, times = [], [], []
    for i in idx:
        data, t0 = first[i], time.perf_counter()
        for attempt in range(1, max_redraws + 2):
            try:
                samples.append(refit(data, full))
                break
            except ValueError as exc:
                fails.append(f"sample {i}: {exc}")
                if attempt > max_redraws:
                    raise ValueError(f"sample {i}: no fit in {attempt} draws; the last: {exc}") from None
                data = draw(np.random.default_rng([seed, int(i), attempt]))
        times.append(time.perf_counter() - t0)
    return full, samples, {"failures": fails, "time_per_sample": times, "indices": idx}


def samples_dataset(name: str, spec: dict, n: int, *, seed: int = 0, base_dir=".", full=None, indices=None):
    """Bootstrap samples of a measured-data fit spec (all ``n``, or ``indices`` of them), as one dataset.

    Parameters
    ----------
    name : str
        The fit's name (``fits.<name>`` in the config; used in errors and attributes).
    spec : dict
        The fit spec, ``{model: prony, method?: spectrum, data: {file, T_ref, shift_file?, shift_model?,
        instrument_lag?}}``
        (:mod:`vcor.fitting.fits`); the data must be raw multi-temperature sets.
    n : int
        Number of bootstrap samples.
    seed : int
        Seed of the resampling.
    base_dir : path
        Folder that relative data paths are taken from.
    full : path or DMAFit, optional
        The full-data fit of the spec: its material file (written by the workflow's fit rule,
        :func:`vcor.fitting.fits.full_fit_from_file`) or the fit itself; default: fitted here.
    indices : array_like of int, optional
        The samples to fit (:func:`vcor.fitting.samples.part_indices`); default 0..n-1;
        :func:`vcor.fitting.samples.merge_samples` joins the parts.

    Returns
    -------
    xarray.Dataset
        Dimensions ``sample`` (the samples fitted, ascending), ``mode`` (the largest number of Prony terms
        over them), ``T_set`` (the sets' temperatures, deg C). Variables: ``E_inf`` (sample) [Pa], ``E``
        and ``beta`` (sample, mode) [Pa, 1/s], ``n_modes`` (sample): a sample with fewer terms than
        ``mode`` is padded at the end with E = 0 and beta = NaN (terms sorted by rate, padding last);
        ``log_aT`` (sample, T_set) [decades, 0 at T_ref]; ``wlf_C1``, ``wlf_C2`` [K],
        ``arrhenius_E_a`` [J/mol] (sample) fitted to each sample's shifts; ``lag`` (sample) [s], the
        instrument lag of each sample's fit (0 when not fitted); ``iterations`` (sample), the joint
        solve's Levenberg-Marquardt iterations (0 without one); ``log_aT_full`` and ``log_aT_std``
        (T_set): the full-data shifts and their linearised standard errors.
        Attributes: ``spec``, ``n``, ``seed``, ``mode`` (resampling), ``T_ref``, ``shift_model``,
        ``fit_name``, ``smoothing`` (held fixed), ``instrument_lag_full_s`` and its standard error (the
        full-data fit's lag, s), ``failures``, ``not_converged`` (sample -> the notes of a refit that stopped
        short of convergence; such samples stay in the band), and ``material`` and ``shift`` of the
        full-data fit (so the file reads as a material file, :func:`vcor.materials.from_file`).

    Raises
    ------
    ValueError
        A spec that is not a measured-data fit by method spectrum, data that are not raw sets at two or
        more temperatures, a full-data fit of other sets or another T_ref, sets that cannot be superposed,
        fewer points than modes (each naming the fit).
    """
    where = f"fits.{name}"
    raw, T_ref, given = _bootstrap_data(spec, where, base_dir)
    d = spec["data"]
    if full is not None and not isinstance(full, dma.DMAFit):
        full = fits.full_fit_from_file(full)
    try:
        if full is not None:
            _check_full(full, raw, T_ref, given)
        idx = _checked_indices(n, indices)
        full, samples, info = bootstrap(raw, T_ref, n, seed, log_aT=given, lag=bool(d.get("instrument_lag", False)),
                                        full=full, indices=np.sort(idx))
    except ValueError as exc:
        raise ValueError(f"{where}: {exc}") from None
    ds = _samples_variables(full, samples, info["indices"])
    shift_model = d.get("shift_model", SHIFT_MODELS[0])
    ds.attrs.update({
        "fit_name": name, "spec": json.dumps(spec, sort_keys=True), "n": int(n), "seed": int(seed),
        "mode": MODES[0], "T_ref": T_ref, "shift_model": shift_model,
        "smoothing": json.dumps(full.smoothing, sort_keys=True, default=float),
        "instrument_lag_full_s": float(full.lag), "instrument_lag_std_full_s": float(full.lag_std),
        "failures": json.dumps(info["failures"]),
        # samples whose refit stopped short of convergence (kept in the band: a stopped solve is near its
        # optimum, and leaving them out would bias it), named so that a reader can judge
        "not_converged": json.dumps({str(int(i)): [n for n in s.notes if "not converged" in n]
                                     for i, s in zip(info["indices"], samples)
                                     if any("not converged" in n for n in s.notes)}),
        "material": json.dumps(full.material().to_dict()),
        "shift": json.dumps(dma.shift_function(full, shift_model).to_dict()),
    })
    return ds


def _check_full(full, raw, T_ref, given) -> None:
    """ValueError unless ``full`` is a fit of these sets at this T_ref (with these given shifts)."""
    T = np.array([s.T for s in dma.split_sets(raw)])
    if full.T.shape != T.shape or not np.allclose(full.T, T, rtol=0, atol=1e-9) or full.T_ref != T_ref:
        raise ValueError(f"the full-data fit is of sets at {np.round(full.T, 4).tolist()} deg C, T_ref {full.T_ref:g}; "
                         f"the data have sets at {np.round(T, 4).tolist()} deg C, T_ref {T_ref:g}: fit the data again")
    if given is not None and not np.array_equal(full.log_aT, given):
        raise ValueError("the full-data fit holds other shift factors than the shift file: fit the data again")


def _bootstrap_data(spec, where, base_dir):
    """(raw table, T_ref [deg C], given shifts or None) of a measured-data fit spec a bootstrap can resample;
    ValueError naming ``where`` otherwise."""
    check_fit_spec(spec, base_dir=base_dir, where=where)
    d = spec.get("data") or {}
    if "file" not in d:
        raise ValueError(f"{where}: a bootstrap resamples measured data (data: {{file, T_ref}}), got {d!r}")
    raw = dma.read_table(Path(base_dir) / d["file"])
    if not raw.is_raw:
        raise ValueError(f"{where}: {raw.path} is a master curve (no T, Set columns): a bootstrap over sets needs "
                         f"raw sets at two or more temperatures")
    T_ref = float(d["T_ref"])
    given = None
    if "shift_file" in d:
        T = np.array([s.T for s in dma.split_sets(raw)])
        given = dma.given_shifts(dma.read_table(Path(base_dir) / d["shift_file"]), T, T_ref)
    return raw, T_ref, given


def _samples_variables(full, samples, indices):
    """The samples' Prony terms (padded to the widest), shifts, shift laws and lags as a dataset (docstring of
    :func:`samples_dataset`)."""
    import xarray as xr

    n = len(samples)
    terms = [s.prony_terms() for s in samples]
    width = max(len(e) for _, e, _ in terms)
    E = np.zeros((n, width))
    beta = np.full((n, width), math.nan)
    for i, (_, e, b) in enumerate(terms):
        E[i, :len(e)], beta[i, :len(b)] = e, b
    return xr.Dataset(
        {"E_inf": ("sample", np.array([t[0] for t in terms]),
                   {"units": "Pa", "long_name": "equilibrium modulus E_inf"}),
         "E": (("sample", "mode"), E, {"units": "Pa", "long_name": "Prony term modulus (0: padding)"}),
         "beta": (("sample", "mode"), beta, {"units": "s-1", "long_name": "Prony relaxation rate (NaN: padding)"}),
         "n_modes": ("sample", np.array([len(e) for _, e, _ in terms]), {"units": "1", "long_name": "Prony terms"}),
         "log_aT": (("sample", "T_set"), np.array([s.log_aT for s in samples]),
                    {"units": "1", "long_name": "log10 of the shift factor a_T (0 at T_ref)"}),
         "wlf_C1": ("sample", np.array([s.wlf["C1"] for s in samples]), {"units": "1", "long_name": "WLF C1"}),
         "wlf_C2": ("sample", np.array([s.wlf["C2"] for s in samples]), {"units": "K", "long_name": "WLF C2"}),
         "arrhenius_E_a": ("sample", np.array([s.arrhenius["E_a"] for s in samples]),
                           {"units": "J mol-1", "long_name": "Arrhenius activation energy"}),
         "lag": ("sample", np.array([s.lag for s in samples]),
                 {"units": "s", "long_name": "instrument time lag between force and displacement (0: not fitted)"}),
         "iterations": ("sample", np.array([s.joint.nfev if s.joint is not None else 0 for s in samples]),
                        {"units": "1", "long_name": "Levenberg-Marquardt iterations of the joint solve (0: none)"}),
         "log_aT_full": ("T_set", full.log_aT, {"units": "1", "long_name": "log10 a_T of the full-data fit"}),
         "log_aT_std": ("T_set", full.log_aT_std,
                        {"units": "1", "long_name": "linearised standard error of log10 a_T (full data)"})},
        coords={"sample": ("sample", np.asarray(indices), {"units": "1", "long_name": "bootstrap sample",
                                                                  "standard_name": "realization"}),
                "mode": ("mode", np.arange(width), {"units": "1", "long_name": "Prony term index (by rate)"}),
                "T_set": ("T_set", full.T, {"units": "degC", "long_name": "temperature of the measured set"})})
