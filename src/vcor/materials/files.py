"""Material files: a material written as NetCDF (fits, calibrations, config materials) and read back.

A material file holds the attribute ``material`` (the JSON of ``Material.to_dict()``), optionally
``shift`` (its shift function, :class:`vcor.materials.shift.ShiftFunction`) and whatever its writer
records beside it (fit residuals, calibration statistics). :func:`from_file` reads the material;
a JSON file holding the same dict is accepted too.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from ..io.yamlfile import load_json
from .models import Material, from_dict
from .specs import from_spec, shift_function

__all__ = ["from_file", "material_dataset"]


def from_file(path) -> Material:
    """Load a material file (module docstring); ValueError naming the path when it is missing, cannot
    be read, or holds no material."""
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"material file {str(path)!r} does not exist")
    if path.suffix == ".json":
        record = load_json(path, what="material file")  # a key given twice is refused, naming both lines
        try:
            return from_dict(record)
        except (ValueError, TypeError, KeyError) as exc:
            raise ValueError(f"material file {str(path)!r}: not a material ({exc})") from None
    import xarray as xr

    try:
        with xr.open_dataset(path) as ds:
            text = ds.attrs.get("material")
    except (OSError, ValueError) as exc:
        raise ValueError(f"material file {str(path)!r} cannot be read as NetCDF ({exc})") from None
    if text is None:
        raise ValueError(f"material file {str(path)!r} has no attribute 'material'")
    try:
        return from_dict(json.loads(text))
    except (ValueError, TypeError, KeyError) as exc:
        raise ValueError(f"material file {str(path)!r}: attribute 'material' is not a material ({exc})") from None


def material_dataset(name: str, spec: dict, *, base_dir="."):
    """(dataset, attributes) of a config material: E(t) on a log grid (1 ns .. 1000 s) and the
    attributes ``material`` (its parameters), ``spec`` (the config spec) and ``shift``."""
    import xarray as xr

    mat = from_spec(spec, name=name, base_dir=base_dir)
    t = np.geomspace(1e-9, 1e3, 121)
    ds = xr.Dataset({"E_t": ("t", mat.relaxation_modulus(t), {"units": "Pa", "long_name": "relaxation modulus E(t)"})},
                    coords={"t": ("t", t, {"units": "s", "long_name": "time"})})
    attrs = {"material": json.dumps(mat.to_dict()), "spec": json.dumps(spec, sort_keys=True)}
    shift = shift_function(spec, name)
    if shift is not None:
        attrs["shift"] = json.dumps(shift.to_dict())
    return ds, attrs
