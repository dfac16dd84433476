"""Measured DMA files: pyvisco's CSV conventions, read and checked.

Files (the column and units conventions of NREL's pyvisco input files):

* frequency domain ``f,E_stor,E_loss`` (Hz; Pa, kPa, MPa or GPa),
* time domain ``t,E_relax`` (s; a modulus unit),
* raw multi-temperature sets: either of the above plus ``T,Set`` (deg C, written ``C``, ``°C`` or ``degC``,
  or K; set number),
* shift factors ``T,log_aT`` (deg C or K, as for sets; log10 of a_T, a_T = 10^log_aT).

A second row of unit names is allowed (and read); without it the values are SI (Hz, s, Pa, deg C).
A UTF-8 byte-order mark is accepted. Every error names the file, the line (1-based) and the column.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...io.csvfile import cell_number, data_rows, read_rows, units_row
from ...io.csvfile import header as column_names
from ...materials.shift import TABLE_TOLERANCE, ZERO_CELSIUS
from .sets import split_sets

__all__ = ["KINDS", "UNITS", "DMATable", "check_data", "read_table"]

MODULUS_UNITS = {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9}
#: per column, its units: a factor to SI, for T an offset to deg C
UNITS = {"f": {"Hz": 1.0}, "t": {"s": 1.0}, "E_stor": MODULUS_UNITS, "E_loss": MODULUS_UNITS,
         "E_relax": MODULUS_UNITS, "T": {"C": 0.0, "°C": 0.0, "degC": 0.0, "K": -ZERO_CELSIUS},
         "Set": {"-": 1.0, "": 1.0},
         "log_aT": {"-": 1.0, "": 1.0}}
#: the kinds of file, by the columns that make them
KINDS = {"frequency": ("f", "E_stor", "E_loss"), "time": ("t", "E_relax"), "shift": ("T", "log_aT")}
POSITIVE = ("f", "t", "E_stor", "E_loss", "E_relax")


@dataclass(frozen=True, kw_only=True)
class DMATable:
    """A read file: ``kind`` (frequency, time or shift), columns in SI (Hz, s, Pa, deg C), the path, and
    the line of each row in the file (1-based; None for a table not read from a file)."""

    kind: str
    columns: dict
    path: str
    lines: np.ndarray | None = field(default=None, compare=False, repr=False)

    @property
    def is_raw(self) -> bool:
        return "T" in self.columns and "Set" in self.columns and self.kind != "shift"


def _where(path, line, col=None):
    return f"{path}, line {line}" + (f", column {col!r}" if col is not None else "")


def _kind(path, header):
    """The file's kind from its header; ValueError naming the file's first line."""
    kind = next((k for k, cols in KINDS.items() if set(cols) <= set(header)), None)
    allowed = set().union(*KINDS.values(), {"Set"})
    unknown = [h for h in header if h not in allowed]
    if kind is None or unknown:
        raise ValueError(f"{_where(path, 1)}: columns {header}: {'' if kind else _missing(header)}"
                         f"expected f,E_stor,E_loss (frequency), t,E_relax "
                         f"(time) or T,log_aT (shift factors), optionally with T,Set"
                         + (f"; unknown (misspelt?) columns {unknown}" if unknown else ""))
    if kind != "shift" and ("T" in header) != ("Set" in header):
        raise ValueError(f"{_where(path, 1)}: a raw multi-temperature set needs both T and Set columns")
    return kind


def _missing(header) -> str:
    """"missing column(s) ...; " for the kind of file whose own columns (besides T and Set, which raw sets
    share) the header holds most of; "" when that is no single kind."""
    given = set(header) - {"T", "Set"}
    shared = {k: len(given & set(cols)) for k, cols in KINDS.items()}
    best = max(shared.values())
    if best == 0 or list(shared.values()).count(best) > 1:
        return ""
    kind = max(shared, key=shared.get)
    lacking = [c for c in KINDS[kind] if c not in header]
    return f"missing column{'s' if len(lacking) > 1 else ''} {', '.join(lacking)}; "


def _check_monotone_shifts(path, cols, lines):
    """Refuse shift factors that are not strictly monotone in T, at the ``lines`` (per row) of the first
    row out of order."""
    order = np.argsort(cols["T"])
    d = np.diff(cols["log_aT"][order])
    if np.any(np.diff(cols["T"][order]) == 0) or not (np.all(d < 0) or np.all(d > 0)):
        i = int(np.argmax(d >= 0)) if np.any(d >= 0) else 0
        line = int(lines[order[i + 1]])
        raise ValueError(f"{_where(path, line, 'log_aT')}: shift factors must be strictly monotone in T "
                         f"(log_aT falls as T rises), and temperatures distinct")


def read_table(path) -> DMATable:
    """Read and check a DMA/shift-factor CSV (module docstring); errors name file, line and column."""
    path = Path(path)
    rows = read_rows(path, "DMA file")
    header = column_names(path, rows)
    kind = _kind(path, header)
    # T: the unit's value is an offset to deg C; every other column's a factor to SI
    scale, start = units_row(path, rows, header, UNITS, {h: 0.0 if h == "T" else 1.0 for h in header})
    values, lines = {h: [] for h in header}, []
    for lineno, row in data_rows(path, rows, header, start):
        lines.append(lineno)
        for h, cell in zip(header, row):
            v = cell_number(path, lineno, h, cell)
            if h in POSITIVE and not v > 0:
                raise ValueError(f"{_where(path, lineno, h)}: {cell.strip()} must be > 0")
            values[h].append(v * scale[h] if h != "T" else v + scale[h])
    if not values[header[0]]:
        raise ValueError(f"{path}: no data rows")
    cols = {h: np.array(v) for h, v in values.items()}
    if kind == "shift":
        _check_monotone_shifts(path, cols, lines)
    return DMATable(kind=kind, columns=cols, path=str(path), lines=np.array(lines))


def check_data(raw: DMATable, shifts: DMATable | None = None) -> None:
    """What a fit needs of its files, checked before fitting: frequency-domain data; raw sets at two or
    more temperatures; a shift-factor file (T, log_aT) covering the sets' temperatures."""
    if raw.kind != "frequency":
        raise ValueError(f"{raw.path}: measured-data fits take frequency-domain data (f,E_stor,E_loss)")
    if shifts is not None and shifts.kind != "shift":
        raise ValueError(f"{shifts.path}: not a shift-factor file (T,log_aT)")
    if not raw.is_raw:
        return
    T = np.array([s.T for s in split_sets(raw)])
    if shifts is not None:
        ts = shifts.columns["T"]
        if T.min() < ts.min() - TABLE_TOLERANCE or T.max() > ts.max() + TABLE_TOLERANCE:
            raise ValueError(f"{shifts.path}: shift factors cover {ts.min():g}..{ts.max():g} deg C, the sets "
                             f"{T.min():g}..{T.max():g} deg C")
