"""Every NetCDF file the workflow writes passes the IOOS compliance checker's CF-1.10 test with no error
and no warning (docs, Datasets, "Conventions"), in one small project that writes every kind of dataset;
a config with a key given twice stops the run before any job."""

import json

import netCDF4
import numpy as np
import pytest
from cf_check import cf_problems
from synthetic_dma import synthetic, write_csv

import vcor
from vcor import materials as M
from vcor.io import netcdf

pytestmark = pytest.mark.slow  # runs Snakemake (about 1.5 min on two cores)

CONFIG = {
    "shard_size": 100,
    "material_dir": "results/materials",
    "materials": {"mine": {"model": "sls", "E_glassy": 20e6, "alpha": 300.0, "beta": 1200.0}},
    "fits": {"measured": {"model": "prony", "data": {"file": "data/dma.csv", "T_ref": 20.0}},
             "tiny-prony": {"model": "prony", "n_terms": 3}},
    "calibrations": {"cal": {"data": "cor.csv",
                             "material": {"model": "sls", "E_glassy": 10e6, "alpha": 300, "beta": 2000},
                             "free": {"E_glassy": [1e6, 1e9], "beta": [400.0, 1e6]}}},
    "scenes": {
        # a band (bootstrap samples of a fit to measured data) over a temperature axis
        "band": {"materials": ["measured"], "grid": {"v0": [1.0, 3.0], "T": [0.0, 40.0]},
                 "geometry": {"rigid": True}, "uncertainty": {"bootstrap": 2, "seed": 1},
                 "figures": {"cor_temperature": {}, "master_curve": {"materials": ["measured"]}}},
        # an error estimate, moduli, histories; a preset, a config material, a calibration and a fit
        "paper": {"materials": ["sls", "mine", "cal", "tiny-prony"], "grid": {"v0": [2.0, 10.0]},
                  "error_estimate": True, "histories": {"v0": 10.0, "runs": [["sls", "direct"], ["mine", "ive"]]},
                  "figures": {"fig2": {}, "fig5": {"reference": "sls", "v0": 10.0}}},
        "balls": {"spheres": {"b": [0.01, 0.1], "tau_ratio": [0.1]}, "figures": {"spheres_eps": {}}},
        "ladder": {"convergence": {"materials": ["butyl-fc"], "v0": [10.0]}, "figures": {"work_precision": {}}},
    },
    # every DEM law (the LAMMPS ones share a parameter name), per temperature
    "dem": {"pair": {"sphere": {"material": "measured", "r": 0.005, "rho": 1100, "nu": 0.45},
                     "target": {"sphere": {}}, "v0": {"start": 0.1, "stop": 10, "num": 5, "log": True},
                     "T": [0.0, 40.0]}},
}
#: one file of each kind the workflow writes
KINDS = {"sweep with a band": "band/sweep.nc", "sweep with an error estimate": "paper/sweep.nc",
         "shard": "paper/shards/*.nc", "moduli": "paper/moduli.nc", "histories": "paper/histories.nc",
         "spheres": "balls/spheres.nc", "work-precision case": "ladder/convergence/butyl-fc.nc",
         "work-precision study": "ladder/convergence.nc", "fit to built-in data": "materials/tiny-prony.nc",
         "fit to measured data": "materials/measured.nc", "bootstrap samples": "materials/samples/measured-b2-s1.nc",
         "part of the samples": "materials/samples/measured-b2-s1-p0of2.nc", "config material": "materials/mine.nc",
         "calibration": "calibrations/cal.nc", "calibrated material": "materials/cal.nc", "DEM entry": "dem/pair.nc"}
#: variables that hold values of several units, one per calibrated parameter (attribute units_by_parameter)
PER_PARAMETER = {"estimate", "stderr", "lower95", "upper95", "start", "lower_bound", "upper_bound"}


@pytest.fixture(scope="module")
def project(make_project, smk, tmp_path_factory):
    path = make_project(tmp_path_factory.mktemp("cf"), CONFIG)
    (path / "data").mkdir(exist_ok=True)
    write_csv(path / "data/dma.csv", synthetic(1))
    v0 = np.geomspace(1.0, 30.0, 6)
    cor = [vcor.simulate(M.SLS(15e6, 300.0, 1200.0), v, method="adaptive").cor for v in v0]
    (path / "cor.csv").write_text("v0,cor\nm/s,-\n" + "".join(f"{a:.17g},{b:.17g}\n" for a, b in zip(v0, cor)))
    smk(path, "-j2")
    return path


def test_every_dataset_passes_the_cf_checker(project):
    results = project / "results"
    for kind, pattern in KINDS.items():
        assert list(results.glob(pattern)), f"no {kind} ({pattern})"
    files = sorted(results.rglob("*.nc"))
    found = {}
    for path in files:
        errors, warnings = cf_problems(path)
        if errors or warnings:
            found[str(path.relative_to(results))] = errors + warnings
    assert found == {}, found
    assert len(files) >= len(KINDS)


