"""Bad input as a new user would try it: one table, a row each. Every row must raise a ValueError
(or the workflow's WorkflowError) whose text names the parameter and, where there is one, the
allowed range, before any work is done. Rows that a user might expect to fail but that are valid
(the paper's own elastic limit in case 1, a fit to one domain only) are in ``VALID`` below."""

import math
import re
from pathlib import Path

import numpy as np
import pytest
import yaml

import vcor
from vcor import materials as M
from vcor import spheres as S
from vcor.fitting import calibrate, dma, fits, spec
from vcor.fitting import prony as fit
from vcor.solvers.options import METHOD_NAMES
from vcor.study import scene
from vcor.study.config import load_project

ROOT = Path(__file__).resolve().parents[1]


def _config_with(mutate):
    cfg = yaml.safe_load((ROOT / "config.yaml").read_text())
    mutate(cfg)
    return cfg


def _validate(cfg, base=ROOT):
    """What the workflow does before any job: JSON schema, then vcor's config checks."""
    from vcor.study.schema import check_schema

    load_project(check_schema(cfg, ROOT / "workflow/schemas/config.schema.yaml"), base)


def _scene(name, **changes):
    """The config with scene ``name`` changed (keys set, or removed when the value is None)."""
    def mutate(cfg):
        for k, v in changes.items():
            if v is None:
                cfg["scenes"][name].pop(k, None)
            else:
                cfg["scenes"][name][k] = v
    return _config_with(mutate)


_BT = fit.bagley_torvik_data()
_FREQ_ONLY = fit.FitData(omega=_BT.omega, E_star=_BT.E_star)

