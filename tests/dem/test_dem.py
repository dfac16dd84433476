"""The DEM bridge (docs, "DEM codes"): particle-particle collisions, each DEM law fitted to vcor's
COR with its error, the dataset and table, and bad dem: entries refused before any job."""

import csv
import json
import math

import numpy as np
import pytest
import yaml

import vcor
from vcor import materials as M
from vcor.dem import export, fit, laws, trend
from vcor.study.config import load_project

KV = M.KelvinVoigt(15e6, 1e-4)


@pytest.mark.parametrize("material", ["sls", "butyl-prony3", "kelvin-voigt", "butyl-fc"])
@pytest.mark.parametrize("method", ["adaptive", "direct"])
def test_two_equal_spheres_are_one_half_sphere_on_a_rigid_target(material, method):
    """Two equal spheres (R, rho) give the COR of one sphere of radius R/2 and density 4 rho on a rigid
    target with the modulus halved, to 1e-9, in every method that solves the material."""
    r, rho, nu = 0.01, 1100.0, 0.45
    pair = vcor.simulate(material, 5.0, target={"sphere": {}}, r=r, rho_a=rho, nu=nu, method=method)
    half = vcor.simulate(M.get(material).scaled(0.5), 5.0, rigid=True, r=r / 2, rho_a=4 * rho, nu=nu, method=method)
    assert pair.ok and half.ok
    assert abs(pair.cor - half.cor) < 1e-9 and abs(pair.t0 / half.t0 - 1) < 1e-9


def test_target_keyword():
    """``target``: rigid is the default geometry with rigid=True; a twin sphere by default; a sphere of
    another material combines by Eq. 1 (every method; the default adaptive within 1e-6 of direct); bad
    targets are refused naming them."""
    assert vcor.simulate("sls", 5.0, target="rigid").cor == vcor.simulate("sls", 5.0, rigid=True).cor
    twin = vcor.simulate("sls", 5.0, target={"sphere": {}}, r=0.01)
    same = vcor.simulate("sls", 5.0, target={"sphere": {"material": "sls", "r": 0.01, "rho": 1100.0, "nu": 0.5}},
                         r=0.01)
    assert twin.cor == same.cor
    mixed = vcor.simulate("sls", 5.0, target={"sphere": {"material": "butyl-prony3"}}, method="direct",
                          steps_per_contact=16000)
    assert mixed.ok and mixed.cor != twin.cor
    fast = vcor.simulate("sls", 5.0, target={"sphere": {"material": "butyl-prony3"}})
    assert fast.ok and fast.method == "adaptive" and abs(fast.cor / mixed.cor - 1) <= 1e-6
    with pytest.raises(ValueError, match=r"sphere.material \(kelvin-voigt\) on target.sphere.material \(sls\)"):
        vcor.simulate("kelvin-voigt", 5.0, target={"sphere": {"material": "sls"}})
    for bad, words in [({"sphere": {}, "plate": {}}, "one kind"), ("wall", "target must be"),
                       ({"sphere": {"radius": 1}}, "radius")]:
        with pytest.raises(ValueError, match=words):
            vcor.simulate("sls", 5.0, target=bad)
    with pytest.raises(ValueError, match=r"\['h'\]"):
        vcor.simulate("sls", 5.0, target={"sphere": {}}, h=0.01)


