"""A fit spec (the config's ``fits:`` entries) checked before anything is fitted.

What the workflow's planning needs of a fit, cheaply: names expanded (``butyl-prony-n{n}``), the model,
and for measured data the keys, T_ref, the shift model, and the data files read and checked (line and
column of a bad cell). Nothing here fits: :mod:`vcor.fitting.fits` runs the fits. Kept apart so that
planning a run (the Snakefile, every ``snakemake`` call) loads no optimiser.
"""

from __future__ import annotations

import inspect
import math

import numpy as np

from ..checks import positive
from ..io.csvfile import named_by, project_file
from ..materials.catalogue import FIT_SCALARS
from .dma.laws import SHIFT_LAWS

__all__ = ["BUILTIN_DATA_KEYS", "DMA_DATA_KEYS", "FIT_METHODS", "FIT_MODELS", "REMOVED_METHODS", "SHIFT_MODELS",
           "check_builtin_data", "check_fit_spec", "check_measured", "check_method", "expand_fits", "fit_families"]

#: shift functions a measured-data fit may store (:mod:`vcor.fitting.dma.laws`); the first is the default
SHIFT_MODELS = SHIFT_LAWS


def expand_fits(fits: dict, where: str = "fits") -> dict:
    """Config ``fits`` -> {material name: spec}. A name containing ``{n}`` with a list ``n_terms``
    expands to one Prony fit per N (e.g. ``butyl-prony-n{n}`` -> butyl-prony-n1, ...).

    Examples
    --------
    >>> from vcor.fitting.spec import expand_fits
    >>> expand_fits({"butyl-prony-n{n}": {"model": "prony", "n_terms": [2, 3]}})
    {'butyl-prony-n2': {'model': 'prony', 'n_terms': 2}, 'butyl-prony-n3': {'model': 'prony', 'n_terms': 3}}
    """
    out = {}
    for name, spec in (fits or {}).items():
        n_terms = spec.get("n_terms", "auto")
        if "{n}" in name:
            if not isinstance(n_terms, list):
                raise ValueError(f"{where}.{name}: a name with {{n}} needs a list n_terms")
            for n in n_terms:
                out[name.replace("{n}", str(int(n)))] = {**spec, "n_terms": int(n)}
        else:
            if isinstance(n_terms, list):
                raise ValueError(f"{where}.{name}: a list n_terms needs {{n}} in the name")
            out[name] = dict(spec)
    return out


def fit_families(fits: dict) -> dict[str, list[str]]:
    """{family name: member names} of the config's fit families (a name containing ``{n}``, one fit
    per N of its list ``n_terms``; :func:`expand_fits` names the members the same way).

    Examples
    --------
    >>> from vcor.fitting.spec import fit_families
    >>> fit_families({"butyl-prony-n{n}": {"model": "prony", "n_terms": [2, 3]}, "one": {"model": "cerf"}})
    {'butyl-prony-n{n}': ['butyl-prony-n2', 'butyl-prony-n3']}
    """
    return {name: list(dict.fromkeys(name.replace("{n}", str(int(n))) for n in spec["n_terms"]))
            for name, spec in (fits or {}).items() if "{n}" in name and isinstance(spec.get("n_terms"), list)}


#: the models a fit may have (the scalar parameters of each: vcor.materials.catalogue.FIT_SCALARS)
FIT_MODELS = tuple(FIT_SCALARS)
#: keys of a measured-data fit's ``data`` mapping
DMA_DATA_KEYS = {"file", "T_ref", "shift_file", "shift_model", "instrument_lag"}
#: methods of a measured-data fit (module docstring); the first is the default
FIT_METHODS = ("spectrum",)
#: method names vcor does not fit, and what replaces each (the one-line refusal names it)
REMOVED_METHODS = {"free": "method: spectrum replaces it (smooth spectrum with start-free shifts: on pyvisco's "
                           "data E' 0.89 % rms against 6.6 % and 3 tan delta extrema against 50); drop the key"}