ROWS = [
    # (what a user tries, callable, words the error must contain)
    # --- numbers: type and range -------------------------------------------------------------
    ("r = True", lambda: vcor.simulate("sls", 10.0, r=True), ["r must be in [1e-09, 1000] m", "True"]),
    ("r = 'abc'", lambda: vcor.simulate("sls", 10.0, r="abc"), ["r must be in [1e-09, 1000] m", "'abc'"]),
    ("r negative", lambda: vcor.simulate("sls", 10.0, r=-0.01), ["r must be in [1e-09, 1000] m", "-0.01"]),
    ("r NaN", lambda: vcor.simulate("sls", 10.0, r=math.nan), ["r must"]),
    ("rho_a = 0", lambda: vcor.simulate("sls", 10.0, rho_a=0.0), ["rho_a must be in [0.001, 1e+06] kg/m^3"]),
    ("rho_b negative", lambda: vcor.simulate("sls", 10.0, rho_b=-1.0), ["rho_b must be in [0.001, 1e+06] kg/m^3"]),
    ("nu = 0.7", lambda: vcor.simulate("sls", 10.0, nu=0.7), ["nu", "(-1, 0.5]"]),
    ("nu = -1", lambda: vcor.simulate("sls", 10.0, nu=-1.0), ["nu", "(-1, 0.5]"]),
    ("h = False", lambda: vcor.simulate("sls", 10.0, h=False), ["h must be in [1e-09, 1000] m"]),
    ("h = [1e-3] (unhashable: past the geometry cache)", lambda: vcor.simulate("sls", 10.0, h=[1e-3]),
     ["h must be in [1e-09, 1000] m", "[0.001]"]),
    ("E_plate outside case 4 (was ignored)", lambda: vcor.simulate("sls", 2.0, E_plate=7e10),
     ["E_plate", "case 4 only", "case 3", "give case=4"]),
    ("nu_plate outside case 4 and plate bodies (was ignored)", lambda: vcor.simulate("sls", 2.0, nu_plate=0.25),
     ["nu_plate", "case 3", "give nu"]),
    ("E_plate swept in a case-3 scene (a flat curve)",
     lambda: vcor.sweep({"materials": ["sls"], "grid": {"v0": [1.0], "E_plate": [1e9, 2e11]}}, workers=1,
                        progress=False), ["E_plate", "case 4 only"]),
    ("v0 = 0", lambda: vcor.simulate("sls", 0.0), ["v0 must be in [1e-09, 100000] m/s"]),
    ("v0 negative", lambda: vcor.simulate("sls", -3.0), ["v0 must be in [1e-09, 100000] m/s"]),
    ("v0 = NaN", lambda: vcor.simulate("sls", math.nan), ["v0"]),
    ("v0 = '10'", lambda: vcor.simulate("sls", "10"), ["v0 must be in [1e-09, 100000] m/s", "'10'"]),
    ("rho_a = 1e-300 (was ok with COR inf)", lambda: vcor.simulate("sls", 10.0, rho_a=1e-300),
     ["rho_a must be in [0.001, 1e+06] kg/m^3"]),
    ("v0 = 10**400", lambda: vcor.simulate("sls", 10**400),
     ["v0 must be in", "floating-point range", "401 characters"]),
    ("v0 = 5e-324", lambda: vcor.simulate("sls", 5e-324), ["v0 must be in [1e-09, 100000] m/s", "5e-324"]),
    ("case = 1.0", lambda: vcor.simulate("sls", 10.0, case=1.0),
     ["case must be one of 1, 2, 3, 4 (an integer)", "1.0"]),
    ("history = 'no'", lambda: vcor.simulate("sls", 10.0, history="no"), ["history must be true or false", "'no'"]),
    ("soe_tol = 1e-300", lambda: vcor.simulate("sls", 10.0, method="soe", soe_tol=1e-300),
     ["soe_tol must be in [1e-13, 0.01)", "1e-300"]),
    ("rtol = 1e-20", lambda: vcor.simulate("sls", 10.0, method="ive", rtol=1e-20), ["rtol must be in [1e-13, 1)"]),
    ("case = 5", lambda: vcor.simulate("sls", 10.0, case=5), ["case", "1, 2, 3, 4"]),
    ("case = True", lambda: vcor.simulate("sls", 10.0, case=True), ["case", "1, 2, 3, 4"]),
    ("rigid = 'yes'", lambda: vcor.simulate("sls", 10.0, rigid="yes"), ["rigid", "true or false"]),
    ("unknown keyword", lambda: vcor.simulate("sls", 10.0, thickness=0.02), ["unknown keyword", "thickness", "'h'"]),
    ("unknown material", lambda: vcor.simulate("rubber", 10.0), ["unknown material", "sls"]),
    # --- materials ---------------------------------------------------------------------------
    ("SLS(alpha=True)", lambda: M.SLS(15e6, True, 1200), ["alpha", "[0, inf) 1/s", "True"]),
    ("SLS negative modulus", lambda: M.SLS(-15e6, 300, 1200), ["E_glassy", "(0, 1e+20] Pa"]),
    ("SLS E_glassy = '15e6'", lambda: M.SLS("15e6", 300, 1200), ["E_glassy", "(0, 1e+20] Pa"]),
    ("SLS increasing modulus", lambda: M.SLS(15e6, 2400, 1200), ["alpha", "increase"]),
    ("Prony negative term", lambda: M.Prony(1e6, (-5e5,), (100.0,)), ["E[0]", "increase"]),
    ("Prony negative rate", lambda: M.Prony(1e6, (1e6,), (-10.0,)), ["beta[0]", "[0, inf) 1/s"]),
    ("Prony term True", lambda: M.Prony(1e6, (True,), (10.0,)), ["E[0]", "True"]),
    ("Prony lengths differ", lambda: M.Prony(1e6, (1e6, 2e6), (10.0,)), ["equal length"]),
    ("fractional E0 negative", lambda: M.FractionalPower(-1.0, 1.0), ["E0", "[0, 1e+20] Pa"]),
    ("CERF b1 = 0", lambda: M.Cerf(1.0, 1.0, 0.0), ["b1", "(0, inf)"]),
    ("Kelvin-Voigt tau negative", lambda: M.KelvinVoigt(1e6, -1.0), ["tau", "[0, inf) s"]),
    ("Elastic E NaN", lambda: M.Elastic(float("nan")), ["E must be in (0, 1e+20] Pa"]),
    ("preset name unknown", lambda: M.get("rubber"), ["unknown material", "sls"]),
    # --- cases and solver options ------------------------------------------------------------
    ("case 1 with a relaxing material", lambda: vcor.simulate("sls", 10.0, case=1), ["case 1", "elastic material"]),
    ("case 1 with Kelvin-Voigt", lambda: vcor.simulate("kelvin-voigt", 10.0, case=1),
     ["case 1", "elastic material", "kelvin-voigt"]),
    ("dt bigger than the contact", lambda: vcor.simulate("sls", 10.0, method="direct", dt=0.1), ["dt must be in"]),
    ("dt negative", lambda: vcor.simulate("sls", 10.0, dt=-1e-6), ["dt must be in (0, inf) s"]),
    ("dt with ive", lambda: vcor.simulate("sls", 10.0, method="ive", dt=1e-6), ["dt", "not used by method 'ive'"]),
    ("rtol with direct", lambda: vcor.simulate("sls", 10.0, method="direct", rtol=1e-8),
     ["rtol", "not used by method 'direct'"]),
    ("c2 without volterra", lambda: vcor.simulate("sls", 10.0, c2=2.0), ["c2", "volterra"]),
    ("volterra with ive-numba", lambda: vcor.simulate("sls", 10.0, method="ive-numba", volterra=True),
     ["volterra", "ive-numba"]),
    ("method unknown", lambda: vcor.simulate("sls", 10.0, method="euler"), ["method", "direct"]),
    ("steps_per_contact = 5", lambda: vcor.simulate("sls", 10.0, steps_per_contact=5),
     ["steps_per_contact", "an integer in [10, 1000000000]"]),
    ("form b, fractional kernel", lambda: vcor.simulate("butyl-fc", 10.0, method="direct", form="b"), ["form 'b'"]),
    ("ive, fractional kernel", lambda: vcor.simulate("butyl-fc", 10.0, method="ive"), ["Prony", "'ive'"]),
    ("options twice", lambda: vcor.simulate("sls", 10.0, options={"method": "ive"}, rule="overlap"), ["not both"]),
    # --- fits ---------------------------------------------------------------------------------
    ("fit data: zero loss modulus",
     lambda: fit.FitData(omega=[1.0, 2.0, 3.0], E_star=[1 + 1j, 2 + 0j, 3 + 1j]),
     ["loss modulus", "> 0 Pa", "omega = 2"]),
    ("fit data: negative loss modulus",
     lambda: fit.FitData(omega=[1.0, 2.0, 3.0], E_star=[1 + 1j, 2 - 1j, 3 + 1j]), ["loss modulus", "> 0 Pa"]),
    ("fit data: increasing E(t)", lambda: fit.FitData(t=[1e-3, 2e-3, 3e-3], E_t=[1e6, 2e6, 1.5e6]), ["increases"]),
    ("fit data: negative E(t)", lambda: fit.FitData(t=[1e-3, 2e-3, 3e-3], E_t=[1e6, -2e6, -3e6]), ["> 0 Pa"]),
    ("fit data: unsorted times", lambda: fit.FitData(t=[3e-3, 2e-3, 1e-3], E_t=[3e6, 2e6, 1e6]),
     ["strictly increasing"]),
    ("fit data: decreasing storage",
     lambda: fit.FitData(omega=[1.0, 2.0, 3.0], E_star=[3 + 1j, 2 + 1j, 1 + 1j]), ["storage modulus decreases"]),
    ("fit data: none", lambda: fit.FitData(), ["needs relaxation data"]),
    ("fit: time domain asked, frequency data only",
     lambda: fit.fit({"model": "prony", "n_terms": 3, "domain": "time"}, _FREQ_ONLY), ["domain 'time' has no data"]),
    ("fit: unknown model", lambda: fit.fit({"model": "maxwell"}), ["model"]),
    ("fit: n_terms = 0", lambda: fit.fit_prony(_BT, 0), ["n_terms"]),
    # --- spheres ------------------------------------------------------------------------------
    ("spheres: b negative", lambda: S.cor_numeric(-0.1), ["b must"]),
    ("spheres: b NaN", lambda: S.cor_series(float("nan")), ["b must"]),
    ("spheres: series order 5", lambda: S.cor_series(0.1, 5), ["order"]),
    ("spheres: rule unknown", lambda: S.cor_numeric(0.1, "touch"), ["rule"]),
    ("spheres: m1 = 0", lambda: S.b_group(R1=0.01, R2=0.01, m1=0.0, m2=0.1, E=1e7, nu=0.3, A=1e-5, g=1.0), ["m1"]),
    ("spheres: g negative",
     lambda: S.cor_spheres(R1=0.01, R2=0.01, m1=0.1, m2=0.1, E=1e7, nu=0.3, A=1e-5, g=-2.0), ["g must"]),
    ("spheres: nu outside Eq. 4", lambda: S.dissipative_constant(1.0, 1.0, 1e7, 0.6), ["nu"]),
    # --- grids and configs --------------------------------------------------------------------
    ("empty grid", lambda: scene.axis_values([]), ["empty"]),
    ("empty grid in a config", lambda: _validate(_config_with(lambda c: c["scenes"]["sls"]["grid"].update(v0=[]))),
     ["v0"]),
    ("config: grid value is text",
     lambda: _validate(_config_with(lambda c: c["scenes"]["sls"]["grid"].update(beta="fast"))), ["beta"]),
    ("config: unknown key", lambda: _validate(_config_with(lambda c: c["scenes"]["sls"].update(speed=3))), ["speed"]),
    ("config: unknown material",
     lambda: _validate(_config_with(lambda c: c["scenes"]["butyl"].update(materials=["butyl-xyz"]))),
     ["scenes.butyl.materials", "butyl-xyz"]),
    ("config: misspelt grid axis", lambda: _validate(_scene("sls", grid={"v0": [1, 10], "bta": [600, 1200]})),
     ["scenes.sls.grid.bta", "no parameter 'bta'", "'beta'"]),
    ("config: grid axis of one material only",
     lambda: _validate(_scene("butyl", grid={"v0": [1, 10], "E0": [1e6, 2e6]})),
     ["scenes.butyl.grid.E0", "materials ['butyl-prony3'] have no parameter 'E0'"]),
    ("config: a fit's grid axis by its model",
     lambda: _validate(_scene("pyvisco", grid={"v0": [1], "E0": [1e6]}, figures={})),
     ["scenes.pyvisco.grid.E0", "E_inf"]),
    ("config: geometry keyword that is no number",
     lambda: _validate(_scene("sls", grid={"v0": [1], "case": [1, 2]}, tie=None)),
     ["scenes.sls.grid.case"]),
    ("config: tie target that is an axis",
     lambda: _validate(_scene("sls", tie={"beta": {"to": "v0", "ratio": 1.0}})), ["scenes.sls.tie.beta", "grid axis"]),
    ("config: NaN in a grid", lambda: _validate(_scene("sls", grid={"v0": [1, math.nan]})),
     ["scenes.sls.grid.v0", "finite number", "nan"]),
    ("config: inf in a grid", lambda: _validate(_scene("sls", grid={"v0": [1, math.inf]})),
     ["scenes.sls.grid.v0", "finite number", "inf"]),
    ("config: empty range", lambda: _validate(_scene("sls", grid={"v0": {"start": 5, "stop": 1, "step": 1}})),
     ["scenes.sls.grid.v0", "empty"]),
    ("config: range with step and num",
     lambda: scene.validate_scene("s", {"materials": ["sls"],
                                        "grid": {"v0": {"start": 1, "stop": 5, "step": 1, "num": 3}}}),
     ["scenes.s.grid.v0", "{start, stop, step}"]),
    ("config: grid too large for its jobs",
     lambda: _validate(_config_with(lambda c: (c.update(shard_size=10), c["scenes"]["sls"].update(
         grid={"v0": {"start": 1, "stop": 1000, "step": 1}, "beta": {"start": 1, "stop": 1000, "step": 1}})))),
     ["scenes.sls.grid", "1000000 points in 100000 sweep jobs", "at most", "5000 jobs"]),
    ("config: axis too long",
     lambda: _validate(_scene("sls", grid={"v0": {"start": 1, "stop": 1e9, "step": 1}}, tie=None)),
     ["scenes.sls.grid", "1000000000 points", "at most 1000000 points"]),
    ("API: axis too long", lambda: scene.axis_values({"start": 1, "stop": 1e9, "step": 1}),
     ["1000000000 values", "100000"]),
    ("config: figure needs an axis the grid lacks", lambda: _validate(_scene("sls", grid={"v0": [1, 10]}, tie=None)),
     ["scenes.sls.figures.fig4", "grid axis beta"]),
    ("config: figure names a material not in the scene",
     lambda: _validate(_scene("butyl", figures={"fig9": {"material": "sls"}})),
     ["scenes.butyl.figures.fig9.material", "'sls'", "butyl-fc"]),
    ("config: figure's default material not in the scene",
     lambda: _validate(_scene("butyl", materials=["butyl-cerf"], figures={"fig8": {}, "fig9": {}})),
     ["scenes.butyl.figures.fig9.material", "'butyl-fc'"]),
    ("config: unknown figure option", lambda: _validate(_scene("sls", figures={"fig4": {"colour": "red"}})),
     ["scenes.sls.figures.fig4.colour", "takes no option", "material"]),
    ("config: figure option off the grid",
     lambda: _validate(_scene("butyl", figures={"fig5": {"reference": "butyl-fc", "v0": 10.5}})),
     ["scenes.butyl.figures.fig5.v0", "10.5", "not on the grid axis v0"]),
    ("config: figure runs not in the histories",
     lambda: _validate(_scene("butyl", figures={"fig6": {"runs": ["butyl-fc/ive"]}})),
     ["scenes.butyl.figures.fig6.runs", "butyl-fc/direct"]),
    ("config: empty material_dir", lambda: _validate(_config_with(lambda c: c.update(material_dir=""))),
     ["material_dir", "non-empty path inside the project"]),
    ("config: material_dir outside", lambda: _validate(_config_with(lambda c: c.update(material_dir="../elsewhere"))),
     ["material_dir", "inside the project"]),
    ("config: data file outside the project",
     lambda: _validate(_config_with(lambda c: c["fits"]["pyvisco-polymer"]["data"].update(file="/tmp/x.csv"))),
     ["fits.pyvisco-polymer.data.file", "relative path inside the project"]),
    ("config: an absolute data path inside the project", lambda: _validate(_config_with(
        lambda c: c["fits"]["pyvisco-polymer"]["data"].update(file=str(ROOT / "data/pyvisco/freq_user_raw.csv")))),
     ["fits.pyvisco-polymer.data.file", "relative path inside the project", "write 'data/pyvisco/freq_user_raw.csv'"]),
    ("config: DMA file missing", lambda: _validate(_config_with(
        lambda c: c["fits"]["pyvisco-polymer"]["data"].update(file="data/pyvisco/none.csv"))),
     [f"fits.pyvisco-polymer.data.file: the DMA file 'data/pyvisco/none.csv' does not exist in {str(ROOT)!r} (the "
      f"project folder, which relative paths are taken from)"]),
    ("config: shift-factor file missing", lambda: _validate(_config_with(
        lambda c: c["fits"]["pyvisco-polymer"]["data"].update(shift_file="none.csv"))),
     ["fits.pyvisco-polymer.data.shift_file: the shift-factor file 'none.csv' does not exist in", "project folder"]),
    ("fit: instrument_lag not a boolean", lambda: spec.check_fit_spec(
        {"model": "prony", "data": {"file": "data/pyvisco/freq_user_raw.csv", "T_ref": -5, "instrument_lag": "yes"}},
        base_dir=ROOT, where="fits.x"), ["fits.x.data.instrument_lag", "true or false", "'yes'"]),
    ("fit: method free is refused", lambda: spec.check_fit_spec(
        {"model": "prony", "method": "free", "data": {"file": "data/pyvisco/freq_user_raw.csv", "T_ref": -5}},
        base_dir=ROOT, where="fits.x"), ["fits.x.method", "'free'", "method: spectrum"]),
    ("fit: T_ref outside the sets with a WLF shift function", lambda: spec.check_fit_spec(
        {"model": "prony", "data": {"file": "data/pyvisco/freq_user_raw.csv", "T_ref": 120, "shift_model": "wlf"}},
        base_dir=ROOT, where="fits.x"), ["fits.x.data.T_ref", "120 deg C lies outside the sets'", "among the data"]),
    ("fit: a shift model for a master curve", lambda: spec.check_fit_spec(
        {"model": "prony", "data": {"file": "data/pyvisco/freq_user_master.csv", "T_ref": -5, "shift_model": "wlf"}},
        base_dir=ROOT, where="fits.x"), ["fits.x.data.shift_model", "master curve", "no shift factors"]),
    ("config: a temperature axis over a fit to a master curve", lambda: _validate(_config_with(lambda c: c.update(
        fits={"mfit": {"model": "prony", "data": {"file": "data/pyvisco/freq_user_master.csv", "T_ref": -5}}},
        scenes={"s": {"materials": ["mfit"], "grid": {"v0": [1.0], "T": [0.0, 10.0]}}}))),
     ["scenes.s.grid.T", "fit 'mfit' has no shift function", "master curve", "raw sets"]),
    ("fit: the built-in data's band reversed", lambda: vcor.fit(
        {"model": "prony", "n_terms": 3, "data": {"f_min": 1e4, "f_max": 10.0}}, name="x"),
     ["fit.data: f_min < f_max (Hz), got f_min = 10000, f_max = 10"]),
    ("fit: a measured-data key without a file", lambda: vcor.fit(
        {"model": "prony", "n_terms": 3, "data": {"T_ref": 20.0}}, name="x"),
     ["fit.data: T_ref belongs to measured data, which needs file", "the built-in data take"]),
    ("fit: measured data without T_ref", lambda: spec.check_fit_spec(
        {"model": "prony", "data": {"file": "data/pyvisco/freq_user_raw.csv"}}, base_dir=ROOT, where="fits.x"),
     ["fits.x.data.T_ref missing: the master curve's reference temperature (deg C)"]),
    ("calibrate: a COR data file that does not exist", lambda: vcor.calibrate(
        {"data": "nothere.csv", "material": "sls", "free": {"beta": [100.0, 1e5]}}, name="c"),
     ["calibration.data: the COR data file 'nothere.csv' does not exist in", "(the project folder, which relative "
      "paths are taken from)"]),
    ("calibrate: COR data of unequal lengths", lambda: calibrate.CorData(v0=[1.0, 2.0], cor=[0.5]),
     ["CorData: v0, cor (and cor_std) need one value per impact, got lengths [2, 1]"]),
    ("calibrate: a NaN COR", lambda: calibrate.CorData(v0=[1.0, 2.0], cor=[0.5, math.nan]),
     ["CorData.cor[1]: a COR must be in (0, 1], got nan"]),
    ("calibrate: a COR above 1", lambda: calibrate.CorData(v0=[1.0], cor=[1.2]), ["CorData.cor[0]", "(0, 1]", "1.2"]),
    ("calibrate: a zero standard deviation", lambda: calibrate.CorData(v0=[1.0], cor=[0.5], cor_std=[0.0]),
     ["CorData.cor_std[0]: a standard deviation must be > 0, got 0.0"]),
    ("simulate: dt and steps_per_contact both given", lambda: vcor.simulate(
        "sls", 1.0, method="direct", dt=1e-7, steps_per_contact=100),
     ["dt = 1e-07 s and steps_per_contact = 100 both set the time step: give one of them"]),
    ("simulate: a dt of fewer than 10 steps per contact", lambda: vcor.simulate("sls", 1.0, method="direct", dt=1e-3),
     ["dt must be in [2.739e-12, 0.0002739] s (from 10 to 1000000000 steps per contact-time estimate", "got 0.001"]),
    ("simulate: a dt of more than a billion steps per contact (it would run only to its step budget)",
     lambda: vcor.simulate("sls", 1.0, method="direct", dt=1e-30),
     ["dt must be in [2.739e-12, 0.0002739] s", "got 1e-30"]),
    ("simulate: more than a billion steps per contact", lambda: vcor.simulate("sls", 1.0, method="soe",
                                                                               steps_per_contact=10**12),
     ["solver option steps_per_contact must be an integer in [10, 1000000000], got 1000000000000"]),
    ("simulate: a rigid target with rigid=False", lambda: vcor.simulate("sls", 1.0, target="rigid", rigid=False),
     ["target 'rigid' with rigid=False: give one of them"]),
    ("config: an empty grid axis", lambda: _validate(_config_with(
        lambda c: c.update(scenes={"s": {"materials": ["sls"], "grid": {"v0": []}}}))),
     ["scenes.s.grid.v0: the list is empty; give at least 1 value(s)"]),
    ("config: a length written with its unit", lambda: _validate(_config_with(
        lambda c: c.update(scenes={"s": {"materials": ["sls"], "grid": {"v0": [1.0]}, "geometry": {"r": "3 mm"}}}))),
     ["scenes.s.geometry.r: expected a number (in m, > 0), got '3 mm'"]),
    ("config: a negative speed in a listed grid axis is named by its index", lambda: _validate(_config_with(
        lambda c: c.update(scenes={"s": {"materials": ["sls"], "grid": {"v0": [1.0, -3.0, 10.0]}}}))),
     ["scenes.s.grid.v0[1]: impact speeds must be > 0 m/s, got -3"]),
    ("config: a NaN in a listed grid axis is named by its index", lambda: _validate(_config_with(
        lambda c: c.update(scenes={"s": {"materials": ["sls"], "grid": {"v0": [1.0, math.nan]}}}))),
     ["scenes.s.grid.v0[1]: must be a finite number, got nan"]),
    ("config: a DEM speed written with its unit is named by its index", lambda: _validate(_config_with(
        lambda c: c.update(dem={"d": {"sphere": {"material": "sls"}, "v0": [1.0, "3 m/s"]}}))),
     ["dem.d.v0[1]: must be a finite number, got '3 m/s'"]),
    ("config: a temperature axis beyond a table-shift fit's sets", lambda: _validate(_config_with(lambda c: c.update(
        scenes={"s": {"materials": ["pyvisco-polymer"], "grid": {"v0": [1.0], "T": [-60.0, 20.0]}}}))),
     ["scenes.s.grid.T", "fit 'pyvisco-polymer'", "[-50.4094, 100.485] deg C", "not extrapolated", "got -60"]),
    ("fit: instrument_lag on a master curve", lambda: spec.check_fit_spec(
        {"model": "prony", "data": {"file": "data/pyvisco/freq_user_master.csv", "T_ref": -5, "instrument_lag": True}},
        base_dir=ROOT, where="fits.x"), ["fits.x.data.instrument_lag", "master curve", "two or more temperatures"]),
    ("dma: a lag beyond the measured loss angle", lambda: dma.superpose(
        dma.read_table(ROOT / "data/pyvisco/freq_user_raw.csv"), -5.0, log_aT=np.zeros(21), lag=1e-3),
     ["freq_user_raw.csv", "loss angle below the instrument lag's phase", "deg C", "Hz", "does not describe"]),
    ("config: instrument_lag not a boolean", lambda: _validate(_config_with(
        lambda c: c["fits"]["pyvisco-polymer"]["data"].update(instrument_lag="yes"))), ["instrument_lag"]),
    ("config: a method that cannot solve a scene's material",
     lambda: _validate(_config_with(lambda c: c["scenes"]["butyl"].update(solver={"method": "ive"}))),
     ["scenes.butyl.solver.method", "material 'butyl-fc'", "method 'ive' needs a Prony kernel", "'adaptive'"]),
    ("sweep: a method that cannot solve the material", lambda: vcor.sweep(
        {"materials": ["butyl-fc"], "grid": {"v0": [1, 2]}, "solver": {"method": "ive"}}, workers=1, progress=False),
     ["solver.method", "material 'butyl-fc'", "method 'ive' needs a Prony kernel"]),
    ("sweep: the paper's explicit scheme on a Kelvin-Voigt material", lambda: vcor.sweep(
        {"materials": ["kelvin-voigt"], "grid": {"v0": [1, 2]}, "solver": {"method": "paper"}}, workers=1,
        progress=False), ["solver.method", "method 'paper' has no Dirac (Kelvin-Voigt) term", "'direct'"]),
    ("config: a history run whose method cannot solve its material", lambda: _validate(_config_with(
        lambda c: c["scenes"]["butyl"]["histories"]["runs"].append(["butyl-fc", "ive"]))),
     ["scenes.butyl.histories.runs", "[butyl-fc, ive]", "method 'ive' needs a Prony kernel"]),
    ("dem: a method that cannot solve the collision", lambda: vcor.dem_export(
        {"sphere": {"material": "butyl-fc"}, "v0": [1, 2], "solver": {"method": "ive"}}),
     ["dem.solver.method", "method 'ive' needs a Prony kernel"]),
    ("config: a scene name YAML reads as a number", lambda: _validate(_config_with(
        lambda c: c["scenes"].update({2026: c["scenes"]["sls"]}))),
     ["scenes: the key 2026 is read as a number", "quote it, '2026'"]),
    ("config: a grid axis YAML reads as a boolean", lambda: _validate(_config_with(
        lambda c: c["scenes"]["sls"]["grid"].update({True: [1.0]}))),
     ["scenes.sls.grid: the key True is read as a boolean", "on, off, yes, no", "quote the word"]),
    ("sweep: a scene called on in a config mapping", lambda: vcor.sweep(
        "on", config={"scenes": {True: {"materials": ["sls"], "grid": {"v0": [1.0]}}}}),
     ["scenes: the key True is read as a boolean"]),
    ("dem: an entry the config does not have", lambda: vcor.dem_export("nope", config={"dem": {
        "a": {"sphere": {"material": "sls"}, "v0": [1, 2]}, "b": {"sphere": {"material": "sls"}, "v0": [1, 2]}}}),
     ["'nope' is not an entry of the config's dem block", "['a', 'b']"]),
    ("config: a history run whose method cannot take the scene's options", lambda: _validate(_config_with(
        lambda c: c["scenes"].update(h={"materials": ["butyl-fc"], "solver": {"method": "direct", "form": "b"},
                                        "histories": {"v0": 10, "runs": [["butyl-fc", "direct"]]}}))),
     ["scenes.h.histories.runs", "[butyl-fc, direct]", "form 'b'"]),
    ("config: an empty moduli list", lambda: _validate(_scene("sls", moduli=[])), ["scenes.sls.moduli"]),
    ("config: a history speed out of range", lambda: _validate(_config_with(
        lambda c: c["scenes"]["butyl"]["histories"].update(v0=1.0e7))),
     ["scenes.butyl.histories (v0 = 10000000.0 m/s", "v0 must be in", "m/s"]),
    ("sweep: a name that is no scene name", lambda: vcor.sweep(
        {"materials": ["sls"], "grid": {"v0": [1.0]}}, name="my study"), ["name must be", "'my study'"]),
    ("sweep: a name beside a scene's name", lambda: vcor.sweep("sls", config=ROOT / "config.yaml", name="x"),
     ["name names a scene given as a mapping", "'sls'"]),
    ("rigid target with a plate thickness", lambda: vcor.simulate("sls", 1.0, rigid=True, h=0.01),
     ["h describes a plate", "rigid=True", "not both"]),
    ("a material spec with a bad key", lambda: vcor.simulate({"model": "sls", "E_glassy": 1e7, "alpha": 300}, 1.0),
     ["material", "beta"]),
    ("config: option the method ignores",
     lambda: _validate(_config_with(lambda c: c["scenes"]["sls"].update(solver={"method": "ive", "dt": 1e-6}))),
     ["scenes.sls.solver", "dt", "not used by method 'ive'"]),
    # --- the work-precision study: what its jobs would meet after the kernels and the ladders -----
    ("config: a work-precision material twice",
     lambda: _validate(_scene("convergence", convergence={"materials": ["sls", "sls"], "v0": [10]})),
     ["scenes.convergence.convergence.materials", "at most once", "['sls', 'sls']"]),
    ("config: a work-precision speed twice",
     lambda: _validate(_scene("convergence", convergence={"materials": ["sls"], "v0": [10, 10.0]})),
     ["scenes.convergence.convergence.v0", "at most once"]),
    ("config: a work-precision speed NaN",
     lambda: _validate(_scene("convergence", convergence={"materials": ["sls"], "v0": [10, math.nan]})),
     ["scenes.convergence.convergence.v0[1]", "v0 must be in [1e-09, 100000] m/s", "nan"]),
    ("config: a work-precision speed out of range",
     lambda: _validate(_scene("convergence", convergence={"materials": ["sls"], "v0": [1.0e9]})),
     ["scenes.convergence.convergence.v0[0]", "v0 must be in [1e-09, 100000] m/s"]),
    ("study: a work-precision speed infinite",
     lambda: vcor.convergence({"convergence": {"materials": ["sls"], "v0": [math.inf]}}),
     ["scene.convergence.v0[0]", "v0 must be in [1e-09, 100000] m/s", "inf"]),
    ("config: a geometry the work-precision study would not solve",
     lambda: _validate(_scene("convergence", geometry={"h": 0.005})),
     ["scenes.convergence.geometry", "default geometry", "takes no geometry"]),
    ("config: a plate the work-precision study would not solve",
     lambda: _validate(_scene("convergence", plate={"material": "sls", "h": 0.005})),
     ["scenes.convergence.plate", "default geometry"]),
]


