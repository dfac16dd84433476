"""Draw docs/_static/overview.svg: the COR against the impact speed for the paper's presets.

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

PRESETS = ("sls", "butyl-fc", "butyl-cerf", "butyl-prony3")
SPEEDS = np.geomspace(0.5, 50.0, 13)  # m/s
OUT = Path(__file__).resolve().parent / "overview.svg"


def main():
    fig, ax = plt.subplots(figsize=(6.0, 3.6), layout="constrained")
    for name in PRESETS:
        cor = []
        for v0 in SPEEDS:
            r = vcor.simulate(name, float(v0))
            cor.append(r.cor if r.status == "ok" else np.nan)
        ax.semilogx(SPEEDS, cor, "o-", ms=3.5, lw=1.2, label=name)
    ax.set_xlabel("impact speed $v_0$ [m/s]")
    ax.set_ylabel("coefficient of restitution [1]")
    ax.set_title("Steel sphere on a viscoelastic plate (Green 2026 presets)", fontsize=10)
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    ax.legend(fontsize=8, frameon=False)
    fig.savefig(OUT, metadata={"Date": None})
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
