"""vcor.histories, vcor.moduli, vcor.viscoelastic_spheres and vcor.convergence against the workflow: each
returns ``results/<scene>/<dataset>.nc`` of the same scene, equal in every variable, coordinate and
attribute but the ``history`` attribute and the measured wall times (of the histories' runs and the
work-precision study's); with a
config material and a fitted one (computed by the call in a folder without the workflow's files too)."""

import shutil

import pytest
import xarray as xr

import vcor
from vcor.io.netcdf import read_dataset

pytestmark = pytest.mark.slow

CONFIG = {
    "materials": {"soft": {"model": "sls", "E_glassy": 2.0e7, "alpha": 300.0, "beta": 1200.0}},
    "fits": {"cerf": {"model": "cerf"}},
    "scenes": {
        "traces": {"materials": ["soft", "cerf"], "moduli": ["soft", "cerf", "butyl-fc"],
                   "histories": {"v0": 3.0, "runs": [["soft", "adaptive"], ["cerf", "direct"]]},
                   "geometry": {"r": 0.005}},
        "balls": {"spheres": {"b": {"start": 0.01, "stop": 1.0, "num": 4, "log": True}, "rules": ["overlap"],
                              "tau_ratio": [0.1]}},
        "ladder": {"convergence": {"materials": ["soft"], "v0": [2.0]}},
    },
}
#: (scene, dataset, function, variables whose values are measured times)
CASES = [("traces", "histories", vcor.histories, ("wall_time",)), ("traces", "moduli", vcor.moduli, ()),
         ("balls", "spheres", vcor.viscoelastic_spheres, ()),
         ("ladder", "convergence", vcor.convergence, ("wall_time",))]


def _same(ours, theirs, timed):
    a, b = ours.drop_vars(list(timed)), theirs.drop_vars(list(timed))
    assert a.attrs.pop("history") != "" and b.attrs.pop("history") != ""
    xr.testing.assert_identical(a, b)


@pytest.fixture(scope="module")
def project(make_project, smk, tmp_path_factory):
    path = make_project(tmp_path_factory.mktemp("scene-functions"), CONFIG)
    smk(path, "-j2", *[f"results/{scene}/{dataset}.nc" for scene, dataset, _, _ in CASES])
    return path


@pytest.mark.parametrize("scene, dataset, function, timed", CASES, ids=[c[1] for c in CASES])
def test_each_function_returns_the_workflows_dataset(project, scene, dataset, function, timed):
    ours = function(scene, config=project / "config.yaml")
    _same(ours, read_dataset(project / "results" / scene / f"{dataset}.nc"), timed)


def test_without_the_workflows_files_the_fit_is_computed(project, tmp_path):
    """A copy of the config without results/ or the material folder: the histories and moduli of the
    fitted material are the same numbers."""
    shutil.copy(project / "config.yaml", tmp_path / "config.yaml")
    for dataset, function, timed in (("histories", vcor.histories, ("wall_time",)), ("moduli", vcor.moduli, ())):
        ours = function("traces", config=tmp_path / "config.yaml")
        _same(ours, read_dataset(project / "results" / "traces" / f"{dataset}.nc"), timed)
    assert not (tmp_path / "results").exists()
