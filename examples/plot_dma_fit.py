"""
From measured DMA data to a material
====================================

NREL pyvisco's example data (``data/pyvisco/freq_user_raw.csv``): storage and loss moduli of a
polymer at 21 temperatures from -50 to 100 deg C, 0.1 to 100 Hz each. :func:`~vcor.fitting.dma.pipeline.fit_dma`
finds the shift factors of all sets at once, refines them with a smooth relaxation spectrum and
merges that spectrum into a Prony series (the user guide's *DMA data and temperature* explains each
step). The result is a material at the reference temperature and a shift function for any other.
"""

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import vcor
from vcor.fitting.dma import fit_dma, master_curve, read_table, shift_function
from vcor.fitting.resample import bootstrap
from vcor.materials.shift import at_temperature

# the repository's data folder, whether this runs as a script or in the manual's build
here = Path(__file__).resolve().parent if "__file__" in globals() else Path.cwd()
DATA = next(p / "data" / "pyvisco" for p in (here, *here.parents) if (p / "data" / "pyvisco").is_dir())

raw = read_table(DATA / "freq_user_raw.csv")
fit = fit_dma(raw.columns, T_ref=-5.0)
material = fit.material()
print(f"{len(fit.T)} sets, {fit.T[0]:g} to {fit.T[-1]:g} deg C, reference {fit.T_ref:g} deg C")
print(f"Prony series: {len(material.E)} terms, E_inf = {material.E_inf / 1e6:.3g} MPa, "
      f"rates {min(material.beta):.3g} to {max(material.beta):.3g} 1/s")
print(f"WLF through the shifts: C1 = {fit.wlf['C1']:.3g}, C2 = {fit.wlf['C2']:.3g} K")
print(f"fit time {fit.times['total']:.2f} s; notes: {fit.notes or 'none'}")

# %%
# The measured sets
# -----------------
# Each set is one temperature; cold sets are stiff (glassy), hot sets soft (rubbery).

cols = raw.columns
fig, ax = plt.subplots(figsize=(6, 4.2))
cmap = plt.get_cmap("coolwarm")
for k, T in enumerate(fit.T):
    sel = np.isclose(cols["T"], T, atol=0.6)
    ax.loglog(cols["f"][sel], cols["E_stor"][sel] / 1e6, ".-", color=cmap(k / (len(fit.T) - 1)), ms=3, lw=0.8)
ax.set_xlabel("frequency f [Hz]")
ax.set_ylabel("storage modulus E' [MPa]")
ax.set_title("pyvisco raw sets, blue (cold) to red (hot)")
fig.tight_layout()

# %%
# The master curve
# ----------------
# The sets shifted by the fitted factors lie on one curve at -5 deg C; the lines are the Prony
# material's :math:`E'(\omega)` and :math:`E''(\omega)`.
# The measured :math:`E''` rises at the top of every set, by an amount that grows with the measured
# frequency alike at every temperature: the instrument's lag between force and displacement, not the
# material. The config's fit of these data (``fits: pyvisco-polymer``) fits that lag too
# (``instrument_lag: true``); this example leaves it out to stay short.

mc = master_curve(cols, fit.log_aT)
f = np.geomspace(mc.f_red.min(), mc.f_red.max(), 400)
e = material.complex_modulus(2 * np.pi * f)
fig, ax = plt.subplots(figsize=(6, 4.2))
ax.loglog(mc.f_red, mc.E_stor / 1e6, ".", color="C0", ms=3, label="E' measured, shifted")
ax.loglog(mc.f_red, mc.E_loss / 1e6, ".", color="C1", ms=3, label="E'' measured, shifted")
ax.loglog(f, e.real / 1e6, color="C0", label="E' of the Prony fit")
ax.loglog(f, e.imag / 1e6, color="C1", label="E'' of the Prony fit")
ax.set_xlabel("reduced frequency f a_T [Hz]")
ax.set_ylabel("modulus [MPa]")
ax.legend(fontsize=8)
fig.tight_layout()

# %%
# Shift factors and relaxation spectrum
# -------------------------------------
# Left: the fitted :math:`\log_{10} a_T` of each set with its standard error, and the WLF law fitted
# through them. Right: the smooth spectrum on its fixed grid and the merged Prony terms.

fig, (a1, a2) = plt.subplots(1, 2, figsize=(9, 3.8))
a1.errorbar(fit.T, fit.log_aT, yerr=fit.log_aT_std, fmt="o", ms=3, label="per set")
T = np.linspace(fit.T[0], fit.T[-1], 200)
wlf = shift_function(fit, "wlf")
a1.plot(T, [wlf.log_aT(x) for x in T], "k--", lw=1, label="WLF")
a1.set_xlabel("temperature T [deg C]")
a1.set_ylabel("log10 a_T")
a1.legend(fontsize=8)
a2.loglog(fit.spectrum.tau, fit.spectrum.h / 1e6, "-", label="smooth spectrum h(tau)")
a2.loglog(fit.reduced.tau, fit.reduced.E / 1e6, "o", ms=4, label="merged Prony moduli E_j")
a2.set_xlabel("relaxation time tau [s]")
a2.set_ylabel("[MPa]")
a2.legend(fontsize=8)
fig.tight_layout()

# %%
# COR against temperature, with a band
# ------------------------------------
# A 5 mm sphere of this polymer on a rigid wall at 1 m/s: the material at temperature T is the
# reference material with time stretched by :math:`a_T` (tabulated shifts, interpolated in T).
# The band is a small bootstrap (:func:`vcor.fitting.resample.bootstrap`): the fit repeated on 20
# wild-bootstrap samples of the data, with the shift factors held at the fitted ones so that each
# refit takes a fraction of a second. It therefore shows the spectrum's uncertainty only; the
# ``pyvisco`` scene's band (user guide, *Uncertainty from measured data*) refits the shifts too,
# with 50 samples. Open markers are flagged results.

shift = shift_function(fit, "table")
temps = np.arange(-50.0, 101.0, 15.0)


def cor_against_T(mat):
    return [vcor.simulate(at_temperature(mat, shift, float(t)), 1.0, rigid=True, r=0.005, rho_a=1100.0, nu=0.5)
            for t in temps]


runs = cor_against_T(material)
cor = np.array([r.cor for r in runs])
bad = np.array([r.validity != 0 for r in runs])
_, samples, _ = bootstrap(raw.columns, fit.T_ref, 20, seed=0, log_aT=fit.log_aT)
cors = np.array([[r.cor for r in cor_against_T(s.material())] for s in samples])
lo, hi = np.quantile(cors, [0.025, 0.975], axis=0)
print("T [deg C]  COR    95 % band")
for t, c, a, b in zip(temps, cor, lo, hi):
    print(f"{t:8.0f}  {c:.4f}  {a:.4f} .. {b:.4f}")

fig, ax = plt.subplots(figsize=(6, 4.2))
ax.fill_between(temps, lo, hi, color="C2", alpha=0.3, label="95 % band (20 samples, shifts held)")
ax.plot(temps, cor, "-", color="C2")
ax.plot(temps[~bad], cor[~bad], "o", color="C2", label="full-data fit")
ax.plot(temps[bad], cor[bad], "o", mfc="none", color="C2", label="full-data fit, flagged (validity != 0)")
ax.set_xlabel("temperature T [deg C]")
ax.set_ylabel("COR at 1 m/s")
ax.legend(fontsize=8)
fig.tight_layout()
plt.show()
