"""
COR against impact speed, with what the model cannot vouch for
==============================================================

The COR of the four plate materials of Green (2026) against the impact speed: one sweep,
:func:`vcor.sweep <vcor.study.api.sweep>`, over the materials and a grid of speeds, solved on the
machine's cores into an ``xarray.Dataset``. Every point carries ``validity``: 0
inside the model's stated range, else a bit mask of the reasons (:data:`vcor.solvers.validity.FLAGS`)
with a sentence in ``validity_message``. Flagged points are drawn open: they are computed
accurately, but Hertz contact (indentation much smaller than the radius) or a quasi-static contact
(impact slow against the plate's wave speed) no longer holds there.
"""

import matplotlib.pyplot as plt
import numpy as np

import vcor
from vcor.contact.impact import GEOMETRY_DEFAULTS
from vcor.solvers.validity import FLAGS, MAX_INDENTATION

presets = ["sls", "butyl-fc", "butyl-cerf", "butyl-prony3"]
ds = vcor.sweep({"materials": presets, "grid": {"v0": np.geomspace(0.1, 50.0, 12)}}, progress=False)
v0s = ds["v0"].values  # m/s

print(f"{'material':14s} {'flagged from':>13s}  reasons (at 50 m/s)")
for name in presets:
    validity = ds["validity"].sel(material=name).values
    flagged = v0s[validity != 0]
    reasons = [f for f, mask in FLAGS.items() if validity[-1] & mask]
    first = f"{flagged[0]:.2f} m/s" if flagged.size else "never"
    print(f"{name:14s} {first:>13s}  {', '.join(reasons) or '-'}")

# %%
# The figure: filled markers inside the model's range, open markers flagged.

fig, ax = plt.subplots(figsize=(6, 4.2))
for i, name in enumerate(presets):
    cor = ds["cor"].sel(material=name).values
    bad = ds["validity"].sel(material=name).values != 0
    color = f"C{i}"
    ax.plot(v0s, cor, color=color, lw=1, label=name)
    ax.plot(v0s[~bad], cor[~bad], "o", color=color)
    ax.plot(v0s[bad], cor[bad], "o", mfc="none", color=color)
ax.plot([], [], "o", color="0.3", label="inside the model's range")
ax.plot([], [], "o", mfc="none", color="0.3", label="flagged (validity != 0)")
ax.set_xscale("log")
ax.set_xlabel("impact speed v0 [m/s]")
ax.set_ylabel("COR")
ax.legend(fontsize=8, ncol=2)
fig.tight_layout()

# %%
# Why they are flagged
# --------------------
# The peak indentation relative to the sphere's radius, against the limit of the
# ``large_indentation`` flag.

fig, ax = plt.subplots(figsize=(6, 4.2))
for i, name in enumerate(presets):
    ax.plot(v0s, ds["s_max"].sel(material=name) / GEOMETRY_DEFAULTS["r"], "o-", color=f"C{i}", label=name, ms=4)
ax.axhline(MAX_INDENTATION, color="k", ls="--", label=f"limit s_max/r = {MAX_INDENTATION:g}")
ax.set_xscale("log")
ax.set_yscale("log")
ax.set_xlabel("impact speed v0 [m/s]")
ax.set_ylabel("s_max / r")
ax.legend(fontsize=8)
fig.tight_layout()

# %%
# The work behind each point
# --------------------------
# ``steps`` is the number of time steps the default method (``adaptive``) took: it chooses its steps
# from a local error estimate, so fast relaxation and long contacts cost more. The time per impact
# on the reference machine is in the Benchmarks page.

fig, ax = plt.subplots(figsize=(6, 4.2))
for i, name in enumerate(presets):
    ax.plot(v0s, ds["steps"].sel(material=name), "o-", color=f"C{i}", label=name, ms=4)
ax.set_xscale("log")
ax.set_xlabel("impact speed v0 [m/s]")
ax.set_ylabel("time steps per impact")
ax.legend(fontsize=8)
fig.tight_layout()
plt.show()
