"""Time-temperature superposition: shift functions log10 a_T(T) and the one scaling they drive.

The convention is pyvisco's: the master curve is measured at T_ref, and a material at temperature T
relaxes a_T times slower than at T_ref,

.. math:: E(t; T) = E_{ref}(t / a_T(T)),

applied to every model through :meth:`vcor.materials.Material.scaled` (Prony rates divided by
a_T, the fractional E1 times sqrt(a_T), the CERF b1 divided by sqrt(a_T), a Kelvin-Voigt tau times
a_T). Shift functions (T in deg C, C2 in K, E_a in J/mol):

* WLF: log10 a_T = -C1 (T - T_ref) / (C2 + T - T_ref), defined for T > T_ref - C2;
* Arrhenius: log10 a_T = E_a / (R ln 10) (1/T - 1/T_ref) with T in K;
* table: log10 a_T given at temperatures T_1 < ... < T_K (a fit's per-set shift factors), between
  them the monotone piecewise-cubic Hermite interpolant (PCHIP, Fritsch & Carlson 1980;
  ``scipy.interpolate.PchipInterpolator``): it passes through every tabulated value, is continuous
  with its slope (so COR(T) has no kinks at the sets), and is monotone wherever the table is, so it
  adds no extremum of a_T between sets. Shift factors curve in T (WLF): on WLF shifts 15 K apart,
  straight lines between the sets are up to 0.10 decade off, PCHIP 0.02
  (``python -m pytest -s tests/fitting/test_superpose.py -k tabulated`` prints both). It is not
  extrapolated: outside [T_1 - 0.5 K, T_K + 0.5 K] it refuses, naming the range. The 0.5 K
  (:data:`TABLE_TOLERANCE`) is the scatter of a DMA set's temperature readings about their mean (the
  set's temperature); within it the end pieces are continued. A measured set's shift function is a
  table by default: WLF does not describe every material's shifts (pyvisco's example leaves 0.78
  decade rms, ``docs/user-guide/dma.md``).
"""

from __future__ import annotations

import functools
import json
import math
from dataclasses import dataclass

import numpy as np

from ..checks import number, positive
from ..io.fileversion import version
from .models import Material

__all__ = ["GAS_CONSTANT", "SHIFT_MODELS", "TABLE_TOLERANCE", "ZERO_CELSIUS", "ShiftFunction", "at_temperature",
           "shift_from_file", "table_log_aT", "time_shifted", "wlf_log_aT"]

#: molar gas constant, J/(mol K)
GAS_CONSTANT = 8.314462618
#: 0 deg C in K: temperatures are given in deg C, absolute ones (Arrhenius) are T + ZERO_CELSIUS
ZERO_CELSIUS = 273.15
#: the shift-function models
SHIFT_MODELS = ("wlf", "arrhenius", "table")
#: how far (K) a table reaches beyond its first and last temperature (module docstring)
TABLE_TOLERANCE = 0.5


def wlf_log_aT(T, T_ref, C1, C2):
    """WLF: log10 a_T = -C1 (T - T_ref) / (C2 + T - T_ref) (T, T_ref in deg C, C2 in K; C1 dimensionless)."""
    dT = np.asarray(T, dtype=float) - T_ref
    return -C1 * dT / (C2 + dT)


def time_shifted(material: Material, log_aT: float) -> Material:
    """``material`` at a temperature where log10 a_T = ``log_aT`` relative to its reference:
    E(t; T) = E_ref(t / a_T) (module docstring)."""
    value = number("log_aT", log_aT, -300.0, 300.0, unit="(log10 of a_T)")
    return material.scaled(time=10.0**value)


