"""The study model (docs: Scenes, Config reference): one typed model of a project built once from the
config, every top-level section optional, one catalogue for every material reference, one-line
refusals, the grid's typed axes and indexed points, shards joined by index."""

import json
from pathlib import Path

import numpy as np
import pytest
import yaml

from vcor import provenance
from vcor.materials import Catalogue
from vcor.study import aggregation, paths, runner, shards
from vcor.study.config import load_project
from vcor.study.grid import AXIS_UNITS, Grid, axis_role, axis_values, point_key
from vcor.study.project import DEFAULTS
from vcor.study.scene import grid_of, settings_of
from vcor.study.schema import SchemaError, check_schema, load_schema
from vcor.study.uncertainty import uncertainty_of

ROOT = Path(__file__).resolve().parents[2]
SCHEMA = ROOT / "workflow" / "schemas" / "config.schema.yaml"
MY_SLS = {"model": "sls", "E_glassy": 15.0e6, "alpha": 300.0, "beta": 1200.0}


def check(config, base=ROOT):
    """What the workflow does before any job: the schema (defaults filled in), then vcor's checks."""
    return load_project(check_schema(config, SCHEMA), base)


# -- every top-level section optional --------------------------------------------------------------
def test_a_config_of_only_calibrations_builds_the_calibration(tmp_path):
    (tmp_path / "cor.csv").write_text("v0,cor\n1,0.8\n3,0.7\n10,0.6\n")
    project = check({"calibrations": {"mine": {"data": "cor.csv", "material": "sls", "free": {"beta": [100, 1e4]}}}},
                    tmp_path)
    assert project.scenes == {} and project.dem == {}
    assert {"results/calibrations/mine.nc", "results/calibrations/mine.png",
            "results/materials/mine.nc"} <= set(project.all_targets())


def test_a_config_of_only_materials_and_dem_builds_the_dem_entry():
    project = check({"materials": {"my-sls": MY_SLS},
                     "dem": {"pair": {"sphere": {"material": "my-sls", "r": 0.005}, "target": {"sphere": {}},
                                      "v0": [0.5, 5.0]}}})
    assert project.all_targets() == project.dem_targets("pair") + ["results/dem/pair/MANIFEST.txt"]
    assert "results/dem/pair/lammps/in.pair" in project.all_targets()


def test_a_config_of_only_fits_builds_every_fit_and_a_scene_only_the_fits_it_uses():
    fits = {"f{n}": {"model": "prony", "n_terms": [2, 3]}}
    project = check({"fits": fits})
    assert project.all_targets() == ["results/materials/f2.nc", "results/materials/f2.txt",
                                     "results/materials/f3.nc", "results/materials/f3.txt"]
    with_scene = check({"fits": fits, "scenes": {"s": {"materials": ["f2"], "grid": {"v0": [1.0]}}}})
    built = with_scene.all_targets()
    assert "results/materials/f2.nc" in built and not any("f3" in t for t in built)


def test_a_fit_family_is_fitted_whole_when_the_project_builds_any_of_its_members(tmp_path):
    fits = {"f{n}": {"model": "prony", "n_terms": [1, 2, 3]}, "g": {"model": "cerf"},
            "one{n}": {"model": "prony", "n_terms": [4]}}
    whole = {"f{n}": ["f1", "f2", "f3"]}
    assert check({"fits": fits}).fit_groups() == whole  # a family of one member is an ordinary fit

    def scene(*materials):
        return {"s": {"materials": list(materials), "grid": {"v0": [1.0]}}}

    # the same job whichever members are used: a scene that starts using f2 changes nothing already built
    assert check({"fits": fits, "scenes": scene("f1", "g")}).fit_groups() == whole
    assert check({"fits": fits, "scenes": scene("f2", "f3")}).fit_groups() == whole
    assert check({"fits": fits, "scenes": scene("g")}).fit_groups() == {}  # no member built: no job
    dem = {"d": {"sphere": {"material": "f2", "r": 0.005}, "target": "rigid", "v0": [1.0, 2.0]}}
    assert check({"fits": fits, "dem": dem}).fit_groups() == whole
    (tmp_path / "cor.csv").write_text("v0,cor\n1,0.8\n3,0.7\n")
    inline = {"data": "cor.csv", "material": MY_SLS, "free": {"beta": [100, 1e4]}}  # a calibration's inline start
    assert check({"fits": fits, "calibrations": {"c": inline}}, tmp_path).fit_groups() == {}
    with pytest.raises(ValueError, match="n_terms: each value at most once"):  # the same N twice: the same fit
        check({"fits": {"f{n}": {"model": "prony", "n_terms": [2, 2, 3]}}})
    assert paths.family_slug("f{n}") == "fN"


