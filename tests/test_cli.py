"""The ``vcor`` command line: impact (text with units and significant digits, JSON with full precision,
validity in words, wall time without kernel loading, the compile notice), bad numbers refused before
any work, materials with units, formulas and sources, export, ``python -m vcor``, --version, and every
option's help naming its unit."""

import csv
import io
import json
import os
import subprocess
import sys

import pytest

import vcor
from vcor import cli
from vcor.contact.impact import RANGES
from vcor.io.netcdf import write_dataset
from vcor.materials.models import Material
from vcor.solvers.common import UNITS
from vcor.solvers.validity import FLAGS
from vcor.study import aggregation, runner, scene

PYTHON_M_VCOR = [sys.executable, "-m", "vcor"]


def _run(*args, env=None):
    return subprocess.run([*PYTHON_M_VCOR, *args], capture_output=True, text=True, check=False, env=env)


def _text_rows(text: str) -> dict:
    """{name: (value, unit)} of the numeric lines of ``vcor impact``'s text output."""
    rows = {}
    for line in text.splitlines():
        parts = line.split()
        if len(parts) >= 3 and parts[2].startswith("["):
            rows[parts[0]] = (parts[1], parts[2].strip("[]"))
    return rows


def _significant_digits(text: str) -> int:
    mantissa = text.lstrip("-").split("e")[0].replace(".", "").lstrip("0")
    return len(mantissa)


