"""NetCDF output with CF metadata (provenance from :mod:`vcor.provenance`), and the reader that gives
a file back as its writer held it.

The archives follow CF-1.10 (checked with the IOOS ``compliance-checker --test cf:1.10``, no errors;
docs, Datasets). One function, :func:`encode`, decides how a dataset vcor holds in memory becomes
the file, for every writer:

* a *coordinate variable* (a one-dimensional variable named like its dimension) is numeric and
  strictly monotonic, as CF requires (CF 1.10 section 1.3). A dimension coordinate of text (material
  names, history runs, solvers, DEM laws, calibrated parameters) is written as a CF *label*, a string
  auxiliary coordinate variable ``<dim>_label`` along the dimension (CF section 6.1), which the data
  variables name in their ``coordinates`` attribute; any other that is not strictly monotonic numbers
  (repeated frequencies of measured data) likewise as ``<dim>_values``. The dimension keeps its name.
* no coordinate (dimension or auxiliary) carries ``_FillValue``: CF allows no missing values in
  coordinate variables, and vcor's coordinates never hold any;
* ``flag_values`` and ``flag_masks`` have the type of their variable (CF section 3.5);
* a variable name that CF does not allow (letters, digits and underscores, starting with a letter) is
  written under an allowed one (every other character replaced by ``_``, a suffix ``_2``... when the
  result is taken, case ignored);
* every variable written under another name than its name in vcor keeps that name in the attribute
  ``vcor_name`` (:data:`NAME_ATTR`), and :func:`read_dataset` restores it (a label becomes the
  dimension's index again);
* a data variable is linked by ``ancillary_variables`` (CF section 3.4) to the status and validity
  flags (``standard_name`` ``status_flag`` / ``quality_flag``) of the same dimensions.

Files in the layout without ``vcor_name`` attributes (text dimension coordinates, ``_FillValue`` on
coordinates) are read as they are.
"""

from __future__ import annotations

import datetime as _dt
import json
import re
import sys
from pathlib import Path

import numpy as np

from .. import provenance as _provenance
from .receipts import atomic, write_receipt

__all__ = ["NAME_ATTR", "REFERENCES", "archive_form", "cf_name", "decode", "encode", "read_dataset",
           "scalar_dataset_check", "write_dataset"]

REFERENCES = (
    "Green, I. (2026) The viscoelastic coefficient of restitution: integrating the wave equation with "
    "hereditary physics, J. Tribol., doi:10.1115/1.4071256; "
    "Ramirez, R., Poeschel, T., Brilliantov, N. V., Schwager, T. (1999) Coefficient of restitution of "
    "colliding viscoelastic spheres, Phys. Rev. E 60, 4465"
)
#: the attribute that keeps a variable's name in vcor when the file holds it under another
NAME_ATTR = "vcor_name"
#: the CF standard names of flag variables that qualify the data variables of their dimensions
FLAG_STANDARD_NAMES = ("status_flag", "quality_flag")
#: names CF allows (CF 1.10 section 2.3)
_CF_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_]*\Z")


def cf_name(name: str, taken=()) -> str:
    """A name CF allows for ``name`` (itself when allowed and not in ``taken``): every character but
    letters, digits and ``_`` replaced by ``_``, ``v_`` in front when it does not start with a letter,
    then ``_2``, ``_3``... until it differs from every name in ``taken``, case ignored (CF recommends
    names that differ in more than case).

    Examples
    --------
    >>> from vcor.io.netcdf import cf_name
    >>> cf_name("E_lammps_lammps-coeff-restitution")
    'E_lammps_lammps_coeff_restitution'
    >>> cf_name("material_label", taken={"material_label"})
    'material_label_2'
    """
    taken = {t.lower() for t in taken}
    base = re.sub(r"[^A-Za-z0-9_]", "_", name)
    if not base[:1].isalpha() or not base.isascii():
        base = f"v_{base}"
    new, k = base, 2
    while new.lower() in taken:
        new, k = f"{base}_{k}", k + 1
    return new


