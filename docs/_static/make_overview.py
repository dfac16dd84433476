"""Draw docs/_static/overview.svg: the COR against the impact speed for the paper's presets, with the
points outside the model's stated range drawn as every vcor figure draws them (open markers on dashed
segments, a legend entry naming the reasons: :func:`vcor.plots.common.sweep_line`).

Run: python docs/_static/make_overview.py   (a few seconds; the default method, adaptive, and the
paper's geometry: a steel sphere, r = 10 mm, on a plate of half-thickness 2 r). The SVG is
deterministic (no date, fixed hash salt), so re-running it changes the file only if the numbers move.
"""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
matplotlib.rcParams["svg.hashsalt"] = "vcor-docs"
matplotlib.rcParams["svg.fonttype"] = "none"  # text stays text: smaller file, selectable labels

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import vcor  # noqa: E402
from vcor.plots.common import Drawn, flag_legend, sweep_line  # noqa: E402
from vcor.status import code  # noqa: E402

PRESETS = ("sls", "butyl-fc", "butyl-cerf", "butyl-prony3")
SPEEDS = np.geomspace(0.5, 50.0, 13)  # m/s
OUT = Path(__file__).resolve().parent / "overview.svg"


def main():
    fig, ax = plt.subplots(figsize=(6.4, 4.2), layout="constrained")
    drawn = []
    for name in PRESETS:
        results = [vcor.simulate(name, float(v0)) for v0 in SPEEDS]
        drawn.append(sweep_line(ax, SPEEDS, [r.cor for r in results], [code(r.status) for r in results],
                                [r.validity for r in results], label=name, ms=3.5))
    ax.set_xscale("log")
    flag_legend(ax, Drawn.total(drawn).flags)
    ax.set_xlabel("impact speed $v_0$ [m/s]")
    ax.set_ylabel("coefficient of restitution [1]")
    ax.set_title("Steel sphere on a viscoelastic plate (Green 2026 presets)", fontsize=10)
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center", ncol=3, fontsize=8,
               frameon=False)
    fig.savefig(OUT, metadata={"Date": None})
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
