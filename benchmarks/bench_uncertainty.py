"""Uncertainty from measured data (docs: User guide, Uncertainty): does the bootstrap band cover the
truth, and what does it cost?

``coverage``: synthetic DMA data of known Prony materials shifted by WLF (C1 = 8.86,
C2 = 101.6 K, T_ref = 20 deg C; five sets at -10..50 deg C, ten frequencies 0.1..100 Hz, 1 % noise on
E' and E''), one data set per seed; each is fitted and resampled (vcor.fitting.resample.samples_dataset,
B samples) and the COR of a
steel sphere (r = 10 mm) on a rigid target at 1 m/s is computed for every sample at 0, 20 and 40 deg C.
The table counts the seeds whose 95 % band (2.5 % .. 97.5 % quantiles) holds the true material's COR,
and gives the band's median width; a noise-free data set gives the band's width without noise. This
part is not a timing (the per-seed fit time is printed for information only).

``spread``: for each known material, at T_ref (no shift between the data and the impact), the actual
scatter of the full-data fit's COR over SEEDS noisy data sets beside the median spread of the samples,
for three ways of making them: the default wild bootstrap, the Bayesian pairs bootstrap, and a
parametric bootstrap that draws the true noise law (1 % normal on E' and E'') about the full-data fit;
every sample refitted as the bootstrap refits it, from the full-data fit (vcor.fitting.resample.refit).
A ratio below 1 that the parametric bootstrap shares says the spread depends on the material itself
(refits of data from the smoother fitted material vary less than those of the true material's data),
not on the resampling.

``cost``: the default config's ``pyvisco`` scene (both fits of pyvisco's raw data, 50 bootstrap
samples, 620 grid points: 31000 impacts) in a fresh copy of the project with an empty numba cache:
``snakemake -j2 results/pyvisco/sweep.nc``, wall time, RUNS runs, median (min-max); and the same scene
without ``uncertainty`` for the ratio. From the banded sweep it also counts the turns of COR(T) that
are larger than the band (:func:`reversals`).

Run: python benchmarks/bench_uncertainty.py [coverage] [spread] [cost] [--seeds 20] [--bootstrap 50] [--runs 2]
     [--quick] [--out FILE]
"""

from __future__ import annotations

import shutil
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import yaml

import timing
from vcor.io.yamlfile import load_yaml

ROOT = timing.ROOT
TEMPS = (0.0, 20.0, 40.0)
V0 = 1.0


def _spaced(weights, rates, total=600e6):
    w = np.asarray(weights, float)
    return 2e6, tuple(w * total / w.sum()), tuple(rates)


#: the known materials (Prony: E_inf [Pa], E [Pa], beta [1/s]; 600 MPa in the terms) and their WLF shift
#: (C1, C2 [K], T_ref [deg C]). The first two have smooth spectra (17 terms, two per decade, 1..1e8 1/s):
#: a log-normal (centre 1e4 1/s, 1.5 decades wide) and a power-law wedge (E_j ~ beta_j^0.35) cut off at
#: 1e8 1/s. The third is five terms 1.5 decades apart: its tan delta has 8 extrema between the terms,
#: ripple that a smooth-spectrum fit does not follow by construction (model error, not in the band).
RATES17 = 10.0 ** np.arange(0.0, 8.01, 0.5)
MATERIALS = {
    "log-normal spectrum, 17 terms": _spaced(np.exp(-(np.log10(RATES17) - 4.0) ** 2 / (2 * 1.5**2)), RATES17),
    "power-law wedge, 17 terms": _spaced((RATES17 / 1e8) ** 0.35, RATES17),
    "5 terms, 1e1..1e7 1/s (sparse)": (2e6, (5e6, 20e6, 60e6, 150e6, 400e6), tuple(10.0 ** np.linspace(1, 7, 5))),
}
WLF = (8.86, 101.6, 20.0)
SETS = (-10.0, 5.0, 20.0, 35.0, 50.0)  # deg C
FREQ = np.geomspace(0.1, 100, 10)  # Hz