def _strictly_monotonic(values) -> bool:
    d = np.diff(values)
    return bool(np.all(d > 0) or np.all(d < 0))


def _rename(ds, old: str, new: str):
    """``ds`` with variable ``old`` named ``new`` and its vcor name kept in :data:`NAME_ATTR`."""
    var = ds[old].variable.copy()
    var.attrs[NAME_ATTR] = old
    is_coord = old in ds.coords
    ds = ds.drop_vars(old)
    return ds.assign_coords({new: var}) if is_coord else ds.assign({new: var})


def encode(ds):
    """``(dataset, encoding)``: ``ds`` as the file holds it and the netCDF4 encoding of each variable
    (module docstring: labels, names, flag types, no fill value on coordinates, ancillary variables;
    float64 with zlib level 1 for floats, zlib for integers, text as strings). ``ds`` is not changed."""
    ds = ds.copy()
    for name, var in list(ds.variables.items()):
        if var.dtype.kind == "O":  # text held as Python objects: as fixed-width text (a U array already is)
            ds[name] = var.astype(str)
    for dim in list(ds.dims):
        if dim not in ds.coords:
            continue
        values = ds[dim].values
        text = values.dtype.kind in "USO"
        if text or values.dtype.kind not in "iufmM" or not _strictly_monotonic(values):
            taken = set(ds.variables) | set(ds.dims)
            ds = _rename(ds, dim, cf_name(f"{dim}_label" if text else f"{dim}_values", taken))
    for name in list(ds.variables):
        if not _CF_NAME.match(name):
            ds = _rename(ds, name, cf_name(name, (set(ds.variables) | set(ds.dims)) - {name}))
    bad_dims = [d for d in ds.dims if not _CF_NAME.match(str(d))]
    if bad_dims:
        raise ValueError(f"dimension names {bad_dims}: CF allows letters, digits and underscores, starting with a "
                         f"letter")
    for var in ds.variables.values():
        for key in ("flag_values", "flag_masks"):
            if key in var.attrs:
                flags = np.asarray(var.attrs[key])
                typed = flags.astype(var.dtype)
                if not np.array_equal(typed, flags):
                    raise ValueError(f"{key} {flags.tolist()} do not fit the type {var.dtype} of their variable")
                var.attrs[key] = typed
    _link_flags(ds)
    encoding = {}
    for name, var in ds.variables.items():
        if var.dtype.kind == "f":
            encoding[name] = {"zlib": True, "complevel": 1, "dtype": "float64"}
        elif var.dtype.kind in "iu":
            encoding[name] = {"zlib": True, "complevel": 1}
        if name in ds.coords and var.dtype.kind in "fiu":
            encoding.setdefault(name, {})["_FillValue"] = None
    return ds, encoding


def _link_flags(ds) -> None:
    """``ancillary_variables`` of every numeric data variable: the flag variables over its dimensions or a
    part of them (a run's status qualifies each of its time samples; a point's status each law's value at
    it), in place; a variable that names its own is left as it is."""
    flags = [n for n, v in ds.data_vars.items() if v.attrs.get("standard_name") in FLAG_STANDARD_NAMES]
    for name, var in ds.data_vars.items():
        if name in flags or var.dtype.kind not in "fiu" or "ancillary_variables" in var.attrs:
            continue
        linked = [f for f in flags if ds[f].dims and set(ds[f].dims) <= set(var.dims)]
        if linked:
            var.attrs["ancillary_variables"] = " ".join(linked)


