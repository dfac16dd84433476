"""A calibration's geometry and solver are checked before any job as a scene's are (the schema's keys, ranges
and units, then the start material's impacts and the method), in one line naming the key; a config
material's missing Prony table names its key, its place in the file and the folder it was looked for in
(docs: Calibration, Scenes)."""

import math
import re
from pathlib import Path

import pytest

import vcor
from vcor.fitting import calibrate as C
from vcor.study.config import load_project
from vcor.study.schema import check_schema

ROOT = Path(__file__).resolve().parents[2]
SCHEMA = ROOT / "workflow" / "schemas" / "config.schema.yaml"
DATA = "v0,cor\n1.0,0.40\n3.0,0.41\n10.0,0.43\n"
SPEC = {"data": "cor.csv", "material": "sls", "free": {"beta": [100.0, 1.0e5]}}


def _project(tmp_path, spec):
    (tmp_path / "cor.csv").write_text(DATA)
    return load_project(check_schema({"calibrations": {"c": {**SPEC, **spec}}}, SCHEMA), tmp_path)


@pytest.mark.parametrize("spec, words", [
    ({"geometry": {"radius": 0.01}}, "calibrations.c.geometry.radius: unknown key; allowed: ['E_plate', 'case', 'h'"),
    ({"geometry": {"r": -0.01}}, "calibrations.c.geometry.r: must be > 0 m, got -0.01 m"),
    ({"geometry": {"case": 5}}, "calibrations.c.geometry.case: 5 is not allowed; allowed: [1, 2, 3, 4]"),
    ({"geometry": {"r": 2000.0}}, "calibrations.c.geometry.r: must be in [1e-09, 1000] m, got 2000.0"),
    ({"geometry": {"E_plate": 1.0e9}}, "calibrations.c.geometry.E_plate: is the elastic plate's modulus of "
                                       "case 4 only"),
    ({"solver": {"methd": "adaptive"}}, "calibrations.c.solver.methd: unknown key; allowed: ['c2', 'dt'"),
    ({"solver": {"method": "adaptiv"}}, "calibrations.c.solver.method: 'adaptiv' is not allowed"),
    ({"solver": {"step_tol": 0.5}}, "calibrations.c.solver.step_tol: must be < 0.01, got 0.5"),
    ({"solver": {"dt": 1.0e-6}}, "calibrations.c.solver: solver option dt is not used by method 'adaptive'"),
    ({"material": "butyl-fc", "free": {"E0": [1.0e5, 1.0e8]}, "solver": {"method": "ive"}},
     "calibrations.c.solver.method: method 'ive' needs a Prony kernel"),
])
def test_a_calibrations_geometry_and_solver_are_refused_at_planning_naming_the_key(tmp_path, spec, words):
    with pytest.raises(ValueError) as exc:
        _project(tmp_path, spec)
    text = str(exc.value)
    assert "\n" not in text and len(text) < 400, text
    assert text.startswith(words), (words, text)


def test_a_good_calibration_geometry_and_solver_pass(tmp_path):
    project = _project(tmp_path, {"geometry": {"r": 0.005, "h": 0.02}, "solver": {"method": "direct"}})
    assert project.catalogue.calibrations["c"]["solver"]["method"] == "direct"


def _no_solving(monkeypatch):
    def no_work(*args, **kw):
        raise AssertionError("solving started")

    monkeypatch.setattr(C, "_solve", no_work)


@pytest.mark.parametrize("spec, words", [
    ({"geometry": {"radius": 0.01}}, r"^calibration\.geometry\.radius: unknown key; allowed: "),
    ({"geometry": {"r": -0.01}}, r"^calibration\.geometry\.r: must be > 0 m, got -0\.01 m$"),
    ({"solver": {"methd": "adaptive"}}, r"^calibration\.solver\.methd: unknown key; .*did you mean 'method'\?$"),
])
def test_vcor_calibrate_refuses_a_bad_geometry_or_solver_before_any_work(tmp_path, monkeypatch, spec, words):
    _no_solving(monkeypatch)
    (tmp_path / "cor.csv").write_text(DATA)
    with pytest.raises(ValueError, match=words):
        vcor.calibrate({**SPEC, "data": str(tmp_path / "cor.csv"), **spec})


def test_a_calibration_of_a_config_file_is_refused_at_its_line_and_column(tmp_path, monkeypatch):
    _no_solving(monkeypatch)
    (tmp_path / "cor.csv").write_text(DATA)
    (tmp_path / "my.yaml").write_text("calibrations:\n  x:\n    data: cor.csv\n    material: sls\n"
                                      "    free: {beta: [100, 1.0e+5]}\n    geometry: {radius: 0.01}\n")
    with pytest.raises(ValueError, match=r"^config file .*my\.yaml, line 6, column 16: "
                                         r"calibrations\.x\.geometry\.radius: unknown key"):
        vcor.calibrate("x", config=tmp_path / "my.yaml")


def test_a_malformed_cor_data_file_names_the_key_that_names_it(tmp_path, monkeypatch):
    """A COR data file that cannot be read is refused before any work with the config key that names it (and
    its place in the config file), then the data file, line and column."""
    _no_solving(monkeypatch)
    (tmp_path / "cor.csv").write_text("v0,cor\n1.0,0.40\n3.0,abc\n")
    (tmp_path / "my.yaml").write_text("calibrations:\n  x:\n    data: cor.csv\n    material: sls\n"
                                      "    free: {beta: [100, 1.0e+5]}\n")
    with pytest.raises(ValueError) as err:
        vcor.calibrate("x", config=tmp_path / "my.yaml")
    assert re.fullmatch(r"config file .*my\.yaml, line 3, column 5: calibrations\.x\.data: .*cor\.csv, line 3, "
                        r"column 'cor': 'abc' is not a number", str(err.value)), str(err.value)


