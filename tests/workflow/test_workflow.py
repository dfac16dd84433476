"""Workflow end to end on a tiny config (copied into a temporary folder), dry runs, bad configs."""

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

import vcor
from vcor.io.netcdf import read_dataset
from vcor.materials import Catalogue
from vcor.study import shards

pytestmark = pytest.mark.slow  # each test runs Snakemake

ROOT = Path(__file__).resolve().parents[2]

TINY = {
    "shard_size": 3,
    "material_dir": "results/materials",
    "fits": {"tiny-prony": {"model": "prony", "n_terms": 3}, "unused-cerf": {"model": "cerf"}},
    "scenes": {
        "tiny": {
            "materials": ["sls"],
            "grid": {"v0": [2.0, 10.0], "beta": [1200.0, 2400.0]},
            "tie": {"alpha": {"to": "beta", "ratio": 0.25}},
            "histories": {"v0": 10.0, "runs": [["sls", "direct"], ["sls", "ive"]]},
            "figures": {"fig2": {}, "fig4": {"material": "sls"}},
        },
        "two": {
            "materials": ["butyl-fc", "butyl-prony3", "tiny-prony"],
            "grid": {"v0": [5.0, 10.0]},
            "figures": {"fig8": {}},
        },
        "balls": {
            "spheres": {"b": [0.01, 0.1, 1.0], "tau_ratio": [0.1]},
            "figures": {"spheres_eps": {}, "spheres_hereditary": {}},
        },
        "thin": {
            # h = 2 mm with direct: the contact (0.15 s) outlasts direct's 32 t_c horizon -> step-budget
            "materials": ["sls"],
            "grid": {"v0": [10.0], "h": [0.02, 0.002]},
            "solver": {"method": "direct", "steps_per_contact": 200},
            "figures": {"fig8": {}},
        },
    },
}




@pytest.fixture(scope="module")
def tiny_run(make_project, smk, tmp_path_factory):
    path = make_project(tmp_path_factory.mktemp("wf"), TINY)
    smk(path, "-j2")  # profiles/default is found by Snakemake itself
    return path


def test_outputs_exist(tiny_run):
    for f in ["tiny/sweep.nc", "tiny/histories.nc", "tiny/figures/fig2.png", "tiny/figures/fig2.pdf",
              "tiny/figures/fig4.png", "tiny/MANIFEST.txt", "thin/sweep.nc", "thin/figures/fig8.png"]:
        assert (tiny_run / "results" / f).stat().st_size > 0, f
    # nothing the scenes do not need: no moduli (fig1/fig5 not requested), no histories for "thin",
    # only the fit a scene uses
    assert not (tiny_run / "results/tiny/moduli.nc").exists()
    assert not (tiny_run / "results/thin/histories.nc").exists()
    assert (tiny_run / "results/materials/tiny-prony.nc").exists()
    assert not (tiny_run / "results/materials/unused-cerf.nc").exists()
    table = (tiny_run / "results/two/fit_metrics.txt").read_text()
    assert "tiny-prony" in table and "butyl-prony3" in table


def test_kernels_compiled_in_a_job_per_method(tiny_run):
    # the methods the run solves with: adaptive (scene tiny), direct (thin, histories), and ive (histories:
    # scipy's solve_ivp, nothing to compile, no job)
    logs = sorted(p.stem for p in (tiny_run / "results/logs/kernels").glob("*.log"))
    assert logs == ["adaptive", "direct"], logs
    assert "numba kernels of method adaptive ready" in (tiny_run / "results/logs/kernels/adaptive.log").read_text()
    assert sorted(p.stem for p in (tiny_run / "results/.kernels").glob("*.ready")) == logs


