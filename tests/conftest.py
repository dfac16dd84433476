"""Shared fixtures: a seeded random generator, and a copy of the project to run Snakemake in."""

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


@pytest.fixture
def rng():
    return np.random.default_rng(20261121)


def make_project(path: Path, config: dict | None = None) -> Path:
    """A copy of the workflow (Snakefile, workflow/, profiles/, data/) in ``path``, with ``config`` as
    its config.yaml when given (the repository's otherwise)."""
    path.mkdir(parents=True, exist_ok=True)
    for name in ("Snakefile", "workflow", "profiles", "data"):
        src = ROOT / name
        (shutil.copytree if src.is_dir() else shutil.copy)(src, path / name)
    if config is None:
        shutil.copy(ROOT / "config.yaml", path / "config.yaml")
    else:
        (path / "config.yaml").write_text(yaml.safe_dump(config, sort_keys=False))
    return path


def smk(path: Path, *args, check: bool = True, timeout: int = 600) -> subprocess.CompletedProcess:
    """Run Snakemake in the project at ``path``; AssertionError with its output's end if it fails and
    ``check``."""
    out = subprocess.run(SNAKEMAKE + ["-d", str(path), *args], cwd=path, capture_output=True, text=True,
                         timeout=timeout, check=False)
    if check and out.returncode != 0:
        raise AssertionError(f"snakemake {args} failed:\n{out.stdout[-3000:]}\n{out.stderr[-3000:]}")
    return out