def test_a_missing_prony_table_names_its_key_its_place_and_the_folder(tmp_path):
    """The config's materials are checked whole: a material whose table is missing refuses the config, also
    for an entry that does not use it (as the workflow refuses it)."""
    (tmp_path / "bad.yaml").write_text(
        "materials:\n  csvmat: {model: prony, E_inf: 3.0e+6, file: data/missing.csv}\n"
        "dem:\n  d: {sphere: {material: sls}, v0: [1.0, 2.0]}\n")
    with pytest.raises(ValueError) as exc:
        vcor.dem_export("d", config=tmp_path / "bad.yaml")
    text = str(exc.value)
    folder = re.escape(repr(str(tmp_path.resolve())))
    assert "\n" not in text
    assert re.match(rf"^config file .*bad\.yaml, line 2, column 41: materials\.csvmat\.file: the Prony table "
                    rf"'data/missing\.csv' does not exist in {folder} \(the project folder", text), text


def test_a_config_in_a_subfolder_of_a_project_takes_paths_from_the_project(tmp_path, tmp_path_factory, capsys):
    """A config file kept below a folder with a Snakefile reads its relative paths from that folder, as
    ``snakemake --configfile`` (run there) does, in the study functions and the commands alike; a config
    outside any project from its own folder."""
    from vcor.cli import main

    (tmp_path / "Snakefile").write_text("")
    (tmp_path / "tables").mkdir()
    (tmp_path / "tables" / "terms.csv").write_text("tau,E\n1.0e-3,2.0e+7\n1.0e-4,3.0e+7\n")
    (tmp_path / "configs").mkdir()
    text = "materials:\n  tab: {model: prony, E_inf: 3.0e+6, file: tables/terms.csv}\n"
    (tmp_path / "configs" / "mine.yaml").write_text(text)
    got = vcor.moduli({"materials": ["tab"]}, config=tmp_path / "configs" / "mine.yaml")
    t0 = float(got["t"].values[0])
    exact = 3.0e6 + 2.0e7 * math.exp(-t0 / 1.0e-3) + 3.0e7 * math.exp(-t0 / 1.0e-4)  # the table's terms
    assert float(got["relaxation_modulus"].sel(material="tab").values[0]) == pytest.approx(exact, rel=1e-12)
    assert main(["materials", "--config", str(tmp_path / "configs" / "mine.yaml")]) == 0
    assert "tab" in capsys.readouterr().out
    alone = tmp_path_factory.mktemp("alone")  # no Snakefile at or above it: its own folder
    assert not any((folder / "Snakefile").is_file() for folder in (alone, *alone.parents))
    (alone / "mine.yaml").write_text(text)
    (alone / "tables").mkdir()
    (alone / "tables" / "terms.csv").write_text("tau,E\n1.0e-3,2.0e+7\n")  # one term
    got = vcor.moduli({"materials": ["tab"]}, config=alone / "mine.yaml")
    exact = 3.0e6 + 2.0e7 * math.exp(-t0 / 1.0e-3)
    assert float(got["relaxation_modulus"].sel(material="tab").values[0]) == pytest.approx(exact, rel=1e-12)


def test_a_forward_model_that_fails_names_the_parameters_as_numbers(tmp_path, monkeypatch):
    """A geometry inside its ranges on which the forward model ends step-budget (a 1 nm plate): the refusal
    gives the speed and the parameters' values as numbers (no NumPy reprs)."""
    (tmp_path / "cor.csv").write_text(DATA)
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ValueError, match=r"forward model at v0 = 1 m/s, beta = 1200: step-budget") as err:
        vcor.calibrate({**SPEC, "geometry": {"h": 1e-9}})
    assert "np." not in str(err.value)


def test_a_missing_data_file_names_its_key(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    folder = str(tmp_path.resolve())
    with pytest.raises(ValueError) as refused:
        vcor.calibrate({**SPEC, "data": "nope.csv"})
    assert str(refused.value) == (f"calibration.data: the COR data file 'nope.csv' does not exist in {folder!r} "
                                  f"(the project folder, which relative paths are taken from)")


@pytest.mark.parametrize("calibrations, message", [
    ({"c": {**SPEC, "material": "c"}}, r"calibrations\.c\.material: the calibration starts from itself \(c -> c\)"),
    ({"c": {**SPEC, "material": "d"}, "d": {**SPEC, "material": "c"}},
     r"calibrations\.c\.material: the calibration starts from itself \(c -> d -> c\)"),
])
def test_a_calibration_that_starts_from_itself_is_refused(tmp_path, calibrations, message):
    """Directly or through another calibration (the material would need itself first)."""
    (tmp_path / "cor.csv").write_text(DATA)
    with pytest.raises(ValueError, match=message):
        load_project(check_schema({"calibrations": calibrations}, SCHEMA), tmp_path)


def test_an_unknown_start_is_not_offered_the_calibration_itself(tmp_path):
    (tmp_path / "cor.csv").write_text(DATA)
    with pytest.raises(ValueError, match=r"unknown material 'slss'") as err:
        _project(tmp_path, {"material": "slss"})
    assert "calibrations" not in str(err.value).split("unknown material", 1)[1], str(err.value)
