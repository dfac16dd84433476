"""Fits named in a config (the ``fits:`` block): a spec -> its data -> a fitted material and its
record (residual curves, metrics), and the fit-metrics table of a scene.

Specs: ``{model: prony | cerf, n_terms: int | auto, tol, n_max, domain}`` on the built-in
Bagley-Torvik data (the fractional law of Green Eq. 23 on the paper's band), or
``{model: prony, method?, data: {file, T_ref, shift_file?, shift_model?, instrument_lag?}}`` on measured DMA data
(:mod:`vcor.fitting.dma`). A name containing ``{n}`` with a list ``n_terms`` expands to one fit per N.

Measured data are fitted by one method, ``method: spectrum`` (the default, and the only value):
start-free global shift factors refined together with a smooth relaxation spectrum, merged to 2 modes
per decade (:func:`vcor.fitting.dma.pipeline.fit_dma`). Smooth by construction: no tan delta ripple from
the fit. ``n_terms`` must be ``auto`` (the modes follow from the data's range). ``method: free`` (pairwise
shifts in E', then a Prony series with free relaxation times) is refused, naming ``method: spectrum`` as
its replacement: on pyvisco's data it was worse on every measure (E' 6.6 % rms against 0.89 %, 50 tan
delta extrema against 3, ``docs/user-guide/dma.md``).

``shift_model`` (default ``table``) is the shift function stored with the material: ``table`` (the
per-set log10 a_T, PCHIP in T between the sets, not extrapolated beyond them), ``wlf`` or ``arrhenius`` (fitted
to the per-set shifts).

``instrument_lag: true`` (method ``spectrum``, raw sets; default false) fits a time lag between the
instrument's force and displacement signals together with the shifts and the spectrum
(:func:`vcor.fitting.dma.joint.fit_with_shifts`): the material is then that of the data with the lag
removed, and the fit's record holds the lag, its standard error and the corrected master curve.

A fit of raw sets also records what a bootstrap of its data starts from (attribute ``bootstrap_start``,
:func:`full_fit_record`, read back by :func:`full_fit_from_file`): its shifts, lag, smooth spectrum and
the joint solve's optimum, so that the samples are refitted from this fit without fitting the full
data again (:mod:`vcor.fitting.resample`).
"""

from __future__ import annotations

import json
import math
import time
from pathlib import Path

import numpy as np

from ..materials.files import from_file
from ..materials.presets import get as _preset
from . import dma
from .dma.joint import JointStart
from .dma.laws import arrhenius_fit, wlf_fit
from .dma.pipeline import MODES_PER_DECADE
from .prony import FitData, FitResult, bagley_torvik_data, fit, metrics
from .spec import check_measured
from .spectrum.modes import reduce_modes
from .spectrum.smooth import SpectrumFit

__all__ = ["MEASURED_HEADER", "MEASURED_KEYS", "START_ATTR", "data_from_spec", "full_fit_from_file",
           "full_fit_from_record", "full_fit_record", "metrics_table", "result_dataset", "run_fit",
           "scene_metrics_table"]


def run_fit(spec: dict, base_dir="."):
    """(FitResult, FitData, extra attributes) of a fit spec: the built-in Bagley-Torvik data, or measured
    DMA data (``data: {file, T_ref [deg C], shift_file?, shift_model: table|wlf|arrhenius}``; pyvisco's
    CSV conventions, :mod:`vcor.fitting.dma`). Raw multi-temperature sets are superposed at T_ref (with the
    shift factors of ``shift_file``, or found from the data) and fitted by a smooth spectrum
    (:func:`vcor.fitting.dma.pipeline.fit_dma`); the shift function (``shift_model``, default a table of the
    per-set log a_T) is stored with the material (attribute ``shift``), the per-set shifts and their
    residuals in attribute ``superposition``.

    Examples
    --------
    A 3-term Prony series fitted to the built-in Bagley-Torvik data (the fractional law of Green
    Eq. 23 on 100 Hz..100 kHz):

    >>> from vcor.fitting.fits import run_fit
    >>> result, data, attrs = run_fit({"model": "prony", "n_terms": 3})
    >>> result.material.kind, len(result.material.E), f"|E*| rms error {result.metrics['abs_E_star_rms']:.1%}"
    ('prony', 3, '|E*| rms error 5.1%')
    """
    if "file" not in (spec.get("data") or {}):
        data = data_from_spec(spec)
        return fit(spec, data), data, {}
    d, T_ref, shift_model = check_measured(spec, "fit")
    raw = dma.read_table(Path(base_dir) / d["file"])
    if raw.kind != "frequency":
        raise ValueError(f"{raw.path}: measured-data fits take frequency-domain data (f,E_stor,E_loss)")
    shifts = dma.read_table(Path(base_dir) / d["shift_file"]) if "shift_file" in d else None
    if not raw.is_raw:
        c = raw.columns
        return _run_master(dma.MasterCurve.as_given(c["f"], c["E_stor"], c["E_loss"], T_ref), d)
    return _run_sets(raw, shifts, d, T_ref, shift_model)