@pytest.mark.parametrize("config", [{}, {"scenes": {}}, {"materials": {"m": MY_SLS}}, {"shard_size": 10}])
def test_a_config_that_names_nothing_to_build_is_refused_in_one_line(config):
    with pytest.raises(ValueError, match="names nothing to build") as exc:
        check(config)
    assert "\n" not in str(exc.value) and "scenes, fits, calibrations or dem" in str(exc.value)


# -- one catalogue for every material reference ----------------------------------------------------
def test_a_config_material_is_a_dem_body_material():
    """The sphere and the target of a dem: entry take config materials (the issue's first refusal)."""
    cfg = {"materials": {"my-sls": MY_SLS},
           "dem": {"d": {"sphere": {"material": "sls", "r": 0.005},
                         "target": {"sphere": {"material": "my-sls", "r": 0.005}}, "v0": [0.5, 5.0],
                         "solver": {"method": "direct"}}}}
    check(cfg)
    cfg["dem"]["d"]["target"]["sphere"]["material"] = "my-sl"
    with pytest.raises(ValueError, match=r"dem\.d\.target\.sphere\.material: unknown material 'my-sl'"):
        check(cfg)


def test_a_fit_is_a_scene_body_material_and_a_dem_target_material():
    """A fit as a body's material: its file is an input of the jobs and its identity part of the
    settings, so a refit recomputes the sweep."""
    fits = {"f": {"model": "prony", "n_terms": 3}}
    scene = {"materials": ["sls"], "grid": {"v0": [1.0, 2.0]}, "sphere": {"material": "f"}, "plate": {},
             "solver": {"method": "direct"}}
    project = check({"fits": fits, "scenes": {"s": scene}})
    assert "results/materials/f.nc" in project.material_files_of("s")
    assert project.scenes["s"].settings["body_materials"] == {"f": project.catalogue.identity("f")}
    other = check({"fits": {"f": {"model": "prony", "n_terms": 4}}, "scenes": {"s": scene}})
    assert other.scenes["s"].settings["body_materials"] != project.scenes["s"].settings["body_materials"]
    dem = check({"fits": fits, "dem": {"d": {"sphere": {"material": "sls"}, "target": {"plate": {"material": "f"}},
                                              "v0": [1.0, 2.0]}}})
    assert dem.dem_material_files("d") == ["results/materials/f.nc"]


def test_a_config_material_body_is_inlined_into_the_settings():
    project = check({"materials": {"my-sls": MY_SLS},
                     "scenes": {"s": {"materials": ["butyl-prony3"], "grid": {"v0": [1.0]},
                                      "sphere": {"material": "my-sls"}, "plate": {}, "solver": {"method": "direct"}}}})
    body = project.scenes["s"].settings["bodies"]["sphere"]["material"]
    assert body["model"] == "sls" and body["E_glassy"] == MY_SLS["E_glassy"]


# -- refusals: one short line naming the key ---------------------------------------------------------
def _scene(**changes):
    scene = {"materials": ["sls"], "grid": {"v0": [1.0, 2.0]}}
    scene.update(changes)
    return {"scenes": {"s": scene}}