@pytest.mark.parametrize("what, call, words", ROWS, ids=[r[0] for r in ROWS])
def test_bad_input_row(what, call, words):
    from snakemake.exceptions import WorkflowError

    with pytest.raises((ValueError, WorkflowError)) as info:
        call()
    text = str(info.value)
    for w in words:
        assert w in text, (what, text)


def test_valid_inputs_that_were_refused_or_crashed():
    """The paper's elastic limit SLS(E, 0, 0) in case 1 (was refused); Kelvin-Voigt with tau = 0 in
    case 1; a fit to frequency data only (crashed writing its dataset)."""
    a = vcor.simulate(M.SLS(15e6, 0.0, 0.0), 10.0, case=1)
    b = vcor.simulate(M.Elastic(15e6), 10.0, case=1)
    c = vcor.simulate(M.KelvinVoigt(15e6, 0.0), 10.0, case=1)
    assert a.ok and a.cor == b.cor == c.cor
    res = fit.fit({"model": "prony", "n_terms": 3, "domain": "frequency"}, _FREQ_ONLY)
    ds = fits.result_dataset(res, _FREQ_ONLY, {})
    assert "t" not in ds.coords and np.all(np.isfinite(ds["tan_delta_rel_err"]))
    assert all(np.isfinite(v) for v in res.metrics.values())