def _measured_result(material, mc, d, settings, t_start):
    """(FitResult, FitData) of a material against a master curve ``mc`` (:class:`vcor.fitting.dma.MasterCurve`)."""
    data = FitData(omega=2 * math.pi * mc.f_red, E_star=mc.E_stor + 1j * mc.E_loss, name=str(d["file"]),
                   measured=True, T_point=mc.T_point)
    met = metrics(material, data)
    met["tan_delta_extrema"] = dma.tan_delta_extrema(material, float(mc.f_red.min()), float(mc.f_red.max()))
    return FitResult(material=material, metrics=met, settings=settings, n_terms=len(material.E),
                     fit_time=time.perf_counter() - t_start), data


def _run_master(mc, d):
    """A master curve as given (no temperature sets): the smooth spectrum, merged."""
    t_start = time.perf_counter()
    smooth, reduced = dma.fit_curve(mc.f_red, mc.E_stor, mc.E_loss)
    material = dma.DMAFit(T=mc.T, log_aT=mc.log_aT, log_aT_std=np.zeros(1), T_ref=mc.T_ref, spectrum=smooth,
                          reduced=reduced).material()
    settings = {"model": "prony", "method": "spectrum", "lam": smooth.lam, "modes_fine": smooth.n_modes,
                "merge_change": reduced.change}
    result, data = _measured_result(material, mc, d, settings, t_start)
    return result, data, {}


def _superposition_attrs(fitted, mc, shift, shift_model):
    """The fit's shifts, their errors and shift laws, as the JSON attribute ``superposition``."""
    residual = np.array([shift.log_aT(float(t)) for t in fitted.T]) - fitted.log_aT
    return json.dumps({
        "T_degC": fitted.T.tolist(), "log_aT": fitted.log_aT.tolist(), "log_aT_std": fitted.log_aT_std.tolist(),
        "shift_fit_residual": residual.tolist(), "shift_model": shift_model, "source": mc.source,
        "overlap_rms_log10_E_stor": mc.overlap_rms, "instrument_lag_s": fitted.lag,
        "instrument_lag_std_s": fitted.lag_std,
        "wlf": {k: fitted.wlf[k] for k in ("C1", "C2", "C1_std", "C2_std", "rms")},
        "arrhenius": {k: fitted.arrhenius[k] for k in ("E_a", "E_a_std", "rms")}}, default=float)


