"""The CF encoding of vcor's NetCDF files (vcor.io.netcdf): what the file holds, that reading gives a
dataset back as its writer held it, and that archives written before the encoding still read."""

import json

import netCDF4
import numpy as np
import pytest
import xarray as xr
from cf_check import cf_problems

import vcor
from vcor import provenance
from vcor.dem import export, fit, lammps
from vcor.io import netcdf, table
from vcor.solvers.validity import cf_attrs as validity_attrs
from vcor.status import cf_attrs as status_attrs
from vcor.study import aggregation, runner, scene, shards, summary
from vcor.study.rebuild import scene_from_dataset

SCENE = {"materials": ["sls", "butyl-prony3"], "grid": {"v0": [2.0, 10.0], "nu": [0.5, 0.4]},
         "error_estimate": True}


def write_legacy(ds, path, *, title: str, extra_attrs: dict | None = None):
    """How vcor wrote a dataset before the CF encoding (vcor.io.netcdf.write_dataset of vcor 0.1, without
    the atomic rename and the receipt): xarray's default encoding, so ``_FillValue`` on float coordinates,
    text dimension coordinates as string coordinate variables, flag attributes and names as given."""
    ds = ds.copy()
    attrs = {"Conventions": "CF-1.10", "title": title, "history": "legacy", "source": provenance.source(),
             "code_fingerprint": provenance.code_fingerprint(), "references": netcdf.REFERENCES}
    for k, v in (extra_attrs or {}).items():
        attrs[k] = v if isinstance(v, (str, int, float)) else json.dumps(v, default=float)
    ds.attrs.update(attrs)
    encoding = {}
    for name, var in ds.variables.items():
        if var.dtype.kind == "f":
            encoding[name] = {"zlib": True, "complevel": 1, "dtype": "float64"}
        elif var.dtype.kind in "iu":
            encoding[name] = {"zlib": True, "complevel": 1}
        elif var.dtype.kind == "O":
            ds[name] = var.astype(str)
    ds.to_netcdf(path, format="NETCDF4", engine="netcdf4", encoding=encoding)
    return path


def awkward():
    """A dataset with everything the encoding changes: text and repeated-value dimension coordinates, a
    name CF does not allow, flags of another integer type than their variable, a flag variable."""
    status = np.zeros((2, 3), np.int8)
    status[1, 2] = vcor.status.STATUS_CODES["failed"]
    count = status_attrs("bootstrap samples ok")
    count.pop("standard_name")
    return xr.Dataset(
        {"cor": (("material", "v0"), [[0.9, 0.8, 0.7], [0.6, 0.5, np.nan]], {"units": "1", "long_name": "COR"}),
         "status": (("material", "v0"), status, status_attrs()),
         "validity": (("material", "v0"), np.array([[0, 1, 0], [2, 0, 0]], np.int8), validity_attrs()),
         "samples_ok": (("material", "v0"), np.full((2, 3), 4, np.int16), count),
         "message": (("material", "v0"), np.array([["", "", ""], ["", "", "boom"]], dtype=object),
                     {"long_name": "solver message"}),
         "E_lammps_lammps-coeff-restitution": ((), 3e7, {"units": "Pa", "long_name": "Young's modulus"}),
         "storage": (("omega",), [1.0, 2.0, 3.0], {"units": "Pa", "long_name": "storage modulus, data"})},
        coords={"material": ("material", ["sls", "butyl-fc"], {"long_name": "material"}),
                "v0": ("v0", [1.0, 2.0, 5.0], {"units": "m s-1", "long_name": "impact speed"}),
                "omega": ("omega", [10.0, 10.0, 20.0], {"units": "rad s-1", "long_name": "angular frequency"})})


def test_a_dataset_reads_back_as_it_was_written(tmp_path):
    ds = awkward()
    path = netcdf.write_dataset(ds, tmp_path / "d.nc", title="t", timestamp=False)
    back = netcdf.read_dataset(path)
    expected = ds.assign(message=ds["message"].astype(str))
    xr.testing.assert_identical(back.drop_attrs(deep=False), expected.drop_attrs(deep=False))
    assert back["cor"].sel(material="butyl-fc", v0=2.0).item() == 0.5
    assert back.indexes["material"].tolist() == ["sls", "butyl-fc"]
    assert back["samples_ok"].attrs["flag_values"].dtype == np.int16  # typed as the variable, read back so


