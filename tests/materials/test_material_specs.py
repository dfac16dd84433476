"""Your own materials: the config's ``materials:`` block, ``vcor.material_specs``,
the CLI's ``--config`` and the workflow. docs/user-guide/materials.md, "Your own materials in the
configuration"."""

import json

import pytest
import yaml

import vcor
from vcor import cli
from vcor.io.netcdf import read_dataset
from vcor.materials.specs import from_spec

PRONY3 = vcor.materials.get("butyl-prony3")
E_INF, MODULI, RATES = 10.421e6, [20.181e6, 38.204e6, 87.344e6], [972.0, 6426.0, 34221.0]
E_0 = E_INF + sum(MODULI)


def _forms(tmp_path):
    (tmp_path / "prony3_tau.csv").write_text("tau,E\n"
                                             + "".join(f"{1 / b!r},{e!r}\n" for b, e in zip(RATES, MODULI)))
    (tmp_path / "prony3_g.csv").write_text("tau,g\n"
                                           + "".join(f"{1 / b!r},{e / E_0!r}\n" for b, e in zip(RATES, MODULI)))
    return {
        "class form": {"model": "prony", "E_inf": E_INF, "E": MODULI, "beta": RATES},
        "relaxation times": {"model": "prony", "E_inf": E_INF, "E": MODULI, "tau": [1 / b for b in RATES]},
        "normalised (finite-element) form": {"model": "prony", "E_0": E_0, "g": [e / E_0 for e in MODULI],
                                             "tau": [1 / b for b in RATES]},
        "CSV, tau and E": {"model": "prony", "E_inf": E_INF, "file": "prony3_tau.csv"},
        "CSV, tau and g": {"model": "prony", "E_0": E_0, "file": "prony3_g.csv"},
    }


def test_inline_prony_gives_the_presets_cor(tmp_path):
    """An inline Prony material equal to butyl-prony3 gives its COR to 1e-12
    (every form: rates, times, normalised, CSV)."""
    ref = vcor.simulate(PRONY3, 10.0, method="adaptive").cor
    for label, spec in _forms(tmp_path).items():
        mat = from_spec(spec, name="p3", base_dir=tmp_path)
        assert abs(vcor.simulate(mat, 10.0, method="adaptive").cor - ref) <= 1e-12, label


@pytest.mark.parametrize("preset, spec", [
    ("sls", {"model": "sls", "E_glassy": 15e6, "alpha": 300, "beta": 1200}),
    ("butyl-fc", {"model": "fractional", "E0": 3 * 7.6e5, "E1": 3 * 2.95e5}),
    ("butyl-cerf", {"model": "cerf", "E0": 0.442e6, "E1": 0.6765e9, "b1": 700.0}),
    ("kelvin-voigt", {"model": "kelvin-voigt", "E": 15e6, "tau": 1e-4}),
    ("elastic", {"model": "elastic", "E": 15e6}),
])
def test_every_model_builds_its_class(preset, spec):
    assert from_spec(spec, name=preset) == vcor.materials.get(preset)


