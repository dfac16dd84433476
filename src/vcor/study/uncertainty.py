"""Uncertainty of a scene's results from its measured data: bootstrap samples of the material fits,
each carried through the whole sweep, reduced to a median and a band.

A scene asks for it::

    uncertainty: {bootstrap: 50, seed: 0, level: 0.95}

Every material of such a scene is a fit to measured DMA data (``fits.<name>.data``). The fit's data
are resampled ``bootstrap`` times (:func:`vcor.fitting.resample.samples_dataset`: shift factors and
spectrum refitted for every sample, starting from the full-data fit; the samples split over
:data:`SAMPLE_JOBS` jobs and merged), and the scene's grid gets one more axis, ``sample``
(0 .. bootstrap-1): every grid point is solved once per sample, with that sample's material and
shift factors. The sweep dataset then holds, for ``cor`` and ``t0``,

* ``cor``: the median over the samples,
* ``cor_lo``, ``cor_hi``: the central ``level`` band (the 2.5 % and 97.5 % quantiles at 0.95),
* ``cor_samples``: every sample's value (dims ``(..., sample)``), so that another band can be drawn
  from an archived dataset without solving again;

and every other output as the median over the samples. A point is ``ok`` only when every sample is
``ok``; otherwise its status is that of the first sample that is not, with a message saying how many
samples failed; its numbers are then those of the ``ok`` samples (NaN when none is).

What the band covers: the scatter of the measured data as the fit sees it (which points and sets
the data hold). What it does not cover: the model's own error (Hertz contact, Zener's plate, the
solver's error, far smaller), the choice of the Poisson ratio (a grid axis of its own) and errors
the data share (an instrument's calibration, a phase error common to every set).

A scene without ``uncertainty`` has no sample axis and computes none of this.

:func:`significant_reversals` counts the ups and downs of a curve (COR against T) that are larger than
the band there: the ones the data support.
"""

from __future__ import annotations

import functools

import numpy as np

from ..io.fileversion import version
from ..materials.catalogue import content_hash, with_parameters
from ..materials.shift import at_temperature
from .paths import samples

__all__ = [
    "BANDED",
    "KEYS",
    "MAX_BOOTSTRAP",
    "MIN_BOOTSTRAP",
    "SAMPLE_JOBS",
    "check_uncertainty",
    "reduce_samples",
    "sample_material",
    "samples_file",
    "samples_identity",
    "significant_reversals",
    "uncertainty_of",
]

#: keys of a scene's ``uncertainty`` mapping
KEYS = ("bootstrap", "seed", "level")
#: the most bootstrap samples a scene may ask for, and the fewest
MAX_BOOTSTRAP = 1000
MIN_BOOTSTRAP = 2
#: jobs a fit's bootstrap samples are split over (vcor.fitting.samples.part_indices), run side by side: the
#: reference machine has 2 cores, and the samples of one fit are the longest chain of a banded scene (fit,
#: samples, sweep); at most MIN_BOOTSTRAP, so that every job has a sample
SAMPLE_JOBS = 2
#: outputs stored as median, band and samples; every other float output is the median
BANDED = ("cor", "t0")


def uncertainty_of(scene: dict) -> dict | None:
    """The scene's uncertainty settings, complete (``{bootstrap, seed, level}``), or None."""
    spec = scene.get("uncertainty")
    if not spec:
        return None
    return {"bootstrap": int(spec["bootstrap"]), "seed": int(spec.get("seed", 0)),
            "level": float(spec.get("level", 0.95))}


