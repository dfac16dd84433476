"""A dataset with the way vcor archives it: what a workflow job writes to its file, and what a study
function returns, read back from the same writer's encoding.

:meth:`Archive.write` writes the dataset with :func:`vcor.io.netcdf.write_dataset` (global attributes,
encoding, receipt). :meth:`Archive.loaded` gives the dataset a study function returns: the same
encoding (:func:`vcor.io.netcdf.archive_form`) goes through xarray's netCDF writing into an
``InMemoryDataStore`` and is decoded from there as :func:`vcor.io.netcdf.read_dataset` decodes a file,
with the attributes as the netCDF4 library returns them (numbers as NumPy scalars, lists as arrays). It
is, value for value and attribute for attribute, the one a workflow job archives (the history
attribute aside, which records when and by what command it was written), without a file's HDF5 write
and read, which would cost more than solving a small sweep; ``tests/io/test_archived.py`` holds the two
equal, dtypes and attribute types included, for every kind of dataset.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .netcdf import archive_form, decode, write_dataset

if TYPE_CHECKING:
    import xarray

__all__ = ["Archive"]


@dataclass(frozen=True, kw_only=True)
class Archive:
    """``dataset`` to be written with ``title``, the global attributes ``extra_attrs`` (dicts become JSON)
    and, unless ``timestamp`` is False, the time in its history attribute."""

    dataset: xarray.Dataset
    title: str
    extra_attrs: dict = field(default_factory=dict)
    timestamp: bool = True

    def write(self, path, *, command: str, identity: str | None = None) -> Path:
        """Write the dataset to ``path`` (atomically, with a receipt for ``identity``)."""
        return write_dataset(self.dataset, path, title=self.title, extra_attrs=self.extra_attrs, command=command,
                             timestamp=self.timestamp, identity=identity)

    def loaded(self, *, command: str) -> xarray.Dataset:
        """The dataset as :meth:`write` archives it and :func:`vcor.io.netcdf.read_dataset` reads it back,
        in memory (module docstring)."""
        import xarray as xr
        from xarray.backends.memory import InMemoryDataStore

        out, encoding = archive_form(self.dataset, title=self.title, extra_attrs=self.extra_attrs, command=command,
                                     timestamp=self.timestamp)
        store = InMemoryDataStore()
        out.dump_to_store(store, encoding=encoding)
        ds = xr.load_dataset(store)
        ds.attrs = {k: _as_read(v) for k, v in ds.attrs.items()}
        for var in ds.variables.values():
            var.attrs = {k: _as_read(v) for k, v in var.attrs.items()}
        return decode(ds)


def _as_read(value):
    """An attribute as the netCDF4 library reads it back: text as text, one number as a NumPy scalar,
    several as a NumPy array."""
    if isinstance(value, str):
        return value
    array = np.asarray(value)
    return array.reshape(-1)[0] if array.size == 1 else array
