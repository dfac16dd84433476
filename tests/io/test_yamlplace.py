"""A config refusal that names a key path is given the file, line and column of that key."""

import pytest

from vcor.io.yamlplace import key_path, located


@pytest.mark.parametrize("message, keys", [
    ("scenes.my-grid.grid.v0[0]: expected a number", ["scenes", "my-grid", "grid", "v0", 0]),
    ("scenes.a.histories.runs: [[x, y]]: bad", ["scenes", "a", "histories", "runs"]),
    ("dem.pair[2].v0: must be > 0", ["dem", "pair", 2, "v0"]),
    # a dotted path as the first word: a parameter's range, a material's model in brackets
    ("materials.my-p.E[1] must be in [0, inf) Pa, got -1.0", ["materials", "my-p", "E", 1]),
    ("materials.my-sls2 (sls): missing ['beta']; a sls material takes [...]", ["materials", "my-sls2"]),
    ("materials.m.E_0 belongs to the normalised form (with g)", ["materials", "m", "E_0"]),
    ("shard_size must be >= 1", None),  # one word: not told from a sentence
    ("the config must be a mapping: got list", None),
    ("no colon here", None),
    # a file name or a sentence is no path
    ("fits.csv, line 3, column 'E': not a number", None),
    ("./table.csv not found", None),
    ("Mr. Smith", None),
])
def test_key_path_of_a_message(message, keys):
    assert key_path(message) == keys


def test_the_place_of_the_deepest_key_a_file_holds(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "config.yaml").write_text("scenes:\n  base:\n    materials: [sls]\n")
    (tmp_path / "my.yaml").write_text("materials:\n  my.gel: {model: sls}\nscenes:\n  mine:\n"
                                      "    grid:\n      v0: ['36 km/h', 1]\n")
    files = [str(tmp_path / "config.yaml"), str(tmp_path / "my.yaml")]
    said = located("scenes.mine.grid.v0[0]: expected a number", files)
    assert said == "config file my.yaml, line 6, column 12: scenes.mine.grid.v0[0]: expected a number"
    assert located("scenes.mine.figures: need a grid", files).startswith("config file my.yaml, line 4, column 3: ")
    said = located("scenes.base.materials[0]: unknown", files)
    assert said.startswith("config file config.yaml, line 3, column 17: ")
    assert located("materials.my.gel.alpha: missing", files).startswith("config file my.yaml, line 2, column 3: ")
    assert located("fits.x: unknown", files) == "fits.x: unknown"  # no file holds it
    assert located("scenes.mine.grid: bad", [str(tmp_path / "none.yaml")]) == "scenes.mine.grid: bad"
    # a first word that reads as a path is placed only where the file holds all of it
    for message in ("materials.csv does not exist", "scenes.yaml is not a mapping", "1.5 is not allowed"):
        assert located(message, files) == message
    said = located("materials.my.gel.model must be one of", files)
    assert said.startswith("config file my.yaml, line 2, column 12: ")