def _write_csv(path: Path, material, seed: int, noise: float) -> None:
    """Five sets of the known material, multiplicative normal noise on E' and E''."""
    from vcor.materials.shift import wlf_log_aT

    rng = np.random.default_rng(seed)
    rows = ["f,E_stor,E_loss,T,Set", "Hz, MPa, MPa, C, -"]
    for k, T in enumerate(SETS):
        e = material.complex_modulus(2 * np.pi * FREQ * 10 ** wlf_log_aT(T, WLF[2], WLF[0], WLF[1]))
        n = 1 + noise * rng.standard_normal((2, FREQ.size))
        rows += [f"{f:.17g},{x.real * a / 1e6:.17g},{x.imag * b / 1e6:.17g},{T:g},{k}"
                 for f, x, a, b in zip(FREQ, e, *n)]
    path.write_text("\n".join(rows) + "\n")


def one_seed(material, seed: int, noise: float, n: int, folder: Path) -> dict:
    """Band and truth at TEMPS for one synthetic data set."""
    import vcor
    from vcor.fitting import resample, samples
    from vcor.materials.shift import at_temperature, time_shifted, wlf_log_aT

    _write_csv(folder / "dma.csv", material, seed, noise)
    spec = {"model": "prony", "data": {"file": "dma.csv", "T_ref": WLF[2]}}
    t = time.perf_counter()
    ds = resample.samples_dataset("synthetic", spec, n, seed=seed, base_dir=folder)
    fit_time = time.perf_counter() - t
    mats = samples.sample_materials(ds)
    out = {"fit_time": fit_time, "covered": [], "width": [], "offset": []}
    for T in TEMPS:
        want = vcor.simulate(time_shifted(material, float(wlf_log_aT(T, WLF[2], WLF[0], WLF[1]))), V0, rigid=True).cor
        cor = np.array([vcor.simulate(at_temperature(m, s, T), V0, rigid=True).cor for m, s in mats])
        lo, hi = np.quantile(cor, [0.025, 0.975])
        out["covered"].append(bool(lo <= want <= hi))
        out["width"].append(float(hi - lo))
        out["offset"].append(float(np.median(cor) - want))
    return out


def coverage(args) -> list[str]:
    from vcor.materials import Prony

    seeds = 3 if args.quick else args.seeds
    n = 10 if args.quick else args.bootstrap
    rows = []
    with tempfile.TemporaryDirectory() as d:
        for label, params in MATERIALS.items():
            material = Prony(*params)
            results = []
            for seed in range(seeds):
                r = one_seed(material, seed, 0.01, n, Path(d))
                results.append(r)
                print(f"{label}, seed {seed}: covered {r['covered']}, widths {np.round(r['width'], 5)}, "
                      f"fit {r['fit_time']:.1f} s", file=sys.stderr, flush=True)
            clean = one_seed(material, 0, 0.0, n, Path(d))
            covered = np.array([r["covered"] for r in results])
            widths = np.array([r["width"] for r in results])
            offsets = np.array([r["offset"] for r in results])
            rows += [[label, f"{T:g}", f"{int(covered[:, j].sum())} of {seeds}", f"{np.median(widths[:, j]):.1e}",
                      f"{np.median(offsets[:, j]):+.1e}", f"{np.std(offsets[:, j], ddof=1):.1e}",
                      f"{np.median(widths[:, j]) / (2 * 1.96 * np.std(offsets[:, j], ddof=1)):.2f}",
                      f"{clean['width'][j]:.1e}", f"{clean['offset'][j]:+.1e}"]
                     for j, T in enumerate(TEMPS)]
    return [f"Coverage: {seeds} synthetic data sets per material (five sets at {', '.join(f'{t:g}' for t in SETS)} °C, "
            f"ten frequencies 0.1..100 Hz, 1 % noise), {n} bootstrap samples each, COR of a steel sphere "
            f"(r = 10 mm) at {V0:g} m/s on a rigid target. Offset: median of the samples minus the true COR; its sd "
            "over the seeds is the error the band should hold; width ratio: median band width over 2 x 1.96 x "
            "that sd (1 for a band as wide as a normal 95 % interval of the actual error).",
            timing.table(["material", "T [°C]", "95 % band holds the true COR", "median band width (1)",
                          "median offset (1)", "sd of the offset over seeds (1)", "width ratio",
                          "noise-free data: band width (1)", "noise-free: offset (1)"], rows)]