def test_every_variable_says_what_it_is_and_its_unit(project):
    """long_name on every variable and coordinate, units on every numeric one (a label has none); the
    calibration's per-parameter columns say theirs in units_by_parameter."""
    missing = []
    for path in sorted((project / "results").rglob("*.nc")):
        with netCDF4.Dataset(path) as nc:
            for name, var in nc.variables.items():
                attrs = var.ncattrs()
                need = ["long_name"] if var.dtype is str else ["long_name", "units"]
                if path.name == "cal.nc" and name in PER_PARAMETER:
                    need = ["long_name", "units_by_parameter"]
                missing += [f"{path.name}:{name}:{a}" for a in need if a not in attrs]
    assert missing == []


#: integer data variables that count (not flags)
COUNTS = {"index", "iterations", "n_modes", "samples_ok"}


def test_flags_say_their_values_and_numbers_name_the_flags_that_qualify_them(project):
    """Every integer data variable but a count is a flag with flag_values or flag_masks and flag_meanings (a
    history's ghost, a DEM law's opposite_trend, a calibration's identified included); every other numeric
    data variable over the dimensions of a status flag, or more (a history's samples, each DEM law's values
    at a point), names it in ancillary_variables."""
    bare, unlinked = [], []
    for path in sorted((project / "results").rglob("*.nc")):
        with netCDF4.Dataset(path) as nc:
            statuses = [n for n, v in nc.variables.items() if getattr(v, "standard_name", "") == "status_flag"]
            coords = {c for v in nc.variables.values() for c in getattr(v, "coordinates", "").split()}
            for name, var in nc.variables.items():
                if name in nc.dimensions or name in coords or var.dtype is str:
                    continue
                attrs = set(var.ncattrs())
                flag = bool({"flag_values", "flag_masks"} & attrs and "flag_meanings" in attrs)
                if var.dtype.kind in "iu" and name not in COUNTS and not flag:
                    bare.append(f"{path.name}:{name}")
                if flag and getattr(var, "standard_name", "") in ("status_flag", "quality_flag"):
                    continue  # a status or validity flag is what others name
                covered = [s for s in statuses if set(nc[s].dimensions) <= set(var.dimensions)]
                if var.dtype.kind in "fiu" and covered and not set(covered) <= set(
                        getattr(var, "ancillary_variables", "").split()):
                    unlinked.append(f"{path.name}:{name}")
    assert bare == [] and unlinked == [], (bare, unlinked)
    histories = netcdf.read_dataset(project / "results/paper/histories.nc")
    options = json.loads(histories.attrs["solver_options"])
    assert {run: o["method"] for run, o in options.items()} == {"sls/direct": "direct", "mine/ive": "ive"}
    assert "geometry_defaults" in histories.attrs


def test_the_datasets_read_back_under_their_names(project):
    results = project / "results"
    sweep = netcdf.read_dataset(results / "paper/sweep.nc")
    assert sweep.indexes["material"].tolist() == ["sls", "mine", "cal", "tiny-prony"]
    assert sweep["cor"].sel(material="mine", v0=10.0).item() == \
        vcor.simulate(M.SLS(20e6, 300.0, 1200.0), 10.0, method="adaptive").cor
    with netCDF4.Dataset(results / "dem/pair.nc") as nc:
        assert "model" not in nc.variables and nc["model_label"].vcor_name == "model"
        assert nc["E_lammps_lammps_coeff_restitution"].vcor_name == "E_lammps_lammps-coeff-restitution"
    dem = netcdf.read_dataset(results / "dem/pair.nc")
    assert "lammps-coeff-restitution" in dem.indexes["model"] and "E_lammps_lammps-coeff-restitution" in dem
    deck = (results / "dem/pair/lammps/in.pair").read_text()
    assert f"{float(dem['E_lammps'].values[0]):.12g}" in deck
    for path in results.rglob("*.nc"):
        back = netcdf.read_dataset(path)
        assert not [n for n, v in back.variables.items() if netcdf.NAME_ATTR in v.attrs], path


def test_a_key_given_twice_stops_the_run_before_any_job(make_project, smk, tmp_path):
    path = make_project(tmp_path, {"scenes": {"s": {"materials": ["sls"], "grid": {"v0": [1.0]}}}})
    text = (path / "config.yaml").read_text()
    (path / "config.yaml").write_text(text.replace("      v0:\n", "      v0: [5.0]\n      v0:\n"))
    out = smk(path, "-n", check=False)
    said = out.stdout + out.stderr
    assert out.returncode != 0 and "config file config.yaml, line 7, column 7: key 'v0' is given twice in one " \
                                   "mapping (lines 6 and 7)" in said, said
    (path / "config.yaml").write_text(text)
    (path / "my.yaml").write_text("scenes:\n  t:\n    materials: [sls]\n    materials: [kelvin-voigt]\n"
                                  "    grid: {v0: [1.0]}\n")
    out = smk(path, "-n", "--configfile", "my.yaml", check=False)
    said = out.stdout + out.stderr
    # named as given, relative to the project (Snakemake keeps --configfile paths absolute)
    assert out.returncode != 0 and "config file my.yaml, line 4, column 5: key 'materials' is given twice" in said, said
    assert not (path / "results").exists()