def check_measured(spec: dict, where: str) -> tuple[dict, float, str]:
    """The keys of a measured-data fit spec, checked without reading its files: (data, T_ref [deg C],
    shift model); ValueError naming ``<where>.<key>``."""
    d = spec["data"]
    unknown = set(d) - DMA_DATA_KEYS
    if unknown:
        raise ValueError(f"{where}.data: unknown key{'s' if len(unknown) > 1 else ''} {sorted(unknown)}; it takes "
                         f"{sorted(DMA_DATA_KEYS)} (file and T_ref required)")
    if "T_ref" not in d:
        raise ValueError(f"{where}.data.T_ref missing: the master curve's reference temperature (deg C), among "
                         f"the data's sets (file and T_ref are required)")
    if spec.get("model") != "prony":
        raise ValueError(f"{where}.model: a fit to measured data is a Prony fit (model: prony), "
                         f"got {spec.get('model')!r}")
    check_method(spec, where)
    shift_model = d.get("shift_model", SHIFT_MODELS[0])
    if shift_model not in SHIFT_MODELS:
        raise ValueError(f"{where}.data.shift_model must be one of {list(SHIFT_MODELS)}, got {shift_model!r}")
    lag = d.get("instrument_lag", False)
    if not isinstance(lag, bool):
        raise ValueError(f"{where}.data.instrument_lag: true or false, got {lag!r}")
    try:
        T_ref = float(d["T_ref"])
    except (TypeError, ValueError):
        raise ValueError(f"{where}.data.T_ref must be a temperature in deg C, got {d['T_ref']!r}") from None
    if not math.isfinite(T_ref):
        raise ValueError(f"{where}.data.T_ref must be a finite temperature in deg C, got {d['T_ref']!r}")
    return d, T_ref, shift_model


def check_method(spec: dict, where: str) -> str:
    """The measured-data fit's method (module docstring); ValueError naming ``where.method``."""
    method = spec.get("method", FIT_METHODS[0])
    if method in REMOVED_METHODS:
        raise ValueError(f"{where}.method: {method!r} is not a method; {REMOVED_METHODS[method]}")
    if method not in FIT_METHODS:
        raise ValueError(f"{where}.method must be one of {list(FIT_METHODS)}, got {method!r}")
    if spec.get("n_terms", "auto") != "auto":
        raise ValueError(f"{where}.n_terms: method spectrum places its modes on a fixed grid (2 per decade of the "
                         f"data's reduced range): n_terms must be auto")
    return method


#: the keys of a fit to the built-in data (the Bagley-Torvik law sampled, vcor.fitting.prony.bagley_torvik_data)
BUILTIN_DATA_KEYS = frozenset({"source", "f_min", "f_max", "n_freq", "n_time"})


def check_builtin_data(d, where: str) -> None:
    """The ``data`` block of a fit without a ``file`` (the built-in Bagley-Torvik data): its keys, the band
    0 < f_min < f_max (Hz) and sample counts n_freq, n_time >= 3; ValueError naming ``<where>.<key>``."""
    if not isinstance(d, dict):
        raise ValueError(f"{where}: a mapping, got {d!r}")  # noqa: TRY004 (a config value: ValueError)
    unknown = set(d) - BUILTIN_DATA_KEYS
    if unknown:
        measured = sorted(unknown & DMA_DATA_KEYS)
        said = (f"{', '.join(measured)} belong{'s' if len(measured) == 1 else ''} to measured data, which needs file "
                f"(and T_ref)" if measured else f"unknown key{'s' if len(unknown) > 1 else ''} {sorted(unknown)}")
        raise ValueError(f"{where}: {said}; the built-in data take {sorted(BUILTIN_DATA_KEYS)}")
    if d.get("source", "bagley-torvik") != "bagley-torvik":
        raise ValueError(f"{where}.source must be 'bagley-torvik' (the one built-in data set), got {d['source']!r}")
    if "f_min" in d or "f_max" in d:
        for k in ("f_min", "f_max"):
            if k in d:
                positive(f"{where}.{k}", d[k], unit="Hz")
        from .prony import bagley_torvik_data  # (scipy: not loaded to plan a config that gives no band)

        band_default = inspect.signature(bagley_torvik_data).parameters
        f_min, f_max = (d.get(k, band_default[k].default) for k in ("f_min", "f_max"))
        if not float(f_min) < float(f_max):
            raise ValueError(f"{where}: f_min < f_max (Hz), got f_min = {f_min:g}, f_max = {f_max:g}")
    for k in ("n_freq", "n_time"):
        if k in d and (isinstance(d[k], bool) or not isinstance(d[k], int) or d[k] < 3):
            raise ValueError(f"{where}.{k} must be an integer >= 3, got {d[k]!r}")