def test_missing_kernel_marks_rerun_nothing(smk, tiny_run):
    # an archive restored without results/.kernels: the marks come back, no finished job runs again
    for p in (tiny_run / "results/.kernels").glob("*.ready"):
        p.unlink()
    out = smk(tiny_run, "-n", "-j1")
    text = out.stdout + out.stderr
    marks = "results/.kernels: marks of adaptive, direct, ive-numba, paper, soe written (the project holds results"
    assert "Nothing to be done" in text and marks in text, text
    assert (tiny_run / "results/.kernels/adaptive.ready").exists()
    out = smk(tiny_run, "-n", "-j1")  # the marks written back keep the project up to date
    assert "Nothing to be done" in out.stdout + out.stderr, out.stdout + out.stderr


def test_fit_rule_deterministic_and_used(smk, tiny_run):
    import hashlib

    path = tiny_run / "results/materials/tiny-prony.nc"
    first = hashlib.sha256(path.read_bytes()).hexdigest()
    smk(tiny_run, "-j1", "--forcerun", "fit_material", "--until", "fit_material")
    assert hashlib.sha256(path.read_bytes()).hexdigest() == first
    mat = vcor.materials.from_file(path)
    assert len(mat.E) == 3
    ds = read_dataset(tiny_run / "results/two/sweep.nc")
    assert ds["cor"].sel(material="tiny-prony", v0=10.0).item() == vcor.simulate(mat, 10.0, method="adaptive").cor


def test_sweep_dataset_layout_and_values(tiny_run):
    ds = read_dataset(tiny_run / "results/tiny/sweep.nc")
    assert ds["cor"].dims == ("material", "v0", "beta")
    assert list(ds["v0"].values) == [2.0, 10.0] and list(ds["beta"].values) == [1200.0, 2400.0]
    for v in ["cor", "t0", "s_max", "f_max", "s_residual", "w_h", "omega_min", "energy_residual", "wall_time",
              "status", "v0", "beta"]:
        assert "units" in ds[v].attrs and "long_name" in ds[v].attrs, v
    assert ds["t0"].attrs["units"] == "s" and ds["v0"].attrs["units"] == "m s-1" and ds["f_max"].attrs["units"] == "N"
    assert "flag_values" in ds["status"].attrs and "ok" in ds["status"].attrs["flag_meanings"]
    for a in ["Conventions", "title", "history", "source", "references", "scene_config", "solver_settings",
              "materials"]:
        assert a in ds.attrs, a
    # the shards (archived too) carry the same units and long names: the aggregate takes them from there
    shard = read_dataset(min((tiny_run / "results/tiny/shards").glob("*.nc")))
    for v in shard.data_vars:
        assert "units" in shard[v].attrs or v.endswith("message"), v
        assert shard[v].attrs.get("long_name"), v
        assert {k: np.asarray(x).tolist() for k, x in shard[v].attrs.items()} == \
            {k: np.asarray(x).tolist() for k, x in ds[v].attrs.items()}, v
    stored = json.loads(ds.attrs["scene_config"])  # the effective scene: config + schema defaults
    for key in ("materials", "grid", "tie", "figures"):
        assert stored[key] == TINY["scenes"]["tiny"][key]
    assert stored["error_estimate"] is False
    assert json.loads(ds.attrs["solver_settings"])["solver"]["ghost"] == 0.5  # the resolved options
    assert ds["cor"].dtype == np.float64
    # a few points against the API (alpha tied to beta / 4)
    r = vcor.simulate(vcor.materials.SLS(15e6, 600.0, 2400.0), 2.0, method="adaptive")  # the sweep default
    assert ds["cor"].sel(material="sls", v0=2.0, beta=2400.0).item() == r.cor
    r = vcor.simulate("sls", 10.0, method="adaptive")
    assert ds["t0"].sel(material="sls", v0=10.0, beta=1200.0).item() == r.t0
    assert np.all(ds["status"].values == 0)
    two = read_dataset(tiny_run / "results/two/sweep.nc")
    assert list(two["material"].values) == ["butyl-fc", "butyl-prony3", "tiny-prony"]
    assert (two["cor"].sel(material="butyl-prony3", v0=5.0).item()
            == vcor.simulate("butyl-prony3", 5.0, method="adaptive").cor)


