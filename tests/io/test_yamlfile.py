"""Strict reading of the files a user writes (vcor.io.yamlfile, vcor.io.csvfile.header): a key or column
given twice is refused in one line naming it and where, instead of the last one silently winning."""

import json

import pytest

from vcor import cli
from vcor.fitting import calibrate, dma
from vcor.io.yamlfile import RepeatedKeyError, load_json, load_yaml
from vcor.materials import from_file
from vcor.materials.specs import read_prony_csv
from vcor.study import schema

GRID = "scenes:\n  s:\n    materials: [sls]\n    grid:\n      v0: [1, 2]\n      beta: [600]\n      v0: [3]\n"


@pytest.mark.parametrize("text, words", [
    (GRID, "line 7, column 7: key 'v0' is given twice in one mapping (lines 5 and 7)"),
    ("fits: {}\nscenes: {}\nfits: {a: 1}\n",
     "line 3, column 1: key 'fits' is given twice in one mapping (lines 1 and 3)"),
    ("grid: {v0: [1], v0: [2]}\n", "line 1, column 17: key 'v0' is given twice in one mapping (both on line 1)"),
    ("grid:\n  1: a\n  1.0: b\n", "line 3, column 3: key 1.0 is given twice"),  # equal once read
    ("scenes:\n  s:\n    'v0': 1\n    v0: 2\n", "line 4, column 5: key 'v0' is given twice"),
    ('{"scenes": {"s": {"grid": {"v0": [1],\n\t"v0": [2]}}}}',
     "line 2, column 2: key 'v0' is given twice in one mapping (lines 1 and 2)"),  # JSON, a tab included
])
def test_a_repeated_key_is_refused_naming_it_and_both_lines(tmp_path, text, words):
    path = tmp_path / "config.yaml"
    path.write_text(text)
    with pytest.raises(RepeatedKeyError) as err:
        load_yaml(path)
    assert str(err.value).startswith(f"config file {path}, line ") and words in str(err.value)
    assert "\n" not in str(err.value)


def test_what_is_not_a_repeat_reads_as_pyyaml_reads_it(tmp_path):
    import yaml

    text = ("defaults: &d {materials: [sls], grid: {v0: [1]}}\n"
            "scenes:\n  a: {<<: *d, grid: {v0: [2]}}\n  b:\n    <<: *d\n    description: x\n"
            "  c: {grid: {v0: [1]}}\n  d: {grid: {v0: [1]}}\n")
    path = tmp_path / "c.yaml"
    path.write_text(text)
    assert load_yaml(path) == yaml.safe_load(text)  # merge keys overridden, one key in many mappings
    path.write_text(json.dumps({"scenes": {"s": {"grid": {"v0": [1e3, 2]}}}}, indent="\t"))
    assert load_yaml(path) == {"scenes": {"s": {"grid": {"v0": [1000.0, 2]}}}}  # JSON read as JSON
    path.write_text("")
    assert load_yaml(path) is None


def test_a_broken_or_missing_file_is_named_with_line_and_column(tmp_path):
    path = tmp_path / "c.yaml"
    path.write_text("a: [1, 2\nb: 3\n")
    with pytest.raises(ValueError, match=r"c\.yaml, line 2, column 2: not valid YAML \(did not find expected"):
        load_yaml(path)
    (tmp_path / "m.json").write_text('{"kind": "sls",, }')  # the second comma: column 16
    with pytest.raises(ValueError, match=r"material file .*m\.json, line 1, column 16: not valid JSON"):
        load_json(tmp_path / "m.json", what="material file")
    with pytest.raises(ValueError, match="config file .*none.yaml does not exist"):
        load_yaml(tmp_path / "none.yaml")


def test_material_files_the_cli_config_and_the_schema_are_read_strictly(tmp_path, capsys):
    mat = tmp_path / "m.json"
    mat.write_text('{"kind": "sls", "E_glassy": 15e6, "alpha": 300.0,\n  "beta": 1200.0, "alpha": 30.0}')
    with pytest.raises(RepeatedKeyError, match=r"material file .*m\.json, line 2, column 19: key 'alpha' is given "
                                               r"twice .*\(lines 1 and 2\)"):
        from_file(mat)
    cfg = tmp_path / "config.yaml"
    cfg.write_text("materials:\n  mine: {model: sls, E_glassy: 15e6, alpha: 300, beta: 1200}\n"
                   "  mine: {model: sls, E_glassy: 30e6, alpha: 300, beta: 1200}\n")
    assert cli.main(["impact", "--config", str(cfg), "--material", "mine", "--v0", "10"]) == 2
    assert "--config " + str(cfg) + ", line 3, column 3: key 'mine' is given twice" in capsys.readouterr().err
    bad = tmp_path / "schema.yaml"
    bad.write_text("type: object\nproperties: {}\ntype: array\n")
    with pytest.raises(RepeatedKeyError, match="config schema .*line 3, column 1: key 'type'"):
        schema.load_schema(bad)


@pytest.mark.parametrize("reader, text, words", [
    (calibrate.read_cor_data, "v0,cor,cor\n1,0.5,0.6\n", "line 1: column 'cor' is given twice (columns 2 and 3)"),
    (dma.read_table, "f,E_stor,E_loss,E_stor\n1,2,3,4\n", "line 1: column 'E_stor' is given twice (columns 2 and 4)"),
    (read_prony_csv, "tau,E,E\n1,2,3\n", "line 1: column 'E' is given twice (columns 2 and 3)"),
])
def test_a_data_file_with_a_column_given_twice_is_refused(tmp_path, reader, text, words):
    path = tmp_path / "data.csv"
    path.write_text(text)
    with pytest.raises(ValueError, match="data.csv, " + words.replace("(", r"\(").replace(")", r"\)")):
        reader(path)
