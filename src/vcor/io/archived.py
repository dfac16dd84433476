"""A dataset with the way vcor archives it: what a workflow job writes to its file, and what a study
function returns, read back from the same writer.

:meth:`Archive.write` writes the dataset with :func:`vcor.io.netcdf.write_dataset` (global attributes,
encoding, receipt); :meth:`Archive.loaded` writes it so into a temporary folder and reads it back, so
that the dataset a study function returns is, value for value and attribute for attribute, the one a
workflow job archives (the history attribute aside, which records when and by what command it was
written), and writing it again gives the same file.
"""

from __future__ import annotations

import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from .netcdf import read_dataset, write_dataset

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
        """The dataset as :meth:`write` archives it, read back into memory (an ``xarray.Dataset``)."""
        with tempfile.TemporaryDirectory(prefix="vcor-") as folder:
            path = self.write(Path(folder) / "dataset.nc", command=command)
            return read_dataset(path)