def test_failed_point_kept_with_status(tiny_run):
    ds = read_dataset(tiny_run / "results/thin/sweep.nc")
    st = ds["status"].sel(material="sls", v0=10.0)
    assert st.sel(h=0.02).item() == 0
    assert st.sel(h=0.002).item() == vcor.status.STATUS_CODES["step-budget"]
    assert np.isnan(ds["cor"].sel(material="sls", v0=10.0, h=0.002).item())
    assert "T_max" in str(ds["message"].sel(material="sls", v0=10.0, h=0.002).values)
    assert ds["cor"].sel(material="sls", v0=10.0, h=0.02).item() > 0


def test_spheres_dataset(tiny_run):
    from vcor import spheres as S

    ds = read_dataset(tiny_run / "results/balls/spheres.nc")
    assert ds["eps_numeric"].dims == ("rule", "b") and list(ds["rule"].values) == ["overlap", "force"]
    assert ds["eps_numeric"].sel(rule="force", b=0.1).item() == pytest.approx(S.cor_numeric(0.1, "force"), abs=1e-12)
    assert ds["eps_sls"].dims == ("tau_ratio", "rule", "b") and np.all(np.isfinite(ds["eps_sls"]))
    assert (tiny_run / "results/balls/figures/spheres_hereditary.png").stat().st_size > 0
    assert not (tiny_run / "results/balls/sweep.nc").exists()


def test_histories_dataset(tiny_run):
    ds = read_dataset(tiny_run / "results/tiny/histories.nc")
    assert list(ds["run"].values) == ["sls/direct", "sls/ive"]
    assert ds["t"].attrs["units"] == "s" and ds["F"].attrs["units"] == "N"
    assert ds["ghost"].sum() > 0
    assert abs(ds["cor"].values[0] - ds["cor"].values[1]) < 1e-6


def test_noop_rerun_and_extension_recomputes_only_new_points(smk, tiny_run, tmp_path):
    out = smk(tiny_run, "-n", "-j1")
    assert "Nothing to be done" in out.stdout + out.stderr
    cfg = json.loads(json.dumps(TINY))
    cfg["scenes"]["tiny"]["grid"]["v0"] = [2.0, 10.0, 20.0]
    (tiny_run / "config.yaml").write_text(yaml.safe_dump(cfg, sort_keys=False))
    try:
        out = smk(tiny_run, "-n", "-j1", "--quiet", "rules")
        text = out.stdout + out.stderr
        # 2 new points (2 beta at v0 = 20) -> 1 new shard; old shards untouched
        ids = {"sls": Catalogue().identity("sls")}
        plan = shards.plan_shards(cfg["scenes"]["tiny"], tiny_run / "results/tiny/shards", 3, ids)
        new = [k for k in plan if not (tiny_run / f"results/tiny/shards/{k}.nc").exists()]
        assert len(new) == 1 and sum(len(plan[k].points) for k in new) == 2
        assert all(p["v0"] == 20.0 for k in new for p in plan[k].points)
        lines = {ln.split()[0]: int(ln.split()[1]) for ln in text.splitlines() if len(ln.split()) == 2
                 and ln.split()[1].isdigit()}
        assert lines.get("sweep_shard") == 1, text
        assert lines.get("aggregate") == 1, text
        assert "histories" not in lines  # unchanged
    finally:
        (tiny_run / "config.yaml").write_text(yaml.safe_dump(TINY, sort_keys=False))


def test_report(smk, tiny_run):
    smk(tiny_run, "--report", "report.html")
    html = (tiny_run / "report.html").read_text(errors="replace")
    assert "fig4.png" in html
    # each figure has its own caption (workflow/report/figures/<name>.rst), with the scene's name
    assert "Fig. 4" in html and "Fig. 2" in html


def test_every_figure_has_a_caption():
    from vcor import plots

    captions = {p.stem for p in (ROOT / "workflow/report/figures").glob("*.rst")}
    assert set(plots.FIGURES) == captions