def test_a_fit_to_a_band_of_the_built_in_data_runs():
    """A ``data:`` block of the built-in data (a band, sample counts) is fitted on that band: the measured
    data's keys are not filled in for it (the fit then took them as the built-in data's and raised)."""
    fitted = vcor.fit({"model": "prony", "n_terms": 3, "data": {"f_min": 10.0, "f_max": 1e4, "n_freq": 21}}, name="x")
    omega = fitted.dataset["omega"].values
    assert omega.size == 21 and omega.min() == pytest.approx(2 * math.pi * 10.0)


def test_a_temperature_axis_over_a_fit_is_checked_against_its_sets_before_the_fit():
    """A fit to raw sets with a table shift function (the default) is valid on its sets' mean temperatures
    +- TABLE_TOLERANCE, which the data file gives before the fit: an axis at those ends passes, beyond them is
    refused (the row above); a WLF fit's range follows from its fitted constants, so its axis is not
    refused before the fit."""
    from vcor.fitting.dma.data import read_table
    from vcor.fitting.dma.sets import split_sets

    temps = [s.T for s in split_sets(read_table(ROOT / "data/pyvisco/freq_user_raw.csv"))]
    ends = [round(min(temps) - 0.5, 3) + 0.001, round(max(temps) + 0.5, 3) - 0.001]  # inside by < 2e-3 K

    def scene(T, **data):
        def mutate(c):
            c["fits"]["pyvisco-polymer"]["data"].update(data)
            c["scenes"] = {"s": {"materials": ["pyvisco-polymer"], "grid": {"v0": [1.0], "T": T}}}
        return _config_with(mutate)

    _validate(scene(ends))
    with pytest.raises(ValueError, match=r"scenes\.s\.grid\.T: fit 'pyvisco-polymer'"):
        _validate(scene([ends[0], ends[1] + 0.003]))
    _validate(scene([-60.0, 20.0], shift_model="wlf"))


