"""The workflow on a real single-node SLURM (started and torn down by the test) gives the same
datasets as a local run, point for point. Needs root (it installs slurm-wlm and munge with apt-get
when missing and writes /etc/slurm/slurm.conf). Skip with `-m 'not slurm'`. Takes ~1.5-2 minutes."""

import os
import shutil
import subprocess
from pathlib import Path

import pytest
import xarray as xr

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "workflow/slurm/local_cluster.sh"

pytestmark = [pytest.mark.slow, pytest.mark.slurm]

CONFIG = {
    "shard_size": 3,
    "material_dir": "results/materials",
    "fits": {"tiny-prony": {"model": "prony", "n_terms": 3}},
    "scenes": {
        "tiny": {"materials": ["sls"], "grid": {"v0": [2.0, 10.0, 20.0], "beta": [1200.0, 2400.0]},
                 "tie": {"alpha": {"to": "beta", "ratio": 0.25}}, "error_estimate": True},
        "two": {"materials": ["butyl-fc", "tiny-prony"], "grid": {"v0": [5.0, 10.0]}},
        "thin": {"materials": ["sls"], "grid": {"v0": [10.0], "h": [0.02, 0.002]},
                 "solver": {"method": "direct", "steps_per_contact": 200}},
    },
}

@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    if os.geteuid() != 0 or shutil.which("apt-get") is None and shutil.which("slurmctld") is None:
        pytest.skip("the local SLURM needs root and apt-get (or an installed slurm-wlm)")
    state = tmp_path_factory.mktemp("slurm-state")
    up = subprocess.run(["bash", str(SCRIPT), "start", str(state)], capture_output=True, text=True, timeout=600,
                        check=False)
    assert up.returncode == 0, up.stdout + up.stderr
    yield state
    subprocess.run(["bash", str(SCRIPT), "stop", str(state)], capture_output=True, text=True, timeout=120, check=False)

def test_slurm_run_equals_local_run(make_project, smk, cluster, tmp_path):
    local = make_project(tmp_path / "local", CONFIG)
    smk(local, "-j2")
    remote = make_project(tmp_path / "slurm", CONFIG)
    out = smk(remote, "--workflow-profile", str(remote / "profiles/slurm"))
    text = out.stdout + out.stderr
    submitted = text.count("submitted with SLURM jobid")
    assert submitted >= 8, f"only {submitted} jobs went through SLURM:\n{text[-3000:]}"
    for scene in CONFIG["scenes"]:
        a = xr.load_dataset(local / f"results/{scene}/sweep.nc").drop_vars("wall_time")
        b = xr.load_dataset(remote / f"results/{scene}/sweep.nc").drop_vars("wall_time")
        xr.testing.assert_equal(a, b)  # every value of every point, bit for bit
    a = xr.load_dataset(local / "results/materials/tiny-prony.nc")
    b = xr.load_dataset(remote / "results/materials/tiny-prony.nc")
    xr.testing.assert_identical(a.drop_attrs(), b.drop_attrs())
    assert a.attrs["material"] == b.attrs["material"]
