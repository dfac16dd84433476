"""vcor.sweep against the workflow: for every shape of scene the workflow takes (ties and the error
estimate, bodies, a temperature axis, a fitted material, a bootstrap band over a fit to measured data),
the dataset of ``vcor.sweep`` equals ``results/<scene>/sweep.nc`` in every variable and attribute but the
points' ``wall_time`` and the ``history`` attribute; in a folder without the workflow's results it
computes the fits and the bootstrap samples itself, to the same numbers."""

import shutil

import pytest
import xarray as xr

import vcor
from vcor.io.netcdf import read_dataset

pytestmark = pytest.mark.slow

CONFIG = {
    "materials": {"soft": {"model": "sls", "E_glassy": 2.0e7, "alpha": 300.0, "beta": 1200.0,
                           "shift": {"model": "wlf", "C1": 8.86, "C2": 101.6, "T_ref": 20.0}}},
    "fits": {"cerf": {"model": "cerf"},
             "measured": {"model": "prony", "data": {"file": "data/dma.csv", "T_ref": 20.0}}},
    "scenes": {
        "tied": {"materials": ["sls"], "grid": {"v0": [1.0, 3.0, 10.0], "beta": [600, 1200]},
                 "tie": {"alpha": {"to": "beta", "ratio": 0.25}}, "error_estimate": True},
        "bodies": {"materials": ["sls", "butyl-fc"], "grid": {"v0": [1.0, 5.0]},
                   "sphere": {"material": {"model": "elastic", "E": 2.0e11}, "r": 0.01, "rho": 7800, "nu": 0.3},
                   "plate": {"h": 0.02, "rho": 1100, "nu": 0.5}, "solver": {"method": "direct"}},
        "temperature": {"materials": ["soft"], "grid": {"v0": [1.0, 10.0], "T": [0.0, 20.0, 40.0]}},
        "fitted": {"materials": ["cerf"], "grid": {"v0": [1.0, 10.0]}, "solver": {"method": "direct"}},
        "band": {"materials": ["measured"], "grid": {"v0": [1.0, 3.0], "T": [0.0, 40.0]},
                 "geometry": {"rigid": True}, "uncertainty": {"bootstrap": 4, "seed": 2}},
    },
}
SCENES = list(CONFIG["scenes"])


def _same(ours, theirs):
    """Equal in every variable, coordinate and attribute but wall_time and history."""
    a, b = ours.drop_vars("wall_time"), theirs.drop_vars("wall_time")
    assert a.attrs.pop("history") != "" and b.attrs.pop("history") != ""
    xr.testing.assert_identical(a, b)
    assert set(ours.data_vars) == set(theirs.data_vars)


@pytest.fixture(scope="module")
def project(make_project, smk, tmp_path_factory):
    from synthetic_dma import synthetic, write_csv

    path = make_project(tmp_path_factory.mktemp("sweep-function"), CONFIG)
    (path / "data").mkdir(exist_ok=True)
    write_csv(path / "data/dma.csv", synthetic(1))
    smk(path, "-j2", *[f"results/{s}/sweep.nc" for s in SCENES])
    return path


@pytest.mark.parametrize("scene", SCENES)
def test_sweep_equals_the_workflows_dataset(project, scene):
    ours = vcor.sweep(scene, config=project / "config.yaml", workers=2, progress=False)
    _same(ours, read_dataset(project / "results" / scene / "sweep.nc"))


def test_a_scene_given_as_its_mapping_is_the_same_scene(project):
    """A mapping equal to a config's scene takes its name; ``name=`` names any mapping (its ``scene``
    attribute and title), and the numbers do not depend on it."""
    ours = vcor.sweep(CONFIG["scenes"]["tied"], config=project / "config.yaml", workers=1, progress=False)
    assert ours.attrs["scene"] == "tied"
    _same(ours, read_dataset(project / "results/tied/sweep.nc"))
    named = vcor.sweep(CONFIG["scenes"]["tied"], workers=1, progress=False, name="my-study")
    assert named.attrs["scene"] == "my-study" and named.attrs["title"].endswith("scene my-study")
    xr.testing.assert_identical(named["cor"], ours["cor"])


def test_without_the_workflows_files_the_fits_and_samples_are_computed(project, tmp_path):
    """A folder with the config and the data only: vcor.sweep fits, resamples and solves by itself, and
    writes nothing into the folder."""
    shutil.copy(project / "config.yaml", tmp_path / "config.yaml")
    shutil.copytree(project / "data", tmp_path / "data")
    for scene in ("fitted", "band"):
        ours = vcor.sweep(scene, config=tmp_path / "config.yaml", workers=2, progress=False)
        _same(ours, read_dataset(project / "results" / scene / "sweep.nc"))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["config.yaml", "data"]


def test_the_command_line_writes_the_same_dataset(project, tmp_path):
    from vcor.cli import main

    out = tmp_path / "tied.nc"
    assert main(["sweep", "--config", str(project / "config.yaml"), "--scene", "tied", "--out", str(out),
                 "--workers", "2", "--no-progress"]) == 0
    _same(read_dataset(out), read_dataset(project / "results/tied/sweep.nc"))