@dataclass(kw_only=True, frozen=True)
class ShiftFunction:
    r"""log10 a_T(T) of a material at the reference temperature ``T_ref`` (deg C).

    ``model`` "wlf" (C1, C2 in K), "arrhenius" (E_a in J/mol) or "table" (``T`` in deg C, strictly
    increasing, and ``log_aT`` in decades at those temperatures, PCHIP between them: module
    docstring, :func:`table_log_aT`). Built from a config spec by :meth:`from_spec`; :meth:`to_dict`
    gives that spec back.
    """

    model: str
    T_ref: float
    C1: float = math.nan
    C2: float = math.nan
    E_a: float = math.nan
    T: tuple = ()
    log_aT_table: tuple = ()

    def __post_init__(self):
        if self.model not in SHIFT_MODELS:
            raise ValueError(f"shift model must be one of {list(SHIFT_MODELS)}, got {self.model!r}")
        if self.model == "table":
            _check_table(self.T, self.log_aT_table, self.T_ref, "shift")
            object.__setattr__(self, "T", tuple(float(x) for x in self.T))
            object.__setattr__(self, "log_aT_table", tuple(float(x) for x in self.log_aT_table))

    @classmethod
    def table(cls, T_ref: float, T, log_aT) -> ShiftFunction:
        """A tabulated shift function: ``log_aT`` (decades) at temperatures ``T`` (deg C, increasing)."""
        return cls(model="table", T_ref=float(T_ref), T=tuple(np.asarray(T, float)),
                   log_aT_table=tuple(np.asarray(log_aT, float)))

    @classmethod
    def from_spec(cls, spec: dict, where: str = "shift") -> ShiftFunction:
        """From ``{model: wlf, C1, C2, T_ref}``, ``{model: arrhenius, E_a, T_ref}`` or
        ``{model: table, T: [...], log_aT: [...], T_ref}``; errors name ``where.<key>`` and the allowed
        range."""
        if not isinstance(spec, dict) or spec.get("model") not in SHIFT_MODELS:
            raise ValueError(f"{where}: a mapping with model wlf (C1, C2 [K], T_ref [deg C]), arrhenius "
                             f"(E_a [J/mol], T_ref [deg C]) or table (T [deg C], log_aT, T_ref [deg C]), got {spec!r}")
        need = {"wlf": ("C1", "C2", "T_ref"), "arrhenius": ("E_a", "T_ref"),
                "table": ("T", "log_aT", "T_ref")}[spec["model"]]
        extra = set(spec) - set(need) - {"model"}
        missing = [k for k in need if k not in spec]
        if missing or extra:
            problems = [f"missing {missing}" if missing else "", f"unknown {sorted(extra)}" if extra else ""]
            raise ValueError(f"{where} ({spec['model']}): {'; '.join(p for p in problems if p)}; takes {list(need)}")
        T_ref = number(f"{where}.T_ref", spec["T_ref"], -ZERO_CELSIUS, unit="deg C")
        if spec["model"] == "table":
            _check_table(spec["T"], spec["log_aT"], T_ref, where)
            return cls.table(T_ref, spec["T"], spec["log_aT"])
        units = {"C1": "", "C2": "K", "E_a": "J/mol"}
        values = {k: positive(f"{where}.{k}", spec[k], unit=units[k]) for k in need if k != "T_ref"}
        return cls(model=spec["model"], T_ref=T_ref, **values)

    def valid_range(self) -> tuple[float, float]:
        """Temperatures (deg C) where a_T is defined: T > T_ref - C2 (WLF, open), T > -273.15
        (Arrhenius, open), [T_1 - 0.5, T_K + 0.5] (table, closed; module docstring)."""
        if self.model == "table":
            return self.T[0] - TABLE_TOLERANCE, self.T[-1] + TABLE_TOLERANCE
        lo = self.T_ref - self.C2 if self.model == "wlf" else -ZERO_CELSIUS
        return lo, math.inf

    def log_aT(self, T: float) -> float:
        """log10 a_T at T (deg C); ValueError naming T and the valid range outside it."""
        lo, hi = self.valid_range()
        number_like = not isinstance(T, bool) and isinstance(T, (int, float, np.floating, np.integer))
        if self.model == "table":
            if not (number_like and math.isfinite(T) and lo <= T <= hi):
                raise ValueError(f"temperature T must be in [{lo:g}, {hi:g}] deg C for this tabulated shift function "
                                 f"(the measured sets' range, T_ref = {self.T_ref:g} deg C; a table is not "
                                 f"extrapolated), got {T!r}")
            return float(self._interpolant(T))
        if not (number_like and math.isfinite(T) and lo < T):
            raise ValueError(f"temperature T must be in ({lo:g}, inf) deg C for this {self.model} shift function "
                             f"(T_ref = {self.T_ref:g} deg C), got {T!r}")
        if self.model == "wlf":
            return float(wlf_log_aT(T, self.T_ref, self.C1, self.C2))
        return (self.E_a / (GAS_CONSTANT * math.log(10.0))
                * (1.0 / (T + ZERO_CELSIUS) - 1.0 / (self.T_ref + ZERO_CELSIUS)))

    @functools.cached_property
    def _interpolant(self):
        return _pchip(self.T, self.log_aT_table)

    def to_dict(self) -> dict:
        """The spec :meth:`from_spec` takes (JSON-ready)."""
        d = {"model": self.model, "T_ref": self.T_ref}
        if self.model == "wlf":
            d.update(C1=self.C1, C2=self.C2)
        elif self.model == "arrhenius":
            d.update(E_a=self.E_a)
        else:
            d.update(T=list(self.T), log_aT=list(self.log_aT_table))
        return d


