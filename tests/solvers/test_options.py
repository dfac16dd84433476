"""One table of solver options: the workflow's JSON schema, the CLI and ``simulate`` take their
defaults and allowed values from ``vcor.solvers.options.SolverOptions``."""

import dataclasses
import json
from pathlib import Path

import pytest
import yaml

import vcor
from vcor import cli
from vcor.solvers.options import (
    BOOLEAN_OPTIONS,
    DEFAULT_METHOD,
    SolverOptions,
    solver_options,
)

ROOT = Path(__file__).resolve().parents[2]
SCHEMA = yaml.safe_load((ROOT / "workflow/schemas/config.schema.yaml").read_text())
SOLVER = SCHEMA["properties"]["scenes"]["additionalProperties"]["properties"]["solver"]["properties"]


def test_schema_lists_exactly_the_options():
    assert set(SOLVER) == set(SolverOptions.names())


@pytest.mark.parametrize("name", SolverOptions.names())
def test_schema_default_and_enum_match_the_dataclass(name):
    field = {f.name: f for f in dataclasses.fields(SolverOptions)}[name]
    entry = SOLVER[name]
    # the schema's default is the dataclass field's default (None <-> null: "not set"); a scene's
    # method defaults to DEFAULT_METHOD
    assert entry["default"] == (DEFAULT_METHOD if name == "method" else field.default), name
    allowed = SolverOptions.allowed_of(name)
    if allowed is not None:
        expected = list(allowed) + ([None] if field.default is None else [])
        assert entry["enum"] == expected, name
    if field.default is None and SolverOptions.default_of(name) is not None:
        # the schema says which value "not set" means for the methods that use the option
        value = SolverOptions.default_of(name)
        text = entry.get("description", "")
        assert (f"{value:g}" if isinstance(value, float) else str(value)) in text, (name, text)


def test_schema_bounds_match_the_dataclass():
    assert SOLVER["steps_per_contact"]["minimum"] == 10 and SOLVER["max_steps"]["minimum"] == 100
    for name, bad, good in [("steps_per_contact", 9, 10), ("max_steps", 99, 100)]:
        SolverOptions(method="direct", **{name: good})
        with pytest.raises(ValueError, match=name):
            SolverOptions(method="direct", **{name: bad})
    assert (SOLVER["ghost"]["minimum"], SOLVER["ghost"]["maximum"]) == (0, 10)
    SolverOptions(ghost=0.0), SolverOptions(ghost=10.0)
    assert SOLVER["rtol"]["minimum"] == 1e-13 and SOLVER["rtol"]["exclusiveMaximum"] == 1
    SolverOptions(method="ive", rtol=1e-13)
    with pytest.raises(ValueError, match=r"rtol must be in \[1e-13, 1\)"):
        SolverOptions(method="ive", rtol=1e-20)  # scipy would clamp it with a warning
    assert SOLVER["soe_tol"]["minimum"] == 1e-13 and SOLVER["soe_tol"]["exclusiveMaximum"] == 0.01
    with pytest.raises(ValueError, match=r"soe_tol must be in \[1e-13, 0.01\)"):
        SolverOptions(soe_tol=1e-300)
    assert SOLVER["dt"]["exclusiveMinimum"] == 0


CLI_VALUES = {"method": "ive-numba", "dt": "1e-7", "steps_per_contact": "100", "max_steps": "1000", "c2": "2",
              "form": "b", "rule": "overlap", "rtol": "1e-8", "ive_method": "LSODA", "soe_tol": "1e-8",
              "step_tol": "1e-6", "max_adaptive_steps": "5000"}


def test_cli_flags_are_the_options():
    """Every option except ``ghost`` (histories only) is a flag of ``vcor impact`` with its choices."""
    parser = cli.build_parser()
    for name in SolverOptions.names():
        if name == "ghost":
            continue
        flag = "--" + name.replace("_", "-")
        extra = [flag] if name in BOOLEAN_OPTIONS else [flag, CLI_VALUES[name]]
        args = parser.parse_args(["impact", "--material", "sls", "--v0", "1", *extra])
        got = getattr(args, name)
        if name in BOOLEAN_OPTIONS:
            assert got is True
        else:
            assert str(got) == CLI_VALUES[name] or got == float(CLI_VALUES[name])
        if SolverOptions.allowed_of(name) is not None:
            with pytest.raises(SystemExit):
                parser.parse_args(["impact", "--material", "sls", "--v0", "1", flag, "no-such-value"])


