"""Time-temperature superposition: shift functions log10 a_T(T) and the one scaling they drive.

The convention is pyvisco's: the master curve is measured at T_ref, and a material at temperature T
relaxes a_T times slower than at T_ref,

.. math:: E(t; T) = E_{ref}(t / a_T(T)),

applied to every model through :meth:`vcor.materials.Material.scaled` (Prony rates divided by
a_T, the fractional E1 times sqrt(a_T), the CERF b1 divided by sqrt(a_T), a Kelvin-Voigt tau times
a_T). Shift functions (T in deg C, C2 in K, E_a in J/mol):

* WLF: log10 a_T = -C1 (T - T_ref) / (C2 + T - T_ref), defined for T > T_ref - C2;
* Arrhenius: log10 a_T = E_a / (R ln 10) (1/T - 1/T_ref) with T in K.
"""

from __future__ import annotations

import functools
import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..checks import number, positive
from .models import Material

__all__ = ["GAS_CONSTANT", "ShiftFunction", "at_temperature", "shift_from_file", "time_shifted", "wlf_log_aT"]

#: molar gas constant, J/(mol K)
GAS_CONSTANT = 8.314462618


def wlf_log_aT(T, T_ref, C1, C2):
    """WLF: log10 a_T = -C1 (T - T_ref) / (C2 + T - T_ref) (T, T_ref in deg C, C2 in K; C1 dimensionless)."""
    dT = np.asarray(T, dtype=float) - T_ref
    return -C1 * dT / (C2 + dT)


def time_shifted(material: Material, log_aT: float) -> Material:
    """``material`` at a temperature where log10 a_T = ``log_aT`` relative to its reference:
    E(t; T) = E_ref(t / a_T) (module docstring)."""
    value = number("log_aT", log_aT, -300.0, 300.0, unit="(log10 of a_T)")
    return material.scaled(time=10.0**value)


@dataclass(frozen=True)
class ShiftFunction:
    """log10 a_T(T) of a material: ``model`` "wlf" (C1, C2 in K) or "arrhenius" (E_a in J/mol), at the
    reference temperature ``T_ref`` (deg C). Built from a config spec by :meth:`from_spec`."""

    model: str
    T_ref: float
    C1: float = math.nan
    C2: float = math.nan
    E_a: float = math.nan

    @classmethod
    def from_spec(cls, spec: dict, where: str = "shift") -> ShiftFunction:
        """From ``{model: wlf, C1, C2, T_ref}`` or ``{model: arrhenius, E_a, T_ref}``; errors name
        ``where.<key>`` and the allowed range."""
        if not isinstance(spec, dict) or spec.get("model") not in ("wlf", "arrhenius"):
            raise ValueError(f"{where}: a mapping with model wlf (C1, C2 [K], T_ref [deg C]) or arrhenius "
                             f"(E_a [J/mol], T_ref [deg C]), got {spec!r}")
        need = {"wlf": ("C1", "C2", "T_ref"), "arrhenius": ("E_a", "T_ref")}[spec["model"]]
        extra = set(spec) - set(need) - {"model"}
        missing = [k for k in need if k not in spec]
        if missing or extra:
            raise ValueError(f"{where} ({spec['model']}): missing {missing}, unknown {sorted(extra)}; takes {list(need)}")
        units = {"C1": "", "C2": "K", "E_a": "J/mol"}
        values = {k: (number(f"{where}.T_ref", spec[k], -273.15, unit="deg C") if k == "T_ref"
                      else positive(f"{where}.{k}", spec[k], unit=units[k])) for k in need}
        return cls(spec["model"], **values)

    def valid_range(self) -> tuple[float, float]:
        """Temperatures (deg C, open interval) where a_T is defined: T > T_ref - C2 (WLF), T > -273.15."""
        lo = self.T_ref - self.C2 if self.model == "wlf" else -273.15
        return lo, math.inf

    def log_aT(self, T: float) -> float:
        """log10 a_T at T (deg C); ValueError naming T and the valid range outside it."""
        lo, _ = self.valid_range()
        if isinstance(T, bool) or not isinstance(T, (int, float, np.floating, np.integer)) or not (
                math.isfinite(T) and T > lo):
            raise ValueError(f"temperature T must be in ({lo:g}, inf) deg C for this {self.model} shift function "
                             f"(T_ref = {self.T_ref:g} deg C), got {T!r}")
        if self.model == "wlf":
            return float(wlf_log_aT(T, self.T_ref, self.C1, self.C2))
        return self.E_a / (GAS_CONSTANT * math.log(10.0)) * (1.0 / (T + 273.15) - 1.0 / (self.T_ref + 273.15))

    def to_dict(self) -> dict:
        d = {"model": self.model, "T_ref": self.T_ref}
        d.update({"C1": self.C1, "C2": self.C2} if self.model == "wlf" else {"E_a": self.E_a})
        return d


def at_temperature(material: Material, shift: ShiftFunction | None, T: float, name: str = "material") -> Material:
    """``material`` at temperature T (deg C) through ``shift``; ValueError when it has none."""
    if shift is None:
        raise ValueError(f"material {name!r} has no shift function: a temperature axis T needs one "
                         f"(materials.{name}.shift in the config, or a fit to multi-temperature data)")
    return time_shifted(material, shift.log_aT(T))


def shift_from_file(path) -> ShiftFunction | None:
    """The ShiftFunction stored with a material file (attribute ``shift``), or None. Read once per
    file version (cached on path and modification time: a sweep asks for it at every point)."""
    path = Path(path)
    return _shift_cached(str(path.resolve()), path.stat().st_mtime_ns)


@functools.lru_cache(maxsize=64)
def _shift_cached(path: str, mtime_ns: int):
    import xarray as xr

    with xr.open_dataset(path) as ds:
        text = ds.attrs.get("shift")
    return ShiftFunction.from_spec(json.loads(text)) if text else None
