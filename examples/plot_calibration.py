"""
Calibration from measured COR
=============================

COR measured at several impact speeds back to material parameters, with standard errors,
correlations and a verdict on what the data constrain (:func:`vcor.fitting.calibrate.calibrate`).
The "measurements" here are made up so that the truth is known: the paper's SLS plate
(glassy modulus 15 MPa, rates 300 and 1200 1/s) at ten speeds, with 0.5 % noise.
"""

import matplotlib.pyplot as plt
import numpy as np

import vcor
from vcor.fitting.calibrate import CorData, band, calibrate

rng = np.random.default_rng(1)
truth = vcor.materials.SLS(15e6, 300.0, 1200.0)  # E_glassy (Pa), alpha, beta (1/s)
v0 = np.geomspace(0.5, 20.0, 10)  # m/s
cor_true = np.array([vcor.simulate(truth, float(v)).cor for v in v0])
std = 0.005 * cor_true
data = CorData(v0, cor_true + std * rng.standard_normal(v0.size), std)

# %%
# Two free parameters from a wrong start
# --------------------------------------
# The start is the material passed in; ``free`` gives each free parameter's bounds. The search is
# local: the SLS's COR is not monotone in its rate ``beta`` (Fig. 4 of the paper), and a start far
# from the truth (say ``beta`` = 3000 1/s here) ends at a bound, which the report then says.

start = vcor.materials.SLS(10e6, 300.0, 1800.0)
cal = calibrate(data, start, {"E_glassy": [1e6, 1e8], "beta": [400.0, 1e5]})
print(cal.report())
print("correlation of the estimates:\n", np.round(cal.correlation, 3))

# %%
# The fitted curve and its 95 % band (linearised, from the parameters' covariance) against the
# data; open markers would be flagged points of the fitted model.

grid = np.geomspace(0.5, 20.0, 25)
c, lo, hi = band(cal, grid)
flagged = np.array([vcor.simulate(cal.material, float(v)).validity != 0 for v in grid])
fig, ax = plt.subplots(figsize=(6, 4.2))
ax.errorbar(v0, data.cor, yerr=2 * std, fmt="s", color="k", ms=4, label="data (2 sigma)")
ax.fill_between(grid, lo, hi, color="C0", alpha=0.3, label="95 % band of the fit")
ax.plot(grid, c, "-", color="C0", label="fitted model")
ax.plot(grid[flagged], c[flagged], "o", mfc="none", color="C0", ms=4, label="flagged (validity != 0)")
ax.set_xscale("log")
ax.set_xlabel("impact speed v0 [m/s]")
ax.set_ylabel("COR")
ax.legend(fontsize=8)
fig.tight_layout()

# %%
# A parameter the data cannot constrain
# -------------------------------------
# Freeing ``modulus_scale`` beside ``E_glassy`` asks for two numbers that only enter as their
# product: the calibration says so instead of returning arbitrary values.

cal2 = calibrate(data, start, {"E_glassy": [1e6, 1e8], "modulus_scale": [0.1, 10.0], "beta": [400.0, 1e5]})
print(cal2.report())
plt.show()
