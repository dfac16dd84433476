"""A fit's bootstrap samples file: the parts the samples jobs write, merged, and each sample's material.

:func:`vcor.fitting.resample.samples_dataset` writes the samples (or one job's share of them,
:func:`part_indices`); :func:`merge_samples` joins the parts into the file a scene reads, and
:func:`sample_materials` gives each sample's material and shift function. Apart from the resampling
and refitting (:mod:`vcor.fitting.resample`) so that the jobs that merge or read samples load no
optimiser.
"""

from __future__ import annotations

import json
import math

import numpy as np

from ..materials.models import Prony
from ..materials.shift import ShiftFunction

__all__ = ["BOOTSTRAP_ATTRS", "merge_samples", "not_converged", "part_indices", "sample_materials"]

#: attributes of a samples dataset that name its bootstrap (the same in every part of it; :func:`merge_samples`)
BOOTSTRAP_ATTRS = ("fit_name", "spec", "n", "seed", "mode", "T_ref", "shift_model", "smoothing",
                   "instrument_lag_full_s", "instrument_lag_std_full_s", "material", "shift")


def part_indices(n: int, part: int, parts: int) -> np.ndarray:
    """The samples that part ``part`` (0-based) of ``parts`` jobs fits of a bootstrap of ``n``: consecutive
    blocks of 0..n-1 whose sizes differ by at most one; together the parts hold every sample once."""
    for key, value, low in (("n", n, 1), ("parts", parts, 1), ("part", part, 0)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low:
            raise ValueError(f"{key}: an integer >= {low}, got {value!r}")
    if not part < parts <= n:
        raise ValueError(f"part {part} of {parts} of {n} samples: need 0 <= part < parts <= n")
    return np.array_split(np.arange(n), parts)[part]


def merge_samples(parts):
    """One samples dataset of the parts of a bootstrap (:func:`samples_dataset` with ``indices``): the
    samples in order, padded to the widest Prony series; ValueError unless the parts are of the same
    bootstrap and hold every sample 0..n-1 exactly once. The result is the dataset one job fitting every
    sample writes."""
    import xarray as xr

    parts = sorted(parts, key=lambda p: int(p["sample"].values[0]) if p.sizes["sample"] else -1)
    if not parts:
        raise ValueError("merge_samples: no parts given")
    keep = {k: parts[0].attrs.get(k) for k in BOOTSTRAP_ATTRS}
    for p in parts[1:]:
        other = {k: p.attrs.get(k) for k in BOOTSTRAP_ATTRS}
        if other != keep:
            raise ValueError(f"merge_samples: the parts are of different bootstraps (attributes "
                             f"{sorted(k for k in set(keep) | set(other) if keep.get(k) != other.get(k))} differ)")
    got = np.concatenate([p["sample"].values for p in parts])
    n = int(keep["n"])
    if not np.array_equal(np.sort(got), np.arange(n)):
        raise ValueError(f"merge_samples: the parts hold samples {got.tolist()}, not each of 0..{n - 1} once")
    # variables without a sample dimension (the full-data shifts) must be equal in every part
    ds = xr.concat(parts, dim="sample", data_vars="minimal", coords="minimal", compat="equals", join="outer",
                   fill_value={"E": 0.0, "beta": math.nan}, combine_attrs="override")
    ds["mode"].attrs = dict(parts[0]["mode"].attrs)
    ds.attrs["failures"] = json.dumps([f for p in parts for f in json.loads(p.attrs["failures"])])
    ds.attrs["not_converged"] = json.dumps({str(k): v for p in parts for k, v in not_converged(p).items()})
    return ds


def not_converged(ds) -> dict:
    """{sample: notes} of the samples of a :func:`vcor.fitting.resample.samples_dataset` whose refit stopped
    short of convergence (attribute ``not_converged``; empty for a file without it)."""
    return {int(k): v for k, v in json.loads(ds.attrs.get("not_converged", "{}")).items()}


def sample_materials(ds) -> list:
    """(Prony material, ShiftFunction) of every sample of a :func:`samples_dataset`, in sample order;
    the shift function is the dataset's ``shift_model`` (table: the sample's per-set log10 a_T)."""
    T_ref, model = float(ds.attrs["T_ref"]), ds.attrs["shift_model"]
    T = np.asarray(ds["T_set"].values, float)
    out = []
    for i in range(ds.sizes["sample"]):
        k = int(ds["n_modes"].values[i])
        mat = Prony(float(ds["E_inf"].values[i]), tuple(float(x) for x in ds["E"].values[i, :k]),
                    tuple(float(x) for x in ds["beta"].values[i, :k]))
        if model == "table":
            shift = ShiftFunction.table(T_ref, T, ds["log_aT"].values[i])
        elif model == "wlf":
            shift = ShiftFunction(model="wlf", T_ref=T_ref, C1=float(ds["wlf_C1"].values[i]),
                                  C2=float(ds["wlf_C2"].values[i]))
        else:
            shift = ShiftFunction(model="arrhenius", T_ref=T_ref, E_a=float(ds["arrhenius_E_a"].values[i]))
        out.append((mat, shift))
    return out