def check_uncertainty(where: str, scene: dict, catalogue) -> None:
    """``<where>.uncertainty``: known keys, 2 <= bootstrap <= MAX_BOOTSTRAP, seed >= 0, 0 < level < 1,
    and every material of the scene a fit to measured data; ValueError naming the key otherwise."""
    spec = scene.get("uncertainty")
    if spec is None:
        return
    key = f"{where}.uncertainty"
    if not isinstance(spec, dict):
        raise ValueError(f"{key}: a mapping {{bootstrap: B, seed: 0, level: 0.95}}, got {spec!r}")
    unknown = sorted(set(spec) - set(KEYS))
    if unknown:
        raise ValueError(f"{key}: unknown keys {unknown}; allowed: {list(KEYS)}")
    b = spec.get("bootstrap")
    if isinstance(b, bool) or not isinstance(b, (int, np.integer)) or not MIN_BOOTSTRAP <= b <= MAX_BOOTSTRAP:
        raise ValueError(f"{key}.bootstrap: the number of bootstrap samples, an integer in "
                         f"[{MIN_BOOTSTRAP}, {MAX_BOOTSTRAP}], got {b!r}")
    seed = spec.get("seed", 0)
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ValueError(f"{key}.seed: an integer >= 0, got {seed!r}")
    level = spec.get("level", 0.95)
    if isinstance(level, bool) or not isinstance(level, (int, float)) or not 0 < float(level) < 1:
        raise ValueError(f"{key}.level: the band's probability, a number in (0, 1), got {level!r}")
    if scene.get("error_estimate"):
        raise ValueError(f"{where}.error_estimate: not with {key} (the solver's error, which the estimate "
                         f"measures, is orders of magnitude below a bootstrap band): use a scene of its own")
    if "sample" in (scene.get("grid") or {}):
        raise ValueError(f"{where}.grid.sample: 'sample' is the bootstrap axis of {key}; it is not a grid axis")
    for name in scene.get("materials") or []:
        data = (catalogue.fits.get(name) or {}).get("data") or {}
        if "file" not in data:
            raise ValueError(f"{key}: material {name!r} is not a fit to measured data (fits.<name>.data.file), "
                             f"so there is nothing to resample; an uncertainty scene sweeps such fits only")


def samples_file(material_dir: str, name: str, spec: dict) -> str:
    """The file of a fit's bootstrap samples for ``spec`` (:func:`uncertainty_of`), relative to the project
    (:func:`vcor.study.paths.samples`: every sample, the jobs' parts merged)."""
    return samples(material_dir, name, spec["bootstrap"], spec["seed"])


def samples_identity(catalogue, name: str, spec: dict, part: tuple[int, int] | None = None) -> str:
    """Content identity of a samples file: the fit's identity and the bootstrap settings, and for one job's
    share of the samples (``part``: (k, K), part k of K) that share. The merged file's identity does not
    depend on the split: sample i is the same whichever job fits it."""
    key = {"fit": catalogue.identity(name), "bootstrap": spec["bootstrap"], "seed": spec["seed"]}
    if part is not None:
        key["part"] = [int(part[0]), int(part[1])]
    return content_hash(key)


@functools.lru_cache(maxsize=16)
def _samples(path: str, mtime_ns: int):
    from ..fitting.samples import sample_materials
    from ..io.netcdf import read_dataset

    return sample_materials(read_dataset(path))


def sample_material(path, k: int, overrides: dict | None, T: float | None, name: str):
    """Sample ``k`` of the samples file ``path``: its material with ``overrides`` (grid parameters), at
    temperature ``T`` (deg C) through its own shift factors when given."""
    key = version(path)
    if key is None:
        raise ValueError(f"material {name!r} has no bootstrap samples file {path} yet: it is computed by the "
                         f"workflow's fit_samples rule")
    frozen = tuple(sorted((overrides or {}).items()))
    return _sample_at(*key, int(k), frozen, T, name)


#: materials built per job: a sweep visits each (sample, temperature) once per speed and geometry, and
#: building a sample's material at a temperature costs more than its impact (tens of Prony modes)
BUILT_MATERIALS = 8192


@functools.lru_cache(maxsize=BUILT_MATERIALS)
def _sample_at(path: str, mtime_ns: int, k: int, overrides: tuple, T: float | None, name: str):
    samples = _samples(path, mtime_ns)
    if not 0 <= k < len(samples):
        raise ValueError(f"sample {k} of material {name!r}: the file {path} holds {len(samples)} samples")
    material, shift = samples[k]
    if overrides:
        material = with_parameters(material, dict(overrides), name)
    return material if T is None else at_temperature(material, shift, T, name)