def test_kelvin_voigt_pair_is_the_brilliantov_law():
    """A Kelvin-Voigt sphere pair: the hereditary law is Brilliantov's, so lammps-viscoelastic fits it to
    1e-4 over 0.01..10 m/s, with A = tau and eta_n0 = 2 E_eff tau / m_eff (closed form)."""
    v0 = np.geomspace(0.01, 10.0, 25)
    col = fit.collision(KV, v0, sphere={"r": 0.005, "rho": 1200.0, "nu": 0.45}, target={"sphere": {}})
    laws_ = fit.fit_laws(col)
    e_eff = 15e6 / (2 * (1 - 0.45**2))
    m_eff = 1200.0 * 4 / 3 * math.pi * 0.005**3 / 2
    closed = 2 * e_eff * 1e-4 / m_eff
    err = np.max(np.abs(laws_["lammps-viscoelastic"]["cor"] - col.cor))
    print(f"\nKelvin-Voigt pair: max error {err:.2e}, eta_n0 {laws_['lammps-viscoelastic']['eta_n0']:.8g} "
          f"(closed form {closed:.8g}), A {laws_['mercurydpm-bshp']['A']:.8g} s")
    assert err <= 1e-4
    assert col.contact.e_eff == pytest.approx(e_eff, rel=1e-12) and col.contact.m_eff == pytest.approx(m_eff, rel=1e-12)
    assert laws_["lammps-viscoelastic"]["eta_n0"] == pytest.approx(closed, rel=1e-5)
    assert laws_["mercurydpm-bshp"]["A"] == pytest.approx(1e-4, rel=1e-5)
    assert laws_["yade-mindlin"]["vn"] == pytest.approx(math.sqrt(0.01 * 10.0))
    # Yade's en at vn maps back to the same A through the Pade (the law Yade applies)
    b = col.contact.b(laws_["mercurydpm-bshp"]["A"], laws_["yade-mindlin"]["vn"])
    assert laws_["yade-mindlin"]["en"] == pytest.approx(float(vcor.spheres.cor_pade_force(b)), rel=1e-12)


def test_a_hereditary_curve_the_one_parameter_laws_cannot_follow():
    """The paper's SLS, sphere on a rigid wall: its COR rises with speed where every Brilliantov curve
    falls; the dataset says by how much (the numbers the docs quote are printed here)."""
    v0 = np.geomspace(0.1, 10.0, 13)
    col = fit.collision("sls", v0, sphere={"r": 0.005}, target="rigid")
    laws_ = fit.fit_laws(col)
    ds = export.dem_dataset("t", [col], [laws_])
    errs = {m: float(ds["max_abs_error"].sel(model=m)) for m in laws.MODELS}
    print("\nSLS on a wall, 0.1..10 m/s: max abs error " + ", ".join(f"{m} {e:.3f}" for m, e in errs.items()))
    assert np.all(np.diff(col.cor) > 0)  # rising
    assert errs["table"] == 0.0
    assert errs["lammps-viscoelastic"] == errs["mercurydpm-bshp"] == errs["yade-mindlin"] > 0.05
    assert 0.0 < errs["lammps-coeff-restitution"] < errs["lammps-viscoelastic"]
    assert laws_["lammps-coeff-restitution"]["e"] == pytest.approx(float(np.mean(col.cor)))
    # the Brilliantov laws fall where vcor rises: flagged per law, said in words, the table named
    opposed = {m: int(ds["opposite_trend"].sel(model=m)) for m in laws.MODELS}
    assert opposed == {"lammps-viscoelastic": 1, "lammps-coeff-restitution": 0, "lammps-hereditary": 0,
                       "mercurydpm-bshp": 1, "yade-mindlin": 1, "table": 0}
    # vcor's own law in LAMMPS follows the curve (its error is LAMMPS's time step's) and is named as the route
    assert errs["lammps-hereditary"] < 1e-5
    note = ds.attrs["trend_warning"]
    print(note)
    for words in ("vcor's COR rises", "lammps-viscoelastic, mercurydpm-bshp, yade-mindlin fall", "cor_lookup",
                  f"{col.cor[0]:.3f} at 0.1 m/s", "lammps-hereditary: pair_style vcor/hereditary"):
        assert words in note, words


def test_no_trend_warning_where_the_law_follows():
    """A Kelvin-Voigt pair: vcor's COR and the Brilliantov law fall together; nothing is flagged."""
    col = fit.collision(KV, np.geomspace(0.1, 10.0, 7), sphere={"r": 0.005, "rho": 1200.0, "nu": 0.45},
                        target={"sphere": {}})
    ds = export.dem_dataset("kv", [col], [fit.fit_laws(col)])
    assert not ds["opposite_trend"].values.any() and ds.attrs["trend_warning"] == ""
    assert trend.trend(col.cor, np.isfinite(col.cor)) == -1
    assert trend.trend([0.5, 0.5005], [True, True]) == 0 and trend.trend([0.5, 0.502], [True, True]) == 1
    # opposite trends are flagged only where the law misses the curve by more than the bound
    ok = np.ones(3, dtype=bool)
    rising, falling = np.array([0.80, 0.805, 0.81]), np.array([[0.815, 0.805, 0.795]])
    assert not trend.opposite(rising, falling, ok, 0.02)[0] and trend.opposite(rising, falling, ok, 0.01)[0]


