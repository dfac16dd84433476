"""NetCDF output with CF-style metadata (provenance from :mod:`vcor.provenance`)."""

from __future__ import annotations

import datetime as _dt
import json
import sys
from pathlib import Path

import numpy as np

from .. import provenance as _provenance
from .receipts import atomic, write_receipt

__all__ = ["REFERENCES", "scalar_dataset_check", "write_dataset"]

REFERENCES = (
    "Green, I. (2026) The viscoelastic coefficient of restitution: integrating the wave equation with "
    "hereditary physics, J. Tribol., doi:10.1115/1.4071256; "
    "Ramirez, R., Poeschel, T., Brilliantov, N. V., Schwager, T. (1999) Coefficient of restitution of "
    "colliding viscoelastic spheres, Phys. Rev. E 60, 4465"
)


def write_dataset(ds, path, *, title: str, extra_attrs: dict | None = None, command: str | None = None,
                  timestamp: bool = True, identity: str | None = None):
    """Write ``ds`` as NetCDF4 (float64, zlib level 1, no lossy packing) with global attributes
    Conventions, title, history, source (vcor version, code fingerprint, git commit),
    ``code_fingerprint``, references and ``extra_attrs`` (dicts become JSON, their keys in the given
    order: a scene's grid axes keep theirs). ``timestamp=False`` leaves the time out of ``history`` so
    that the same inputs give the same bytes. The file is written atomically and gets a receipt
    (:mod:`vcor.io.receipts`) for ``identity``."""
    path = Path(path)
    ds = ds.copy()
    now = _dt.datetime.now(_dt.UTC).replace(microsecond=0).isoformat()
    cmd = command or " ".join(sys.argv[:1])
    attrs = {
        "Conventions": "CF-1.10",
        "title": title,
        "history": f"{now} {cmd}" if timestamp else cmd,
        "source": _provenance.source(),
        "code_fingerprint": _provenance.code_fingerprint(),
        "references": REFERENCES,
    }
    for k, v in (extra_attrs or {}).items():
        attrs[k] = v if isinstance(v, (str, int, float)) else json.dumps(v, default=float)
    ds.attrs.update(attrs)
    encoding = {}
    for name, var in ds.variables.items():
        if var.dtype.kind == "f":
            encoding[name] = {"zlib": True, "complevel": 1, "dtype": "float64"}
        elif var.dtype.kind in "iu":
            encoding[name] = {"zlib": True, "complevel": 1}
        elif var.dtype.kind == "O":  # text held as Python objects: as fixed-width text (a U array already is)
            ds[name] = var.astype(str)
    with atomic(path) as tmp:
        ds.to_netcdf(tmp, format="NETCDF4", engine="netcdf4", encoding=encoding)
    write_receipt(path, identity)
    return path


def scalar_dataset_check(ds) -> None:
    """Every variable and coordinate has units and long_name (used by tests and the writer's users)."""
    for name, var in ds.variables.items():
        if var.dtype.kind in "OSU" and name in ("material", "message", "run", "method"):
            continue
        missing = [a for a in ("units", "long_name") if a not in var.attrs]
        if missing:
            raise ValueError(f"variable {name!r} lacks {missing}")
    if np.any([np.isnan(ds[c].values).any() for c in ds.coords if ds[c].dtype.kind == "f"]):
        raise ValueError("coordinates contain NaN")
