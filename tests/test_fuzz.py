"""Hostile input, generated (hypothesis, seeded, bounded time): the API and the config either refuse
an input with a ValueError that names the parameter (or config key), or return results whose ``ok``
numbers are finite. Any other exception fails, and so does an ``ok`` result with a non-finite output.
"""

import copy
import math
import time
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
import yaml
from hypothesis import HealthCheck, Phase, given, seed, settings
from hypothesis import strategies as st

import vcor
from vcor import materials as M
from vcor.solvers.common import OUTCOME
from vcor.solvers.options import METHOD_NAMES
from vcor.study.config import load_project

ROOT = Path(__file__).resolve().parents[1]
API_CASES = 500
CONFIG_CASES = 60

#: values no parameter takes, and edge values of the right type
HOSTILE = st.one_of(
    st.sampled_from([None, "10", "", "nan", True, False, [], [1.0], {}, (1.0,), b"1", object(), 1j, Fraction(1, 3),
                     np.float32(1.5), np.int64(2), np.array([1.0, 2.0]), 10**400, -(10**400), 5e-324, -0.0]),
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(-(10**30), 10**30),
)
GEOMETRY = ("r", "rho_a", "rho_b", "h", "nu", "case", "rigid", "E_plate", "nu_plate")
OPTIONS = ("dt", "steps_per_contact", "max_steps", "volterra", "c2", "form", "rule", "rtol", "ive_method", "soe_tol",
           "step_tol", "richardson", "max_adaptive_steps", "ghost")
#: moderate values of each parameter (the solves stay cheap; hostility comes from HOSTILE)
MODERATE = {
    "r": st.floats(1e-3, 0.1), "rho_a": st.floats(100.0, 20000.0), "rho_b": st.floats(100.0, 5000.0),
    "h": st.floats(5e-3, 1.0), "nu": st.floats(-0.9, 0.5), "case": st.sampled_from([1, 2, 3, 4]),
    "rigid": st.booleans(), "E_plate": st.floats(1e6, 1e12), "nu_plate": st.floats(0.0, 0.5),
}
PRESETS = ["sls", "butyl-fc", "butyl-cerf", "butyl-prony3", "elastic", "kelvin-voigt"]
MATERIALS = st.one_of(
    st.sampled_from(PRESETS),
    st.builds(lambda e, a, b: M.SLS(e, a, b), st.floats(1e5, 1e9), st.floats(0.0, 1e3), st.floats(1e3, 1e6)),
    st.builds(lambda e, t: M.KelvinVoigt(e, t), st.floats(1e5, 1e9), st.floats(0.0, 1e-2)),
    # a Maxwell fluid (rubbery modulus 0), relaxing in up to a nanosecond: on a plate its modulus reaches zero
    st.builds(lambda e, b: M.SLS(e, 0.0, b), st.floats(1e5, 1e9), st.floats(1e3, 1e9)),
)


def _call(material, v0, kwargs):
    """simulate(); ValueError passes if it names the offending parameter (``named``), any other
    exception fails; an ok result must have finite outputs."""
    try:
        r = vcor.simulate(material, v0, **kwargs)
    except ValueError as exc:
        return exc
    if r.ok:
        bad = {k: getattr(r, k) for k in OUTCOME if not math.isfinite(getattr(r, k))}
        assert not bad, (material, v0, kwargs, bad)
    else:
        assert r.message, (material, v0, kwargs, r.status)
    return r


def _hostile_case(data):
    """One call with one hostile parameter and the rest moderate: (material, v0, kwargs, the name)."""
    method = data.draw(st.sampled_from(METHOD_NAMES))
    kwargs = {"method": method}
    if method == "direct":
        kwargs["steps_per_contact"] = 200  # cheap: the hostility is elsewhere
    if method == "ive":
        kwargs["max_steps"] = 2000  # bounded: a Maxwell fluid on a rigid target creeps for ever
    for name in data.draw(st.lists(st.sampled_from(sorted(MODERATE)), max_size=3, unique=True)):
        kwargs[name] = data.draw(MODERATE[name])
    material, v0 = data.draw(MATERIALS), data.draw(st.floats(0.1, 50.0))
    target = data.draw(st.sampled_from(["v0", "material", "history", *GEOMETRY, *OPTIONS]))
    value = data.draw(HOSTILE)
    if target == "v0":
        v0 = value
    elif target == "material":
        material = value
    elif target == "history":
        kwargs["history"] = value
    else:
        kwargs[target] = value
    return material, v0, kwargs, target


