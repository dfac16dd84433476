"""
A parameter study and its ``sweep.nc``
======================================

A study is a **scene** in ``config.yaml``; ``snakemake -j2 results/<scene>/MANIFEST.txt`` plans its
grid into shards, solves each shard in a job and aggregates them into ``results/<scene>/sweep.nc``.
This example runs the same steps in one Python process on a small grid, with the functions the
workflow's jobs call (:func:`vcor.study.runner.run_points` for a shard,
:func:`vcor.study.aggregation.aggregate` for the dataset, :func:`vcor.io.netcdf.write_dataset` to
write it), so that it takes a second rather than the start-up of a job per shard. The dataset it
writes has the layout of the workflow's, and is read back with xarray.
"""

import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import xarray as xr
import yaml

from vcor import plots
from vcor.io.netcdf import write_dataset
from vcor.study.aggregation import aggregate, dataset_attrs
from vcor.study.config import load_project
from vcor.study.runner import run_points
from vcor.study.scene import material_params, settings_of
from vcor.study.shards import identified_points

CONFIG = """
scenes:
  my-first:
    description: "SLS plate: COR against v0 at three relaxation rates"
    materials: [sls]
    grid:
      v0: [1, 3, 10, 30]          # m/s
      beta: [600, 1200, 2400]     # SLS relaxation rate, 1/s
    tie:
      alpha: {to: beta, ratio: 0.25}   # rubbery / glassy modulus = 1/4 at every beta
    figures:
      fig4: {material: sls}
"""

project = load_project(yaml.safe_load(CONFIG))  # the checks Snakemake runs before any job
scene = project.scenes["my-first"]
identities = {m: project.catalogue.identity(m) for m in scene["materials"]}
points = identified_points(scene, identities)
print(f"{len(points)} points, e.g. {points[0]}")

# one shard holding every point, written as the sweep_shard job writes it (with the code's fingerprint
# and the materials' parameters, which the aggregation checks)
results = Path(tempfile.mkdtemp()) / "results" / "my-first"
(results / "shards").mkdir(parents=True)
settings = settings_of(scene)
shard = run_points(points, settings, project.catalogue)
attrs = {"settings": settings, "materials": material_params(scene["materials"], project.catalogue)}
write_dataset(shard, results / "shards" / "all.nc", title="vcor sweep shard", extra_attrs=attrs,
              command="examples/plot_parameter_study.py", identity="all")
sweep = aggregate([xr.load_dataset(results / "shards" / "all.nc")], scene, identities, project.catalogue)
out = results / "sweep.nc"
write_dataset(sweep, out, title="vcor sweep, scene my-first", extra_attrs=dataset_attrs("my-first", scene,
                                                                                         project.catalogue),
              command="examples/plot_parameter_study.py")

# %%
# Reading the dataset
# -------------------
# One variable per result field, each with its ``units`` and ``long_name``; the grid axes are
# dimensions; ``status`` and ``validity`` are CF flag variables.

ds = xr.open_dataset(out)
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
# The scene asks for ``fig4``; the workflow draws it with :data:`vcor.plots.FIGURES` from the same
# dataset.

draw, needs = plots.FIGURES["fig4"]
fig = draw(ds, scene["figures"]["fig4"])
plt.show()