# ----------------------------------------------------------------------------- impact: output
def test_json_output_has_units_full_precision_and_matches_api(capsys):
    assert cli.main(["impact", "--material", "sls", "--v0", "10", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    api = vcor.simulate("sls", 10.0)
    assert out["cor"]["units"] == "1" and out["t0"]["units"] == "s" and out["f_max"]["units"] == "N"
    for key in ("cor", "t0", "s_max", "f_max", "w_h", "energy_residual"):
        assert out[key]["value"] == getattr(api, key), key  # full precision: the same float
    assert out["status"] == "ok" and out["method"] == "adaptive"  # the default method, as in the API
    assert out["kernel_load_time"]["units"] == "s" and out["kernel_load_time"]["value"] >= 0


def test_text_output_has_significant_digits_and_units(capsys):
    assert cli.main(["impact", "--material", "sls", "--v0", "10"]) == 0
    rows = _text_rows(capsys.readouterr().out)
    api = vcor.simulate("sls", 10.0)
    for key in ("cor", "t0", "s_max", "f_max", "s_residual", "w_h", "w_plate", "omega_min", "sphere_velocity"):
        value, unit = rows[key]
        assert _significant_digits(value) <= 5, (key, value)
        assert float(value) == pytest.approx(getattr(api, key), rel=5e-5), (key, value)  # rounded, not changed
        assert unit == cli.TEXT_UNITS.get(UNITS[key], UNITS[key]), (key, unit)
    assert rows["cor"] == (f"{api.cor:.5g}", "1")
    assert "e-" in rows["t0"][0] and rows["t0"][1] == "s"  # 1.3415e-3 s: a small number in powers of ten
    assert _significant_digits(rows["energy_residual"][0]) <= 2
    assert rows["steps"] == (str(api.steps), "1")
    assert rows["wall_time"][1] == "s" and rows["kernel_load_time"][1] == "s"


def test_text_output_of_ive(capsys):
    assert cli.main(["impact", "--material", "butyl-prony3", "--v0", "10", "--method", "ive"]) == 0
    text = capsys.readouterr().out
    assert "ive-Radau" in text and _text_rows(text)["t0"][1] == "s"


# ----------------------------------------------------------------------------- impact: validity in words
def test_validity_flags_decode_every_mask():
    for mask in range(2 ** len(FLAGS)):
        names = cli.validity_flags(mask)
        assert sum(FLAGS[n] for n in names) == mask and list(names) == [n for n in FLAGS if n in names]


@pytest.mark.parametrize("v0, expected", [(1.0, []), (10.0, ["large_indentation"]),
                                          (50.0, ["large_indentation", "fast_impact"])])
def test_validity_in_words_in_text_and_json(v0, expected, capsys):
    api = vcor.simulate("sls", v0)
    assert cli.main(["impact", "--material", "sls", "--v0", str(v0), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["validity_flags"] == expected and out["validity"]["value"] == api.validity
    assert cli.main(["impact", "--material", "sls", "--v0", str(v0)]) == 0
    line = next(ln for ln in capsys.readouterr().out.splitlines() if ln.startswith("validity"))
    if expected:
        assert line.split(None, 1)[1].startswith(", ".join(expected)) and api.validity_message in line
    else:
        assert "inside the model's stated range" in line


def test_a_status_other_than_ok_says_what_to_change(capsys):
    # a thin plate with the fixed-step reference method: it ends at its step budget
    code = cli.main(["impact", "--material", "sls", "--v0", "10", "--h", "0.001", "--method", "direct",
                     "--steps-per-contact", "200"])
    captured = capsys.readouterr()
    assert code == 1 and "status step-budget" in captured.err and "use method adaptive" in captured.err
    assert "validity" not in captured.out  # no validity verdict on a result without one


# ----------------------------------------------------------------------------- impact: times
def test_wall_time_is_the_solve_alone_in_a_fresh_process():
    """A fresh process loads the kernels from numba's cache (or compiles them) on first use: that time
    is kernel_load_time, and wall_time is the solve's (some 0.1 ms here, against ~0.1-1 s of loading)."""
    out = _run("impact", "--material", "sls", "--v0", "10", "--json")
    assert out.returncode == 0, out.stderr
    res = json.loads(out.stdout)
    assert res["kernel_load_time"]["value"] > 0
    assert res["wall_time"]["value"] < res["kernel_load_time"]["value"]
    assert res["cor"]["value"] == vcor.simulate("sls", 10.0).cor  # the reported run is the same impact


def test_kernels_already_loaded_are_not_timed_again(capsys):
    vcor.simulate("sls", 10.0)  # this process has the kernels
    assert cli.main(["impact", "--material", "sls", "--v0", "10", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["kernel_load_time"]["value"] == 0


@pytest.mark.slow
def test_compile_notice_on_a_cold_cache_only(tmp_path):
    """With an empty numba cache the kernels compile (~10 s): one notice on standard error, naming the
    cache; wall_time stays the solve's. The next run loads them: no notice."""
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "numba-cache")}
    cold = _run("impact", "--material", "sls", "--v0", "10", "--json", env=env)
    assert cold.returncode == 0, cold.stderr
    notices = [ln for ln in cold.stderr.splitlines() if ln.startswith("vcor: compiling the solver kernels")]
    assert len(notices) == 1 and str(tmp_path / "numba-cache") in notices[0]
    res = json.loads(cold.stdout)
    assert res["kernel_load_time"]["value"] > 1.0  # compiling, not loading
    assert res["wall_time"]["value"] < 0.1 * res["kernel_load_time"]["value"]
    warm = _run("impact", "--material", "sls", "--v0", "10", "--json", env=env)
    assert warm.returncode == 0 and "compiling" not in warm.stderr
    assert json.loads(warm.stdout)["cor"] == res["cor"]


# ----------------------------------------------------------------------------- impact: bad numbers
@pytest.mark.parametrize("args, flag, words", [
    (["--v0", "abc"], "--v0", ["'abc' is not a number", "[1e-09, 100000] m/s", "unit m/s"]),
    (["--v0", "-1"], "--v0", ["[1e-09, 100000] m/s", "got -1.0", "unit m/s"]),
    (["--v0", "10", "--r", "0"], "--r", ["[1e-09, 1000] m", "got 0.0", "sphere radius", "unit m"]),
    (["--v0", "10", "--nu", "0.7"], "--nu", ["(-1, 0.5]", "no unit"]),
    (["--v0", "10", "--step-tol", "1"], "--step-tol", ["(0, 0.01)", "no unit"]),
    (["--v0", "10", "--max-steps", "1.5"], "--max-steps", ["not an integer", ">= 100"]),
    (["--v0", "10", "--dt", "x"], "--dt", ["(0, inf) s", "unit s"]),
    (["--v0", "10", "--case", "5"], "--case", ["1, 2, 3, 4"]),
])
def test_bad_numbers_are_refused_naming_option_unit_and_range(args, flag, words):
    out = _run("impact", "--material", "sls", *args)
    assert out.returncode == 2 and out.stdout == ""
    assert f"argument {flag}" in out.stderr
    for w in words:
        assert w in out.stderr, (w, out.stderr)
    assert "compiling" not in out.stderr  # refused before any work


def test_bad_numbers_are_refused_before_any_work(monkeypatch, capsys):
    from vcor.solvers import simulate as front_end

    monkeypatch.setattr(front_end, "simulate", lambda *a, **k: pytest.fail("solved a refused input"))
    with pytest.raises(SystemExit) as stop:
        cli.main(["impact", "--material", "sls", "--v0", "abc"])
    assert stop.value.code == 2 and "--v0" in capsys.readouterr().err


def test_every_numeric_flag_checks_like_the_library(capsys):
    """Each numeric flag takes what the library takes and refuses, at parsing, what it refuses."""
    parser = cli.build_parser()
    base = ["impact", "--material", "sls", "--v0", "1"]
    for name in ("r", "rho_a", "rho_b", "h", "E_plate"):
        lo, hi = RANGES[name]
        flag = "--" + name.replace("_", "-")
        for ok in (lo, hi):
            assert getattr(parser.parse_args([*base, flag, repr(ok)]), name) == ok
        for bad in (lo / 2, hi * 2, "nan", "zero"):
            with pytest.raises(SystemExit):
                parser.parse_args([*base, flag, str(bad)])
            err = capsys.readouterr().err
            assert f"argument {flag}" in err and f"[{lo:g}, {hi:g}]" in err and "unit" in err, err
    for name in ("steps_per_contact", "max_steps", "max_adaptive_steps", "step_tol", "rtol", "soe_tol", "dt", "c2"):
        flag = "--" + name.replace("_", "-")
        with pytest.raises(SystemExit):
            parser.parse_args([*base, flag, "abc"])
        err = capsys.readouterr().err
        assert f"argument {flag}" in err and "is not a number" in err and "must be" in err, err
        assert "unit" in err, err


# ----------------------------------------------------------------------------- impact: other errors
def test_material_is_required_and_checked():
    with pytest.raises(SystemExit):
        cli.build_parser().parse_args(["impact", "--v0", "1"])
    out = subprocess.run([sys.executable, "-m", "vcor.cli", "impact", "--material", "rubber", "--v0", "1"],
                         capture_output=True, text=True, check=False)
    assert out.returncode == 2 and "--material" in out.stderr and "sls" in out.stderr


# ----------------------------------------------------------------------------- entry points
def test_console_script_python_m_vcor_and_version():
    args = ["impact", "--v0", "5", "--rigid", "--material", "elastic", "--json"]
    script = subprocess.run(["vcor", *args], capture_output=True, text=True, check=False)
    module = _run(*args)
    assert script.returncode == 0 and module.returncode == 0, module.stderr
    assert abs(json.loads(script.stdout)["cor"]["value"] - 1.0) < 1e-6
    assert json.loads(module.stdout)["cor"] == json.loads(script.stdout)["cor"]
    for command in (["vcor"], PYTHON_M_VCOR):
        version = subprocess.run([*command, "--version"], capture_output=True, text=True, check=False)
        assert version.returncode == 0 and version.stdout.strip() == f"vcor {vcor.__version__}"
    usage = _run()
    assert usage.returncode == 2 and usage.stderr.startswith("vcor: error: the following arguments are required")
    # a refusal of argparse's is one line, as vcor's own (no usage block before it)
    bad = _run("impact", "--material", "sls", "--v0", "-1")
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1, bad.stderr
    assert bad.stderr.startswith("vcor impact: error: argument --v0") and "(options: vcor impact -h)" in bad.stderr


def test_a_reader_that_stops_early_is_not_an_error():
    proc = subprocess.Popen([*PYTHON_M_VCOR, "materials", "--json"], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    proc.stdout.readline()
    proc.stdout.close()
    err = proc.stderr.read().decode()
    proc.stderr.close()
    assert proc.wait() == 0 and "Traceback" not in err, err


def test_impact_takes_a_material_spec(capsys):
    """--material takes a spec as a config's materials block does (the numbers of vcor.simulate with that
    spec); a bad spec is refused in one line naming the flag and the key."""
    spec = {"model": "sls", "E_glassy": 4.0e7, "alpha": 800.0, "beta": 6000.0}
    assert cli.main(["impact", "--material", "{model: sls, E_glassy: 4.0e+7, alpha: 800, beta: 6000}", "--v0", "1",
                     "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["cor"]["value"] == vcor.simulate(spec, 1.0).cor
    for text, message in [("{model: sls, E_glasy: 4.0e+7, alpha: 800, beta: 6000}",
                           "--material.E_glasy: unknown key; a sls material takes ['E_glassy', 'alpha', 'beta']"),
                          ("{model: sls, E_glassy: -4.0e+7, alpha: 800, beta: 6000}",
                           "--material.E_glassy must be in (0, 1e+20] Pa, got -40000000.0"),
                          ("{model: sls", "--material, line 2, column 1: not valid YAML")]:
        assert cli.main(["impact", "--material", text, "--v0", "1"]) == 2
        err = capsys.readouterr().err
        assert message in err and err.count("\n") == 1, err


def test_impact_takes_simulates_targets(capsys, tmp_path):
    """--target takes what vcor.simulate's target takes (a sphere or a plate of a named material, a material
    file, rigid or a spec; rigid), with the same numbers; bad ones are refused in one line naming the flag."""
    fitted = vcor.fit({"model": "prony", "n_terms": 3}, name="p3")
    fitted.write(tmp_path / "p3.nc")
    cases = [("{sphere: {material: sls, r: 0.005}}", {"sphere": {"material": "sls", "r": 0.005}}),
             ("{plate: {material: {model: elastic, E: 7.0e+10}, h: 0.01}}",
              {"plate": {"material": {"model": "elastic", "E": 7e10}, "h": 0.01}}),
             (f"{{plate: {{material: {tmp_path / 'p3.nc'}, h: 0.01}}}}", {"plate": {"material": fitted.material,
                                                                                  "h": 0.01}}),
             ("{plate: {material: rigid}}", {"plate": {"material": "rigid"}}),
             ("rigid", "rigid")]
    for text, target in cases:
        assert cli.main(["impact", "--material", "sls", "--v0", "1", "--target", text, "--json"]) == 0
        out = json.loads(capsys.readouterr().out)
        assert out["cor"]["value"] == vcor.simulate("sls", 1.0, target=target).cor, text
    for argv, message in [(["--target", "{sphere: {material: slss}}"], "--target sphere.material: unknown material"),
                          (["--target", "{sphre: {}}"], "--target must be plate, rigid"),
                          (["--target", "{plate: [1"], "--target, line 2, column 1: not valid YAML"),
                          (["--target", "{plate: {h: 0.02, h: 0.001}}"], "key 'h' is given twice"),
                          (["--target", "{plate: {h: 1e-3}}"], "--target: target.plate.h must be in"),
                          (["--target", "{plate: {h: 1e-3}}"], "got '1e-3': text, not a number"),
                          (["--target", "{sphere: {}}", "--rigid"], "--rigid and --target"),
                          (["--target", "{sphere: {}}", "--h", "0.01"], "geometry keywords ['h']")]:
        assert cli.main(["impact", "--material", "sls", "--v0", "1", *argv]) == 2
        err = capsys.readouterr().err
        assert message in err and len(err.strip().splitlines()) == 1, err


def test_every_option_of_impact_names_its_unit_or_says_it_has_none():
    for action in cli.impact_options():
        if action.dest == "help":
            continue
        assert ("unit " in action.help or "no unit" in action.help), (action.option_strings, action.help)
        assert ("default" in action.help or "required" in action.help), (action.option_strings, action.help)


def test_flags_are_spelt_with_dashes_and_the_old_spellings_still_work():
    parser = cli.build_parser()
    new = parser.parse_args(["impact", "--material", "sls", "--v0", "1", "--rho-a", "7800", "--E-plate", "2e11",
                             "--method", "direct", "--steps-per-contact", "500"])
    old = parser.parse_args(["impact", "--material", "sls", "--v0", "1", "--rho_a", "7800", "--E_plate", "2e11",
                             "--method", "direct", "--steps_per_contact", "500"])
    assert vars(new) == vars(old) and new.rho_a == 7800.0 and new.steps_per_contact == 500
    for action in cli.impact_options():
        if action.option_strings:
            assert "_" not in action.option_strings[0], action.option_strings  # the first spelling: dashes


# ----------------------------------------------------------------------------- materials
def _kinds(cls=Material):
    for sub in cls.__subclasses__():
        yield sub
        yield from _kinds(sub)


def test_every_model_has_a_formula_and_every_parameter_a_unit():
    # eq1 (two bodies) and exponential-sum (a solver's fit) are never named by a spec
    kinds = {getattr(c, "kind", None) for c in _kinds()} - {"eq1", "exponential-sum", None}
    kinds |= {vcor.materials.get(name).kind for name in vcor.materials.PRESETS}
    assert kinds <= set(cli.MODEL_FORMULAS), kinds - set(cli.MODEL_FORMULAS)
    for name in vcor.materials.PRESETS:
        material = vcor.materials.get(name)
        names = [p for p, _ in cli.MODEL_FORMULAS[material.kind][2]]
        assert sorted(names) == sorted(material.params()), name
        assert name in cli.PRESET_REFERENCES


def test_materials_text_has_units_formulas_and_sources(capsys):
    assert cli.main(["materials"]) == 0
    text = capsys.readouterr().out
    for name in vcor.materials.PRESETS:
        material = vcor.materials.get(name)
        assert f"{name}  (preset: {cli.PRESET_REFERENCES[name]})" in text
        formula_name, formula, params = cli.MODEL_FORMULAS[material.kind]
        block = text.split(f"{name}  (preset")[1]
        assert formula_name in block and formula in block
        lines = block.splitlines()[3: 3 + len(params)]
        assert [ln.split()[0] for ln in lines] == [p for p, _ in params]  # the formula's order
        for line, (_, unit) in zip(lines, params):
            assert line.endswith(f" [{cli.TEXT_UNITS.get(unit, unit)}]"), line
    assert "Green 2026, Eq. 14" in text and "Eq. 26" in text and "[Pa s^0.5]" in text


def test_materials_json_and_a_configs_materials(tmp_path, capsys):
    config = tmp_path / "config.yaml"
    config.write_text("materials:\n  my-sls: {model: sls, E_glassy: 2.0e+7, alpha: 100, beta: 1000,\n"
                      "           shift: {model: wlf, C1: 8.86, C2: 101.6, T_ref: 25}}\n")
    assert cli.main(["materials", "--config", str(config), "--json"]) == 0
    rows = {r["name"]: r for r in json.loads(capsys.readouterr().out)}
    mine = rows["my-sls"]
    assert mine["source"] == "config" and mine["reference"].endswith("materials.my-sls")
    assert list(mine["parameters"]) == ["E_glassy", "alpha", "beta"]
    assert mine["parameters"]["E_glassy"] == {"value": 2e7, "units": "Pa"}
    assert mine["parameters"]["alpha"]["units"] == "s-1"
    assert mine["shift"]["model"] == "wlf" and mine["shift"]["parameters"]["C2"] == {"value": 101.6, "units": "K"}
    prony = rows["butyl-prony3"]
    assert prony["source"] == "preset" and prony["reference"] == cli.PRESET_REFERENCES["butyl-prony3"]
    assert list(prony["parameters"]) == ["E_inf", "E", "beta"]
    assert prony["parameters"]["E"]["value"] == list(vcor.materials.get("butyl-prony3").E)  # full precision
    config.write_text("materials:\n  my-sls: {model: sls, E_glassy: -1, alpha: 100, beta: 1000}\n")
    assert cli.main(["materials", "--config", str(config)]) == 2
    assert "materials.my-sls" in capsys.readouterr().err


# ----------------------------------------------------------------------------- export
def test_export_writes_a_tidy_table_with_units(tmp_path, capsys):
    sc = {"materials": ["sls", "butyl-prony3"], "grid": {"v0": [1.0, 10.0], "h": [0.02, 0.005]}}
    points = scene.scene_points(sc)
    shard = runner.run_points(points, scene.settings_of(sc))
    shard.attrs["code_fingerprint"] = vcor.provenance.code_fingerprint()
    ds = aggregation.aggregate([shard], [list(range(len(points)))], scene.grid_of(sc), sc)
    path = write_dataset(ds, tmp_path / "sweep.nc", title="t")
    out = tmp_path / "sweep.csv"
    assert cli.main(["export", str(path), "--csv", str(out)]) == 0
    rows = list(csv.reader(io.StringIO(out.read_text())))
    header = rows[0]
    assert header[:3] == ["material", "v0 [m s-1]", "h [m]"] and "cor [1]" in header and "t0 [s]" in header
    assert "status" in header and "message" in header
    assert len(rows) == 1 + 2 * 2 * 2  # one row per point
    status = header.index("status")
    assert {r[status] for r in rows[1:]} == {"ok"}
    cor = header.index("cor [1]")
    first = dict(zip(header, rows[1]))
    assert float(rows[1][cor]) == pytest.approx(vcor.simulate(first["material"], float(first["v0 [m s-1]"]),
                                                              h=float(first["h [m]"])).cor, rel=1e-15)
    assert cli.main(["export", str(tmp_path / "missing.nc")]) == 2
    assert "does not exist" in capsys.readouterr().err


@pytest.mark.parametrize("command", [["sweep", "--scene", "s"], ["calibrate", "--name", "c"]])
def test_an_output_path_that_cannot_be_a_file_is_refused_before_any_work(tmp_path, capsys, monkeypatch, command):
    """--out naming a folder is refused in one line, exit code 2, and nothing is solved (the rename would fail
    after all the work; on a device node it would replace the device)."""
    from vcor.study import api

    config = tmp_path / "c.yaml"
    config.write_text("scenes:\n  s: {materials: [sls], grid: {v0: [1.0]}}\n")
    monkeypatch.setattr(api, "resolve_scene", lambda *a, **k: pytest.fail("work started"))
    monkeypatch.setattr(api, "resolve_entry", lambda *a, **k: pytest.fail("work started"))
    assert cli.main([command[0], "--config", str(config), *command[1:], "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"--out '{tmp_path}' is a folder" in err


def test_a_sweep_with_no_ok_point_writes_its_dataset_and_exits_1(tmp_path, capsys):
    """Every point stopped by its step budget: the dataset is written with their statuses, the counts are
    printed, and the exit code is 1 (0 as soon as one point is ok)."""
    from vcor.io.netcdf import read_dataset

    config = tmp_path / "c.yaml"
    config.write_text("scenes:\n"
                      "  starved: {materials: [sls], grid: {v0: [1.0, 3.0]}, solver: {max_adaptive_steps: 100},\n"
                      "            geometry: {h: 0.001}}\n"
                      "  fine: {materials: [sls], grid: {v0: [1.0]}}\n")
    out = tmp_path / "starved.nc"
    assert cli.main(["sweep", "--config", str(config), "--scene", "starved", "--out", str(out), "--workers", "1",
                     "--no-progress"]) == 1
    err = capsys.readouterr().err
    assert "vcor sweep: 2 points, 0 ok" in err and "no point ended ok (exit code 1)" in err
    assert (read_dataset(out)["status"].values != 0).all()
    assert cli.main(["sweep", "--config", str(config), "--scene", "fine", "--out", str(tmp_path / "fine.nc"),
                     "--workers", "1", "--no-progress"]) == 0


@pytest.mark.parametrize("value", ["0", "-1", "two"])
def test_sweep_workers_must_be_a_positive_integer(tmp_path, capsys, value):
    """--workers 0, a negative or a word: refused by the option's own check, naming the command and the
    option, before any work (exit code 2), and without Python's None in the text."""
    config = tmp_path / "c.yaml"
    config.write_text("scenes:\n  s: {materials: [sls], grid: {v0: [1.0]}}\n")
    with pytest.raises(SystemExit) as stop:
        cli.main(["sweep", "--config", str(config), "--scene", "s", "--out", str(tmp_path / "s.nc"),
                  "--workers", value])
    assert stop.value.code == 2
    err = capsys.readouterr().err
    assert "vcor sweep: error: argument --workers: must be an integer >= 1" in err and "None" not in err
    assert not (tmp_path / "s.nc").exists()


def test_errors_name_the_command(capsys):
    assert cli.main(["impact", "--material", "slss", "--v0", "1"]) == 2
    assert capsys.readouterr().err.startswith("vcor impact: error: --material: unknown material 'slss'")


def test_the_getting_started_page_shows_what_vcor_impact_prints(capsys):
    """docs/getting-started.md quotes `vcor impact --material sls --v0 10`: every line but the two times (which
    the page says vary) is what the command prints now."""
    from pathlib import Path

    page = (Path(__file__).resolve().parents[1] / "docs" / "getting-started.md").read_text()
    block = page.split("machine to machine):\n\n```text\n", 1)[1].split("```", 1)[0]
    assert cli.main(["impact", "--material", "sls", "--v0", "10"]) == 0
    printed = capsys.readouterr().out

    def steady(text):
        return [line for line in text.splitlines() if not line.startswith(("wall_time", "kernel_load_time"))]

    assert steady(block) == steady(printed)


def test_a_missing_material_file_is_named_as_a_missing_file(capsys):
    assert cli.main(["impact", "--material", "no-such-file.nc", "--v0", "2"]) == 2
    assert "--material 'no-such-file.nc': no such file" in capsys.readouterr().err


def test_every_geometry_option_states_its_range_in_the_help(capsys):
    """The ranges the refusals name (vcor.contact.impact.RANGES; Poisson ratios (-1, 0.5]) are in --help."""
    with pytest.raises(SystemExit):
        cli.main(["impact", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    for key in cli.GEOMETRY_FLAGS:
        lo, hi = RANGES.get(key, (None, None))
        want = f"in [{lo:g}, {hi:g}]" if key in RANGES else "in (-1, 0.5]"
        assert f"{cli.GEOMETRY_FLAGS[key][0]}, {want}" in text, key


@pytest.mark.parametrize("argv", [["impact", "--material", "sls", "--v0", "1", "--bogus"], ["materials", "--bogus"]])
def test_an_unknown_option_is_refused_by_its_command_in_one_line(argv, capsys):
    """An option the command does not take is refused by that command (exit code 2, one line pointing to the
    command's -h), not by the top-level parser."""
    with pytest.raises(SystemExit) as stop:
        cli.main(argv)
    err = capsys.readouterr().err
    assert stop.value.code == 2 and err.count("\n") == 1, err
    assert err == f"vcor {argv[0]}: error: unrecognized arguments: --bogus (options: vcor {argv[0]} -h)\n"


def test_vcor_dem_says_on_stderr_what_it_solved_and_why_a_speed_is_flagged(tmp_path, capsys):
    """Moduli written in MPa (a user's slip): every speed is far outside the small-indentation range. The
    files' paths go to stdout as before; stderr has the counts, one flagged speed's reason (the dataset's
    validity_message) and the trend warning where there is one."""
    config = tmp_path / "c.yaml"
    config.write_text("dem:\n  mpa:\n    sphere: {material: {model: sls, E_glassy: 40, alpha: 600, beta: 5000},"
                      " r: 0.003, rho: 1200}\n    target: {sphere: {}}\n    v0: [0.2, 2.5]\n")
    assert cli.main(["dem", "--config", str(config), "--name", "mpa", "--project", str(tmp_path)]) == 0
    out, err = capsys.readouterr()
    assert out.splitlines()[0].endswith("mpa.nc")
    assert "vcor dem: mpa: 2 points, 0 ok, 2 flagged (large_indentation 2" in err
    assert "vcor dem: a flagged speed: s_max / r = " in err