def test_one_job_draws_all_figures_of_a_scene(smk, tiny_run):
    # one figure of the scene asked for: the scene's one figures job draws both of its figures
    (tiny_run / "results/tiny/figures/fig2.png").unlink()
    out = smk(tiny_run, "-n", "-j1", "results/tiny/figures/fig2.png", "--quiet", "rules")
    text = out.stdout + out.stderr
    lines = {ln.split()[0]: int(ln.split()[1]) for ln in text.splitlines() if len(ln.split()) == 2
             and ln.split()[1].isdigit()}
    assert lines == {"figures_tiny": 1, "total": 1}, text
    smk(tiny_run, "-j1", "results/tiny/figures/fig2.png")
    for f in ("fig2.png", "fig2.pdf", "fig4.png", "fig4.pdf"):
        assert (tiny_run / "results/tiny/figures" / f).stat().st_size > 0
    smk(tiny_run, "-j1")  # the manifest lists the new bytes; the project is up to date for later tests
    out = smk(tiny_run, "-n", "-j1")
    assert "Nothing to be done" in out.stdout + out.stderr


def test_default_config_dry_run_and_scene_selection(make_project, smk, tmp_path):
    path = make_project(tmp_path, yaml.safe_load((ROOT / "config.yaml").read_text()))
    out = smk(path, "-n", "-j1", "--quiet", "rules")
    text = out.stdout + out.stderr
    assert "figure" in text and "sweep_shard" in text
    scenes = yaml.safe_load((ROOT / "config.yaml").read_text())["scenes"].values()
    figures = [f for s in scenes for f in s.get("figures", {})]
    assert {f"fig{i}" for i in range(1, 10)} <= set(figures)
    out = smk(path, "-n", "-j1", "results/hysteresis/MANIFEST.txt", "--quiet", "rules")
    text = out.stdout + out.stderr
    assert "histories" in text and "sweep_shard" not in text and "moduli" not in text


def test_a_fit_family_is_fitted_whole_in_one_job_and_a_new_use_reruns_nothing(make_project, smk, tmp_path):
    fits = {"f{n}": {"model": "prony", "n_terms": [1, 2, 3]}, "g{n}": {"model": "prony", "n_terms": [1, 2]},
            "f-{n}": {"model": "prony", "n_terms": [1, 2]}, "f_{n}": {"model": "prony", "n_terms": [1, 2]}}
    scenes = {"s": {"materials": ["f1"], "grid": {"v0": [1.0]}}}
    path = make_project(tmp_path, {"fits": fits, "scenes": scenes})
    out = smk(path, "-n", "-j1", "--quiet", "rules")
    text = out.stdout + out.stderr
    assert "fit_family_fN" in text and "fit_material" not in text and "fit_family_gN" not in text, text
    smk(path, "-j1")
    for n in (1, 2, 3):
        assert len(vcor.materials.from_file(path / f"results/materials/f{n}.nc").E) == n
    log = (path / "results/materials/logs/families/fN.log").read_text()
    assert all(f"fitted f{n}" in log for n in (1, 2, 3)), log
    # a scene that starts using f2 (and families whose job names would coincide) re-runs nothing of scene s
    scenes["t"] = {"materials": ["f2", "f-1", "f_1"], "grid": {"v0": [1.0]}}
    (path / "config.yaml").write_text(yaml.safe_dump({"fits": fits, "scenes": scenes}, sort_keys=False))
    out = smk(path, "-n", "-j1")
    planned = [line for line in (out.stdout + out.stderr).splitlines() if line.strip().startswith("output:")]
    assert any("results/t/sweep.nc" in line for line in planned), planned
    assert not any(f in line for line in planned for f in ("results/s/", "materials/f1", "materials/f2")), planned
    out = smk(path, "-n", "-j1", "--quiet", "rules")
    text = out.stdout + out.stderr
    assert "fit_family_fN" not in text and "fit_family_f_N" in text and "fit_family_f_N_2" in text, text


