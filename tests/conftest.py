"""Shared fixtures: a seeded random generator, and the one way the tests copy the project and run
Snakemake in it (``make_project``, ``smk``: fixtures built once per test run, so module fixtures can use
them)."""

import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import yaml

ROOT = Path(__file__).resolve().parents[1]
#: Snakemake as the tests run it: the same Python, so the installed vcor is the one under test
SNAKEMAKE = [sys.executable, "-m", "snakemake"]
#: what a copy of the project holds: the workflow, its profiles and the shipped data
PROJECT_PARTS = ("Snakefile", "workflow", "profiles", "data")


@pytest.fixture
def rng():
    return np.random.default_rng(20261121)


def _make_project(path: Path, config: dict | None = None) -> Path:
    path.mkdir(parents=True, exist_ok=True)
    for name in PROJECT_PARTS:
        src = ROOT / name
        (shutil.copytree if src.is_dir() else shutil.copy)(src, path / name)
    if config is None:
        shutil.copy(ROOT / "config.yaml", path / "config.yaml")
    else:
        (path / "config.yaml").write_text(yaml.safe_dump(config, sort_keys=False))
    return path


def _smk(path: Path, *args, check: bool = True, timeout: int = 600, env: dict | None = None
         ) -> subprocess.CompletedProcess:
    out = subprocess.run(SNAKEMAKE + ["-d", str(path), *args], cwd=path, capture_output=True, text=True,
                         timeout=timeout, check=False, env=env)
    if check and out.returncode != 0:
        raise AssertionError(f"snakemake {args} failed:\n{out.stdout[-3000:]}\n{out.stderr[-3000:]}")
    return out


@pytest.fixture(scope="session")
def root() -> Path:
    """The repository's top folder."""
    return ROOT


@pytest.fixture(scope="session")
def make_project():
    """``make_project(path, config=None) -> path``: a copy of the workflow (``PROJECT_PARTS``) in
    ``path``, with ``config`` (a dict) as its config.yaml, or the repository's when None."""
    return _make_project


@pytest.fixture(scope="session")
def smk():
    """``smk(path, *args, check=True, timeout=600, env=None)``: Snakemake run in the project at ``path``
    (its profile found by Snakemake itself); AssertionError with the end of its output when it fails and
    ``check``."""
    return _smk
