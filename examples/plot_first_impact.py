"""
A first impact
==============

A steel sphere (radius 10 mm) hits the paper's standard-linear-solid plate at 10 m/s.
:func:`vcor.simulate <vcor.solvers.simulate.simulate>` returns a
:class:`~vcor.solvers.common.Result`; with ``history=True`` it also keeps the time histories, from
which we draw the force against the indentation: the area inside the loop is the energy the
material dissipates.
"""

import matplotlib.pyplot as plt

import vcor
from vcor.contact.impact import GEOMETRY_DEFAULTS

res = vcor.simulate("sls", 10.0, history=True)

print(f"status   {res.status}")
print(f"COR      {res.cor:.4f}")
print(f"t0       {res.t0 * 1e3:.4f} ms   (contact time)")
print(f"s_max    {res.s_max * 1e3:.3f} mm   (peak indentation)")
print(f"F_max    {res.f_max:.1f} N")
print(f"W_h      {res.w_h:.4f} J    (hysteretic loss)")
print(f"validity {res.validity}: {res.validity_message or 'inside the stated range'}")

# %%
# The run is ``ok`` and accurate, yet flagged: the peak indentation is almost half the sphere's
# radius, while Hertz contact assumes an indentation much smaller than the radius. The number is the
# model's answer; the flag says the model itself is stretched here (the paper's example lies there).
#
# Force against indentation
# -------------------------
# ``res.history`` holds the time ``t`` (s), the indentation ``s`` (m), the force ``F`` (N) and more;
# ``ghost`` marks the samples after separation, kept for plots only.

h = res.history
contact = ~h.ghost
fig, ax = plt.subplots(figsize=(5.5, 4))
ax.plot(h.s[contact] * 1e3, h.F[contact], color="C0", label="contact")
ax.plot(h.s[h.ghost] * 1e3, h.F[h.ghost], color="C0", ls=":", label="after separation (not physical)")
ax.set_xlabel("indentation s [mm]")
ax.set_ylabel("contact force F [N]")
ax.set_title(f"SLS plate, v0 = 10 m/s: COR = {res.cor:.3f}, s_max/r = {res.s_max / GEOMETRY_DEFAULTS['r']:.2f}")
ax.legend(loc="upper right")
fig.tight_layout()

# %%
# Time histories
# --------------
# The force returns to zero at the separation time :math:`t_0` while the indentation is still
# positive: the plate has not yet recovered (the residual indentation ``s_residual``).

fig, ax1 = plt.subplots(figsize=(5.5, 4))
t_ms = h.t * 1e3
ax1.plot(t_ms, h.F, color="C0")
ax1.set_xlabel("time t [ms]")
ax1.set_ylabel("contact force F [N]", color="C0")
ax2 = ax1.twinx()
ax2.plot(t_ms, h.s * 1e3, color="C1")
ax2.set_ylabel("indentation s [mm]", color="C1")
ax1.axvline(res.t0 * 1e3, color="0.5", ls="--")
ax1.text(res.t0 * 1e3, 0.9 * res.f_max, " separation", color="0.4")
fig.tight_layout()
plt.show()