def _parametric(res, rng, noise=0.01):
    """Data drawn from the true noise law about the full-data fit (sets as vcor.fitting.resample.wild_sample)."""
    from vcor.fitting.dma import DMASet

    return [DMASet(T=s.T, f=s.f, E_stor=fs * (1 + noise * rng.standard_normal(s.f.size)),
                   E_loss=fl * (1 + noise * rng.standard_normal(s.f.size)), label=s.label, weight=s.weight)
            for s, fs, fl in zip(res.sets, res.fit_stor, res.fit_loss)]


def spread(args) -> list[str]:
    import vcor
    from vcor.fitting import dma, resample
    from vcor.materials import Prony

    seeds = 3 if args.quick else min(args.seeds, 10)
    n = 5 if args.quick else 30
    rows = []
    with tempfile.TemporaryDirectory() as d:
        for label, params in MATERIALS.items():
            material = Prony(*params)
            want = vcor.simulate(material, V0, rigid=True).cor
            err, sd = [], {"wild": [], "bayesian": [], "parametric": []}
            for seed in range(seeds):
                _write_csv(Path(d) / "dma.csv", material, seed, 0.01)
                raw = dma.read_table(Path(d) / "dma.csv")
                full = dma.fit_dma(raw, WLF[2])
                err.append(vcor.simulate(full.material(), V0, rigid=True).cor - want)
                res = resample.residuals(raw, full)
                rng = np.random.default_rng(seed)
                draw = {"wild": lambda res=res, rng=rng: resample.wild_sample(res, rng),
                        "bayesian": lambda raw=raw, rng=rng: resample.resample(raw, rng, T_ref=WLF[2]),
                        "parametric": lambda res=res, rng=rng: _parametric(res, rng)}
                for mode, make in draw.items():
                    cor = [vcor.simulate(resample.refit(make(), full).material(), V0, rigid=True).cor for _ in range(n)]
                    sd[mode].append(np.std(cor, ddof=1))
                print(f"spread {label}, seed {seed}: error {err[-1]:+.4f}", file=sys.stderr, flush=True)
            actual = float(np.std(err, ddof=1))
            rows.append([label, f"{actual:.1e}"] + [f"{np.median(sd[m]):.1e} ({np.median(sd[m]) / actual:.2f})"
                                                    for m in ("wild", "bayesian", "parametric")])
    return [f"Spread at T_ref = {WLF[2]:g} °C, COR at {V0:g} m/s (rigid target): the sd of the full-data fit's COR "
            f"error over {seeds} data sets (1 % noise), and the median over those data sets of the sd of {n} "
            "samples made three ways (in brackets: over the actual sd).",
            timing.table(["material", "actual sd of the fit's COR (1)", "wild bootstrap sd (1)",
                          "Bayesian pairs bootstrap sd (1)", "parametric, true noise law, sd (1)"], rows)]


def _project(folder: Path, uncertainty: dict | None, quick: bool) -> Path:
    for name in ("Snakefile", "workflow", "profiles", "data"):
        src = ROOT / name
        (shutil.copytree if src.is_dir() else shutil.copy)(src, folder / name)
    cfg = load_yaml(ROOT / "config.yaml")
    scene = cfg["scenes"]["pyvisco"]
    scene.pop("uncertainty", None)
    if uncertainty:
        scene["uncertainty"] = uncertainty
    if quick:
        scene["grid"] = {"v0": [1, 10], "T": [-20, 20], "nu": [0.5]}
        scene.pop("figures", None)          # their options name grid values the small grid lacks
    cfg["scenes"] = {"pyvisco": scene}
    cfg["dem"] = {}
    (folder / "config.yaml").write_text(yaml.safe_dump(cfg, sort_keys=False))
    return folder