def test_other_materials_added_or_reordered_rerun_nothing(make_project, smk, tmp_path):
    """A job is given the catalogue entries of the materials it uses only (Catalogue.subset): a new fit
    or config material, or the fits block reordered, leaves every finished job finished."""
    fits = {"a-fit": {"model": "prony", "n_terms": 2}, "b-fit": {"model": "cerf"}}
    config = {"fits": fits, "scenes": {"s": {"materials": ["sls", "a-fit"], "grid": {"v0": [1.0, 3.0]}}}}
    path = make_project(tmp_path, config)
    smk(path, "-j1")
    config["fits"] = {"c-fit": {"model": "prony", "n_terms": 3}, "b-fit": fits["b-fit"], "a-fit": fits["a-fit"]}
    config["materials"] = {"my-sls": {"model": "sls", "E_glassy": 15.0e6, "alpha": 300.0, "beta": 1200.0}}
    (path / "config.yaml").write_text(yaml.safe_dump(config, sort_keys=False))
    out = smk(path, "-n", "-j1")
    assert "Nothing to be done" in out.stdout + out.stderr, out.stdout[-3000:]


def test_a_number_written_another_way_reruns_nothing(make_project, smk, tmp_path):
    """YAML reads ``5000000`` as an integer and ``5.0e+6`` as a float: one parameter, so rewriting a
    material's number in the other form leaves every finished job finished (the jobs are given the
    specs with every number a float, vcor.materials.specs.canonical)."""
    mat = "my-gel:\n    model: prony\n    E_inf: {}\n    E: [5.0e+6, 2.0e+6]\n    beta: [300.0, 4000.0]\n"
    scenes = "scenes:\n  s:\n    materials: [my-gel]\n    grid: {v0: [1.0, 3.0]}\n"
    path = make_project(tmp_path, {})
    (path / "config.yaml").write_text("materials:\n  " + mat.format("5.0e+6") + scenes)
    smk(path, "-j1")
    (path / "config.yaml").write_text("materials:\n  " + mat.format("5000000") + scenes)
    out = smk(path, "-n", "-j1")
    assert "Nothing to be done" in out.stdout + out.stderr, out.stdout[-3000:]


def test_a_changed_material_reruns_no_shard_without_its_points(make_project, smk, tmp_path):
    """A changed material re-runs no shard that holds none of its points (byte-identical files; its job
    is given the materials its points name), never re-runs a shard that holds its old points (they are
    planned anew with the shard's other points: no number is stored under the identity of another
    definition), and the sweep holds the new numbers."""
    mats = {"gel-a": {"model": "sls", "E_glassy": 15.0e6, "alpha": 300.0, "beta": 1200.0},
            "gel-b": {"model": "sls", "E_glassy": 20.0e6, "alpha": 200.0, "beta": 900.0}}
    config = {"materials": mats, "scenes": {"s": {"materials": ["gel-b"], "grid": {"v0": [1.0, 3.0]}}}}
    path = make_project(tmp_path, config)
    smk(path, "-j1")
    only_b = {p.name: p.read_bytes() for p in (path / "results/s/shards").glob("*.nc")}
    config["scenes"]["s"]["materials"] = ["gel-a", "gel-b"]
    config["scenes"]["s"]["grid"]["v0"] = [1.0, 3.0, 5.0]
    (path / "config.yaml").write_text(yaml.safe_dump(config, sort_keys=False))
    smk(path, "-j1")  # one new shard: gel-a at every speed, gel-b at 5 m/s
    changed = {**mats["gel-a"], "E_glassy": 25.0e6}
    config["materials"]["gel-a"] = changed
    (path / "config.yaml").write_text(yaml.safe_dump(config, sort_keys=False))
    out = smk(path, "-n", "-j1", "--quiet", "rules")
    text = out.stdout + out.stderr
    lines = {ln.split()[0]: int(ln.split()[1]) for ln in text.splitlines() if len(ln.split()) == 2
             and ln.split()[1].isdigit()}
    assert lines.get("sweep_shard") == 1, text
    smk(path, "-j1")
    assert {p.name: p.read_bytes() for p in (path / "results/s/shards").glob("*.nc") if p.name in only_b} == only_b
    with xr.open_dataset(path / "results/s/sweep.nc") as ds:
        a = [str(m) for m in ds["material_label"].values].index("gel-a")
        for v0 in (1.0, 5.0):
            cor = float(ds["cor"].isel(material=a).sel(v0=v0))
            assert cor == pytest.approx(vcor.simulate(changed, v0).cor, rel=1e-9)


