"""Archive.loaded (the dataset a study function returns, read back in memory) against the file the workflow
writes read back by read_dataset: equal in every variable, coordinate, dtype and attribute, attribute types
included, for every kind of dataset vcor archives."""

import dataclasses

import numpy as np
import xarray as xr

import vcor
from vcor.io.netcdf import read_dataset

COMMAND = "vcor test"
V0 = [1.0, 3.0, 10.0]


def _archives(tmp_path):
    (tmp_path / "cor.csv").write_text("v0,cor\n" + "".join(f"{v},{vcor.simulate('sls', v).cor}\n" for v in V0))
    config = {
        "materials": {"alu": {"model": "elastic", "E": 7.0e10}},
        "calibrations": {"cal": {"data": "cor.csv", "material": "sls", "free": {"beta": [300.0, 5000.0]}}},
        "dem": {"pair": {"sphere": {"material": "sls", "r": 0.005}, "target": {"sphere": {}}, "v0": V0}},
        "scenes": {"s": {"materials": ["sls"], "grid": {"v0": V0, "beta": [600, 1200]},
                         "error_estimate": True},
                   "bodies": {"materials": ["sls"], "grid": {"v0": V0}, "sphere": {"material": "alu"},
                              "plate": {"h": 0.02}}},
    }
    path = tmp_path / "config.yaml"
    import yaml

    path.write_text(yaml.safe_dump(config))
    from vcor.study.api import sweep_archive

    return {
        "sweep": sweep_archive("s", config=path, workers=1, progress=False),
        "bodies": sweep_archive("bodies", config=path, workers=1, progress=False),
        "fit": vcor.fit({"model": "prony", "n_terms": 3}, name="p3").archive,
        "calibration": vcor.calibrate("cal", config=path).archive,
        "dem": vcor.dem_export("pair", config=path).archive,
    }


def _attr_types(ds):
    types = {("", k): (type(v), np.asarray(v).dtype) for k, v in ds.attrs.items()}
    for name, var in ds.variables.items():
        types.update({(name, k): (type(v), np.asarray(v).dtype) for k, v in var.attrs.items()})
    return types


def test_loaded_is_the_written_file_read_back(tmp_path):
    for kind, archive in _archives(tmp_path).items():
        archive = dataclasses.replace(archive, timestamp=False)
        ours = archive.loaded(command=COMMAND)
        theirs = read_dataset(archive.write(tmp_path / f"{kind}.nc", command=COMMAND))
        xr.testing.assert_identical(ours, theirs)
        dtypes = {n: v.dtype for n, v in theirs.variables.items()}
        assert {n: v.dtype for n, v in ours.variables.items()} == dtypes, kind
        assert _attr_types(ours) == _attr_types(theirs), kind
        assert list(ours.dims) == list(theirs.dims) and list(ours.variables) == list(theirs.variables), kind


def test_a_calibration_names_its_data_file_as_the_config_does(tmp_path):
    """The archived calibration names its data file relative to the project, as the config writes it, not as
    the process opened it (an absolute path from a notebook would differ from the workflow's file)."""
    import yaml

    (tmp_path / "cor.csv").write_text("v0,cor\n" + "".join(f"{v},{vcor.simulate('sls', v).cor}\n" for v in V0))
    config = {"calibrations": {"cal": {"data": "cor.csv", "material": "sls", "free": {"beta": [300.0, 5000.0]}}}}
    (tmp_path / "config.yaml").write_text(yaml.safe_dump(config))
    ds = vcor.calibrate("cal", config=tmp_path / "config.yaml").archive.loaded(command=COMMAND)
    assert ds.attrs["data"] == "cor.csv"
