"""Measured COR data for a calibration: impact speeds and CORs (and their standard deviations), from a CSV
file ``v0,cor[,cor_std]`` (m/s, dimensionless; a units row ``m/s,-,-`` or ``cm/s`` is allowed) or from
arrays, checked alike (:mod:`vcor.fitting.calibrate` fits a material to them).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..io.csvfile import cell_number, data_rows, read_rows, units_row
from ..io.csvfile import header as column_names

__all__ = ["CorData", "read_cor_data"]

_UNITS = {"v0": {"m/s": 1.0, "cm/s": 0.01}, "cor": {"-": 1.0, "": 1.0, "1": 1.0},
          "cor_std": {"-": 1.0, "": 1.0, "1": 1.0}}


@dataclass(frozen=True)
class CorData:
    """Measured COR: impact speeds ``v0`` (m/s), ``cor``, optional standard deviations ``cor_std``,
    the file and the line of each point."""

    v0: np.ndarray
    cor: np.ndarray
    cor_std: np.ndarray | None = None
    path: str = "data"
    lines: tuple = ()

    def __post_init__(self):
        # what read_cor_data checks per cell, for data given as arrays: errors name the field and the index
        checks = {"v0": (lambda x: x > 0, "an impact speed must be > 0 m/s"),
                  "cor": (lambda x: 0 < x <= 1, "a COR must be in (0, 1]"),
                  "cor_std": (lambda x: x > 0, "a standard deviation must be > 0")}
        sizes = set()
        for name, (ok, rule) in checks.items():
            value = getattr(self, name)
            if value is None:
                continue
            try:
                arr = np.asarray(value, dtype=float)
            except (TypeError, ValueError):
                raise ValueError(f"CorData.{name}: a list of numbers, got {value!r}") from None
            if arr.ndim != 1 or arr.size == 0:
                raise ValueError(f"CorData.{name}: a non-empty list of numbers, got {value!r}")
            for i, x in enumerate(arr):
                if not (math.isfinite(x) and ok(x)):
                    raise ValueError(f"CorData.{name}[{i}]: {rule}, got {float(x)!r}")
            object.__setattr__(self, name, arr)
            sizes.add(arr.size)
        if len(sizes) > 1:
            raise ValueError(f"CorData: v0, cor (and cor_std) need one value per impact, got lengths "
                             f"{[np.size(getattr(self, n)) for n in checks if getattr(self, n) is not None]}")


def read_cor_data(path, what: str = "COR data file") -> CorData:
    """Read ``v0,cor[,cor_std]`` (module docstring); every error names the file (a missing one as ``what``),
    the line and the column: a missing or unknown column, a non-numeric or non-finite cell (NaN), v0 <= 0,
    a COR outside (0, 1], cor_std <= 0."""
    rows = read_rows(path, what)
    header = column_names(path, rows)
    for col in ("v0", "cor"):
        if col not in header:
            raise ValueError(f"{path}, line 1: missing column {col!r} (columns: v0, cor, optional cor_std), "
                             f"got {header}")
    unknown = [c for c in header if c not in _UNITS]
    if unknown:
        raise ValueError(f"{path}, line 1, column {unknown[0]!r}: unknown column; allowed: v0, cor, cor_std")
    scale, start = units_row(path, rows, header, _UNITS, dict.fromkeys(header, 1.0))
    cols, lines = {c: [] for c in header}, []
    for lineno, row in data_rows(path, rows, header, start):
        for col, cell in zip(header, row):
            value = cell_number(path, lineno, col, cell) * scale[col]
            where = f"{path}, line {lineno}, column {col!r}"
            if col == "v0" and not value > 0:
                raise ValueError(f"{where}: impact speed must be > 0 m/s, got {cell.strip()}")
            if col == "cor" and not 0 < value <= 1:
                raise ValueError(f"{where}: a COR must be in (0, 1], got {cell.strip()}")
            if col == "cor_std" and not value > 0:
                raise ValueError(f"{where}: cor_std must be > 0, got {cell.strip()}")
            cols[col].append(value)
        lines.append(lineno)
    if not lines:
        raise ValueError(f"{path}: no data rows")
    std = np.array(cols["cor_std"]) if "cor_std" in cols else None
    return CorData(np.array(cols["v0"]), np.array(cols["cor"]), std, str(path), tuple(lines))