def test_cli_reports_an_ignored_option_by_name(capsys):
    assert cli.main(["impact", "--material", "sls", "--v0", "1", "--method", "ive", "--dt", "1e-7"]) == 2
    assert "solver option dt is not used by method 'ive'" in capsys.readouterr().err


@pytest.mark.parametrize("method, option, value", [
    ("ive", "dt", 1e-7), ("ive", "steps_per_contact", 100), ("ive", "step_tol", 1e-4), ("ive", "form", "b"),
    ("direct", "rtol", 1e-8), ("direct", "ive_method", "LSODA"), ("ive-numba", "form", "a"),
    ("ive-numba", "volterra", True), ("direct", "c2", 2.0),
])
def test_an_option_the_method_ignores_is_an_error_naming_it(method, option, value):
    with pytest.raises(ValueError, match=rf"solver option {option} is not used by method '{method}'"):
        SolverOptions(method=method, **{option: value})
    with pytest.raises(ValueError, match=option):
        vcor.simulate("butyl-prony3", 1.0, method=method, **{option: value})


def test_defaults_are_filled_for_the_method_and_unused_options_stay_unset():
    d = SolverOptions().to_dict()  # the default method, adaptive
    assert d["method"] == "adaptive" and d["step_tol"] == 4e-4 and d["richardson"] is True and d["soe_tol"] == 1e-10
    assert d["dt"] is None and d["steps_per_contact"] is None and d["form"] is None and d["rtol"] is None
    d = SolverOptions(method="direct").to_dict()
    assert d["dt"] is None and d["steps_per_contact"] == 2000 and d["max_steps"] == 200_000 and d["form"] == "a"
    assert d["rtol"] is None and d["ive_method"] is None and d["c2"] is None and d["step_tol"] is None
    i = SolverOptions(method="ive").to_dict()
    assert i["rtol"] == 1e-10 and i["ive_method"] == "Radau" and i["steps_per_contact"] is None and i["form"] is None
    assert i["max_steps"] == 60_000  # solve_ivp's steps: its work is bounded like the other methods'
    assert SolverOptions(method="direct", volterra=True).c2 == 1.0
    # the O(N) methods get a larger step budget (their cost is linear in the steps)
    assert SolverOptions(method="soe").max_steps == SolverOptions(method="ive-numba").max_steps == 4_000_000
    assert SolverOptions(method="soe").soe_tol == 1e-10 and SolverOptions(method="direct").soe_tol is None
    # replace switches method and drops what the new one does not use
    assert SolverOptions(method="direct", dt=1e-7).replace(method="ive").dt is None
    with pytest.raises(dataclasses.FrozenInstanceError):
        SolverOptions().dt = 1.0
    with pytest.raises(TypeError):
        SolverOptions("direct")  # keyword-only
    with pytest.raises(ValueError, match="either as options= or as keywords"):
        solver_options({"method": "ive"}, rtol=1e-8)
    with pytest.raises(ValueError, match="unknown solver option"):
        solver_options({"stepsize": 1e-7})


def test_a_sweep_records_the_resolved_options():
    """Keywords and a SolverOptions give one run; a sweep dataset records the resolved options whole
    (``solver_settings``), every option the method does not use as None."""
    res = vcor.simulate("sls", 1.0, method="ive", rtol=1e-8)
    assert res.ok and res.method.startswith("ive")
    res2 = vcor.simulate("sls", 1.0, options=SolverOptions(method="ive", rtol=1e-8))
    assert res2.cor == res.cor
    ds = vcor.sweep({"materials": ["sls"], "grid": {"v0": [1.0]}, "solver": {"method": "ive", "rtol": 1e-8}},
                    workers=1, progress=False)
    assert json.loads(ds.attrs["solver_settings"])["solver"] == SolverOptions(method="ive", rtol=1e-8).to_dict()