def _run_sets(raw, shifts, d, T_ref, shift_model):
    """Raw sets: shifts (given, or start-free and refined) with the smooth spectrum, merged."""
    t_start = time.perf_counter()
    T = np.array([s.T for s in dma.split_sets(raw)])
    given = dma.given_shifts(shifts, T, T_ref) if shifts is not None else None
    lag = bool(d.get("instrument_lag", False))
    fitted = dma.fit_dma(raw, T_ref, log_aT=given, lag=lag)
    shift = dma.shift_function(fitted, shift_model)
    mc = dma.master_curve(raw, fitted.log_aT, T_ref=T_ref, lag=fitted.lag,
                          source=f"given ({d['shift_file']}), PCHIP in T, zero at T_ref" if shifts is not None else
                          "global superposition of all sets, refined with the spectrum (vcor.fitting.dma)")
    settings = {"model": "prony", "method": "spectrum", "lam": fitted.spectrum.lam, "smoothing": fitted.smoothing,
                "modes_fine": fitted.spectrum.n_modes, "merge_change": fitted.reduced.change,
                "components": [1.0, dma.LOSS_WEIGHT], "notes": fitted.notes}  # no run times: the file is reproducible
    if lag:
        settings["instrument_lag"] = {"lag_s": fitted.lag, "lag_std_s": fitted.lag_std,
                                      "data": "the master curve is the measured data times exp(-i 2 pi f lag)"}
    result, data = _measured_result(fitted.material(), mc, d, settings, t_start)
    attrs = {"shift": json.dumps(shift.to_dict()),
             "superposition": _superposition_attrs(fitted, mc, shift, shift_model),
             START_ATTR: json.dumps(full_fit_record(fitted))}
    return result, data, attrs


#: attribute of a measured-data fit's material file that holds :func:`full_fit_record`
START_ATTR = "bootstrap_start"


def _spectrum_record(sp) -> dict:
    return {"tau_s": sp.tau.tolist(), "E_Pa": sp.E.tolist(), "E_inf_Pa": float(sp.E_inf), "lam": float(sp.lam),
            "method": sp.method, "f_range_Hz": [float(x) for x in sp.f_range], "notes": list(sp.notes)}


def full_fit_record(fitted) -> dict:
    """What a bootstrap starts from, of a fit of raw sets (:class:`vcor.fitting.dma.pipeline.DMAFit`), as
    plain JSON-ready values (floats exact): temperatures [deg C], shifts and their standard errors
    [decades], the lag and its standard error [s], the smooth spectrum (relaxation times [s], moduli
    [Pa], lambda, frequency range [Hz]) and, when the fit ran the joint solve, that solve's optimum
    (grid, spectrum, lag), lambda, which parameters it fitted and its diagnostics. The lambda scan's
    table, the metrics and the timings are left out (:func:`full_fit_from_record`)."""
    joint = fitted.joint
    record = {"T_degC": fitted.T.tolist(), "T_ref_degC": float(fitted.T_ref), "log_aT": fitted.log_aT.tolist(),
              "log_aT_std": np.asarray(fitted.log_aT_std, float).tolist(), "lag_s": float(fitted.lag),
              "lag_std_s": float(fitted.lag_std), "notes": list(fitted.notes),
              "spectrum": _spectrum_record(fitted.spectrum), "joint": None}
    if joint is not None:
        sol = joint.solution
        record["joint"] = {
            "start": {"tau_s": sol.tau.tolist(), "E_Pa": sol.E.tolist(), "E_inf_Pa": float(sol.E_inf),
                      "lag_s": float(sol.lag)},
            "lam_joint": float(joint.lam_joint),
            "components": [np.asarray(c, float).tolist() for c in joint.components],
            "free_shifts": bool(joint.free_shifts), "lag_fitted": bool(joint.lag_fitted),
            "held_set": int(joint.held_set),
            "at_bound": list(joint.at_bound), "objective": float(joint.objective), "iterations": int(joint.nfev),
            "cov": np.asarray(joint.cov, float).tolist(), "notes": list(joint.notes)}
    return record


def _spectrum(r: dict) -> SpectrumFit:
    tau, E = np.array(r["tau_s"], float), np.array(r["E_Pa"], float)
    return SpectrumFit(tau=tau, E=E, E_inf=float(r["E_inf_Pa"]), h=E / math.log(tau[1] / tau[0]), lam=float(r["lam"]),
                       method=r["method"], scan={}, metrics={}, f_range=tuple(r["f_range_Hz"]), time=0.0,
                       notes=list(r["notes"]))