def test_valid_inputs_that_crashed():
    """A Maxwell-like SLS (alpha = 0: the modulus relaxes to zero) and the same as a Prony series
    (E_inf = 0) have a capped contact-time estimate (ZeroDivisionError before); a Fraction is a number."""
    from fractions import Fraction

    a = vcor.simulate(M.SLS(15e6, 0.0, 1e4), 10.0)
    b = vcor.simulate(M.Prony(0.0, (15e6,), (1e4,)), 10.0)
    assert a.ok and b.ok and a.cor == b.cor and 0 < a.cor < 1
    assert vcor.simulate("sls", Fraction(10)).cor == vcor.simulate("sls", 10.0).cor


@pytest.mark.parametrize("method", METHOD_NAMES)
def test_a_maxwell_fluid_gets_a_result_from_every_method(method):
    """SLS(E_glassy, alpha=0, beta=1e9), a Maxwell fluid relaxing in a nanosecond, on the default plate:
    every method returns a result (ive raised ZeroDivisionError before). Where a march reaches the time
    at which the plate's modulus has relaxed to zero in floating point, Zener's plate mobility has no
    bound: status diverged, the message naming the cause and the parameter (alpha); ive's continuous
    solution separates earlier and is ok but flagged (not quasi-static)."""
    fluid = M.SLS(15e6, 0.0, 1e9)
    res = vcor.simulate(fluid, 1.0, method=method)
    assert res.status in ("ok", "diverged"), (res.status, res.message)
    if res.status == "diverged":
        assert "relaxed to zero" in res.message and "alpha" in res.message and "rigid" in res.message
    else:
        assert res.validity != 0 and math.isfinite(res.cor)


