"""
A contact law for a DEM code
============================

A DEM code needs a contact law it knows. For a body pair and a range of speeds, vcor solves the
collisions (:func:`vcor.dem.fit.collision`), fits each DEM law to that COR curve
(:func:`vcor.dem.fit.fit_laws`) and writes a dataset and ready LAMMPS decks; for LAMMPS it also has
its own hereditary contact, a plugin pair style (``lammps-hereditary``, built by ``vcor lammps-plugin
build``), whose COR is vcor's up to the time step. Here: the paper's SLS, a 5 mm sphere hitting its
twin head-on (the config's ``dem: sls-pair`` entry), at 25 speeds from 0.1 to 10 m/s.
"""

import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from vcor.dem import hereditary
from vcor.dem.export import dem_dataset
from vcor.dem.fit import collision, fit_laws
from vcor.dem.lammps import deck_name, write_deck
from vcor.dem.laws import PARAMETERS

v0 = np.geomspace(0.1, 10.0, 25)  # m/s
col = collision("sls", v0, sphere={"r": 0.005}, target={"sphere": {}})
fits = fit_laws(col)
c = col.contact
print(f"contact: m_eff = {c.m_eff * 1e3:.3f} g, R_eff = {c.r_eff * 1e3:.2f} mm, E_eff = {c.e_eff / 1e6:.2f} MPa")
print(f"{'law':26s} {'largest |COR error|':>20s}  parameters")
def show(value) -> str:
    """A parameter: a number, or the terms of a series."""
    return f"{value:.4g}" if np.ndim(value) == 0 else "[" + ", ".join(f"{x:.4g}" for x in value) + "]"


for law, fit in fits.items():
    err = np.nanmax(np.abs(fit["cor"] - col.cor))
    params = ", ".join(f"{k} = {show(fit[k])} {unit}" for k, (unit, _) in PARAMETERS[law].items())
    print(f"{law:26s} {err:20.2e}  {params or '-'}")

# %%
# The laws against vcor's curve
# -----------------------------
# The Brilliantov laws (LAMMPS ``damping viscoelastic``, MercuryDPM, Yade) share one fitted
# dissipation and one curve, which falls with speed where vcor's rises; LAMMPS ``coeff_restitution``
# is a constant; vcor's own law in LAMMPS follows the curve. Open markers are vcor results outside the
# model's range.

bad = np.array([v != 0 for v in col.validity])
fig, ax = plt.subplots(figsize=(6, 4.2))
ax.plot(v0[~bad], col.cor[~bad], "o", color="k", label="vcor (hereditary)")
ax.plot(v0[bad], col.cor[bad], "o", mfc="none", color="k", label="vcor, flagged (validity != 0)")
ax.plot(v0, fits["lammps-viscoelastic"]["cor"], "-", color="C0",
        label="Brilliantov law: LAMMPS viscoelastic, MercuryDPM, Yade")
ax.plot(v0, fits["lammps-coeff-restitution"]["cor"], "--", color="C1", label="LAMMPS coeff_restitution")
ax.plot(v0, fits["lammps-hereditary"]["cor"], "-.", color="C3", label="LAMMPS with vcor's plugin (vcor/hereditary)")
ax.set_xscale("log")
ax.set_xlabel("impact speed v0 [m/s]")
ax.set_ylabel("COR")
ax.legend(fontsize=8, loc="lower right")
fig.tight_layout()

# %%
# The export
# ----------
# The dataset the workflow archives (``results/dem/<name>/``) and the LAMMPS decks written from it:
# the fitted laws' and vcor's own.

ds = dem_dataset("sls-pair", [col], [fits])
folder = Path(tempfile.mkdtemp())
write_deck(folder / deck_name(c.kind), ds)
hereditary.write_deck(folder / hereditary.DECK_NAME, ds)
print(ds)
for name in (deck_name(c.kind), hereditary.DECK_NAME):
    print()
    print("".join((folder / name).read_text().splitlines(keepends=True)[:12]), "...")
plt.show()