@pytest.mark.slow  # hundreds of generated calls, many of them solved: ~20 s
def test_api_refuses_or_solves_every_hostile_call():
    start, counts = time.perf_counter(), {"refused": 0, "solved": 0}

    @seed(20261201)
    @settings(max_examples=API_CASES, deadline=None, database=None, phases=[Phase.explicit, Phase.generate],
              suppress_health_check=list(HealthCheck))
    @given(st.data())
    def check(data):
        material, v0, kwargs, target = _hostile_case(data)
        out = _call(material, v0, kwargs)
        if isinstance(out, ValueError):
            counts["refused"] += 1
            text = str(out)
            # the message names what is wrong: the hostile parameter, or one it conflicts with
            named = [target, "material", "v0", "case", "method", "rigid", *GEOMETRY, *OPTIONS]
            assert any(n in text for n in named), (target, text)
            if target not in ("material",) and target not in text:
                # refused for another parameter: it must be one that was given
                assert any(n in text for n in [*kwargs, "material", "v0", "case 1", "method"]), (target, text)
        else:
            counts["solved"] += 1

    check()
    elapsed = time.perf_counter() - start
    print(f"\n{API_CASES} hostile API calls: {counts}, {elapsed:.1f} s")
    # both branches exercised: how many draws are solvable varies with the code, even at a fixed seed
    # (hypothesis mixes the literal constants of the loaded project modules into its draws; 21 and 41 of
    # 500 have been seen), so the guard asks for a count far below either
    assert sum(counts.values()) >= API_CASES and counts["solved"] >= 10 and counts["refused"] > 200


# --- configs --------------------------------------------------------------------------------------
BASE = yaml.safe_load((ROOT / "config.yaml").read_text())
SCENES = sorted(BASE["scenes"])


def _paths(obj, prefix=()):
    """Every key path of a nested mapping (lists indexed)."""
    if isinstance(obj, dict):
        for k, v in obj.items():
            yield (*prefix, k)
            yield from _paths(v, (*prefix, k))
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            yield (*prefix, i)
            yield from _paths(v, (*prefix, i))


CONFIG_PATHS = sorted(_paths(BASE), key=str)
CONFIG_VALUES = st.one_of(
    HOSTILE.filter(lambda v: isinstance(v, (int, float, str, bool, list, dict, type(None)))
                   and not isinstance(v, np.ndarray)),
    st.sampled_from(["", "/", "../outside", "/tmp/elsewhere.csv", "bta", "sls", "v0", "beta", {"start": 1, "stop": 0,
                     "step": 1}, {"start": 1, "stop": 1e9, "step": 1e-3}, [float("nan")], [], {"v0": [1.0]}]),
)


def _set(cfg, path, value):
    obj = cfg
    for k in path[:-1]:
        obj = obj[k]
    if value is _DELETE:
        del obj[path[-1]]
    else:
        obj[path[-1]] = value


_DELETE = object()


def test_config_checks_refuse_or_accept_every_hostile_config(tmp_path):
    """Each case changes one to three keys of the shipped config to a hostile value (or deletes
    them); the checks the workflow runs before any job (schema, then vcor.study.config) raise a
    ValueError (the schema's SchemaError is one) or accept it; nothing else, and never a write."""
    from vcor.study.schema import check_schema

    start, counts = time.perf_counter(), {"refused": 0, "accepted": 0}
    before = sorted(p.name for p in tmp_path.iterdir())

    @seed(20261202)
    @settings(max_examples=CONFIG_CASES, deadline=None, database=None, phases=[Phase.explicit, Phase.generate],
              suppress_health_check=list(HealthCheck))
    @given(st.lists(st.tuples(st.sampled_from(CONFIG_PATHS), st.one_of(CONFIG_VALUES, st.just(_DELETE))),
                    min_size=1, max_size=3))
    def check(changes):
        cfg = copy.deepcopy(BASE)
        for path, value in changes:
            try:
                _set(cfg, path, copy.deepcopy(value) if value is not _DELETE else value)
            except (KeyError, IndexError, TypeError):
                continue  # an earlier change removed or replaced the parent
        try:
            load_project(check_schema(cfg, ROOT / "workflow/schemas/config.schema.yaml"), ROOT)
        except ValueError:
            counts["refused"] += 1
        else:
            counts["accepted"] += 1

    check()
    elapsed = time.perf_counter() - start
    print(f"\n{CONFIG_CASES} hostile configs: {counts}, {elapsed:.1f} s")
    assert sum(counts.values()) >= CONFIG_CASES and counts["refused"] > CONFIG_CASES // 2
    assert sorted(p.name for p in tmp_path.iterdir()) == before


@pytest.mark.parametrize("key, value", [("material_dir", ""), ("material_dir", "/"), ("material_dir", "../out"),
                                        ("material_dir", "results/../../out")])
def test_no_config_writes_outside_the_project(key, value):
    cfg = copy.deepcopy(BASE)
    cfg[key] = value
    with pytest.raises(ValueError, match=key):
        load_project(cfg, ROOT)