HOSTILE = [
    (_scene(grid={"v0": "1,2,3"}), ["scenes.s.grid.v0", "'1,2,3'", "a list of numbers"]),
    (_scene(grid={"v0": []}), ["scenes.s.grid.v0", "at least 1"]),
    (_scene(grid={"v0": {"start": 1, "stop": 3, "step": 0}}), ["scenes.s.grid.v0.step", "> 0"]),
    (_scene(grid={"v0": {"start": 1, "stop": 3, "num": 0}}), ["scenes.s.grid.v0.num", ">= 1"]),
    (_scene(grid={"v0": {"start": 1, "stop": 3, "num": 1}}), ["scenes.s.grid.v0", "num 1 gives start (1) alone"]),
    (_scene(grid={"v0": [True, 2.0]}), ["scenes.s.grid.v0", "True"]),
    (_scene(grid={"v0": {"start": 1, "stop": 3, "num": 3, "log": "yes"}}), ["scenes.s.grid.v0.log", "true or false"]),
    (_scene(figure={"fig4": {}}), ["scenes.s.figure", "unknown key", "did you mean 'figures'"]),
    ({"materials": "sls"}, ["materials", "a mapping", "'sls'"]),
    ({"scene": {}}, ["scene", "unknown section", "did you mean 'scenes'"]),
    (_scene(figures={"fig44": {}}), ["scenes.s.figures.fig44", "did you mean 'fig4'"]),
    (_scene(solver={"method": "adaptiv"}), ["scenes.s.solver.method", "did you mean 'adaptive'"]),
    (_scene(grid={"v0": [1, 1, 1]}), ["scenes.s.grid.v0", "1 listed more than once"]),
    (_scene(grid={"v0": [1.0, 0.1 * 3, 0.3]}), ["scenes.s.grid.v0", "0.3 listed more than once"]),
    (_scene(materials=["sl"]), ["scenes.s.materials", "unknown material 'sl'"]),
    (_scene(materials=["sls", "sls"]), ["scenes.s.materials", "each value at most once"]),
    (_scene(grid={"v0": [1.0], "bta": [600, 1200]}), ["scenes.s.grid.bta", "did you mean 'beta'"]),
    (_scene(grid={"vo": [1.0]}), ["scenes.s.grid", "missing key 'v0'", "'vo' is written: did you mean 'v0'"]),
    ({"shard_size": 0, **_scene()}, ["shard_size", ">= 1"]),
    (_scene(histories={"v0": 1.0, "runs": [["slx", "direct"]]}),
     ["scenes.s.histories.runs: 'slx' is not in scenes.s.materials ['sls']; did you mean 'sls'?"]),
    (_scene(histories={"v0": -3, "runs": [["sls", "direct"]]}),
     ["scenes.s.histories.v0: must be > 0 m s-1, got -3 m s-1"]),
    (_scene(geometry={"r": -0.01}), ["scenes.s.geometry.r: must be > 0 m, got -0.01 m"]),
    # a grid value that the material or geometry refuses: the axis (and the value's index in a list)
    (_scene(grid={"v0": [1.0], "E_glassy": [1e7, -2e7]}),
     ["scenes.s.grid.E_glassy[1]: point {", "E_glassy must be in (0, 1e+20] Pa, got -20000000.0"]),
    (_scene(grid={"v0": [1.0], "E_glassy": {"start": -1e7, "stop": 1e7, "num": 3}}),
     ["scenes.s.grid.E_glassy: point {", "E_glassy must be in (0, 1e+20] Pa"]),
    (_scene(grid={"v0": [1.0], "alpha": [10, 1e9]}), ["scenes.s.grid.alpha[1]: point {", "SLS alpha must be in"]),
    (_scene(grid={"v0": [1.0], "h": [0.01, -0.1]}), ["scenes.s.grid.h[1]: point {", "h must be in [1e-09, 1000] m"]),
    (_scene(grid={"v0": [1.0], "beta": [600, 1200]}, tie={"alpha": {"to": "beta", "ratio": 2}}),
     ["scenes.s.tie.alpha: point {", "SLS alpha must be in [0, beta]"]),
    ({"scenes": {"s": {"grid": {"v0": [1.0]}}}},
     ["scenes.s", "a mapping with 'materials'; or a mapping with 'spheres'"]),
    ({"dem": {"d": {"sphere": {"material": "sls"}}}}, ["dem.d", "missing key 'v0'"]),
    ({"calibrations": {"c": {"data": "x.csv", "material": "sls"}}}, ["calibrations.c", "missing key 'free'"]),
    ({"fits": {"f": {"model": "pronyy"}}}, ["fits.f.model", "did you mean 'prony'"]),
    (_scene(materials=["sls"], grid={"v0": [1.0, 10.0]}, figures={"fig1": {"material": "sls", "beta": 999}},
            histories={"v0": 1.0, "runs": [["sls", "direct"]]}),
     ["scenes.s.figures.fig1.beta", "999", "own beta (1200.0)"]),
    (_scene(grid={"v0": [1.0, 10.0], "beta": [600, 1200]}, tie={"alpha": {"to": "beta", "ratio": 0.25}},
            figures={"fig1": {"beta": 999}},
            histories={"v0": 1.0, "runs": [["sls", "direct"]]}),
     ["scenes.s.figures.fig1.beta", "999 is not on the grid axis beta"]),
]