@pytest.mark.parametrize("method", ["adaptive", "direct", "soe", "ive-numba"])
def test_a_maxwell_plate_relaxing_within_the_contact_gets_one_verdict(method):
    """SLS(1.5e7, alpha=0, beta=1e6) on the default plate: its modulus falls below 1e-12 of the glassy value
    within the contact (1e-112 Pa, above zero in floating point, in adaptive's march). Every march is
    diverged with the same cause and what to do, and none advises the method it runs."""
    res = vcor.simulate(M.SLS(1.5e7, 0.0, 1e6), 1.0, method=method)
    assert res.status == "diverged" and "relaxed to zero" in res.message and "alpha > 0" in res.message, res.message
    assert "try method adaptive" not in res.message


def test_ive_reports_its_largest_step_and_plain_floats():
    """ive's result gives its largest solve_ivp step as dt (s, finite on an ok result) and plain floats."""
    res = vcor.simulate("sls", 1.0, method="ive")
    assert res.ok and math.isfinite(res.dt) and 0.0 < res.dt < res.t0 and type(res.cor) is float


@pytest.mark.parametrize("method", ["direct", "soe", "ive-numba"])
def test_a_force_creeping_to_zero_is_located_at_its_last_rounding(method):
    """A Maxwell fluid (alpha = 0, relaxing in a microsecond) on a rigid target: the force creeps to zero
    over a second and reaches it from 7e-15 N in one step. The separation is located in that step (the
    bracket is taken at the nodes: the interpolant evaluated there rounded 7e-15 to <= 0 and ive-numba
    raised RuntimeError 'F does not change sign'); the sphere is captured, COR below 1e-12."""
    res = vcor.simulate(M.SLS(1.5e7, 0.0, 1e6), 1.0, target="rigid", method=method)
    assert res.ok and 0.0 <= res.cor < 1e-12 and res.t0 > 1.0, (res.status, res.message, res.cor, res.t0)