def full_fit_from_record(record: dict):
    """The :class:`vcor.fitting.dma.pipeline.DMAFit` of a :func:`full_fit_record`: its merged modes and shift
    laws computed again from the spectrum and the shifts (as the fit did); no spline stage, no lambda
    scan table, metrics or timings."""
    T, log_aT, std = (np.array(record[k], float) for k in ("T_degC", "log_aT", "log_aT_std"))
    T_ref, spec = float(record["T_ref_degC"]), _spectrum(record["spectrum"])
    joint = None
    if record["joint"] is not None:
        j, st = record["joint"], record["joint"]["start"]
        solution = JointStart(tau=np.array(st["tau_s"], float), E_inf=float(st["E_inf_Pa"]),
                              E=np.array(st["E_Pa"], float), lag=float(st["lag_s"]))
        joint = dma.JointFit(T=T, log_aT=log_aT, log_aT_std=std if j["free_shifts"] else np.zeros(T.size),
                             at_bound=list(j["at_bound"]), components=tuple(np.asarray(c) if np.ndim(c) else float(c)
                                                                            for c in j["components"]),
                             lam_joint=float(j["lam_joint"]), spectrum=spec, objective=float(j["objective"]),
                             nfev=int(j["iterations"]), time=0.0, cov=np.array(j["cov"], float), notes=list(j["notes"]),
                             lag=float(record["lag_s"]), lag_std=float(record["lag_std_s"]),
                             lag_fitted=bool(j["lag_fitted"]), free_shifts=bool(j["free_shifts"]),
                             held_set=int(j["held_set"]), solution=solution)
    return dma.DMAFit(T=T, log_aT=log_aT, log_aT_std=std, T_ref=T_ref, joint=joint, spectrum=spec,
                      reduced=reduce_modes(spec, MODES_PER_DECADE), wlf=wlf_fit(T, log_aT, T_ref, sigma=std),
                      arrhenius=arrhenius_fit(T, log_aT, T_ref, sigma=std), notes=list(record["notes"]),
                      lag=float(record["lag_s"]), lag_std=float(record["lag_std_s"]))


def full_fit_from_file(path):
    """The fit of raw sets that a material file records (:func:`full_fit_from_record`); ValueError naming the
    file when it holds none (a fit of a master curve or of built-in data, or a file older than the record)."""
    import xarray as xr

    with xr.open_dataset(path) as ds:
        text = ds.attrs.get(START_ATTR)
    if text is None:
        raise ValueError(f"{path}: no attribute {START_ATTR!r}: not a fit of raw DMA sets by this vcor; fit it again "
                         f"(the workflow's fit_material rule)")
    return full_fit_from_record(json.loads(text))


def data_from_spec(spec: dict) -> FitData:
    """The data a fit spec names (only the Bagley-Torvik fractional law is built in)."""
    d = dict(spec.get("data") or {})
    source = d.pop("source", "bagley-torvik")
    if source != "bagley-torvik":
        raise ValueError(f"fit data source must be 'bagley-torvik', got {source!r}")
    return bagley_torvik_data(**d)