@pytest.mark.parametrize("config, words", HOSTILE, ids=[f"hostile{i}" for i in range(len(HOSTILE))])
def test_every_refusal_is_one_line_naming_the_key(config, words):
    with pytest.raises(ValueError) as exc:
        check(json.loads(json.dumps(config)))
    text = str(exc.value)
    assert "\n" not in text and len(text) < 400, text
    for w in words:
        assert w in text, (w, text)


def test_a_config_that_is_not_a_mapping_is_refused():
    with pytest.raises(SchemaError, match="a mapping of sections"):
        check_schema(["scenes"], SCHEMA)


# -- defaults in one place ---------------------------------------------------------------------------
def _schema_default(*keys):
    node = load_schema(SCHEMA)
    for k in keys:
        node = node["properties"][k] if k != "*" else node["additionalProperties"]
    return node["default"]


def test_the_schema_defaults_are_the_codes():
    assert _schema_default("job_seconds") == DEFAULTS["job_seconds"] == load_project(_scene(), ROOT).job_seconds
    assert "default" not in load_schema(SCHEMA)["properties"]["shard_size"]  # no cap unless a config sets one
    assert DEFAULTS["shard_size"] is None is load_project(_scene(), ROOT).shard_size
    assert _schema_default("material_dir") == DEFAULTS["material_dir"] == load_project(_scene(), ROOT).material_dir
    spec = uncertainty_of({"uncertainty": {"bootstrap": 2}})
    assert _schema_default("scenes", "*", "uncertainty", "seed") == spec["seed"]
    assert _schema_default("scenes", "*", "uncertainty", "level") == spec["level"]
    assert _schema_default("scenes", "*", "error_estimate") is settings_of({"grid": {"v0": [1]}})["error_estimate"]
    # a config without job sizing plans its jobs with the schema's defaults, which are the code's
    project = check({"scenes": {"s": {"materials": ["sls"], "grid": {"v0": {"start": 1, "stop": 3000, "step": 1}}}}})
    assert project.scenes["s"].job_seconds == DEFAULTS["job_seconds"] and project.scenes["s"].shard_size is None


# -- the grid: typed axes, indexed points ---------------------------------------------------------------
def test_axes_have_a_role_and_a_unit_decided_in_one_place():
    grid = Grid.from_scene({"materials": ["sls", "butyl-fc"],
                            "grid": {"T": [20, 0], "v0": [1, 2], "h": [0.01], "beta": [600]}}, samples=3)
    assert [(a.name, a.role, a.unit) for a in grid.axes] == [
        ("T", "temperature", "degC"), ("v0", "speed", "m s-1"), ("h", "geometry", "m"),
        ("beta", "material", "s-1"), ("sample", "sample", "1")]
    assert axis_role("E_plate") == "geometry" and axis_role("E_inf") == "material"
    assert AXIS_UNITS["v0"][0] == "m s-1"
    assert grid.shape == (2, 2, 2, 1, 1, 3) and grid.size == 24
    assert grid.axis("T").values == (0.0, 20.0)  # sorted


def test_points_carry_their_index_and_round_trip():
    grid = Grid.from_scene({"materials": ["a", "b"], "grid": {"v0": [3, 1, 2], "nu": [0.3, 0.5]}})
    points = grid.points()
    assert [p["index"] for p in points] == list(range(12))
    assert points[7] == {"index": 7, "material": "b", "v0": 1.0, "nu": 0.5}
    assert all(grid.index_of(p) == p["index"] for p in points)
    assert Grid.from_dict(json.loads(json.dumps(grid.to_dict()))) == grid
    with pytest.raises(KeyError):
        grid.index_of({"material": "a", "v0": 4.0, "nu": 0.3})
    assert "index" not in point_key(points[7])


