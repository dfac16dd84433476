"""The code style: ``ruff check`` over the whole repository finds nothing. The rules and their reasons
live in ``pyproject.toml`` (``[tool.ruff]``); the developer guide says which and why."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def test_ruff_finds_nothing():
    if importlib.util.find_spec("ruff") is None:
        pytest.skip("ruff is not installed (it is in the test extra: pip install -e '.[test]')")
    # --no-cache: the check writes nothing into the work tree
    done = subprocess.run([sys.executable, "-m", "ruff", "check", "--no-cache", "--output-format", "concise",
                           str(ROOT)], cwd=ROOT, capture_output=True, text=True, timeout=120, check=False)
    assert done.returncode == 0, f"ruff check found style problems:\n{done.stdout}{done.stderr}"
