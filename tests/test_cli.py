"""The ``vcor`` command line: impact (text and JSON with units, errors, statuses that say what to do),
materials, export, --version, and every option's help naming its unit."""

import csv
import io
import json
import subprocess
import sys

import pytest

import vcor
from vcor import cli
from vcor.io.netcdf import write_dataset
from vcor.materials import Catalogue
from vcor.study import aggregation, runner, scene


def test_json_output_has_units_and_matches_api(capsys):
    assert cli.main(["impact", "--material", "sls", "--v0", "10", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["cor"]["units"] == "1" and out["t0"]["units"] == "s" and out["f_max"]["units"] == "N"
    assert out["cor"]["value"] == vcor.simulate("sls", 10.0).cor
    assert out["status"] == "ok" and out["method"] == "adaptive"  # the default method, as in the API


def test_text_output_and_ive(capsys):
    assert cli.main(["impact", "--material", "butyl-prony3", "--v0", "10", "--method", "ive"]) == 0
    text = capsys.readouterr().out
    assert "cor" in text and " s\n" in text and "ive-Radau" in text


def test_bad_input_exit_code():
    out = subprocess.run([sys.executable, "-m", "vcor.cli", "impact", "--material", "sls", "--v0", "-1"],
                         capture_output=True, text=True, check=False)
    assert out.returncode == 2 and "v0 must be in [1e-09, 100000] m/s" in out.stderr


def test_material_is_required_and_checked():
    with pytest.raises(SystemExit):
        cli.build_parser().parse_args(["impact", "--v0", "1"])
    out = subprocess.run([sys.executable, "-m", "vcor.cli", "impact", "--material", "rubber", "--v0", "1"],
                         capture_output=True, text=True, check=False)
    assert out.returncode == 2 and "--material" in out.stderr and "sls" in out.stderr


def test_a_status_other_than_ok_says_what_to_change(capsys):
    # a thin plate with the fixed-step reference method: it ends at its step budget
    code = cli.main(["impact", "--material", "sls", "--v0", "10", "--h", "0.001", "--method", "direct",
                     "--steps-per-contact", "200"])
    err = capsys.readouterr().err
    assert code == 1 and "status step-budget" in err and "use method adaptive" in err


def test_console_script_and_version():
    out = subprocess.run(["vcor", "impact", "--v0", "5", "--rigid", "--material", "elastic", "--json"],
                         capture_output=True, text=True, check=False)
    assert out.returncode == 0
    assert abs(json.loads(out.stdout)["cor"]["value"] - 1.0) < 1e-6
    version = subprocess.run(["vcor", "--version"], capture_output=True, text=True, check=False)
    assert version.returncode == 0 and version.stdout.strip() == f"vcor {vcor.__version__}"


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


def test_materials_lists_presets_and_a_configs_materials(tmp_path, capsys):
    assert cli.main(["materials"]) == 0
    text = capsys.readouterr().out
    for name in vcor.materials.PRESETS:
        assert name in text
    config = tmp_path / "config.yaml"
    config.write_text("materials:\n  my-sls: {model: sls, E_glassy: 2.0e+7, alpha: 100, beta: 1000}\nscenes: {}\n")
    assert cli.main(["materials", "--config", str(config), "--json"]) == 0
    rows = {r["name"]: r for r in json.loads(capsys.readouterr().out)}
    assert rows["my-sls"]["source"] == "config" and rows["my-sls"]["parameters"]["E_glassy"] == 2e7
    assert rows["sls"]["source"] == "preset"
    config.write_text("materials:\n  my-sls: {model: sls, E_glassy: -1, alpha: 100, beta: 1000}\n")
    assert cli.main(["materials", "--config", str(config)]) == 2
    assert "materials.my-sls" in capsys.readouterr().err


def test_export_writes_a_tidy_table_with_units(tmp_path, capsys):
    sc = {"materials": ["sls", "butyl-prony3"], "grid": {"v0": [1.0, 10.0], "h": [0.02, 0.005]}}
    ids = {m: Catalogue().identity(m) for m in sc["materials"]}
    shard = runner.run_points(scene.scene_points(sc), scene.settings_of(sc))
    shard.attrs["code_fingerprint"] = vcor.provenance.code_fingerprint()
    ds = aggregation.aggregate([_with_ids(shard, ids)], sc, ids)
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


def _with_ids(shard, ids):
    shard = shard.copy()
    shard["material_id"] = ("point", [ids[str(m)] for m in shard["material"].values])
    return shard.set_coords("material_id")