def test_axis_values_refuse_duplicates_and_keep_canonical_values():
    assert axis_values({"start": 0.1, "stop": 0.3, "step": 0.1}) == [0.1, 0.2, 0.3]
    with pytest.raises(ValueError, match="2 listed more than once"):
        axis_values([2, 1, 2])


# -- shards: index and units, joined by index ------------------------------------------------------------
SCENE = {"materials": ["sls", "kelvin-voigt"], "grid": {"v0": [2.0, 10.0], "nu": [0.4, 0.5]}}
IDS = {"sls": "id-sls", "kelvin-voigt": "id-kv"}


def _solve(shard):
    ds = runner.run_points(shard.points, settings_of(SCENE))
    ds.attrs["code_fingerprint"] = provenance.code_fingerprint()
    return ds


def test_shards_carry_index_and_units_and_the_aggregate_joins_by_index(tmp_path):
    plan = shards.plan_shards(SCENE, tmp_path, 3, IDS)
    assert sum(len(s.points) for s in plan.values()) == 8
    solved = [_solve(s) for s in plan.values()]
    assert solved[0]["v0"].attrs["units"] == "m s-1" and solved[0]["nu"].attrs["units"] == "1"
    assert list(solved[0]["index"].values) == [p["index"] for p in next(iter(plan.values())).points]
    grid = grid_of(SCENE)
    # the shards in reverse order, rows reversed inside: the join is by index, not by position
    flipped = [ds.isel(point=slice(None, None, -1)) for ds in solved[::-1]]
    rows = [s.rows[::-1] for s in list(plan.values())[::-1]]
    ds = aggregation.aggregate(flipped, rows, grid, SCENE)
    assert ds["cor"].dims == ("material", "v0", "nu") and ds["v0"].attrs["units"] == "m s-1"
    direct = runner.run_points([{**p, "material_id": "x"} for p in grid.points()], settings_of(SCENE))
    np.testing.assert_array_equal(ds["cor"].values.ravel(), direct["cor"].values)
    with pytest.raises(ValueError, match="differ from the grid's"):
        aggregation.aggregate(solved, [s.rows[::-1] for s in plan.values()], grid, SCENE)


def _write(tmp_path, shard, ds):
    from vcor.io import netcdf, receipts

    netcdf.write_dataset(ds, tmp_path / f"{shard.id}.nc", title="shard", identity=shard.id)
    receipts.atomic_text(tmp_path / f"{shard.id}.json", json.dumps({"points": shard.points}))


def test_extending_a_grid_reuses_shards_with_their_rows_in_the_new_grid(tmp_path):
    plan = shards.plan_shards(SCENE, tmp_path, 100, IDS)
    (only,) = plan.values()
    _write(tmp_path, only, _solve(only))
    wider = {**SCENE, "grid": {"v0": [1.0, 2.0, 10.0], "nu": [0.4, 0.5]}}
    again = shards.plan_shards(wider, tmp_path, 100, IDS)
    assert only.id in again and again[only.id].points == only.points  # unchanged params: not re-run
    grid = grid_of(wider)
    for p, row in zip(only.points, again[only.id].rows):
        assert grid.point(row)["v0"] == p["v0"] and grid.point(row)["material"] == p["material"]
    new = [s for k, s in again.items() if k != only.id]
    assert sum(len(s.points) for s in new) == 4 and all(p["v0"] == 1.0 for s in new for p in s.points)


