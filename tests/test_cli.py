"""The `vcor impact` command: text and JSON output with units, errors on bad input."""

import json
import subprocess
import sys

import vcor
from vcor import cli


def test_json_output_has_units_and_matches_api(capsys):
    assert cli.main(["impact", "--material", "sls", "--v0", "10", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["cor"]["units"] == "1" and out["t0"]["units"] == "s" and out["f_max"]["units"] == "N"
    assert out["cor"]["value"] == vcor.simulate("sls", 10.0).cor
    assert out["status"] == "ok"


def test_text_output_and_ive(capsys):
    assert cli.main(["impact", "--material", "butyl-prony3", "--v0", "10", "--method", "ive"]) == 0
    text = capsys.readouterr().out
    assert "cor" in text and " s\n" in text and "ive-Radau" in text


def test_bad_input_exit_code():
    out = subprocess.run([sys.executable, "-m", "vcor.cli", "impact", "--v0", "-1"], capture_output=True, text=True)
    assert out.returncode == 2 and "v0 must be in (0, inf)" in out.stderr


def test_console_script_installed():
    out = subprocess.run(["vcor", "impact", "--v0", "5", "--rigid", "--material", "elastic", "--json"],
                         capture_output=True, text=True)
    assert out.returncode == 0
    assert abs(json.loads(out.stdout)["cor"]["value"] - 1.0) < 1e-6