def test_the_file_holds_what_cf_allows(tmp_path):
    path = netcdf.write_dataset(awkward(), tmp_path / "d.nc", title="t", timestamp=False)
    with netCDF4.Dataset(path) as nc:
        v = nc.variables
        # text and repeated values are labels (auxiliary coordinates) along dimensions that keep their names
        assert "material" not in v and "omega" not in v and v["v0"].dimensions == ("v0",)
        assert v["material_label"].dimensions == ("material",) and v["material_label"].vcor_name == "material"
        assert v["omega_values"].vcor_name == "omega" and v["omega_values"][:].tolist() == [10.0, 10.0, 20.0]
        assert set(v["cor"].coordinates.split()) == {"material_label"}
        assert v["storage"].coordinates == "omega_values"
        for name in ("v0", "omega_values"):
            assert "_FillValue" not in v[name].ncattrs(), name
        assert "_FillValue" in v["cor"].ncattrs()  # a missing result is NaN, marked as missing
        assert v["E_lammps_lammps_coeff_restitution"].vcor_name == "E_lammps_lammps-coeff-restitution"
        assert v["samples_ok"].flag_values.dtype == np.int16 and v["status"].flag_values.dtype == np.int8
        assert v["status"].standard_name == "status_flag" and v["validity"].standard_name == "quality_flag"
        assert v["cor"].ancillary_variables == "status validity"
        assert v["samples_ok"].ancillary_variables == "status validity"
        assert "ancillary_variables" not in v["status"].ncattrs()
    errors, warnings = cf_problems(path)
    assert errors == [] and warnings == []


def test_a_taken_label_name_and_flags_that_do_not_fit_their_type(tmp_path):
    ds = awkward().assign(material_label=((), 1.0, {"units": "1", "long_name": "in the way"}))
    out, _ = netcdf.encode(ds)
    assert out["material_label_2"].attrs[netcdf.NAME_ATTR] == "material"
    assert out["material_label"].attrs["long_name"] == "in the way"
    bad = awkward()
    bad["status"].attrs["flag_values"] = np.array([0, 300], np.int16)
    with pytest.raises(ValueError, match=r"flag_values \[0, 300\] do not fit the type int8"):
        netcdf.write_dataset(bad, tmp_path / "bad.nc", title="t")
    assert not (tmp_path / "bad.nc").exists()


def _shard():
    ids = dict.fromkeys(SCENE["materials"], "x")
    points = shards.identified_points(SCENE, ids)
    ds = runner.run_points(points, scene.settings_of(SCENE))
    ds.attrs["materials"] = json.dumps(scene.material_params(SCENE["materials"], None))
    return ds, [p["index"] for p in points]


def test_archives_written_before_the_cf_encoding_still_read(tmp_path):
    """Files without vcor_name attributes (text coordinate variables, _FillValue on coordinates,
    hyphenated names): the aggregate combines such shards, rebuild reads such a sweep, the run summary,
    the table and the DEM deck read such files, each exactly as it reads the same data in the CF encoding."""
    shard, rows = _shard()
    grid = scene.grid_of(SCENE)
    old, new = {}, {}
    for out, kind, write in ((old, "old", write_legacy), (new, "new", netcdf.write_dataset)):
        write(shard, tmp_path / f"{kind}-shard.nc", title="shard")
        back = netcdf.read_dataset(tmp_path / f"{kind}-shard.nc")
        out["sweep"] = aggregation.aggregate([back], [rows], grid, SCENE)
        write(out["sweep"], tmp_path / f"{kind}-sweep.nc", title="sweep",
              extra_attrs=aggregation.dataset_attrs("s", SCENE))
        out["read"] = netcdf.read_dataset(tmp_path / f"{kind}-sweep.nc")
    with netCDF4.Dataset(tmp_path / "old-sweep.nc") as nc:  # the old layout indeed
        assert nc["material"].dimensions == ("material",) and "_FillValue" in nc["v0"].ncattrs()
    xr.testing.assert_identical(old["sweep"], new["sweep"])
    a, b = old["read"], new["read"]
    xr.testing.assert_equal(a, b)
    assert a["cor"].sel(material="butyl-prony3", v0=10.0, nu=0.4).item() == \
        vcor.simulate("butyl-prony3", 10.0, nu=0.4, method="adaptive").cor
    rebuilt, _ = scene_from_dataset(a)
    assert rebuilt.grid.names == ["v0", "nu"] and rebuilt.config["error_estimate"] is True
    assert summary.read_outcome(tmp_path / "old-sweep.nc") == summary.read_outcome(tmp_path / "new-sweep.nc")
    assert table.dataset_table(tmp_path / "old-sweep.nc") == table.dataset_table(tmp_path / "new-sweep.nc")
    col = fit.collision("sls", np.geomspace(0.1, 10.0, 4), sphere={"r": 0.005}, target={"sphere": {}})
    dem = export.dem_dataset("d", [col], [fit.fit_laws(col)])
    assert "E_lammps_lammps-coeff-restitution" in dem
    for kind, write in (("old", write_legacy), ("new", netcdf.write_dataset)):
        write(dem, tmp_path / f"{kind}-dem.nc", title="dem")
        lammps.write_deck(tmp_path / f"{kind}-in.pair", netcdf.read_dataset(tmp_path / f"{kind}-dem.nc"))
    assert (tmp_path / "old-in.pair").read_text() == (tmp_path / "new-in.pair").read_text()
    xr.testing.assert_equal(netcdf.read_dataset(tmp_path / "old-dem.nc"), netcdf.read_dataset(tmp_path / "new-dem.nc"))