BAD = [
    ({"model": "maxwell"}, ["materials.m.model", "one of"]),
    ({"model": "sls", "E_glassy": 1e6, "alpha": 10}, ["materials.m", "missing ['beta']"]),
    ({"model": "sls", "E_glassy": 1e6, "alpha": 10, "beta": 20, "eta": 1},
     ["materials.m.eta: unknown key; a sls material takes ['E_glassy', 'alpha', 'beta']"]),
    ({"model": "sls", "E_glasy": 1e6, "alpha": 10, "beta": 20},
     ["materials.m.E_glasy: unknown key", "(missing ['E_glassy'])", "did you mean 'E_glassy'?"]),
    ({"model": "sls", "E_glassy": "soft", "alpha": 10, "beta": 20}, ["materials.m.E_glassy", "number"]),
    # a modulus written with an unsigned exponent (text to YAML): its real range, and the fix
    ({"model": "elastic", "E": "7.0e10"}, ["materials.m.E must be in (0, 1e+20] Pa", "write 7.0e+10"]),
    ({"model": "sls", "E_glassy": 1e6, "alpha": 30, "beta": 20}, ["materials.m", "alpha must be in [0, beta]"]),
    ({"model": "prony", "E_inf": 1e6, "E": [-2e6], "beta": [10]}, ["materials.m", "E[0]", "[0, 1e+20] Pa"]),
    # each value's true range, also for a number that arrived as text
    ({"model": "prony", "E_inf": 1e6, "E": ["2e6"], "beta": [10]}, ["materials.m.E[0] must be in [0, 1e+20] Pa"]),
    ({"model": "prony", "E_inf": 1e6, "E": [2e6], "beta": [-10]}, ["materials.m.beta[0] must be in [0, inf) 1/s"]),
    ({"model": "prony", "E_inf": "1e6", "E": [2e6], "beta": [10]}, ["materials.m.E_inf must be in [0, 1e+20] Pa"]),
    ({"model": "prony", "E_0": 1e7, "g": ["0.5"], "tau": [1]}, ["materials.m.g[0] must be in [0, 1) (a number)"]),
    ({"model": "prony", "E_inf": 1e6, "E": [2e6, 1e6], "beta": [10]}, ["2 moduli but 1"]),
    ({"model": "prony", "E_inf": 1e6, "E": [2e6], "beta": [10], "tau": [0.1]}, ["tau", "beta", "not both"]),
    ({"model": "prony", "E_0": 1e7, "g": [0.6, 0.5], "tau": [1, 2]}, ["materials.m.g", "sum < 1"]),
    ({"model": "prony", "E_0": 1e7, "g": [0.5], "tau": [0.0]}, ["materials.m.tau[0]", "(0, inf) s"]),
    ({"model": "prony", "E_inf": 1e6, "E": [2e6]}, ["needs rates beta"]),
    ({"model": "prony", "E_inf": 1e6, "file": "missing.csv"}, ["missing.csv", "does not exist"]),
]


@pytest.mark.parametrize("spec, words", BAD)
def test_bad_specs_name_the_key(tmp_path, spec, words):
    with pytest.raises(ValueError) as err:
        from_spec(spec, name="m", base_dir=tmp_path)
    for w in words:
        assert w in str(err.value), (w, str(err.value))


SCENE_T = "scenes:\n  t:\n    materials: [{name}]\n    grid: {{v0: [1, 2]}}\n"
IN_FILE = [  # (the material's entry, the text its refusal points at, the refusal after the place)
    ("my-sls2: {model: sls, E_glasy: 40.0e+6, alpha: 500, beta: 5000}", "E_glasy",
     "materials.my-sls2.E_glasy: unknown key; a sls material takes ['E_glassy', 'alpha', 'beta'] (missing "
     "['E_glassy']); did you mean 'E_glassy'?"),
    ("my-sls2: {model: sls, E_glassy: -40.0e+6, alpha: 500, beta: 5000}", "E_glassy",
     "materials.my-sls2.E_glassy must be in (0, 1e+20] Pa, got -40000000.0"),
    ('my-sls2: {model: sls, E_glassy: "40 MPa", alpha: 500, beta: 5000}', "E_glassy",
     "materials.my-sls2.E_glassy must be in (0, 1e+20] Pa (a number), got '40 MPa'"),
    ("my-sls2: {model: sls, E_glassy: 40e6, alpha: 500, beta: 5000}", "E_glassy",
     "materials.my-sls2.E_glassy must be in (0, 1e+20] Pa (a number), got '40e6': text, not a number"),
    ("my-p: {model: prony, E_inf: 5.0e+6, E: [12e6, 25.0e+6], tau: [3.0e-3, 5.0e-4]}", "12e6",
     "materials.my-p.E[0] must be in [0, 1e+20] Pa (a number), got '12e6': text, not a number"),
    ("my-p:\n    model: prony\n    E_inf: 5.0e+6\n    E: [12.0e+6, -25.0e+6, 40.0e+6]\n"
     "    tau: [3.0e-3, 5.0e-4, 8.0e-5]", "-25.0e+6", "materials.my-p.E[1] must be in [0, 1e+20] Pa, got -25000000.0"),
    ("my-sls2: {model: sls, E_glassy: 40.0e+6, alpha: 6000, beta: 5000}", "alpha",
     "materials.my-sls2.alpha must be in [0, beta] = [0, 5000.0] 1/s (alpha > beta makes the relaxation modulus "
     "increase), got 6000.0"),
    ("my-sls2: {model: sls, E_glassy: 1.0e+300, alpha: 300, beta: 1200}", "E_glassy",
     "materials.my-sls2.E_glassy must be in (0, 1e+20] Pa, got 1e+300"),
    ("my-sls2: {model: sls, E_glassy: 40.0e+6, alpha: 500}", "my-sls2",
     "materials.my-sls2 (sls): missing ['beta']; a sls material takes ['E_glassy', 'alpha', 'beta']"),
]