def _pchip(T, log_aT):
    from scipy.interpolate import PchipInterpolator

    return PchipInterpolator(np.asarray(T, float), np.asarray(log_aT, float), extrapolate=True)


def table_log_aT(T_table, log_aT_table, T):
    """log10 a_T at ``T`` (deg C, scalar or array) from a table (temperatures deg C, strictly
    increasing; log_aT decades): the monotone piecewise-cubic Hermite interpolant (module docstring),
    its end pieces continued beyond the table (callers limit that to :data:`TABLE_TOLERANCE`)."""
    return _pchip(T_table, log_aT_table)(np.asarray(T, float))


def _check_table(T, log_aT, T_ref, where):
    """A table's temperatures (deg C): finite, strictly increasing, at least two, as many as log_aT
    (finite, decades); T_ref inside the range (a fit's table is 0 there; a given one is taken as it is)."""
    try:
        x, y = np.asarray(T, dtype=float), np.asarray(log_aT, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{where}: T and log_aT must be lists of numbers, got {T!r} and {log_aT!r}") from None
    if x.ndim != 1 or x.shape != y.shape or x.size < 2:
        raise ValueError(f"{where}: T and log_aT must be lists of equal length >= 2, "
                         f"got {np.shape(x)} and {np.shape(y)}")
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y)) and np.all(np.diff(x) > 0) and x[0] > -ZERO_CELSIUS):
        raise ValueError(f"{where}.T: temperatures (deg C) must be finite, above {-ZERO_CELSIUS:g} and strictly "
                         f"increasing, with finite log_aT; got T = {x.tolist()}")
    if not x[0] <= T_ref <= x[-1]:
        raise ValueError(f"{where}.T_ref: {T_ref:g} deg C lies outside the table's {x[0]:g}..{x[-1]:g} deg C")


def at_temperature(material: Material, shift: ShiftFunction | None, T: float, name: str = "material") -> Material:
    """``material`` at temperature T (deg C) through ``shift``; ValueError when it has none."""
    if shift is None:
        raise ValueError(f"material {name!r} has no shift function: a temperature axis T needs one "
                         f"(materials.{name}.shift in the config, or a fit to multi-temperature data)")
    return time_shifted(material, shift.log_aT(T))


def shift_from_file(path) -> ShiftFunction | None:
    """The ShiftFunction stored with a material file (attribute ``shift``), or None. Read once per
    file version (cached on path and modification time: a sweep asks for it at every point)."""
    key = version(path)
    if key is None:
        raise FileNotFoundError(f"no material file {path}")
    return _shift_cached(*key)


@functools.lru_cache(maxsize=64)
def _shift_cached(path: str, mtime_ns: int):
    import xarray as xr

    with xr.open_dataset(path) as ds:
        text = ds.attrs.get("shift")
    return ShiftFunction.from_spec(json.loads(text)) if text else None