def result_dataset(result: FitResult, data: FitData, spec: dict):
    """NetCDF-ready record of a fit: parameters (attrs), metrics, data and fit curves, residuals.
    Deterministic: no time stamps or timings inside.

    Examples
    --------
    >>> from vcor.fitting.fits import result_dataset, run_fit
    >>> spec = {"model": "prony", "n_terms": 3}
    >>> ds = result_dataset(*run_fit(spec)[:2], spec)
    >>> ds["storage_fit"].attrs["units"], sorted(ds.coords)
    ('Pa', ['omega', 't'])
    """
    import xarray as xr

    mat = result.material
    ds = xr.Dataset()
    if data.has_time:
        ds = ds.assign_coords(t=("t", data.t, {"units": "s", "long_name": "time (fit window)"}))
        ef = mat.relaxation_modulus(data.t)
        ds["E_t_data"] = ("t", data.E_t, {"units": "Pa", "long_name": "relaxation modulus, data"})
        ds["E_t_fit"] = ("t", ef, {"units": "Pa", "long_name": "relaxation modulus, fit"})
        ds["E_t_rel_err"] = ("t", ef / data.E_t - 1, {"units": "1", "long_name": "relative error of E(t)"})
    if data.has_freq:
        ds = ds.assign_coords(omega=("omega", data.omega, {"units": "rad s-1", "long_name": (
            "reduced angular frequency at the reference temperature (a measured set's own times its a_T; fit band)"
            if data.measured else "angular frequency (fit band)")}))
        es = mat.complex_modulus(data.omega)
        for part, fn in (("storage", np.real), ("loss", np.imag)):
            ds[f"{part}_data"] = ("omega", fn(data.E_star), {"units": "Pa", "long_name": f"{part} modulus, data"})
            ds[f"{part}_fit"] = ("omega", fn(es), {"units": "Pa", "long_name": f"{part} modulus, fit"})
        ds["abs_E_star_rel_err"] = ("omega", np.abs(es) / np.abs(data.E_star) - 1,
                                    {"units": "1", "long_name": "relative error of |E*|"})
        if data.T_point is not None:
            ds["T_set"] = ("omega", np.asarray(data.T_point, float),
                           {"units": "degC", "long_name": "temperature of the measured set of each point"})
        ds["tan_delta_rel_err"] = ("omega", (es.imag / es.real) / (data.E_star.imag / data.E_star.real) - 1,
                                   {"units": "1", "long_name": "relative error of tan delta"})
    ds.attrs.update({
        "material": json.dumps(mat.to_dict(), sort_keys=True),
        "fit_spec": json.dumps(spec, sort_keys=True),
        "fit_settings": json.dumps(result.settings, sort_keys=True, default=str),
        "metrics": json.dumps(result.metrics, sort_keys=True),
        "n_terms_tried": json.dumps(result.tried),
        "data": data.name,
    })
    return ds


def scene_metrics_table(names, material_dir) -> str:
    """The fit-metrics table of a scene: fits of the built-in Bagley-Torvik data beside the paper's own
    sets, evaluated on those data; fits of measured data against their own (superposed) data, as
    recorded in their files (attribute ``metrics``)."""
    import xarray as xr

    builtin, measured = [], []
    for name in names:
        path = Path(material_dir) / f"{name}.nc"
        with xr.open_dataset(path) as ds:
            spec, met = json.loads(ds.attrs["fit_spec"]), json.loads(ds.attrs["metrics"])
        mat = from_file(path)
        (measured if "file" in (spec.get("data") or {}) else builtin).append((name, mat, met))
    out = ""
    if builtin or not measured:
        data = bagley_torvik_data()
        rows = [(n, _preset(n), None) for n in ("butyl-cerf", "butyl-prony3")] + builtin
        out += metrics_table([(n, m, metrics(m, data)) for n, m, _ in rows])
    if measured:
        out += metrics_table(measured, MEASURED_KEYS, MEASURED_HEADER)
    return out


#: the metrics and the header of a table of fits to measured data
MEASURED_KEYS = ["abs_E_star_rms", "storage_rms", "loss_rms", "tan_delta_rms", "storage_max", "loss_max",
                 "tan_delta_max"]
MEASURED_HEADER = ("# fits of measured data: relative errors against their own superposed data (master\n"
                   "# curve at T_ref: E', E'', tan delta); max and RMS, dimensionless")


def metrics_table(rows, keys=None, header=None) -> str:
    """Plain-text table of metrics: rows = [(name, material, metrics dict)]."""
    keys = keys or ["E_t_max", "E_t_rms", "abs_E_star_max", "abs_E_star_rms", "tan_delta_max", "tan_delta_rms"]
    head = f"{'material':22s} {'terms':>5s} " + " ".join(f"{k:>15s}" for k in keys)
    header = header or ("# relative errors against each fit's data (built-in fits: the Bagley-Torvik fractional law,"
                        " E(t)\n# over the window, |E*| and tan delta over 1e2..1e5 Hz); max and RMS, dimensionless")
    lines = [header, head]
    for name, mat, met in rows:
        terms = str(len(mat.E)) if getattr(mat, "kind", "") == "prony" else "-"
        lines.append(f"{name:22s} {terms:>5s} " + " ".join(f"{met.get(k, math.nan):15.4e}" for k in keys))
    return "\n".join(lines) + "\n"