@pytest.mark.parametrize("entry, at, said", IN_FILE, ids=[f"in_file{i}" for i in range(len(IN_FILE))])
def test_a_bad_material_in_a_config_file_names_the_place_of_its_parameter(tmp_path, monkeypatch, entry, at, said):
    """A refusal of a config material's value gives the file, line and column of that value (or of the
    unknown key, or of the material for a missing key), its key path and its range with the unit."""
    text = f"materials:\n  {entry}\n" + SCENE_T.format(name=entry.split(":")[0])
    (tmp_path / "my.yaml").write_text(text)
    monkeypatch.chdir(tmp_path)
    before = text[:text.index(at)]
    line, column = before.count("\n") + 1, len(before) - before.rfind("\n")
    with pytest.raises(ValueError) as err:
        vcor.sweep("t", config="my.yaml")
    print(err.value)
    assert str(err.value).startswith(f"config file my.yaml, line {line}, column {column}: {said}"), str(err.value)
    assert "\n" not in str(err.value)


@pytest.mark.parametrize("table, words", [
    ("tau,E\n0.1,1e6\n0.01,lots\n", ["t.csv, line 3, column 'E'", "'lots' is not a number"]),
    ("tau,E\n0.1,1e300\n", ["t.csv, line 2, column 'E'", "[0, 1e+20] Pa"]),
    ("tau,modulus\n0.1,1e6\n", ["t.csv, line 1", "one of E (Pa) or g"]),
    ("tau,E\n0.1,-1e6\n", ["t.csv, line 2, column 'E'", "[0, 1e+20] Pa"]),
    ("tau,E\n0,1e6\n", ["t.csv, line 2, column 'tau'", "(0, inf) s"]),
    ("beta,E\n-1,1e6\n", ["t.csv, line 2, column 'beta'", "[0, inf) 1/s"]),
    ("tau,E\n0.1\n", ["t.csv, line 2", "1 cells"]),
    ("tau,E\n", ["no terms"]),
])
def test_bad_csv_names_file_line_and_column(tmp_path, table, words):
    (tmp_path / "t.csv").write_text(table)
    with pytest.raises(ValueError) as err:
        from_spec({"model": "prony", "E_inf": 1e6, "file": "t.csv"}, name="m", base_dir=tmp_path)
    for w in words:
        assert w in str(err.value), (w, str(err.value))


def test_a_malformed_table_is_refused_naming_the_config_key_that_names_it(tmp_path, monkeypatch):
    """A config material's table that cannot be read is refused with the key that names the file (and that
    key's place in the config file) before the table's own file, line and column."""
    (tmp_path / "t.csv").write_text("tau,E\n0.1,1e6\n0.01,lots\n")
    entry = "tab: {model: prony, E_inf: 3.0e+6, file: t.csv}"
    (tmp_path / "my.yaml").write_text(f"materials:\n  {entry}\n" + SCENE_T.format(name="tab"))
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ValueError) as err:
        vcor.sweep("t", config="my.yaml")
    text = str(err.value)
    assert text.startswith(f"config file my.yaml, line 2, column {3 + entry.index('file')}: materials.tab.file: "), text
    assert text.endswith("t.csv, line 3, column 'E': 'lots' is not a number") and "\n" not in text, text


