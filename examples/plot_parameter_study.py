"""
A parameter study and its ``sweep.nc``
======================================

A study is a **scene** in ``config.yaml``. Snakemake plans the scene's grid into jobs, solves them
and aggregates the results into ``results/<scene>/sweep.nc``, a NetCDF dataset with units on every
variable. This example writes a project with one small scene into a temporary folder, runs the
workflow on it, and reads the dataset with xarray (through vcor's reader). It needs the workflow extra
(``pip install -e '.[workflow]'``) and a clone of the repository (for ``Snakefile`` and ``workflow/``).
"""

import shutil
import subprocess
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt

from vcor import plots
from vcor.io.netcdf import read_dataset

CONFIG = """\
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

# the repository (Snakefile, workflow/, profiles/), whether this runs as a script or in the manual's build
here = Path(__file__).resolve().parent if "__file__" in globals() else Path.cwd()
repo = next(p for p in (here, *here.parents) if (p / "Snakefile").is_file())
workdir = tempfile.TemporaryDirectory(prefix="vcor-example-")  # removed when the example ends
project = Path(workdir.name)
for part in ("Snakefile", "workflow", "profiles"):
    (shutil.copytree if (repo / part).is_dir() else shutil.copy)(repo / part, project / part)
(project / "config.yaml").write_text(CONFIG)

run = subprocess.run(["snakemake", "-j2", "results/my-first/sweep.nc"], cwd=project, capture_output=True,
                     text=True, check=False)
print("snakemake -j2 results/my-first/sweep.nc: exit code", run.returncode)
print("\n".join(run.stderr.strip().splitlines()[-6:]))
run.check_returncode()

# %%
# Reading the dataset
# -------------------
# One variable per result field, each with its ``units`` and ``long_name``; the grid axes are
# dimensions; ``status`` and ``validity`` are CF flag variables. The file follows CF-1.10, which keeps
# text out of coordinate variables: the material names are the label ``material_label`` along the
# dimension ``material``. :func:`vcor.io.netcdf.read_dataset` (``xarray.load_dataset`` and the step
# back) makes them the dimension's index again, so that ``sel(material="sls")`` works.

ds = read_dataset(project / "results" / "my-first" / "sweep.nc")
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
# ``results/my-first/figures/``. Here it is drawn from the same dataset by the same function
# (``vcor.plots.FIGURES``).

draw, needs = plots.FIGURES["fig4"]
fig = draw(ds, {"material": "sls"})
plt.show()
