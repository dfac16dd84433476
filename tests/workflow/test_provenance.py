"""Provenance-safe archives (docs/user-guide/datasets.md, "Provenance"): a shard's identity covers the
computing code and the material's content; changed code recomputes the affected shards (and ``snakemake -n`` lists
them); an aggregate never combines shards of different code or material parameters."""

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import vcor
from vcor import provenance
from vcor.materials import Catalogue
from vcor.materials.catalogue import content_hash
from vcor.study import aggregation, runner, scene, shards

ROOT = Path(__file__).resolve().parents[2]
SCENE = {"materials": ["sls"], "grid": {"v0": [2.0, 10.0]}, "shard_size": 1}
CONFIG = {"shard_size": 1, "material_dir": "results/materials", "scenes": {"tiny": SCENE}}
TARGET = "results/tiny/sweep.nc"


def _run(smk, path, env, *args):
    out = smk(path, "-j1", *args, TARGET, env=env)
    return out.stdout + out.stderr


def _fingerprint(env):
    code = "from vcor import provenance; print(provenance.code_fingerprint(), provenance.__file__)"
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    fp, where = out.stdout.split()
    return fp, where


def _jobs(text, rule):
    """Number of jobs of ``rule`` in Snakemake's job-stats table (0 when absent)."""
    m = re.search(rf"^{rule}\s+(\d+)\s*$", text, flags=re.MULTILINE)
    return int(m.group(1)) if m else 0


@pytest.fixture(scope="module")
def project(make_project, tmp_path_factory):
    """A workflow copy whose scripts import a private copy of the package (on PYTHONPATH)."""
    path = make_project(tmp_path_factory.mktemp("prov"), CONFIG)
    pkg = path / "pkg"
    shutil.copytree(Path(vcor.__file__).parent, pkg / "vcor", ignore=shutil.ignore_patterns("__pycache__"))
    env = {**os.environ, "PYTHONPATH": str(pkg), "NUMBA_CACHE_DIR": str(path / "numba-cache")}
    _, where = _fingerprint(env)
    assert Path(where).is_relative_to(pkg)  # the copy is the code that runs
    return path, pkg, env


@pytest.mark.slow
def test_changed_code_recomputes_the_shards_and_the_aggregate_carries_one_fingerprint(smk, project):
    path, pkg, env = project
    _run(smk, path, env)
    first, _ = _fingerprint(env)
    assert _jobs(_run(smk, path, env, "-n"), "sweep_shard") == 0  # nothing to do: finished shards are reused
    # a change of the computing code (a comment is enough: the fingerprint hashes the source), in a
    # module without numba kernels so that the re-run reuses the compiled ones
    with open(pkg / "vcor" / "solvers" / "validity.py", "a") as fh:
        fh.write("\n# provenance test: a changed line\n")
    second, _ = _fingerprint(env)
    assert second != first
    dry = _run(smk, path, env, "-n")
    assert _jobs(dry, "sweep_shard") == 2 and _jobs(dry, "aggregate") == 1, dry[-2000:]
    _run(smk, path, env)
    ds = xr.open_dataset(path / TARGET)
    assert ds.attrs["code_fingerprint"] == second and second in ds.attrs["source"]
    # every shard the new plan uses carries the new fingerprint; the stale ones are not inputs
    new = sorted((path / "results/tiny/shards").glob(f"{content_hash({**_settings(), 'code': second}, 10)}-*.nc"))
    old = sorted((path / "results/tiny/shards").glob(f"{content_hash({**_settings(), 'code': first}, 10)}-*.nc"))
    assert len(new) == 2 and len(old) == 2
    assert {xr.open_dataset(p).attrs["code_fingerprint"] for p in new} == {second}
    assert {xr.open_dataset(p).attrs["code_fingerprint"] for p in old} == {first}
    np.testing.assert_array_equal(ds["status"].values, 0)


def _settings():
    return scene.settings_of(SCENE)


_GRID = scene.grid_of(SCENE)
_ROWS = list(range(_GRID.size))


def _shard(code):
    pts = [{**p, "material_id": "x"} for p in scene.scene_points(SCENE)]  # every point, index order
    ds = runner.run_points(pts, _settings())
    ds.attrs["code_fingerprint"] = code
    ds.attrs["materials"] = json.dumps({"sls": vcor.materials.get("sls").to_dict()})
    return ds


def test_aggregate_refuses_shards_of_different_code():
    current = provenance.code_fingerprint()
    with pytest.raises(ValueError, match="different code"):
        aggregation.aggregate([_shard(current), _shard("0123456789abcdef")], [_ROWS, _ROWS], _GRID, SCENE)
    with pytest.raises(ValueError, match="different code"):
        aggregation.aggregate([_shard("0123456789abcdef")], [_ROWS], _GRID, SCENE)