def test_dma_file_is_checked_before_any_job(tmp_path):
    """A DMA file without its Set column is refused when the config is loaded, naming file and line
    (it failed inside the fit job before)."""
    (tmp_path / "data").mkdir()
    rows = (ROOT / "data/pyvisco/freq_user_raw.csv").read_text(encoding="utf-8-sig").splitlines()
    (tmp_path / "data/m.csv").write_text("\n".join(",".join(r.split(",")[:4]) for r in rows) + "\n")
    cfg = {"fits": {"m": {"model": "prony", "data": {"file": "data/m.csv", "T_ref": -5}}}}
    with pytest.raises(ValueError, match=r"data/m.csv, line 1: a raw multi-temperature set needs both T and Set"):
        load_project(cfg, tmp_path)
    (tmp_path / "data/one.csv").write_text("\n".join(r for r in rows if r.split(",")[-1].strip() in ("Set", "-", "0")))
    cfg["fits"]["m"]["data"]["file"] = "data/one.csv"
    with pytest.raises(ValueError, match="two or more temperatures, got 1"):
        load_project(cfg, tmp_path)


def test_cached_geometries_and_options_keep_the_type_of_a_value():
    """Geometries and option sets are validated once per distinct value (``checks.interned``); True
    equals 1 in Python, so a cache keyed by value alone would hand h = True the geometry of h = 1 and
    skip its error. The key holds the type."""
    assert vcor.simulate("sls", 10.0, h=1, rigid=False).ok
    with pytest.raises(ValueError, match="h must be in"):
        vcor.simulate("sls", 10.0, h=True, rigid=False)
    assert vcor.simulate("sls", 10.0, method="direct", volterra=True).ok
    with pytest.raises(ValueError, match="volterra must be true or false"):
        vcor.simulate("sls", 10.0, method="direct", volterra=1)


def test_a_number_read_as_text_says_why():
    """PyYAML reads ``3.0e7`` (no sign in the exponent) as text: the refusal says how to write it, in YAML
    and from Python."""
    from vcor.checks import number
    from vcor.materials.specs import from_spec

    spec = yaml.safe_load("{model: sls, E_glassy: 3.0e7, alpha: 300.0, beta: 1200.0}")
    with pytest.raises(ValueError, match=r"E_glassy .*got '3.0e7': text, not a number .*write 3.0e\+7"):
        from_spec(spec, name="stiff")
    with pytest.raises(ValueError, match="write it without quotes"):
        number("x", "12")
    with pytest.raises(ValueError) as exc:
        number("x", "abc")
    assert "text, not a number" not in str(exc.value)
    # the same text from a Python caller (a scene as a mapping): the hint speaks to Python too
    with pytest.raises(ValueError, match=r"v0\[0\]: .*got '1e0': text, not a number \(from Python, write it without "
                       r"quotes; in a YAML file .*write 1.0e\+0\)"):
        vcor.sweep({"materials": ["sls"], "grid": {"v0": ["1e0"]}}, progress=False)


@pytest.mark.parametrize("written, fix", [("3.0e7", "3.0e+7"), ("3e+7", "3.0e+7"), ("1e-9", "1.0e-9")])
def test_every_number_yaml_reads_as_text_gets_the_fix_in_material_specs_and_in_the_config(written, fix):
    """YAML 1.1 reads an exponent as a number only with a dot in the mantissa and a sign in the exponent; the
    material check and the config schema (grids, solver options) both say how to write it."""
    from vcor.materials.specs import from_spec
    from vcor.study.inputs import schema_path
    from vcor.study.schema import check_schema

    value = yaml.safe_load(f"x: {written}")["x"]
    assert isinstance(value, str)
    with pytest.raises(ValueError, match=f"write {re.escape(fix)}"):
        from_spec({"model": "elastic", "E": value}, name="m")
    with pytest.raises(ValueError, match=rf"scenes\.s\.grid\.v0\[0\].*write {re.escape(fix)}"):
        check_schema({"scenes": {"s": {"materials": ["sls"], "grid": {"v0": [value]}}}}, schema_path())


@pytest.mark.filterwarnings("error")
@pytest.mark.parametrize("spec", [{"model": "fractional", "E0": 1e6, "E1": 0.0},
                                  {"model": "cerf", "E0": 1e6, "E1": 0.0, "b1": 3.0}])
@pytest.mark.parametrize("method", ["adaptive", "direct", "soe"])
def test_a_fractional_or_cerf_law_without_its_transient_is_elastic(spec, method):
    """E1 = 0 leaves the constant E0: every method solves it as the elastic law of that modulus (same
    numbers to rounding, no warning, no 0/0 in the exponential sum)."""
    res = vcor.simulate(spec, 1.0, method=method)
    ref = vcor.simulate({"model": "elastic", "E": 1e6}, 1.0, method=method)
    assert res.ok and res.cor == pytest.approx(ref.cor, rel=1e-12, abs=0.0), (res.status, res.message)


@pytest.mark.parametrize("target, words", [
    ({"sphere": {"r": 1e-12}}, "target.sphere.r must be in [1e-09, 1000] m, got 1e-12"),
    ({"sphere": {"rho": 1e-6}}, "target.sphere.rho must be in [0.001, 1e+06] kg/m^3, got 1e-06"),
    ({"plate": {"h": 1e-12}}, "target.plate.h must be in [1e-09, 1000] m, got 1e-12"),
])
def test_a_target_body_out_of_range_is_named_as_written(target, words):
    """The target's own radius, thickness and density are checked against the geometry's ranges and named
    as the user wrote them (not the pair's reduced radius or density)."""
    with pytest.raises(ValueError) as err:
        vcor.simulate("sls", 1.0, target=target)
    assert str(err.value) == words


@pytest.mark.parametrize("target, words", [
    ({"sphere": 5}, "target.sphere: a mapping with keys"),
    ({"plate": "abc"}, "target.plate: a mapping with keys"),
    ({"sphere": {"r": True}}, "target.sphere.r"),
    ({"sphere": {"rho": True}}, "target.sphere.rho"),
])
def test_a_target_body_that_is_not_a_mapping_of_numbers_is_named(target, words):
    """A target body given as something other than a mapping, or a bool for a number, is refused naming
    it (a TypeError, or a run as r = 1 m)."""
    with pytest.raises(ValueError, match=re.escape(words)):
        vcor.simulate("sls", 1.0, target=target)


