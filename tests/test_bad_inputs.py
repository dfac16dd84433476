"""Bad input as a new user would try it: one table, a row each. Every row must raise a ValueError
(or the workflow's WorkflowError) whose text names the parameter and, where there is one, the
allowed range, before any work is done. Rows that a user might expect to fail but that are valid
(the paper's own elastic limit in case 1, a fit to one domain only) are in ``VALID`` below."""

import math
from pathlib import Path

import numpy as np
import pytest
import yaml

import vcor
from vcor.fitting import fits
from vcor.fitting import prony as fit
from vcor.materials import Catalogue
from vcor.study import scene
from vcor import materials as M
from vcor import spheres as S

ROOT = Path(__file__).resolve().parents[1]


def _config_with(mutate):
    cfg = yaml.safe_load((ROOT / "config.yaml").read_text())
    mutate(cfg)
    return cfg


def _validate(cfg):
    """What the workflow does before any job: JSON schema, then the semantic scene checks."""
    from snakemake.utils import validate

    validate(cfg, str(ROOT / "workflow/schemas/config.schema.yaml"))
    for name, sc in cfg["scenes"].items():
        if "grid" in sc:
            scene.validate_scene(name, sc, Catalogue(fits=dict(cfg.get("fits", {}))))


_BT = fit.bagley_torvik_data()
_FREQ_ONLY = fit.FitData(omega=_BT.omega, E_star=_BT.E_star)