def test_configfile_runs_only_its_scenes(make_project, smk, tmp_path):
    """``--configfile my.yaml`` replaces config.yaml (it is not merged with it): only my.yaml's scenes
    are planned (docs, "Your own scenes")."""
    path = make_project(tmp_path, yaml.safe_load((ROOT / "config.yaml").read_text()))
    mine = {"scenes": {"mine": {"materials": ["sls"], "grid": {"v0": [1.0, 2.0]}, "figures": {"fig8": {}}}}}
    (path / "my.yaml").write_text(yaml.safe_dump(mine))
    out = smk(path, "-n", "-j1", "--configfile", "my.yaml")
    text = out.stdout + out.stderr
    assert "results/mine/sweep.nc" in text
    assert "results/sls/" not in text and "results/butyl/" not in text


def test_a_config_error_names_its_file_line_and_column(make_project, smk, tmp_path):
    """A refusal that names a key path says where that key is: the --configfile, line and column."""
    path = make_project(tmp_path, TINY)
    (path / "my.yaml").write_text("scenes:\n  mine:\n    materials: [sls]\n    grid:\n      v0: ['36 km/h', 1.0]\n")
    out = smk(path, "-n", "-j1", "--configfile", "my.yaml", check=False)
    said = out.stdout + out.stderr
    assert out.returncode != 0 and "config file my.yaml, line 5, column 12: scenes.mine.grid.v0[0]: " in said, said
    (path / "my.yaml").write_text("scenes:\n  mine:\n    materials: [sls]\n    grid: {v0: [1.0], h: [0.01, -0.1]}\n")
    out = smk(path, "-n", "-j1", "--configfile", "my.yaml", check=False)
    said = out.stdout + out.stderr
    assert "config file my.yaml, line 4, column 33: scenes.mine.grid.h[1]: point" in said, said
    out = smk(path, "-n", "-j1", "--config", "job_seconds=-1", check=False)
    said = out.stdout + out.stderr  # set on the command line: no file holds it
    assert "config: job_seconds: must be > 0 s, got -1 s" in said and "config file config.yaml, line" not in said, said


@pytest.mark.parametrize(
    "mutate, words",
    [
        (lambda c: c["scenes"]["tiny"]["grid"].pop("v0"), ["v0"]),
        (lambda c: c["scenes"]["tiny"]["grid"].update(v0=[-1.0, 2.0]), ["scenes.tiny.grid.v0"]),
        (lambda c: c["scenes"]["tiny"].update(materials=["unobtainium"]), ["scenes.tiny.materials", "unobtainium"]),
        (lambda c: c["scenes"]["tiny"]["figures"].update(fig10={}), ["fig10"]),
        (lambda c: c["scenes"]["tiny"].update(solver={"method": "euler"}), ["euler"]),
        (lambda c: c["scenes"]["tiny"]["geometry"].update(nu=0.7) if "geometry" in c["scenes"]["tiny"]
         else c["scenes"]["tiny"].update(geometry={"nu": 0.7}), ["nu"]),
        (lambda c: c["scenes"]["thin"]["grid"].update(h=[0.02, -0.1]), ["scenes.thin", "h must be in"]),
        (lambda c: c["scenes"]["tiny"].update(materials=["butyl-fc"]),
         ["scenes.tiny.grid.beta", "no parameter 'beta'"]),
        (lambda c: c.update(shard_size=0), ["shard_size"]),
        (lambda c: c["scenes"]["thin"].update(figures={"fig2": {}}), ["scenes.thin", "histories"]),
        (lambda c: c["scenes"]["thin"].update(figures={"master_curve": {"materials": ["sls"]}}),
         ["scenes.thin.figures.master_curve.materials", "list of fits"]),
        (lambda c: c["scenes"]["tiny"]["figures"].update(cor_temperature={}), ["cor_temperature", "grid axis T"]),
    ],
)
def test_bad_config_fails_before_any_job(make_project, smk, tmp_path, mutate, words):
    cfg = json.loads(json.dumps(TINY))
    mutate(cfg)
    path = make_project(tmp_path, cfg)
    out = smk(path, "-n", "-j1", check=False)
    text = out.stdout + out.stderr
    assert out.returncode != 0
    for w in words:
        assert w in text, (w, text[-2000:])
    assert not (path / "results").exists()