def test_a_target_body_takes_numpy_scalars():
    ref = vcor.simulate("sls", 1.0, target={"sphere": {"r": 0.01}})
    assert vcor.simulate("sls", 1.0, target={"sphere": {"r": np.float32(0.01)}}).cor == pytest.approx(ref.cor,
                                                                                                     rel=1e-6)


@pytest.mark.parametrize("call", [
    lambda: vcor.simulate({"model": "elastic", "E": 5e-324}, 1.0),
    lambda: vcor.simulate({"model": "elastic", "E": 1e-310}, 1.0),
    lambda: vcor.simulate({"model": "fractional", "E0": 0, "E1": 1e-300}, 1.0),
    lambda: vcor.simulate({"model": "fractional", "E0": 0, "E1": 1e-300}, 1.0, method="direct"),
    lambda: vcor.simulate("sls", 1.0, method="direct", dt=5e-324),
    lambda: vcor.simulate("sls", 1.0, method="soe", steps_per_contact=10**308, max_steps=100),
])
def test_moduli_and_steps_at_the_end_of_the_float_range_give_a_verdict_or_a_named_refusal(call):
    """Underflowing moduli and steps: a ValueError naming what cannot be done, or a non-ok status with its
    message (ZeroDivisionError, OverflowError and NaN-to-integer errors)."""
    try:
        res = call()
    except ValueError as exc:
        assert any(w in str(exc) for w in ("contact time", "dt", "steps_per_contact")), str(exc)
    else:
        assert res.status != "ok" and res.message, (res.status, res.message)


def test_two_fluid_spheres_get_a_result():
    """Two Maxwell-fluid spheres: the combined modulus is 0 where both have relaxed (no 0/0)."""
    res = vcor.simulate(M.SLS(1e6, 0, 1e6), 1.0, target={"sphere": {"material": M.SLS(2e6, 0, 1e6)}})
    assert res.status in ("ok", "no-separation", "diverged") and res.message is not None


@pytest.mark.parametrize("material", [M.SLS(1e20, 0, 1e300), M.Prony(0.0, (1e20,), (1e300,))])
def test_ive_on_overflowing_scales_is_diverged_with_its_reason(material):
    """The largest modulus (vcor.materials.base.MAX_MODULUS) relaxing at a rate of 1e300/s."""
    res = vcor.simulate(material, 1.0, method="ive")
    assert res.status == "diverged" and "non-finite" in res.message, res.message


@pytest.mark.filterwarnings("ignore::RuntimeWarning")
@pytest.mark.parametrize("method", ["direct", "soe", "adaptive"])
def test_a_cerf_rate_beyond_double_precision_gets_a_verdict_or_a_refusal(method):
    """b1 = 1e300 s^-1/2 (b1^4 overflows): a non-ok status or a ValueError, not Python's OverflowError."""
    try:
        res = vcor.simulate({"model": "cerf", "E0": 1e20, "E1": 1e20, "b1": 1e300}, 1.0, method=method)
    except ValueError as exc:
        assert str(exc)
    else:
        assert res.status != "ok" and res.message


@pytest.mark.parametrize("spec", [{"model": "fractional", "E0": 1e6, "E1": 1e-10},
                                  {"model": "cerf", "E0": 1e6, "E1": 1e6, "b1": 1e12},
                                  {"model": "cerf", "E0": 1e6, "E1": 1e6, "b1": 1e-3},
                                  {"model": "cerf", "E0": 1e6, "E1": 1e6, "b1": 1e-8}])
def test_nearly_elastic_fractional_and_cerf_laws_run_by_default(spec):
    """A transient far below E0 (the sum's check cancelled E0 against itself) and a CERF rate b1^2 far
    from the contact's (its spectrum's weight below the nodes' low end) get their exponential sum: the
    default method within 2e-7 of direct at 32000 steps per contact (printed)."""
    res = vcor.simulate(spec, 1.0)
    ref = vcor.simulate(spec, 1.0, method="direct", steps_per_contact=32000)
    print(f"\n{spec}: adaptive {res.cor:.10f}, direct {ref.cor:.10f}, relative {abs(res.cor / ref.cor - 1):.1e}")
    assert res.ok and abs(res.cor / ref.cor - 1) < 2e-7


def test_the_smallest_allowed_soe_tol_is_taken_and_a_smaller_one_refused():
    """soe_tol's range is what a sum checked in double precision reaches: its lower end runs (and meets it);
    below it, a refusal naming soe_tol before any work."""
    from vcor.materials.expsums import MIN_SOE_TOL as SOE_TOL_MIN

    for method in ("soe", "adaptive"):
        res = vcor.simulate("butyl-fc", 1.0, method=method, soe_tol=SOE_TOL_MIN)
        assert res.ok and res.soe_error <= SOE_TOL_MIN, (method, res.status, res.soe_error)
    with pytest.raises(ValueError, match=r"soe_tol"):
        vcor.simulate("butyl-fc", 1.0, soe_tol=SOE_TOL_MIN / 10)


def test_a_zero_dimensional_array_for_a_grid_axis_is_refused_as_a_number():
    """np.array(1.0) is a number, not a list: refused as the number 1.0 would be (a TypeError)."""
    with pytest.raises(ValueError, match=r"^scene\.grid\.v0: got 1\.0; allowed: a list of numbers"):
        vcor.sweep({"materials": ["sls"], "grid": {"v0": np.array(1.0)}}, progress=False, workers=1)


def test_a_grid_step_far_below_its_range_is_refused_in_one_short_line():
    """A step of 1e-300 on [1, 2] m/s: its count of points in three significant digits, not 300 of them."""
    said = r"^scene\.grid: 1e\+300 points in one sweep job \(no shard_size\); a scene"
    with pytest.raises(ValueError, match=said) as err:
        vcor.sweep({"materials": ["sls"], "grid": {"v0": {"start": 1, "stop": 2, "step": 1e-300}}}, progress=False)
    assert len(str(err.value)) < 200


@pytest.mark.parametrize("given, said", [
    ({"target": {"sphere": {"rho": 1e6, "r": 1e-3}}, "rho_a": 1e6, "r": 1e-3}, "density 4e+06 kg/m^3"),
    ({"target": {"sphere": {"r": 1e-9}}, "r": 1e-9}, "reduced radius 5e-10 m"),
])
def test_two_spheres_whose_equivalent_sphere_leaves_the_ranges_are_refused_as_a_pair(given, said):
    """Each sphere in range, their equivalent sphere (what the solver takes) not: the refusal names the pair
    and the equivalent values, not an r or rho_a the user never gave."""
    with pytest.raises(ValueError, match=r"^sphere and target\.sphere: their equivalent sphere \(") as err:
        vcor.simulate("sls", 1.0, **given)
    assert said in str(err.value) and "geometry ranges" in str(err.value)