def test_dataset_layout_units_and_the_within_range():
    v0 = np.geomspace(0.1, 10.0, 5)
    col = fit.collision("sls", v0, sphere={"r": 0.005}, target={"sphere": {}})
    ds = export.dem_dataset("t", [col], [fit.fit_laws(col)])
    assert list(ds["model"].values) == list(laws.MODELS)
    assert ds["cor_model"].dims == ("model", "v0") and ds["cor"].dims == ("v0",)
    for var, unit in [("cor", "1"), ("eta_n0", "m-1 s-1"), ("A", "s"), ("e", "1"), ("vn", "m s-1"), ("E_lammps", "Pa"),
                      ("v0_within_lo", "m s-1"), ("v0", "m s-1"), ("young", "Pa"), ("E_eff", "Pa"),
                      ("opposite_trend", "1"), ("soe_error", "1")]:
        assert ds[var].attrs["units"] == unit, var
    # an SLS pair's kernel is its own Prony series: no approximation
    assert ds["soe_error"].dims == ("v0",) and np.all(ds["soe_error"].values == 0.0)
    # Yade's young: both bodies of this modulus give Yade's E* = E_eff
    young, nu = float(ds["young"]), col.contact.nu
    assert young * young / (2 * (1 - nu**2) * young) == pytest.approx(float(ds["E_eff"]), rel=1e-12)
    assert ds.attrs["yade_version_required"] == "2024.02a"
    assert "2024.02a" in json.loads(ds.attrs["models"])["yade-mindlin"]["requires"]
    np.testing.assert_array_equal(ds["error"].values, ds["cor_model"].values - ds["cor"].values[None, :])
    assert export.within_range(np.arange(6.0), np.array([0.02, 0.0, 0.005, 0.02, 0.0, 0.0])) == (1.0, 2.0)
    assert all(math.isnan(x) for x in export.within_range(np.arange(2.0), np.array([0.5, 0.5])))


def test_a_two_body_entry_stores_its_fitted_modulus_error_per_speed():
    """An elastic aluminium sphere on an SLS plate (Eq. 1, an exponential sum fitted to soe_tol) with no
    solver given: every speed ok, and the fit's error stored per speed (0 < soe_error <= 1e-10) and named."""
    v0 = np.array([0.1, 1.0, 10.0])
    col = fit.collision({"model": "elastic", "E": 7.0e10}, v0, sphere={"r": 0.005, "rho": 2700.0},
                        target={"plate": {"material": "sls", "h": 0.01}})
    ds = export.dem_dataset("alu", [col], [fit.fit_laws(col, ["table"])])
    assert list(col.status) == ["ok"] * 3
    assert np.all((ds["soe_error"].values > 0.0) & (ds["soe_error"].values <= 1e-10))
    assert "exponential sums" in ds["soe_error"].attrs["long_name"]


BASE = {"dem": {"d": {"sphere": {"material": "sls", "r": 0.005}, "target": {"sphere": {}},
                      "v0": {"start": 0.1, "stop": 10, "num": 5, "log": True}}}}


def _with(**changes):
    cfg = yaml.safe_load(yaml.safe_dump(BASE))
    cfg["dem"]["d"].update(changes)
    return cfg