def _read(key: str, value, base_dir, what: str):
    """The DMA or shift-factor table the config ``key`` names (:func:`vcor.fitting.dma.data.read_table`); its
    refusals name the key, and the file, line and column."""
    from .dma.data import read_table

    path = project_file(key, value, base_dir, what)
    with named_by(key):
        return read_table(path)


def check_fit_spec(spec: dict, base_dir=".", where: str = "fit") -> None:
    """What can be checked of a fit spec before fitting, naming ``<where>.<key>`` (for a data file's content,
    that key and then the file's line and column): the model, and for measured data the keys, T_ref, and the
    files read and checked (frequency-domain data; raw sets at two or more temperatures; shift factors covering
    the sets).

    Examples
    --------
    >>> from vcor.fitting.spec import check_fit_spec
    >>> check_fit_spec({"model": "prony", "n_terms": 3}) is None
    True
    >>> check_fit_spec({"model": "maxwell"}, where="fits.rubber")
    Traceback (most recent call last):
    ...
    ValueError: fits.rubber.model: one of ['prony', 'cerf'], got 'maxwell'
    """
    model = spec.get("model")
    if model not in FIT_MODELS:
        raise ValueError(f"{where}.model: one of {list(FIT_MODELS)}, got {model!r}")
    if "file" not in (spec.get("data") or {}):
        check_builtin_data(spec.get("data") or {}, f"{where}.data")
        return
    from .dma.data import check_data
    from .dma.sets import split_sets

    d, T_ref, shift_model = check_measured(spec, where)
    raw = _read(f"{where}.data.file", d["file"], base_dir, "the DMA file")
    shifts = (_read(f"{where}.data.shift_file", d["shift_file"], base_dir, "the shift-factor file")
              if "shift_file" in d else None)
    with named_by(f"{where}.data"):  # the sets of the data file, the shift factors' cover of them
        check_data(raw, shifts)
    if d.get("instrument_lag") and not raw.is_raw:
        raise ValueError(f"{where}.data.instrument_lag: {raw.path} is a master curve (no T, Set columns); the lag is "
                         f"told from the material by superposing sets at two or more temperatures")
    if shift_model != SHIFT_MODELS[0] and not raw.is_raw:  # (the default, table, is what a config omits)
        raise ValueError(f"{where}.data.shift_model: {raw.path} is a master curve (no T, Set columns): it has no "
                         f"shift factors to fit a shift function to; give raw sets at two or more temperatures")
    if raw.is_raw and "shift_file" not in d:
        # the sets' shifts are zero at T_ref by interpolation between the sets around it: outside them the
        # zero would be extrapolated and the shift function fitted through it, off inside the data
        T = np.array([s.T for s in split_sets(raw)])
        if not T.min() <= T_ref <= T.max():
            raise ValueError(f"{where}.data.T_ref: {T_ref:g} deg C lies outside the sets' {T.min():.4g}..{T.max():.4g} "
                             f"deg C: the master curve's reference must lie among the data (other temperatures "
                             f"follow from the shift function)")