def test_a_shard_with_points_of_a_changed_material_is_not_reused(tmp_path):
    """A finished shard holding points of a material whose identity changed (or that left the scene) is
    not reused: all its still-wanted points are planned again, none is solved for an identity it was not
    planned with. A shard's job is given only the swept materials its points name (``shard_materials``);
    ``check_current`` refuses a point whose identity is not the catalogue's."""
    plan = shards.plan_shards(SCENE, tmp_path, 100, IDS)
    (only,) = plan.values()
    _write(tmp_path, only, _solve(only))
    assert list(shards.plan_shards(SCENE, tmp_path, 100, IDS)) == [only.id]
    changed, removed = {**IDS, "kelvin-voigt": "id-kv-2"}, {"sls": IDS["sls"]}
    for ids, scene in ((changed, SCENE), (removed, {**SCENE, "materials": ["sls"]})):
        again = shards.plan_shards(scene, tmp_path, 100, ids)
        assert only.id not in again
        assert all(p["material_id"] == ids[p["material"]] for s in again.values() for p in s.points)
        assert sum(len(s.points) for s in again.values()) == 4 * len(scene["materials"])
    sls_only = [p for p in only.points if p["material"] == "sls"]
    assert shards.shard_materials(sls_only, ["tpu"]) == ["sls", "tpu"]  # tpu: the scene's sphere, say
    shards.check_current([{"material": "sls", "material_id": Catalogue().identity("sls")}], Catalogue(), "abc")
    with pytest.raises(ValueError, match=r"shard abc: its points of material 'sls' were planned for identity id-sls"):
        shards.check_current([{"material": "sls", "material_id": "id-sls"}], Catalogue(), "abc")
    with pytest.raises(ValueError, match="now gives no such material"):
        shards.check_current([{"material": "gone", "material_id": "x"}], Catalogue(), "abc")


def test_a_shard_without_point_indices_is_recomputed_never_misread(tmp_path):
    plan = shards.plan_shards(SCENE, tmp_path, 100, IDS)
    (only,) = plan.values()
    old = [{k: v for k, v in p.items() if k != "index"} for p in only.points]
    _write(tmp_path, shards.Shard(id=only.id, points=old, rows=only.rows), _solve(only))
    told = []
    again = shards.plan_shards(SCENE, tmp_path, 100, IDS, on_invalid=lambda path, why: told.append(why))
    assert told and "no point indices" in told[0]
    assert all("index" in p for s in again.values() for p in s.points)


def test_a_dataset_the_config_asks_for_is_built_without_a_figure():
    """histories: (and moduli:, spheres:, convergence:) in a scene build their dataset with no figure to draw
    it: a histories-only scene builds its histories; with none of them, the scene builds its sweep only."""
    project = check({"scenes": {"h": {"materials": ["sls"], "histories": {"v0": 3.0, "runs": [["sls", "direct"]]}},
                                "m": {"materials": ["sls"], "grid": {"v0": [1.0]}, "moduli": ["butyl-fc"]},
                                "s": {"materials": ["sls"], "grid": {"v0": [1.0]}}}})
    assert project.scenes["h"].datasets() == ["histories"]
    assert project.scenes["m"].datasets() == ["sweep", "moduli"]
    assert project.scenes["s"].datasets() == ["sweep"]
    assert paths.fmt(paths.DATASET, scene="h", dataset="histories") in project.scene_targets("h")


def test_result_paths_come_from_one_module():
    project = check(_scene(figures={"fig4": {"material": "sls"}}, grid={"v0": [1.0], "beta": [600, 1200]},
                           tie={"alpha": {"to": "beta", "ratio": 0.25}}))
    assert paths.fmt(paths.SWEEP, scene="s") in project.scene_targets("s")
    assert paths.fmt(paths.FIGURE, scene="s", fig="fig4", ext="png") in project.scene_targets("s")
    rules = "".join(p.read_text() for p in (ROOT / "workflow" / "rules").glob("*.smk"))
    assert '"results/' not in rules and "f\"results/" not in rules


def test_the_default_config_is_one_model():
    cfg = yaml.safe_load((ROOT / "config.yaml").read_text())
    project = check(cfg)
    sls = project.scenes["sls"]
    assert sls.grid.names == ["v0", "beta"] and sls.grid.axis("beta").role == "material"
    assert project.scenes["pyvisco"].grid.names == ["v0", "T", "nu", "sample"]


def test_schema_read_with_libyaml_is_the_safe_load():
    from vcor.study import schema

    path = Path(__file__).resolve().parents[2] / "workflow" / "schemas" / "config.schema.yaml"
    assert schema.load_schema(path) == yaml.safe_load(path.read_text())