@pytest.mark.parametrize("cfg, words", [
    (_with(target={"sphere": {}, "plate": {}}), ["dem.d.target", "one kind"]),
    (_with(v0={"start": 10, "stop": 0.1, "num": 5}), ["dem.d.v0", "stop > start"]),
    (_with(v0=[0.0, 1.0]), ["dem.d.v0", "> 0 m/s"]),
    (_with(v0=[1.0]), ["dem.d.v0", "at least two"]),
    (_with(T=[0, 20]), ["dem.d.T", "no shift function"]),
    (_with(models=["lammps-hooke"]), ["dem.d.models", "lammps-viscoelastic"]),
    (_with(sphere={"material": "rubber"}), ["dem.d.sphere.material", "rubber"]),
    (_with(sphere={"r": 0.005}), ["dem.d.sphere", "material"]),
    (_with(target={"sphere": {"material": "kelvin-voigt"}}),
     ["dem.d", "sphere.material (sls) on target.sphere.material (kelvin-voigt)", "no method"]),
    (_with(speed=3), ["dem.d", "speed"]),
    (_with(sphere={"material": {"model": "prony", "file": "../x.nc"}}), ["dem.d.sphere.material.file", "inside"]),
    (_with(solver={"methd": "direct"}),
     ["dem.d.solver", "unknown solver option(s) ['methd']", "did you mean 'method'"]),
    (_with(target={"plate": {"material": "sls", "h": -0.01}}), ["dem.d.target.plate.h: must be in [1e-09, 1000] m"]),
    (_with(target={"sphere": {"h": 0.01}}), ["dem.d.target.sphere: unknown key(s) ['h']"]),
], ids=["two kinds", "reversed range", "zero speed", "one speed", "T without shift", "unknown model",
        "unknown material", "no material", "Kelvin-Voigt partner", "unknown key", "file outside", "solver key",
        "target key range", "target unknown key"])
def test_bad_dem_entries_are_refused_before_any_job(cfg, words):
    with pytest.raises(ValueError) as err:
        load_project(cfg, ".")
    for w in words:
        assert w in str(err.value), (w, str(err.value))


def test_the_parameters_file_lists_every_law_with_units(tmp_path):
    """parameters.csv: the code versions as comments, then every law's parameters with units (the
    modulus each code takes among them) and the contact; values equal to the dataset's."""
    col = fit.collision("sls", np.geomspace(0.1, 10.0, 5), sphere={"r": 0.005}, target="rigid")
    ds = export.dem_dataset("t", [col], [fit.fit_laws(col)])
    path = tmp_path / "parameters.csv"
    export.parameters_csv(path, ds)
    text = path.read_text()
    assert "# yade-mindlin requires: Yade >= 2024.02a" in text
    rows = list(csv.DictReader(line for line in text.splitlines() if not line.startswith("#")))
    got = {(r["model"], r["parameter"]): (float(r["value"]), r["unit"]) for r in rows}
    for model, params in laws.PARAMETERS.items():
        for p, (unit, _) in params.items():
            series = export.TERM_DIM in ds[p].dims  # one row per term of a series: hereditary_E[1], ...
            assert got[(model, f"{p}[1]" if series else p)][1] == unit
    assert got[("yade-mindlin", "young")] == (pytest.approx(float(ds["young"]), rel=1e-11), "Pa")
    assert got[("mercurydpm-bshp", "E_eff")][0] == pytest.approx(float(ds["E_eff"]), rel=1e-11)
    assert got[("lammps-coeff-restitution", "E_lammps")][0] == pytest.approx(float(ds["E_lammps"]), rel=1e-11)
    assert got[("contact", "density_1")] == (1100.0, "kg m-3")
    # the SLS on a wall: E/(1 - nu^2) = 20 MPa, of which E_inf = 5 MPa, and the rate 1200/s
    assert [got[("lammps-hereditary", p)] for p in ("hereditary_E_inf", "hereditary_E[1]", "hereditary_beta[1]")] == [
        (pytest.approx(5e6, rel=1e-12), "Pa"), (pytest.approx(15e6, rel=1e-12), "Pa"), (1200.0, "s-1")]


