"""A calibration's geometry and solver, and a config material's Prony table, are refused at planning
(``snakemake -n``) in one line naming the config file, the line, the column and the key; nothing runs."""

import pytest

pytestmark = pytest.mark.slow  # each test runs Snakemake

CALIBRATION = ("calibrations:\n  x:\n    data: data/examples/my_cor.csv\n"
               "    material: {model: sls, E_glassy: 15.0e+6, alpha: 300, beta: 1200}\n"
               "    free: {E_glassy: [1.0e+6, 1.0e+9], beta: [10, 1.0e+6]}\n")


@pytest.fixture(scope="module")
def project(make_project, tmp_path_factory):
    return make_project(tmp_path_factory.mktemp("calibration-refusals"), {"scenes": {"s": {
        "materials": ["sls"], "grid": {"v0": [1.0]}}}})


@pytest.mark.parametrize("text, said", [
    (CALIBRATION + "    geometry: {radius: 0.01}\n",
     "config file my.yaml, line 6, column 16: calibrations.x.geometry.radius: unknown key; allowed: "),
    (CALIBRATION + "    geometry: {r: -0.01}\n",
     "config file my.yaml, line 6, column 16: calibrations.x.geometry.r: must be > 0 m, got -0.01 m"),
    (CALIBRATION + "    solver: {methd: adaptive}\n",
     "config file my.yaml, line 6, column 14: calibrations.x.solver.methd: unknown key; allowed: "),
    (CALIBRATION + "    solver: {dt: 1.0e-6}\n",
     "config file my.yaml, line 6, column 5: calibrations.x.solver: solver option dt is not used by method "
     "'adaptive'"),
    ("materials:\n  csvmat: {model: prony, E_inf: 3.0e+6, file: data/missing.csv}\n"
     "scenes:\n  s: {materials: [sls], grid: {v0: [1.0]}}\n",
     "config file my.yaml, line 2, column 41: materials.csvmat.file: the Prony table 'data/missing.csv' does not "
     "exist in '{project}' (the project folder"),
], ids=["geometry-key", "geometry-range", "solver-key", "solver-method", "material-file"])
def test_planning_refuses_naming_the_file_line_column_and_key(smk, project, text, said):
    (project / "my.yaml").write_text(text)
    out = smk(project, "-n", "-j1", "--configfile", "my.yaml", check=False)
    output = out.stdout + out.stderr
    assert out.returncode != 0 and said.format(project=project.resolve()) in output, output
    assert not (project / "results").exists()
