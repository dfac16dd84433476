"""Planning a run stays light: the modules the Snakefile's process imports (workflow/rules/common.smk)
load no scipy, numba, matplotlib or xarray; every snakemake call, a no-op included, pays for them. A job
that solves nothing loads no solver (numba)."""

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
HEAVY = ("scipy", "numba", "matplotlib", "xarray")


def test_the_snakefile_imports_load_no_heavy_package():
    text = (ROOT / "workflow" / "rules" / "common.smk").read_text()
    modules = re.findall(r"^import (vcor[\w.]*) as \w+$", text, flags=re.M)
    modules += re.findall(r"^from (vcor[\w.]*) import", text, flags=re.M)
    assert len(modules) >= 8, modules  # the pattern still finds the Snakefile's imports
    code = (f"import sys; import {', '.join(modules)}; "
            f"print(' '.join(m for m in {HEAVY!r} if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == [], f"planning imports {out.stdout.split()}"


@pytest.mark.parametrize("script", ["aggregate.py", "moduli.py", "convergence.py"])
def test_a_job_that_solves_nothing_loads_no_solver(script):
    """The jobs that combine shards (aggregate), tabulate moduli (moduli) or combine the work-precision
    cases (convergence) load no numba with their imports: the solvers load where impacts are solved
    (vcor.study.sweep.solve_points, the convergence cases, the histories)."""
    text = (ROOT / "workflow" / "scripts" / script).read_text()
    lines = re.findall(r"^(?:from vcor[\w.]* import .+|import vcor[\w.]*)$", text, flags=re.M)
    assert len(lines) >= 3, lines  # the pattern still finds the script's imports
    code = "; ".join(["import sys", *lines, "print('numba' in sys.modules)"])
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