def test_a_temperature_entry_fits_every_law_per_temperature():
    spec = {"sphere": {"material": {"model": "sls", "E_glassy": 15e6, "alpha": 300, "beta": 1200,
                                    "shift": {"model": "wlf", "C1": 8.0, "C2": 120.0, "T_ref": 20.0}}, "r": 0.005},
            "target": "rigid", "v0": [0.5, 2.0, 8.0], "T": [0.0, 20.0, 40.0]}
    project = load_project({"dem": {"hot": spec}}, ".")
    from vcor.study import dem

    cols, fits, temps = dem.run_dem("hot", spec, project.catalogue)
    ds = export.dem_dataset("hot", cols, fits, temps)
    assert ds["eta_n0"].dims == ("T",) and ds["cor_model"].dims == ("T", "model", "v0")
    at20 = fit.collision("sls", [0.5, 2.0, 8.0], sphere={"r": 0.005, "rho": 1100.0, "nu": 0.5}, target="rigid")
    np.testing.assert_array_equal(ds["cor"].sel(T=20.0).values, at20.cor)  # T_ref: the material as given
    assert len(set(np.round(ds["eta_n0"].values, 6))) == 3  # one value per temperature


def test_a_corrupt_dem_dataset_is_found_by_the_archive_check(tmp_path):
    from vcor.study import archive

    project = load_project(BASE, str(tmp_path))
    path = tmp_path / "results" / "dem" / "d.nc"
    path.parent.mkdir(parents=True)
    path.write_bytes(b"not a NetCDF file")
    assert [p for p, _ in archive.problems(project, tmp_path)] == [path]


def test_a_deck_holds_the_lammps_laws_the_entry_fitted(tmp_path):
    """An entry with one LAMMPS law gets a deck of that law alone (its default, the only model it
    accepts); one with none is refused naming the models a deck needs."""
    from vcor.dem import lammps

    col = fit.collision("sls", np.geomspace(0.1, 10.0, 5), sphere={"r": 0.005}, target="rigid")
    for only, name, var in [("lammps-viscoelastic", "viscoelastic", "eta_n0"),
                            ("lammps-coeff-restitution", "coeff_restitution", "e")]:
        ds = export.dem_dataset("t", [col], [fit.fit_laws(col, [only, "table"])])
        lammps.write_deck(tmp_path / "in.wall", ds)
        text = (tmp_path / "in.wall").read_text()
        assert f"variable model   index {name}\n" in text and f"print 'model must be {name}'" in text
        assert f"variable {var:<7s} index {float(ds[var]):.12g}" in text
        other = "e" if var == "eta_n0" else "eta_n0"
        assert f"variable {other:<7s} index" not in text and "elif" not in text
    with pytest.raises(ValueError, match="no LAMMPS law"):
        lammps.write_deck(tmp_path / "x", export.dem_dataset("t", [col], [fit.fit_laws(col, ["table"])]))


def test_every_file_the_dem_rules_write_is_a_target_of_the_entry():
    """The default target and an entry's MANIFEST.txt require every output of the DEM rules (the entry's
    job writes ``Project.dem_files``, workflow/rules/dem.smk; the figure rule its PNG and PDF), so
    `snakemake results/dem/<name>/MANIFEST.txt` builds them all."""
    from pathlib import Path

    from vcor.study import paths

    rules = (Path(__file__).resolve().parents[2] / "workflow" / "rules" / "dem.smk").read_text()
    assert "**PROJECT.dem_files(_dem)" in rules and "vpaths.DEM_FIGURE" in rules
    project = load_project(BASE, ".")
    files = project.dem_files("d")
    # the entry fits LAMMPS and Yade laws and has vcor's own law in LAMMPS
    assert set(files) == {"nc", "table", "parameters", "deck", "hereditary", "yade"}
    figures = {paths.fmt(paths.DEM_FIGURE, dem="d", ext=e) for e in ("png", "pdf")}
    expected = set(files.values()) | figures
    targets = set(project.dem_targets("d"))
    assert expected == targets, sorted(expected ^ targets)


def test_an_entrys_solver_method_is_its_own_or_the_default():
    from vcor.solvers.options import DEFAULT_METHOD
    from vcor.study.dem import solver_method

    assert solver_method({"sphere": {}}) == DEFAULT_METHOD == solver_method({"solver": None})
    assert solver_method({"solver": {"method": "direct"}}) == "direct"