def test_aggregate_refuses_changed_material_parameters():
    ds = _shard(provenance.code_fingerprint())
    p = vcor.materials.get("sls").to_dict()
    p["E0"] = p.get("E0", 1.0) * 1.01
    ds.attrs["materials"] = json.dumps({"sls": p})
    with pytest.raises(ValueError, match="material 'sls'"):
        aggregation.aggregate([ds], [_ROWS], _GRID, SCENE)


def test_shard_identity_covers_code_material_content_and_options():
    ident = {"sls": Catalogue().identity("sls")}
    base = shards.plan_shards(SCENE, "/nonexistent", 1, ident)
    # a material's identity is its content, not its name
    assert Catalogue().identity("sls") == content_hash({"material": vcor.materials.get("sls").to_dict()})
    assert Catalogue().identity("sls") != Catalogue().identity("butyl-prony3")
    # another fit spec, another identity (the fitted parameters follow from it)
    fits = {"f": {"model": "prony", "n_terms": 3}}
    a = Catalogue(fits=fits).identity("f")
    b = Catalogue(fits={"f": {"model": "prony", "n_terms": 4}}).identity("f")
    assert a != b
    # another material content: other shard names; other solver options: other shard names
    other = shards.plan_shards(SCENE, "/nonexistent", 1, {"sls": "another-content"})
    assert set(other).isdisjoint(base)
    stiff = {**SCENE, "solver": {"method": "direct", "steps_per_contact": 4000}}
    assert set(shards.plan_shards(stiff, "/nonexistent", 1, ident)).isdisjoint(base)
    assert shards.shard_settings(SCENE)["code"] == provenance.code_fingerprint()


def test_a_sweep_rebuilds_from_its_dataset_bit_for_bit(tmp_path):
    """A sweep's attributes rebuild its scene (grid axes in their config order, a fit's parameters and
    shift function, a config material's shift function) without the config or the fit's file, and
    the rebuilt scene re-runs to the dataset's numbers bit for bit."""
    from vcor.io import netcdf
    from vcor.materials.files import material_dataset
    from vcor.study.rebuild import scene_from_dataset

    wlf = {"model": "wlf", "C1": 8.0, "C2": 120.0, "T_ref": 20.0}
    fitted, attrs = material_dataset("fitted", {"model": "prony", "E_inf": 2e6, "E": [5e7, 1e7],
                                                "beta": [3e4, 300.0], "shift": wlf})
    netcdf.write_dataset(fitted, tmp_path / "mats/fitted.nc", title="a fitted material", extra_attrs=attrs)
    arrhenius = {"model": "arrhenius", "E_a": 2e5, "T_ref": 25.0}
    catalogue = Catalogue(specs={"mine": {"model": "sls", "E_glassy": 15e6, "alpha": 300, "beta": 1200,
                                          "shift": arrhenius}},
                          fits={"fitted": {"model": "prony", "data": {"file": "dma.csv", "T_ref": 20.0}}},
                          material_dir=str(tmp_path / "mats"))
    sc = {"materials": ["fitted", "mine"], "grid": {"T": [40.0, 0.0], "v0": [2.0, 10.0], "nu": [0.5, 0.4]}}

    def sweep(sc, catalogue):
        ids = {m: catalogue.identity(m) for m in sc["materials"]}
        points = shards.identified_points(sc, ids)
        ds = runner.run_points(points, scene.settings_of(sc), catalogue)
        ds.attrs["code_fingerprint"] = provenance.code_fingerprint()  # what the shard file records
        return aggregation.aggregate([ds], [[p["index"] for p in points]], scene.grid_of(sc), sc, catalogue)

    path = tmp_path / "sweep.nc"
    netcdf.write_dataset(sweep(sc, catalogue), path, title="sweep",
                         extra_attrs=aggregation.dataset_attrs("s", sc, catalogue))
    (tmp_path / "mats/fitted.nc").unlink()  # the rebuild needs the dataset only
    back = netcdf.read_dataset(path)
    rebuilt, cat2 = scene_from_dataset(back)
    assert rebuilt.grid.names == ["T", "v0", "nu"] and list(back["cor"].dims) == ["material", "T", "v0", "nu"]
    assert cat2.shift("fitted").to_dict() == wlf and cat2.shift("mine").to_dict() == arrhenius
    again = sweep(rebuilt.config, cat2)
    assert int((back["status"] == 0).sum()) == back["status"].size
    assert set(again.data_vars) == set(back.data_vars)
    for v in set(back.data_vars) - {"wall_time"}:  # wall_time: the run's clock, not a result
        np.testing.assert_array_equal(again[v].values, back[v].values, err_msg=v)
