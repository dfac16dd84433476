"""The public functions' type hints, checked by mypy: the study functions (vcor.study.api) and the modules
behind them type-check, a user's code that calls them as documented type-checks through the lazy names of
``vcor``, and a call with a wrong type is caught."""

import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[1]
#: the modules of the public study surface, checked in full (their imports are followed silently)
CHECKED = ["__init__.py", "study/api.py", "study/inputs.py", "study/pool.py", "study/progress.py", "study/sweep.py",
           "study/computed.py", "io/archived.py", "cli_study.py"]

USER_CODE = '''
import xarray

import vcor
from vcor.materials import SLS

ds: xarray.Dataset = vcor.sweep({"materials": [SLS(15e6, 300.0, 1200.0)], "grid": {"v0": [1.0, 10.0]}},
                                workers=2, progress=False)
fitted = vcor.fit({"model": "prony", "n_terms": 3}, name="p3")
table: str = fitted.table
record: xarray.Dataset = vcor.calibrate("cal", config="config.yaml").dataset
files: dict = vcor.dem_export("pair", config="config.yaml").files
cor: float = vcor.simulate("sls", 10.0).cor
'''
WRONG = 'import vcor\nvcor.sweep({"materials": ["sls"]}, workers="2")\n'


def _mypy(tmp_path, *files):
    return subprocess.run([sys.executable, "-m", "mypy", "--follow-imports=silent", "--ignore-missing-imports",
                           "--cache-dir", str(tmp_path / "cache"), *map(str, files)],
                          capture_output=True, text=True, cwd=ROOT, check=False,
                          env={"MYPYPATH": str(ROOT / "src"), "PATH": "/usr/bin:/bin"})


def test_the_public_functions_type_check(tmp_path):
    user = tmp_path / "user.py"
    user.write_text(USER_CODE)
    out = _mypy(tmp_path, *[ROOT / "src" / "vcor" / f for f in CHECKED], user)
    assert out.returncode == 0, out.stdout + out.stderr


def test_a_wrong_type_is_caught(tmp_path):
    wrong = tmp_path / "wrong.py"
    wrong.write_text(WRONG)
    out = _mypy(tmp_path, wrong)
    assert out.returncode == 1 and 'Argument "workers" to "sweep" has incompatible type "str"' in out.stdout