def test_a_table_takes_the_ranges_of_inline_lists(tmp_path):
    """A Prony table's columns have the ranges of a config's inline lists: a rate of 0 (a constant term)
    is taken as inline, a relative modulus g >= 1 is refused at its line."""
    (tmp_path / "t.csv").write_text("beta,E\n0,1e6\n100,2e6\n")
    table = from_spec({"model": "prony", "E_inf": 1e6, "file": "t.csv"}, name="m", base_dir=tmp_path)
    assert table == from_spec({"model": "prony", "E_inf": 1e6, "E": [1e6, 2e6], "beta": [0.0, 100.0]})
    (tmp_path / "g.csv").write_text("tau,g\n0.1,0.5\n0.01,1.0\n")
    with pytest.raises(ValueError, match=r"g\.csv, line 3, column 'g': 1\.0 is outside \[0, 1\)"):
        from_spec({"model": "prony", "E_0": 1e7, "file": "g.csv"}, name="m", base_dir=tmp_path)


def test_cli_takes_a_config_material(tmp_path, capsys):
    cfg = tmp_path / "config.yaml"
    mine = {"model": "sls", "E_glassy": 15e6, "alpha": 300, "beta": 1200}
    cfg.write_text(yaml.safe_dump({"materials": {"mine": mine}}))
    assert cli.main(["impact", "--config", str(cfg), "--material", "mine", "--v0", "10", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["cor"]["value"] == vcor.simulate("sls", 10.0).cor
    assert cli.main(["impact", "--config", str(cfg), "--material", "other", "--v0", "10"]) == 2
    assert "config materials ['mine']" in capsys.readouterr().err


CONFIG = {
    "shard_size": 100,
    "material_dir": "results/materials",
    "materials": {
        "my-prony": {"model": "prony", "E_inf": E_INF, "file": "data/prony3.csv"},
        "my-sls": {"model": "sls", "E_glassy": 15e6, "alpha": 300, "beta": 1200},
    },
    "scenes": {"own": {"materials": ["my-prony", "my-sls", "sls"], "grid": {"v0": [5.0, 10.0]},
                       "figures": {"fig8": {}}}},
}


@pytest.mark.slow
def test_workflow_uses_config_materials_like_presets(make_project, smk, tmp_path):
    path = make_project(tmp_path, CONFIG)
    (path / "data").mkdir(exist_ok=True)
    (path / "data/prony3.csv").write_text("tau,E\n" + "".join(f"{1 / b!r},{e!r}\n" for b, e in zip(RATES, MODULI)))
    smk(path, "-j2")
    ds = read_dataset(path / "results/own/sweep.nc")
    cor = ds["cor"].sel(v0=10.0)
    # the file holds tau = 1 / beta, read back as beta = 1 / tau (972 comes back one ulp off)
    from_file = vcor.materials.models.Prony(PRONY3.E_inf, PRONY3.E, tuple(1.0 / (1.0 / b) for b in PRONY3.beta))
    assert cor.sel(material="my-prony").item() == vcor.simulate(from_file, 10.0, method="adaptive").cor
    assert cor.sel(material="my-sls").item() == cor.sel(material="sls").item()
    # the table is an input: editing it recomputes the shard that uses it
    (path / "data/prony3.csv").write_text("tau,E\n" + "".join(f"{1 / b!r},{2 * e!r}\n" for b, e in zip(RATES, MODULI)))
    dry = smk(path, "-n", "-j1").stdout
    assert "sweep_shard" in dry and "config_material" in dry


@pytest.mark.slow
def test_workflow_refuses_a_bad_config_material(make_project, smk, tmp_path):
    bad = {**CONFIG, "materials": {"my-sls": {"model": "sls", "E_glassy": 15e6, "alpha": 3000, "beta": 1200}},
           "scenes": {"own": {"materials": ["my-sls"], "grid": {"v0": [5.0]}}}}
    out = smk(make_project(tmp_path, bad), "-n", check=False)
    assert out.returncode != 0
    assert "materials.my-sls" in out.stdout + out.stderr and "alpha must be in [0, beta]" in out.stdout + out.stderr
    taken = {**CONFIG, "materials": {"sls": {"model": "elastic", "E": 1e6}}, "scenes": bad["scenes"]}
    (tmp_path / "t").mkdir()
    out = smk(make_project(tmp_path / "t", taken), "-n", check=False)
    assert "materials.sls: the name is taken by a preset" in out.stdout + out.stderr


@pytest.mark.parametrize("case, sphere, plate", [(1, 7800.0, 1100.0), (2, 1100.0, 1100.0), (3, 7800.0, 1100.0),
                                                 (4, 1100.0, 7800.0)])
def test_the_cases_are_shortcuts_with_their_densities(case, sphere, plate):
    """The viscoelastic body has the polymer's density, a stiff elastic one steel's (cases 2
    and 4 used to take case 3's steel sphere and polymer plate); given densities still win."""
    from vcor.contact.impact import Geometry

    g = Geometry(case=case)
    assert (g.sphere_density, g.plate_density) == (sphere, plate)
    assert Geometry(case=case, rho_a=2000.0, rho_b=3000.0).sphere_density == 2000.0
    assert Geometry(case=case, rho_a=2000.0, rho_b=3000.0).plate_density == 3000.0
    assert g.mass == pytest.approx(4 / 3 * 3.141592653589793 * 0.01**3 * sphere, rel=1e-15)


WLF = {"model": "wlf", "C1": 8.86, "C2": 101.6, "T_ref": 20.0}
T_CONFIG = {
    "shard_size": 100,
    "material_dir": "results/materials",
    "materials": {"warm-prony": {"model": "prony", "E_inf": E_INF, "E": MODULI, "beta": RATES, "shift": WLF}},
    "scenes": {"temp": {"materials": ["warm-prony"], "grid": {"v0": [1.0, 10.0], "T": [0.0, 20.0, 40.0]}}},
}


@pytest.mark.slow
def test_temperature_axis_shifts_the_material(make_project, smk, tmp_path):
    """A material with a shift function; T (deg C) as a grid axis, E(t; T) = E(t / a_T)."""
    from vcor.materials import shift as tts

    path = make_project(tmp_path, T_CONFIG)
    smk(path, "-j2")
    ds = read_dataset(path / "results/temp/sweep.nc")
    assert ds["T"].attrs["units"] == "degC"
    shift = tts.ShiftFunction.from_spec(WLF)
    for T in (0.0, 20.0, 40.0):
        mat = tts.time_shifted(PRONY3, shift.log_aT(T))
        got = ds["cor"].sel(material="warm-prony", v0=10.0, T=T).item()
        assert got == vcor.simulate(mat, 10.0, method="adaptive").cor
    at_ref = ds["cor"].sel(material="warm-prony", v0=10.0, T=20.0).item()
    assert at_ref == vcor.simulate(PRONY3, 10.0, method="adaptive").cor
    # colder is stiffer-and-slower: the curve moves, it is not the same number
    assert ds["cor"].sel(v0=10.0, T=0.0).item() != ds["cor"].sel(v0=10.0, T=40.0).item()


@pytest.mark.parametrize("change, words", [
    (lambda c: c["scenes"]["temp"].update(materials=["sls"]), ["scenes.temp", "'sls'", "no shift function"]),
    (lambda c: c["scenes"]["temp"]["grid"].update(T=[-90.0, 20.0]), ["scenes.temp.grid.T", "(-81.6, inf) deg C"]),
    (lambda c: c["materials"]["warm-prony"]["shift"].update(C2=-5), ["materials.warm-prony.shift.C2", "(0, inf)"]),
])
@pytest.mark.slow
def test_temperature_axis_errors_name_the_key(make_project, smk, tmp_path, change, words):
    import copy

    cfg = copy.deepcopy(T_CONFIG)
    change(cfg)
    out = smk(make_project(tmp_path, cfg), "-n", check=False)
    text = out.stdout + out.stderr
    assert out.returncode != 0
    for w in words:
        assert w in text, (w, text[-2000:])


def test_a_changed_shift_function_changes_the_identity():
    from vcor.materials import Catalogue

    other = {**T_CONFIG["materials"]["warm-prony"], "shift": {**WLF, "C1": 9.0}}
    a = Catalogue(specs=T_CONFIG["materials"]).identity("warm-prony")
    b = Catalogue(specs={"warm-prony": other}).identity("warm-prony")
    assert a != b
    # every model shifts (one time-temperature scaling, vcor.materials.Material.scaled)
    assert from_spec({"model": "fractional", "E0": 1e6, "E1": 1e6, "shift": WLF}, name="f").kind == "fractional"
    with pytest.raises(ValueError, match="materials.f.shift.C2"):
        from_spec({"model": "fractional", "E0": 1e6, "E1": 1e6, "shift": {**WLF, "C2": -1.0}}, name="f")


def test_a_scene_without_a_temperature_axis_takes_its_materials_without_shift_functions():
    """A scene without a T axis is given the catalogue without config shift functions: the same material,
    the identity of that material without a shift function (so an edited C1 changes none of its points),
    while a scene with a T axis keeps the shift and its identity."""
    from vcor.materials import Catalogue
    from vcor.study.config import load_project

    other = {**T_CONFIG["materials"]["warm-prony"], "shift": {**WLF, "C1": 9.0}}
    bare = {k: v for k, v in other.items() if k != "shift"}
    for spec in (T_CONFIG["materials"]["warm-prony"], other):
        cat = Catalogue(specs={"warm-prony": spec})
        plain = cat.without_shifts()
        assert plain.shift("warm-prony") is None and cat.shift("warm-prony") is not None
        assert plain.material("warm-prony") == cat.material("warm-prony")
        assert plain.identity("warm-prony") == Catalogue(specs={"warm-prony": bare}).identity("warm-prony")
    cold = {"materials": ["warm-prony"], "grid": {"v0": [1.0]}}
    config = {**T_CONFIG, "scenes": {**T_CONFIG["scenes"], "cold": cold}}
    project = load_project(config)
    assert project.scene_catalogue("cold").shift("warm-prony") is None
    assert project.scene_catalogue("temp").shift("warm-prony") is not None
    entry = {"sphere": {"material": "warm-prony"}, "v0": [1.0, 3.0]}
    project = load_project({**config, "dem": {"cold": entry, "warm": {**entry, "T": [0.0, 20.0]}}})
    assert project.dem_catalogue("cold").shift("warm-prony") is None
    assert project.dem_catalogue("warm").shift("warm-prony") is not None


def test_a_catalogue_subset_holds_the_named_materials_and_what_they_are_built_from(tmp_path):
    from vcor.materials import Catalogue

    (tmp_path / "x.csv").write_text("v0,cor\n1,0.8\n")
    cat = Catalogue(specs={"z-mat": {"model": "sls", "E_glassy": 1e7, "alpha": 300.0, "beta": 1200.0}, "other": {}},
                    fits={"f": {"model": "cerf"}, "g": {"model": "cerf"}},
                    calibrations={"cal": {"material": "f", "data": "x.csv"}, "cal2": {"material": {"model": "sls"}}},
                    material_dir="m", base_dir=str(tmp_path))
    sub = cat.subset(["sls", "cal", "z-mat", {"model": "sls"}])  # a preset and an inline spec need no entry
    assert (sub.specs, list(sub.fits), list(sub.calibrations)) == ({"z-mat": cat.specs["z-mat"]}, ["f"], ["cal"])
    assert (sub.material_dir, sub.base_dir) == ("m", str(tmp_path))
    assert sub.identity("cal") == cat.identity("cal")  # what the jobs record is what planning computed
    assert list(cat.subset(["g", "f"]).fits) == ["f", "g"]  # name order, whatever the config's
