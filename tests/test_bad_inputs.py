"""Bad input as a new user would try it: each row gets a clear error naming the parameter."""

import math
from pathlib import Path

import pytest
import yaml

import vcor
from vcor import materials as M
from vcor import sweep

ROOT = Path(__file__).resolve().parents[1]


def _config_with(mutate):
    cfg = yaml.safe_load((ROOT / "config.yaml").read_text())
    mutate(cfg)
    return cfg


def _validate(cfg):
    """What the workflow does before any job: JSON schema, then the semantic scene checks."""
    from snakemake.utils import validate

    validate(cfg, str(ROOT / "workflow/schemas/config.schema.yaml"))
    for name, scene in cfg["scenes"].items():
        if "grid" in scene:
            sweep.validate_scene(name, scene, fitted=set(cfg.get("fits", {})))


ROWS = [
    # (what a user tries, callable, words the error must contain)
    ("negative modulus", lambda: M.SLS(-15e6, 300, 1200), ["E_glassy", "(0, inf)"]),
    ("nu = 0.7", lambda: vcor.simulate("sls", 10.0, nu=0.7), ["nu", "(-1, 0.5]"]),
    ("v0 = 0", lambda: vcor.simulate("sls", 0.0), ["v0", "(0, inf)"]),
    ("v0 = NaN", lambda: vcor.simulate("sls", math.nan), ["v0"]),
    ("radius NaN", lambda: vcor.simulate("sls", 10.0, r=math.nan), ["r must"]),
    ("increasing 'relaxation' modulus (Prony)", lambda: M.Prony(1e6, (-5e5,), (100.0,)), ["E[0]", "increase"]),
    ("increasing 'relaxation' modulus (SLS)", lambda: M.SLS(15e6, 2400, 1200), ["alpha", "increase"]),
    ("dt bigger than the contact time", lambda: vcor.simulate("sls", 10.0, dt=0.1), ["dt must be in"]),
    ("unknown material", lambda: vcor.simulate("rubber", 10.0), ["unknown material", "sls"]),
    ("unknown geometry keyword", lambda: vcor.simulate("sls", 10.0, thickness=0.02), ["unknown geometry", "h"]),
    ("empty grid", lambda: sweep.axis_values([]), ["empty"]),
    ("empty grid in a config", lambda: _validate(_config_with(lambda c: c["scenes"]["sls"]["grid"].update(v0=[]))),
     ["v0"]),
    ("malformed config: grid value is text",
     lambda: _validate(_config_with(lambda c: c["scenes"]["sls"]["grid"].update(beta="fast"))), ["beta"]),
    ("malformed config: unknown key", lambda: _validate(_config_with(lambda c: c["scenes"]["sls"].update(speed=3))),
     ["speed"]),
    ("malformed config: unknown material",
     lambda: _validate(_config_with(lambda c: c["scenes"]["butyl"].update(materials=["butyl-xyz"]))),
     ["scenes.butyl.materials", "butyl-xyz"]),
]


@pytest.mark.parametrize("what, call, words", ROWS, ids=[r[0] for r in ROWS])
def test_bad_input_row(what, call, words):
    from snakemake.exceptions import WorkflowError

    with pytest.raises((ValueError, WorkflowError)) as info:
        call()
    text = str(info.value)
    for w in words:
        assert w in text, (what, text)