def decode(ds):
    """The dataset vcor wrote as :func:`encode` gave it to the file: every variable under its
    :data:`NAME_ATTR` name (a label or value list along its own dimension becomes that dimension's index
    again), without the ``ancillary_variables`` the encoding added. A dataset without such attributes
    (the layout without them, or written by other code) is returned as it is."""
    renamed = {n: v.attrs[NAME_ATTR] for n, v in ds.variables.items() if NAME_ATTR in v.attrs}
    linked = [n for n, v in ds.data_vars.items() if "ancillary_variables" in v.attrs]
    if not renamed and not linked:
        return ds
    ds = ds.copy()
    for name in linked:
        del ds[name].attrs["ancillary_variables"]
    for name, old in renamed.items():
        var = ds[name].variable.copy()
        del var.attrs[NAME_ATTR]
        is_coord = name in ds.coords
        ds = ds.drop_vars(name)
        if var.dims == (old,):
            ds = ds.assign_coords({old: var.to_index_variable()})
        else:
            ds = ds.assign_coords({old: var}) if is_coord else ds.assign({old: var})
    return ds


def read_dataset(path):
    """The dataset vcor wrote at ``path`` (:func:`write_dataset`), loaded into memory with the names,
    labels and indexes it had when written (:func:`decode`); a file in the layout without
    ``vcor_name`` attributes reads the same way.

    Examples
    --------
    >>> import tempfile, numpy as np, xarray as xr
    >>> from pathlib import Path
    >>> from vcor.io.netcdf import read_dataset, write_dataset
    >>> ds = xr.Dataset({"cor": (("material", "v0"), [[0.9, 0.8]], {"units": "1", "long_name": "COR"})},
    ...                 coords={"material": ["sls"], "v0": ("v0", [1.0, 2.0], {"units": "m s-1"})})
    >>> path = write_dataset(ds, Path(tempfile.mkdtemp()) / "d.nc", title="example", timestamp=False)
    >>> read_dataset(path)["cor"].sel(material="sls", v0=2.0).item()
    0.8
    """
    import xarray as xr

    return decode(xr.load_dataset(path))


def archive_form(ds, *, title: str, extra_attrs: dict | None = None, command: str | None = None,
                 timestamp: bool = True):
    """``(dataset, encoding)``: ``ds`` as :func:`write_dataset` hands it to the netCDF4 writer (CF encoding by
    :func:`encode`, global attributes added)."""
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
    out, encoding = encode(ds)
    out.attrs.update(attrs)
    return out, encoding


def write_dataset(ds, path, *, title: str, extra_attrs: dict | None = None, command: str | None = None,
                  timestamp: bool = True, identity: str | None = None):
    """Write ``ds`` as NetCDF4 (float64, zlib level 1, no lossy packing; CF encoding by :func:`encode`)
    with global attributes Conventions, title, history, source (vcor version, code fingerprint, git
    commit), ``code_fingerprint``, references and ``extra_attrs`` (dicts become JSON, their keys in the
    given order: a scene's grid axes keep theirs). ``timestamp=False`` leaves the time out of ``history``
    so that the same inputs give the same bytes. The file is written atomically and gets a receipt
    (:mod:`vcor.io.receipts`) for ``identity``. :func:`read_dataset` reads it back."""
    path = Path(path)
    out, encoding = archive_form(ds, title=title, extra_attrs=extra_attrs, command=command, timestamp=timestamp)
    with atomic(path) as tmp:
        out.to_netcdf(tmp, format="NETCDF4", engine="netcdf4", encoding=encoding)
    write_receipt(path, identity)
    return path


def scalar_dataset_check(ds) -> None:
    """Every numeric variable and coordinate has ``units`` and ``long_name``, every text one a
    ``long_name`` (a label has no unit: CF section 3.1 asks units of dimensional quantities), and no
    coordinate holds NaN (used by tests and the writer's users)."""
    for name, var in ds.variables.items():
        wanted = ("long_name",) if var.dtype.kind in "OSU" else ("units", "long_name")
        missing = [a for a in wanted if a not in var.attrs]
        if missing:
            raise ValueError(f"variable {name!r} lacks {missing}")
    if np.any([np.isnan(ds[c].values).any() for c in ds.coords if ds[c].dtype.kind == "f"]):
        raise ValueError("coordinates contain NaN")
