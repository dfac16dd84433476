"""Reading small numeric CSV files with errors that name the file, the line and the column (and, for a file a
config names, the config key: :func:`named_by`)."""

from __future__ import annotations

import contextlib
import csv
import math
from pathlib import Path

__all__ = ["cell_number", "data_rows", "header", "is_number", "named_by", "project_file", "read_rows", "units_row"]


def project_file(key: str, value, base_dir, what: str) -> Path:
    """The file ``value`` names (a relative path: in ``base_dir``, the project folder); ValueError naming
    the config ``key``, ``what`` the file is (``the Prony table``) and the folder it was looked for in
    when there is no such file."""
    path = Path(value)
    full = path if path.is_absolute() else Path(base_dir) / path
    if not full.is_file():
        folder = "" if path.is_absolute() else (f" in {str(Path(base_dir).resolve())!r} (the project folder, which "
                                                f"relative paths are taken from)")
        raise ValueError(f"{key}: {what} {str(value)!r} does not exist{folder}")
    return full


@contextlib.contextmanager
def named_by(key: str):
    """Read a file that the config ``key`` names: a ValueError raised within (the file's refusal, naming the
    file, the line and the column) is raised again with the key in front, as the config's other refusals
    start: ``fits.f.data.file: data/dma.csv, line 3, column 'E_stor': 'oops' is not a number``."""
    try:
        yield
    except ValueError as exc:
        raise ValueError(f"{key}: {exc}") from None


def read_rows(path, what: str) -> list[list[str]]:
    """All rows of ``path`` (a UTF-8 byte-order mark is accepted); ``what`` names the file's role in
    the error when it does not exist or is empty."""
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"{what} {str(path)!r} does not exist")
    with path.open(newline="", encoding="utf-8-sig") as fh:
        rows = list(csv.reader(fh))
    if not rows:
        raise ValueError(f"{path}: empty file")
    return rows


def header(path, rows) -> list[str]:
    """The column names of the first row, stripped; a name given twice is an error naming the file, line 1
    and both columns (read by name, one of the two columns would be lost)."""
    names = [c.strip() for c in rows[0]]
    for j, name in enumerate(names):
        if name in names[:j]:
            raise ValueError(f"{path}, line 1: column {name!r} is given twice (columns {names.index(name) + 1} and "
                             f"{j + 1}); remove or rename one")
    return names


def data_rows(path, rows, header, start):
    """(line number, cells) of the non-blank rows from index ``start``, each with as many cells as
    ``header`` (else an error naming the line)."""
    for lineno, row in enumerate(rows[start:], start=start + 1):
        if not any(cell.strip() for cell in row):
            continue
        if len(row) != len(header):
            raise ValueError(f"{path}, line {lineno}: {len(row)} cells, the header has {len(header)}")
        yield lineno, row


def cell_number(path, lineno, column, cell) -> float:
    """The finite number in ``cell`` (else an error naming file, line and column)."""
    where = f"{path}, line {lineno}, column {column!r}"
    try:
        value = float(cell)
    except ValueError:
        raise ValueError(f"{where}: {cell.strip()!r} is not a number") from None
    if not math.isfinite(value):
        raise ValueError(f"{where}: {cell.strip()!r} is not finite")
    return value


def is_number(cell) -> bool:
    try:
        float(cell)
    except ValueError:
        return False
    return True


def units_row(path, rows, header, units: dict, defaults: dict) -> tuple[dict, int]:
    """(the value ``units[column][unit]`` of each column's unit, index of the first data row): the second
    row is a units row when its first cell is not a number; without one, ``defaults``. Errors name the
    file, line 2 and the column (an unknown unit, or as many units as columns)."""
    if not (len(rows) > 1 and rows[1] and not is_number(rows[1][0])):
        return dict(defaults), 1
    names = [u.strip() for u in rows[1]]
    if len(names) != len(header):
        raise ValueError(f"{path}, line 2: {len(names)} units for {len(header)} columns")
    out = {}
    for column, unit in zip(header, names):
        if unit not in units[column]:
            raise ValueError(f"{path}, line 2, column {column!r}: unknown unit {unit!r}; allowed: "
                             f"{sorted(u for u in units[column] if u)}")
        out[column] = units[column][unit]
    return out, 2
