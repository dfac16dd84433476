"""
COR against impact speed, with what the model cannot vouch for
==============================================================

The COR of the four plate materials of Green (2026) against the impact speed, each point one call
of :func:`vcor.simulate <vcor.solvers.simulate.simulate>`. Every result carries ``validity``: 0
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
v0s = np.geomspace(0.1, 50.0, 12)  # m/s
results = {name: [vcor.simulate(name, float(v)) for v in v0s] for name in presets}

print(f"{'material':14s} {'flagged from':>13s}  reasons (at 50 m/s)")
for name, runs in results.items():
    flagged = [v for v, r in zip(v0s, runs) if r.validity]
    reasons = [f for f, mask in FLAGS.items() if runs[-1].validity & mask]
    first = f"{flagged[0]:.2f} m/s" if flagged else "never"
    print(f"{name:14s} {first:>13s}  {', '.join(reasons) or '-'}")

# %%
# The figure: filled markers inside the model's range, open markers flagged.

fig, ax = plt.subplots(figsize=(6, 4.2))
for i, (name, runs) in enumerate(results.items()):
    cor = np.array([r.cor for r in runs])
    bad = np.array([r.validity != 0 for r in runs])
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
for i, (name, runs) in enumerate(results.items()):
    ax.plot(v0s, [r.s_max / GEOMETRY_DEFAULTS['r'] for r in runs], "o-", color=f"C{i}", label=name, ms=4)
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
for i, (name, runs) in enumerate(results.items()):
    ax.plot(v0s, [r.steps for r in runs], "o-", color=f"C{i}", label=name, ms=4)
ax.set_xscale("log")
ax.set_xlabel("impact speed v0 [m/s]")
ax.set_ylabel("time steps per impact")
ax.legend(fontsize=8)
fig.tight_layout()
plt.show()
