"""Reading small numeric CSV files with errors that name the file, the line and the column."""

from __future__ import annotations

import csv
import math
from pathlib import Path

__all__ = ["cell_number", "data_rows", "read_rows"]


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