def test_the_files_a_dem_user_reads_say_how_well_each_law_follows_vcor(tmp_path):
    """The deck, the Yade script and the parameters file carry, in words, each law's largest error against
    vcor's COR (the dataset's max_abs_error), the trend warning and the speeds whose vcor result is flagged:
    a DEM user who reads only them is told what the dataset says."""
    import vcor

    spec = {"sphere": {"material": {"model": "sls", "E_glassy": 20e6, "alpha": 500, "beta": 2500}, "r": 0.004},
            "target": {"sphere": {}}, "v0": {"start": 0.2, "stop": 5, "num": 6, "log": True}}
    export_ = vcor.dem_export(spec, name="rising")
    files = export_.write(tmp_path)
    ds = export_.dataset
    assert ds.attrs["trend_warning"] and int(ds["validity"].max()) > 0
    # the words point to the dataset's validity_message: it holds, per flagged speed, why
    flagged = ds["validity"].values != 0
    reasons = ds["validity_message"].values
    assert all(reasons[flagged]) and not any(reasons[~flagged]), reasons
    assert "s_max / r" in reasons[flagged][-1] and ds["validity_message"].attrs["long_name"]
    for key, names in (("deck", ["lammps-viscoelastic", "lammps-coeff-restitution"]), ("yade", ["yade-mindlin"]),
                      ("parameters", [str(m) for m in ds["model"].values])):
        text = files[key].read_text()
        assert f"# WARNING: {ds.attrs['trend_warning']}" in text, key
        assert "is outside the model's stated range" in text, key
        for law in names:
            err = float(ds["max_abs_error"].sel(model=law))
            assert f"# {law}: largest |COR of the law - vcor's COR| {err:.3g} over the speeds" in text, (key, law)


def test_with_temperatures_each_law_is_said_per_temperature():
    """A law that misses at one temperature may follow vcor at another: the words give, per temperature,
    the largest error and the speeds within WITHIN (the dataset's values at that temperature)."""
    from vcor.study import dem

    spec = {"sphere": {"material": {"model": "sls", "E_glassy": 15e6, "alpha": 300, "beta": 1200,
                                    "shift": {"model": "wlf", "C1": 8.0, "C2": 120.0, "T_ref": 20.0}}, "r": 0.005},
            "target": "rigid", "v0": [0.5, 2.0, 8.0], "T": [0.0, 40.0], "models": ["lammps-viscoelastic"]}
    cols, fits, temps = dem.run_dem("hot", spec, load_project({"dem": {"hot": spec}}, ".").catalogue)
    ds = export.dem_dataset("hot", cols, fits, temps)
    [line] = [x for x in export.quality_lines(ds) if x.startswith("lammps-viscoelastic:")]
    errs = ds["max_abs_error"].sel(model="lammps-viscoelastic").values
    assert f"{float(np.max(errs)):.3g} over the speeds and temperatures" in line
    for T, e in zip(ds["T"].values, errs):
        assert f"at {T:g} degC {float(e):.3g}, " in line, line


def test_an_export_moves_aside_the_files_an_earlier_version_of_the_entry_wrote(tmp_path, capsys):
    """An entry written as a sphere pair and then as a sphere on a wall: the pair's decks (in.pair, and
    in.hereditary where the wall's material gets none) are moved aside as .stale, saying so; the wall's
    files are in place (the Yade script too, where the entry has no Yade law now)."""
    import vcor

    pair = {"sphere": {"material": "sls", "r": 0.005}, "target": {"sphere": {}}, "v0": [0.5, 2.0]}
    first = vcor.dem_export(pair, name="e").write(tmp_path)
    assert first["deck"].name == "in.pair" and "hereditary" in first
    wall = {**pair, "target": "rigid", "models": ["lammps-viscoelastic", "table"]}
    second = vcor.dem_export(wall, name="e").write(tmp_path)
    lammps_dir = second["deck"].parent
    assert second["deck"].name == "in.wall" and "hereditary" not in second
    assert sorted(p.name for p in lammps_dir.iterdir()) == ["in.hereditary.stale", "in.pair.stale", "in.wall"]
    assert sorted(p.name for p in first["yade"].parent.iterdir()) == ["collision.py.stale"]  # no Yade law now
    said = capsys.readouterr().err
    assert "in.pair is not a file of entry e as configured" in said and "in.pair.stale" in said
