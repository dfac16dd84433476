"""Configs as Snakemake meets them: every config block of the README and the manual runs on its own
(``snakemake -n --configfile``), and every refusal of a hostile config is at most five lines.

A YAML block in README.md or docs/ is a config unless the line before its fence is the comment
``<!-- fragment -->`` (optionally with a reason after the word): a block that only makes sense beside
another (materials for a scene shown elsewhere, a scene of a fit defined above)."""

import re
from pathlib import Path

import pytest
import yaml

pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[2]

FENCE = re.compile(r"(?P<before>[^\n]*)\n```yaml\n(?P<body>.*?)```", re.S)


def doc_configs():
    """(file:line, YAML text) of every config block (module docstring)."""
    out = []
    for path in [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]:
        if "_build" in path.parts:
            continue
        text = path.read_text()
        for m in FENCE.finditer(text):
            if m.group("before").strip().startswith("<!-- fragment"):
                continue
            line = text[: m.start("body")].count("\n") + 1
            out.append((f"{path.relative_to(ROOT)}:{line}", m.group("body")))
    return out


@pytest.fixture(scope="module")
def project(make_project, tmp_path_factory):
    return make_project(tmp_path_factory.mktemp("docs-configs"))


@pytest.mark.parametrize("where, text", doc_configs(), ids=[w for w, _ in doc_configs()])
def test_every_config_of_the_docs_runs_on_its_own(smk, project, where, text):
    assert isinstance(yaml.safe_load(text), dict), where
    (project / "my.yaml").write_text(text)
    out = smk(project, "-n", "-j1", "--configfile", "my.yaml", check=False)
    assert out.returncode == 0, f"{where}:\n{(out.stdout + out.stderr)[-2500:]}"


HOSTILE = {
    "no scenes, only a calibration without its free parameters": "calibrations: {c: {data: x.csv, material: sls}}\n",
    "v0 as a text": "scenes: {s: {materials: [sls], grid: {v0: '1,2,3'}}}\n",
    "an empty axis": "scenes: {s: {materials: [sls], grid: {v0: []}}}\n",
    "step 0": "scenes: {s: {materials: [sls], grid: {v0: {start: 1, stop: 3, step: 0}}}}\n",
    "num 0": "scenes: {s: {materials: [sls], grid: {v0: {start: 1, stop: 3, num: 0}}}}\n",
    "booleans in a grid": "scenes: {s: {materials: [sls], grid: {v0: [true, false]}}}\n",
    "misspelt figures": "scenes: {s: {materials: [sls], grid: {v0: [1, 2]}, figure: {fig4: {}}}}\n",
    "materials not a mapping": "materials: sls\n",
    "a repeated value": "scenes: {s: {materials: [sls], grid: {v0: [1, 1, 1]}}}\n",
    "nothing to build": "materials: {m: {model: elastic, E: 1.0e+9}}\n",
    "an empty file": "",
    "a list": "- scenes\n",
}


@pytest.mark.parametrize("name", list(HOSTILE))
def test_every_refusal_of_a_config_is_at_most_five_lines(smk, project, name):
    (project / "bad.yaml").write_text(HOSTILE[name])
    out = smk(project, "-n", "-j1", "--configfile", "bad.yaml", check=False)
    lines = [line for line in (out.stdout + out.stderr).splitlines() if line.strip()]
    assert out.returncode != 0, name
    assert len(lines) <= 5, "\n".join(lines)
    assert not (project / "results").exists()