ROWS = [
    # (what a user tries, callable, words the error must contain)
    # --- numbers: type and range -------------------------------------------------------------
    ("r = True", lambda: vcor.simulate("sls", 10.0, r=True), ["r must be in (0, inf) m", "True"]),
    ("r = 'abc'", lambda: vcor.simulate("sls", 10.0, r="abc"), ["r must be in (0, inf) m", "'abc'"]),
    ("r negative", lambda: vcor.simulate("sls", 10.0, r=-0.01), ["r must be in (0, inf)"]),
    ("r NaN", lambda: vcor.simulate("sls", 10.0, r=math.nan), ["r must"]),
    ("rho_a = 0", lambda: vcor.simulate("sls", 10.0, rho_a=0.0), ["rho_a", "(0, inf)"]),
    ("rho_b negative", lambda: vcor.simulate("sls", 10.0, rho_b=-1.0), ["rho_b", "(0, inf)"]),
    ("nu = 0.7", lambda: vcor.simulate("sls", 10.0, nu=0.7), ["nu", "(-1, 0.5]"]),
    ("nu = -1", lambda: vcor.simulate("sls", 10.0, nu=-1.0), ["nu", "(-1, 0.5]"]),
    ("h = False", lambda: vcor.simulate("sls", 10.0, h=False), ["h must be in (0, inf) m"]),
    ("h = [1e-3] (unhashable: past the geometry cache)", lambda: vcor.simulate("sls", 10.0, h=[1e-3]),
     ["h must be in (0, inf) m", "[0.001]"]),
    ("v0 = 0", lambda: vcor.simulate("sls", 0.0), ["v0", "(0, inf) m/s"]),
    ("v0 negative", lambda: vcor.simulate("sls", -3.0), ["v0", "(0, inf)"]),
    ("v0 = NaN", lambda: vcor.simulate("sls", math.nan), ["v0"]),
    ("v0 = '10'", lambda: vcor.simulate("sls", "10"), ["v0", "(0, inf)", "'10'"]),
    ("case = 5", lambda: vcor.simulate("sls", 10.0, case=5), ["case", "1, 2, 3, 4"]),
    ("case = True", lambda: vcor.simulate("sls", 10.0, case=True), ["case", "1, 2, 3, 4"]),
    ("rigid = 'yes'", lambda: vcor.simulate("sls", 10.0, rigid="yes"), ["rigid", "true or false"]),
    ("unknown keyword", lambda: vcor.simulate("sls", 10.0, thickness=0.02), ["unknown keyword", "thickness", "'h'"]),
    ("unknown material", lambda: vcor.simulate("rubber", 10.0), ["unknown material", "sls"]),
    # --- materials ---------------------------------------------------------------------------
    ("SLS(alpha=True)", lambda: M.SLS(15e6, True, 1200), ["alpha", "[0, inf) 1/s", "True"]),
    ("SLS negative modulus", lambda: M.SLS(-15e6, 300, 1200), ["E_glassy", "(0, inf) Pa"]),
    ("SLS E_glassy = '15e6'", lambda: M.SLS("15e6", 300, 1200), ["E_glassy", "(0, inf) Pa"]),
    ("SLS increasing modulus", lambda: M.SLS(15e6, 2400, 1200), ["alpha", "increase"]),
    ("Prony negative term", lambda: M.Prony(1e6, (-5e5,), (100.0,)), ["E[0]", "increase"]),
    ("Prony negative rate", lambda: M.Prony(1e6, (1e6,), (-10.0,)), ["beta[0]", "[0, inf) 1/s"]),
    ("Prony term True", lambda: M.Prony(1e6, (True,), (10.0,)), ["E[0]", "True"]),
    ("Prony lengths differ", lambda: M.Prony(1e6, (1e6, 2e6), (10.0,)), ["equal length"]),
    ("fractional E0 negative", lambda: M.FractionalPower(-1.0, 1.0), ["E0", "[0, inf) Pa"]),
    ("CERF b1 = 0", lambda: M.Cerf(1.0, 1.0, 0.0), ["b1", "(0, inf)"]),
    ("Kelvin-Voigt tau negative", lambda: M.KelvinVoigt(1e6, -1.0), ["tau", "[0, inf) s"]),
    ("Elastic E NaN", lambda: M.Elastic(float("nan")), ["E must be in (0, inf) Pa"]),
    ("preset name unknown", lambda: M.get("rubber"), ["unknown material", "sls"]),
    # --- cases and solver options ------------------------------------------------------------
    ("case 1 with a relaxing material", lambda: vcor.simulate("sls", 10.0, case=1), ["case 1", "elastic material"]),
    ("case 1 with Kelvin-Voigt", lambda: vcor.simulate("kelvin-voigt", 10.0, case=1),
     ["case 1", "elastic material", "kelvin-voigt"]),
    ("dt bigger than the contact", lambda: vcor.simulate("sls", 10.0, method="direct", dt=0.1), ["dt must be in"]),
    ("dt negative", lambda: vcor.simulate("sls", 10.0, dt=-1e-6), ["dt must be in (0, inf) s"]),
    ("dt with ive", lambda: vcor.simulate("sls", 10.0, method="ive", dt=1e-6), ["dt", "not used by method 'ive'"]),
    ("rtol with direct", lambda: vcor.simulate("sls", 10.0, method="direct", rtol=1e-8), ["rtol", "not used by method 'direct'"]),
    ("c2 without volterra", lambda: vcor.simulate("sls", 10.0, c2=2.0), ["c2", "volterra"]),
    ("volterra with ive-numba", lambda: vcor.simulate("sls", 10.0, method="ive-numba", volterra=True),
     ["volterra", "ive-numba"]),
    ("method unknown", lambda: vcor.simulate("sls", 10.0, method="euler"), ["method", "direct"]),
    ("steps_per_contact = 5", lambda: vcor.simulate("sls", 10.0, steps_per_contact=5), ["steps_per_contact", ">= 10"]),
    ("form b, fractional kernel", lambda: vcor.simulate("butyl-fc", 10.0, method="direct", form="b"), ["form 'b'"]),
    ("ive, fractional kernel", lambda: vcor.simulate("butyl-fc", 10.0, method="ive"), ["Prony", "'ive'"]),
    ("options twice", lambda: vcor.simulate("sls", 10.0, options={"method": "ive"}, rule="overlap"), ["not both"]),
    # --- fits ---------------------------------------------------------------------------------
    ("fit data: zero loss modulus",
     lambda: fit.FitData(omega=[1.0, 2.0, 3.0], E_star=[1 + 1j, 2 + 0j, 3 + 1j]), ["loss modulus", "> 0 Pa", "omega = 2"]),
    ("fit data: negative loss modulus",
     lambda: fit.FitData(omega=[1.0, 2.0, 3.0], E_star=[1 + 1j, 2 - 1j, 3 + 1j]), ["loss modulus", "> 0 Pa"]),
    ("fit data: increasing E(t)", lambda: fit.FitData(t=[1e-3, 2e-3, 3e-3], E_t=[1e6, 2e6, 1.5e6]), ["increases"]),
    ("fit data: negative E(t)", lambda: fit.FitData(t=[1e-3, 2e-3, 3e-3], E_t=[1e6, -2e6, -3e6]), ["> 0 Pa"]),
    ("fit data: unsorted times", lambda: fit.FitData(t=[3e-3, 2e-3, 1e-3], E_t=[3e6, 2e6, 1e6]), ["strictly increasing"]),
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
    ("config: option the method ignores",
     lambda: _validate(_config_with(lambda c: c["scenes"]["sls"].update(solver={"method": "ive", "dt": 1e-6}))),
     ["scenes.sls.solver", "dt", "not used by method 'ive'"]),
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