# We ship no conda environment (conda channels are unreachable here, so it could not be tested; the README
# says so). Snakemake's linter asks for one on every rule; that is the only lint we accept.
ACCEPTED_LINT = "Specify a conda environment or container for each rule."


def test_lint_and_format(smk):
    out = smk(ROOT, "--lint", check=False)
    text = out.stdout + out.stderr
    items = [line.strip() for line in text.splitlines() if line.strip().startswith("* ")]
    assert items, text[-3000:]  # the linter ran and reported the expected rule lint
    other = [i for i in items if ACCEPTED_LINT not in i]
    assert not other, text[-3000:]
    fmt = subprocess.run([sys.executable, "-m", "snakefmt", "--check", "Snakefile", "workflow/"], cwd=ROOT,
                         capture_output=True, text=True, check=False)
    assert fmt.returncode == 0, fmt.stderr


def test_an_edited_shift_function_reruns_only_scenes_with_a_temperature_axis(make_project, smk, tmp_path):
    """A scene without a temperature axis takes its materials at their reference temperature: editing a
    config material's WLF constants re-solves the scene that sweeps T and none of the other's jobs (its
    points keep their identity, that of the material without a shift function)."""
    gum = {"model": "sls", "E_glassy": 2.0e7, "alpha": 500.0, "beta": 2000.0,
           "shift": {"model": "wlf", "C1": 8.0, "C2": 120.0, "T_ref": 20.0}}
    config = {"materials": {"gum": gum},
              "scenes": {"plain": {"materials": ["gum"], "grid": {"v0": [1.0, 3.0]}, "moduli": ["gum"]},
                         "warm": {"materials": ["gum"], "grid": {"v0": [1.0], "T": [20.0, 40.0]}}}}
    path = make_project(tmp_path, config)
    smk(path, "-j1")
    plain = {p.name: p.read_bytes() for p in (path / "results/plain").rglob("*.nc")}
    config["materials"]["gum"]["shift"]["C1"] = 9.0
    (path / "config.yaml").write_text(yaml.safe_dump(config, sort_keys=False))
    out = smk(path, "-n", "-j1", "--quiet", "rules")
    text = out.stdout + out.stderr
    lines = {ln.split()[0]: int(ln.split()[1]) for ln in text.splitlines() if len(ln.split()) == 2
             and ln.split()[1].isdigit()}
    assert lines.get("sweep_shard") == 1 and lines.get("aggregate") == 1 and "moduli" not in lines, text
    smk(path, "-j1")
    assert {p.name: p.read_bytes() for p in (path / "results/plain").rglob("*.nc")} == plain
    with xr.open_dataset(path / "results/warm/sweep.nc") as ds:
        cor = float(ds["cor"].isel(material=0).sel(T=40.0, v0=1.0))
    catalogue = Catalogue(specs=config["materials"])
    assert cor == pytest.approx(vcor.simulate(catalogue.at("gum", T=40.0), 1.0).cor, rel=1e-9)
