"""A dataset as a tidy table: one row per point, one column per coordinate and variable, each header
``name [unit]`` (UDUNITS; "1" for dimensionless), statuses by name (their CF flag meanings)."""

from __future__ import annotations

import csv
import io
from pathlib import Path

import numpy as np

__all__ = ["dataset_table"]


def _status_names(var) -> dict:
    values = np.asarray(var.attrs["flag_values"]).tolist()
    return dict(zip(values, (m.replace("_", "-") for m in var.attrs["flag_meanings"].split())))


def _point_dims(ds) -> tuple:
    """The dims of the point variables: those of ``cor`` (a sweep), else of the variable with most dims."""
    if "cor" in ds and ds["cor"].ndim:
        return ds["cor"].dims
    return max((v.dims for v in ds.data_vars.values()), key=len)


def dataset_table(path) -> str:
    """CSV text of the point variables of the NetCDF dataset at ``path`` (module docstring); ValueError
    naming the file when it cannot be read or has no point variables."""
    from .netcdf import read_dataset

    path = Path(path)
    if not path.is_file():
        raise ValueError(f"dataset {str(path)!r} does not exist")
    try:
        ds = read_dataset(path)
    except (OSError, ValueError) as exc:
        raise ValueError(f"dataset {str(path)!r} cannot be read as NetCDF ({exc})") from None
    if not ds.data_vars:
        raise ValueError(f"dataset {str(path)!r} has no variables")
    dims = _point_dims(ds)
    names = [n for n, v in ds.data_vars.items() if v.dims == dims]
    columns = list(dims) + names
    flat = {d: np.broadcast_to(ds[d].values.reshape([-1 if e == d else 1 for e in dims]),
                               tuple(ds.sizes[e] for e in dims)).ravel() if d in ds.coords else None for d in dims}
    for n in names:
        values = ds[n].values.ravel()
        if "flag_values" in ds[n].attrs:
            lookup = _status_names(ds[n])
            values = np.array([lookup.get(int(c), str(c)) for c in values], dtype=object)
        flat[n] = values
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    header = []
    for c in columns:
        attrs = ds[c].attrs if c in ds.variables else {}
        unit = attrs.get("units")
        header.append(f"{c} [{unit}]" if unit and "flag_values" not in attrs else c)
    writer.writerow(header)
    size = int(np.prod([ds.sizes[d] for d in dims]))
    for i in range(size):
        writer.writerow([_cell(flat[c][i]) if flat[c] is not None else i for c in columns])
    return out.getvalue()


def _cell(x):
    if isinstance(x, (float, np.floating)):
        return repr(float(x))
    return x.item() if isinstance(x, np.generic) else x