def reversals(sweep_path: Path) -> list[list[str]]:
    """Per material, nu and v0 of a banded sweep: the turns of the median COR(T) larger than the band's
    half-width there (vcor.study.uncertainty.significant_reversals), and the band's largest half-width."""
    from vcor.io.netcdf import read_dataset
    from vcor.study.uncertainty import significant_reversals

    rows = []
    with read_dataset(sweep_path) as ds:
        for m in ds["material"].values:
            for nu in ds["nu"].values:
                for v0 in ds["v0"].values:
                    d = ds.sel(material=m, nu=nu, v0=v0).sortby("T")
                    ok = d["status"].values == 0
                    hw = 0.5 * (d["cor_hi"].values - d["cor_lo"].values)
                    n = significant_reversals(d["cor"].values[ok], hw[ok])
                    rows.append([str(m), f"{nu:g}", f"{v0:g}", f"{int(ok.sum())} of {ok.size}", str(n),
                                 f"{np.max(hw[ok]):.1e}"])
    return rows


def sweep_work(path: Path) -> tuple[int, float, float]:
    """(sweep jobs, their estimated work by vcor.study.cost, their measured work from the job logs; s) of
    the finished ``pyvisco`` scene in the project at ``path``."""
    import json
    import re

    from vcor.study.config import load_project
    from vcor.study.cost import point_seconds

    data = load_project(load_yaml(path / "config.yaml"), path).fitted_to_data
    shards = sorted((path / "results/pyvisco/shards").glob("*.json"))
    estimate = 0.0
    for index in shards:
        spec = json.loads(index.read_text())
        estimate += sum(point_seconds(p, spec["settings"], data) for p in spec["points"])
    logs = (path / "results/pyvisco/logs/shards").glob("*.log")
    work = sum(float(m.group(1)) for log in logs for m in re.finditer(r"job sweep_shard: .*, work ([\d.]+) s",
                                                                        log.read_text()))
    return len(shards), estimate, work


def cost(args) -> list[str]:
    bootstrap = 4 if args.quick else args.bootstrap
    cmd = [sys.executable, "-m", "snakemake", "-j2", "results/pyvisco/sweep.nc"]
    rows, turns, works = {}, [], {}
    for label, unc in (("without uncertainty", None), (f"bootstrap {bootstrap}", {"bootstrap": bootstrap})):
        walls, work = [], []
        for _ in range(args.runs):
            with tempfile.TemporaryDirectory() as d:
                path = _project(Path(d), unc, args.quick)
                walls.append(timing.run_fresh(cmd, cwd=path).wall)
                work.append(sweep_work(path))
                if unc:
                    turns = reversals(path / "results/pyvisco/sweep.nc")
        rows[label], works[label] = walls, work
    base = timing.median(rows["without uncertainty"])
    lines = [[label, timing.cell(w, fmt=".1f"), f"{timing.median(w) / base:.1f}", str(works[label][0][0]),
              f"{works[label][0][1]:.1f}", timing.cell([x[2] for x in works[label]], fmt=".1f")]
             for label, w in rows.items()]
    return [f"Cost: the default config's `pyvisco` scene{' (quick: a 2 x 2 x 1 grid)' if args.quick else ''}, "
            "`snakemake -j2 results/pyvisco/sweep.nc` in a fresh copy of the project (fits, samples, "
            "shards, aggregate), empty numba cache.",
            timing.table(["scene", "wall time [s], median (min-max)", "ratio", "sweep jobs",
                          "estimated sweep work (vcor.study.cost) [s]", "sweep jobs' measured work [s]"], lines),
            (f"Turns of COR(T) in that scene's sweep (bootstrap {bootstrap}, the last run) larger than the band's "
             "half-width on both sides (vcor.study.uncertainty.significant_reversals; ok points only); the "
             "acceptance is at most one, the minimum."),
            timing.table(["material", "nu (1)", "v0 [m/s]", "ok points", "turns larger than the band",
                          "largest half-width (1)"], turns)]


def main() -> None:
    p = timing.parser(__doc__, quick="3 seeds with 10 samples; the cost on a 4-point grid with 4 samples")
    p.add_argument("parts", nargs="*", choices=["coverage", "spread", "cost"], default=[])
    p.add_argument("--seeds", type=int, default=20)
    p.add_argument("--bootstrap", type=int, default=50)
    args = p.parse_args()
    parts = args.parts or ["coverage", "cost"]
    blocks = []
    for part in parts:
        blocks += {"coverage": coverage, "spread": spread, "cost": cost}[part](args)
    timing.publish(args.out, args.runs, blocks)


if __name__ == "__main__":
    main()