def reduce_samples(ds, level: float):
    """A sweep dataset with a ``sample`` dimension -> the dataset of the module docstring."""
    import xarray as xr

    from .. import status as _status

    if "sample" not in ds.dims:
        raise ValueError("the dataset has no 'sample' dimension to reduce")
    q = ((1.0 - level) / 2.0, (1.0 + level) / 2.0)
    ok = ds["status"] == _status.code("ok")
    out = {}
    for v in ds.data_vars:
        da = ds[v]
        if "sample" not in da.dims:
            out[v] = da
        elif np.issubdtype(da.dtype, np.floating):
            good = da.where(ok)
            med = good.median("sample", skipna=True)
            out[v] = med.assign_attrs(da.attrs)
            if v in BANDED:
                ln = da.attrs.get("long_name", v)
                lo = good.quantile(q[0], dim="sample", skipna=True).drop_vars("quantile")
                hi = good.quantile(q[1], dim="sample", skipna=True).drop_vars("quantile")
                out[v].attrs["long_name"] = f"{ln}, median over bootstrap samples"
                out[f"{v}_lo"] = lo.assign_attrs(units=da.attrs.get("units", "1"),
                                                 long_name=f"{ln}, lower end of the {level:g} bootstrap band")
                out[f"{v}_hi"] = hi.assign_attrs(units=da.attrs.get("units", "1"),
                                                 long_name=f"{ln}, upper end of the {level:g} bootstrap band")
                out[f"{v}_samples"] = da.assign_attrs(long_name=f"{ln}, per bootstrap sample")
    n_bad = (~ok).sum("sample")
    first_bad = (~ok).argmax("sample")
    status = ds["status"].isel(sample=first_bad)
    message = ds["message"].isel(sample=first_bad).values.astype(object)
    n = ds.sizes["sample"]
    bad = n_bad.values > 0
    for idx in zip(*np.nonzero(bad)):
        message[idx] = f"{int(n_bad.values[idx])} of {n} bootstrap samples not ok; sample " \
                       f"{int(first_bad.values[idx])}: {message[idx]}"
    out["status"] = status.where(bad, _status.code("ok")).astype(np.int8).assign_attrs(ds["status"].attrs)
    out["message"] = xr.DataArray(np.where(bad, message, "").astype(str), dims=status.dims,
                                  attrs=ds["message"].attrs)
    out["samples_ok"] = xr.DataArray((n - n_bad.values).astype(np.int16), dims=status.dims,
                                     attrs={"units": "1", "long_name": "bootstrap samples ok (a count)"})
    if "validity" in ds:  # a flag of any sample marks the point, with the first flagged sample's message
        axis = ds["validity"].dims.index("sample")
        flags = ds["validity"].values
        out["validity"] = xr.DataArray(np.bitwise_or.reduce(flags, axis=axis), dims=status.dims,
                                       attrs=ds["validity"].attrs)
        first_flag = (ds["validity"] != 0).argmax("sample")
        out["validity_message"] = ds["validity_message"].isel(sample=first_flag)
    coords = {c: ds[c] for c in ds.coords if c != "sample" and "sample" not in ds[c].dims}
    red = xr.Dataset(out, coords={**coords, "sample": ds["sample"]})
    red.attrs.update(ds.attrs)
    red.attrs["uncertainty_level"] = level
    red["sample"].attrs.update(units="1", long_name="bootstrap sample of the fitted materials",
                               standard_name="realization")
    return red


def significant_reversals(y, half_width) -> int:
    """Turns of a sampled curve that the band supports: interior local extrema of ``y`` (sign changes of
    its steps, flat steps skipped) whose rise or fall to the neighbouring extremum (or end) on *both*
    sides is larger than ``half_width`` at the extremum. A wiggle inside the band is not counted, nor is
    a turn whose one side is; one minimum of COR(T) counts 1.

    Parameters
    ----------
    y : array_like
        The curve (e.g. the median COR over a temperature grid), finite.
    half_width : array_like or float
        The band's half-width at each point ((cor_hi - cor_lo) / 2), same unit as ``y``.
    """
    y = np.asarray(y, float)
    hw = np.broadcast_to(np.asarray(half_width, float), y.shape)
    keep = np.flatnonzero(np.r_[True, np.diff(y) != 0])     # drop repeated values (flat steps)
    yk = y[keep]
    d = np.sign(np.diff(yk))
    turns = keep[1:-1][d[1:] != d[:-1]] if yk.size > 2 else np.array([], int)
    ends = np.concatenate([[0], turns, [y.size - 1]])
    count = 0
    for j in range(1, ends.size - 1):
        e = ends[j]
        if min(abs(y[e] - y[ends[j - 1]]), abs(y[e] - y[ends[j + 1]])) > hw[e]:
            count += 1
    return count
