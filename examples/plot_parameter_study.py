"""
A parameter study and its ``sweep.nc``
======================================

A study is a **scene**: materials, a grid of speeds and parameters, ties between them, solver options.
:func:`vcor.sweep <vcor.study.api.sweep>` solves a scene's grid on the machine's cores and returns the
dataset the workflow archives as ``results/<scene>/sweep.nc`` (units on every variable, status and
validity flags, the scene's config), here for the scene ``my-first`` of the getting-started page, as
it would stand under ``scenes:`` in ``config.yaml``. ``snakemake -j2`` builds the same file from the
config; ``vcor sweep --config config.yaml --scene my-first --out sweep.nc`` writes it without Snakemake.
"""

import matplotlib.pyplot as plt

import vcor
from vcor import plots

scene = {
    "description": "SLS plate: COR against v0 at three relaxation rates",
    "materials": ["sls"],
    "grid": {"v0": [1, 3, 10, 30], "beta": [600, 1200, 2400]},  # m/s, 1/s
    "tie": {"alpha": {"to": "beta", "ratio": 0.25}},  # rubbery / glassy modulus = 1/4 at every beta
    "figures": {"fig4": {"material": "sls"}},
}
ds = vcor.sweep(scene, progress=False)

# %%
# Reading the dataset
# -------------------
# One variable per result field, each with its ``units`` and ``long_name``; the grid axes are
# dimensions; ``status`` and ``validity`` are CF flag variables. The archived file follows CF-1.10,
# which keeps text out of coordinate variables: it holds the material names as the label
# ``material_label`` along the dimension ``material``; :func:`vcor.io.netcdf.read_dataset` reads such a
# file back as here, with the names as the dimension's index, so that ``sel(material="sls")`` works.

print(ds)
print()
print("cor:", ds["cor"].attrs["long_name"], f"[{ds['cor'].attrs['units']}]")
print("validity flags:", ds["validity"].attrs["flag_meanings"])
print(ds["cor"].sel(material="sls").round(4).to_pandas())

# %%
# Selecting and plotting with xarray
# ----------------------------------
# Flagged points (``validity != 0``) are drawn open.

fig, ax = plt.subplots(figsize=(6, 4.2))
sls = ds.sel(material="sls")
for i, beta in enumerate(sls["beta"].values):
    one = sls.sel(beta=beta)
    flagged = one["validity"].values != 0
    ax.plot(one["v0"], one["cor"], "-", color=f"C{i}", label=f"beta = {beta:g} 1/s")
    ax.plot(one["v0"][~flagged], one["cor"][~flagged], "o", color=f"C{i}")
    ax.plot(one["v0"][flagged], one["cor"][flagged], "o", mfc="none", color=f"C{i}")
ax.plot([], [], "o", mfc="none", color="0.3", label="flagged (validity != 0)")
ax.set_xscale("log")
ax.set_xlabel(f"impact speed v0 [{ds['v0'].attrs['units']}]")
ax.set_ylabel("COR")
ax.legend(fontsize=8)
fig.tight_layout()

# %%
# The workflow's own figure
# -------------------------
# The scene asks for ``fig4``; ``snakemake -j2 results/my-first/MANIFEST.txt`` would draw it into
# ``results/my-first/figures/``. Here it is drawn from the dataset ``vcor.sweep`` returned by the same
# function (``vcor.plots.FIGURES``).

draw, needs = plots.FIGURES["fig4"]
fig = draw(ds, {"material": "sls"})
plt.show()
