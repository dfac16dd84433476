"""The registry of material models: every family is in it once, the spec reader and material files read
it (a model registered later included), and every parameter carries a unit that its scaling obeys."""

import gc
import math
import re
from dataclasses import dataclass
from pathlib import Path
from typing import ClassVar

import numpy as np
import pytest
import yaml

import vcor
from vcor.materials import models
from vcor.materials.base import REGISTRY, Material, Parameter, from_dict, unregister
from vcor.materials.specs import from_spec, spec_models

ROOT = Path(__file__).resolve().parents[2]
FAMILIES = {"prony": models.Prony, "sls": models.SLS, "elastic": models.Elastic,
            "fractional": models.FractionalPower, "cerf": models.Cerf, "kelvin-voigt": models.KelvinVoigt,
            "eq1": models.EqOne, "exponential-sum": models.ExponentialSum}
#: one spec per model a config may name
SPECS = {
    "sls": {"model": "sls", "E_glassy": 2e7, "alpha": 50.0, "beta": 5000.0},
    "prony": {"model": "prony", "E_inf": 1e6, "E": [3e6, 5e5], "beta": [1e2, 1e5]},
    "elastic": {"model": "elastic", "E": 2e7},
    "fractional": {"model": "fractional", "E0": 1e6, "E1": 4e5},
    "cerf": {"model": "cerf", "E0": 1e6, "E1": 2e8, "b1": 300.0},
    "kelvin-voigt": {"model": "kelvin-voigt", "E": 1e7, "tau": 3e-5},
}


def _subclasses(cls):
    for sub in cls.__subclasses__():
        yield sub
        yield from _subclasses(sub)


def _examples():
    out = [from_spec(spec) for spec in SPECS.values()]
    out.append(models.EqOne(vcor.materials.get("sls"), 1 / (1 - 0.25), vcor.materials.get("butyl-fc"), 1.0))
    return out


def test_the_registry_lists_every_family_once():
    assert {kind: fam.cls for kind, fam in REGISTRY.items()} == FAMILIES
    package = [c for c in _subclasses(Material) if c.__module__.startswith("vcor.materials.")]
    assert sorted(c.__name__ for c in package) == sorted(c.__name__ for c in FAMILIES.values())
    for kind, fam in REGISTRY.items():
        assert fam.cls.kind == kind and fam.title and fam.formula
    assert vcor.materials.REGISTRY is models.REGISTRY


@pytest.mark.parametrize("mat", [*_examples(), models.ExponentialSum(2.0, (1.0, -0.5), (10.0, 20.0))],
                         ids=lambda m: m.kind)
def test_every_model_is_zero_before_the_strain_step(mat):
    """E(t) is causal: every model's time functions give 0 at t < 0, elementwise, an array holding some negative
    times not refused (the SLS formula extrapolated gave 41 MPa at t = -1 ms, the fractional law NaN), and at
    t >= 0 what they give without the negative times beside them."""
    t = np.array([[-1.0, -1e-3, -1e-300], [0.0, 1e-4, 1e-3]])
    functions = {"relaxation_modulus": mat.relaxation_modulus, "relaxation_rate": mat.relaxation_rate,
                 "antiderivative 1": lambda x: mat.antiderivative(x, 1),
                 "antiderivative 2": lambda x: mat.antiderivative(x, 2)}
    with np.errstate(all="raise"):
        for name, fn in functions.items():
            out = fn(t)
            assert out.shape == t.shape, name
            np.testing.assert_array_equal(out[0], 0.0, err_msg=name)
            np.testing.assert_array_equal(out[1, 1:], fn(t[1, 1:]), err_msg=name)
            assert fn(-1e-3) == 0.0 and np.ndim(fn(-1e-3)) == 0, name
        assert mat.modulus_at(-1e-3) == 0.0
    with pytest.raises(ValueError, match="order must be 1 or 2"):
        mat.antiderivative(-1.0, 3)  # the arguments are checked also where every time is negative


def test_every_spec_model_maps_to_one_class():
    models_ = spec_models()
    assert set(models_) == set(SPECS) == {k for k, fam in REGISTRY.items() if fam.configurable}
    classes = [REGISTRY[k].cls for k in models_]
    assert len(set(classes)) == len(classes)
    for kind, spec in SPECS.items():
        assert type(from_spec(spec, name=kind)) is REGISTRY[kind].cls, kind
    with pytest.raises(ValueError, match=r"materials.m.model must be one of \['cerf'"):
        from_spec({"model": "eq1"}, name="m")


def test_every_family_round_trips_through_its_dict():
    for mat in _examples():
        assert from_dict(mat.to_dict()) == mat, mat.kind
        assert set(mat.params()) == set(REGISTRY[mat.kind].names), mat.kind


def _exponents(unit: str) -> dict:
    """{base unit: exponent} of a UDUNITS product such as "Pa s0.5" or "s-1" ("1": dimensionless)."""
    out = {}
    for token in unit.split():
        m = re.fullmatch(r"(Pa|s|1)(-?\d+(?:\.\d+)?)?", token)
        assert m, f"unit {unit!r}: token {token!r} is not Pa, s or 1 with an exponent"
        if m.group(1) != "1":
            out[m.group(1)] = float(m.group(2) or 1)
    return out


@pytest.mark.parametrize("material", _examples(), ids=lambda m: m.kind)
def test_parameters_carry_units_that_scaling_obeys(material):
    """E(t) -> m E(t / a) multiplies a parameter of unit Pa^p s^q by m^p a^q: the registered units are the
    parameters' dimensions, not labels."""
    m, a = 1.7, 3.3
    before, after = material.params(), material.scaled(m, a).params()
    for p in REGISTRY[material.kind].parameters:
        assert isinstance(p, Parameter) and p.meaning
        if p.shape == "material":
            assert p.unit is None
            continue
        e = _exponents(p.unit)
        factor = m ** e.get("Pa", 0.0) * a ** e.get("s", 0.0)
        np.testing.assert_allclose(after[p.name], np.asarray(before[p.name]) * factor, rtol=1e-14,
                                   err_msg=f"{material.kind}.{p.name} [{p.unit}]")


# ----------------------------------------------------------------------------- a model added from outside
def _maxwell():
    """A Maxwell element E(t) = E exp(-t / tau), registered as "maxwell-test" by being defined."""

    @dataclass(frozen=True)
    class Maxwell(Material, kind="maxwell-test"):
        """E(t) = E exp(-t / tau)."""

        TITLE: ClassVar[str] = "Maxwell element (a test model)"
        FORMULA: ClassVar[str] = "E(t) = E exp(-t / tau)"
        PARAMETERS: ClassVar[tuple] = (Parameter(name="E", unit="Pa", meaning="glassy modulus"),
                                       Parameter(name="tau", unit="s", meaning="relaxation time"))

        E: float
        tau: float

        def relaxation_modulus(self, t):
            return self.E * np.exp(-np.asarray(t, dtype=float) / self.tau)

        def params(self):
            return {"E": self.E, "tau": self.tau}

    return Maxwell


def _read_back(maxwell):
    assert "maxwell-test" in spec_models()
    mat = from_spec({"model": "maxwell-test", "E": 2e6, "tau": 1e-3}, name="mx")
    assert type(mat) is maxwell
    assert mat.relaxation_modulus(1e-3) == pytest.approx(2e6 / math.e, rel=1e-15)
    # causal as every model (Material wraps the model's own E(t)), its formula not extrapolated to t < 0
    assert mat.relaxation_modulus(-1e-3) == 0.0 and mat.modulus_at(-1e-3) == 0.0
    assert from_dict(mat.to_dict()) == mat
    with pytest.raises(ValueError, match=r"materials.mx \(maxwell-test\): missing \['tau'\]"):
        from_spec({"model": "maxwell-test", "E": 2e6}, name="mx")


def _package_kinds():
    gc.collect()  # classes sit in reference cycles: only the collector frees them
    return {getattr(c, "kind", None) for c in _subclasses(Material)}


def test_a_registered_model_is_read_by_the_spec_reader_and_from_dict():
    """A model defined outside the package is read by name; once unregistered and dropped, no other
    test sees it (no class left among Material's subclasses)."""
    maxwell = _maxwell()
    try:
        _read_back(maxwell)
    finally:
        unregister("maxwell-test")
    del maxwell
    assert "maxwell-test" not in _package_kinds() and "maxwell-test" not in REGISTRY


def _refusal(name, namespace, kind) -> str:
    """The message of the ValueError that defining a Material subclass raises (only the text is kept,
    so the refused class is not held by a traceback)."""
    try:
        type(name, (Material,), namespace, kind=kind)
    except ValueError as exc:
        return str(exc)
    return ""


def test_a_taken_kind_or_a_model_without_parameters_is_refused():
    one = {"TITLE": "t", "FORMULA": "f", "PARAMETERS": (Parameter(name="E", unit="Pa", meaning="modulus"),)}
    assert "material kind 'sls' is already registered by SLS" in _refusal("Again", one, "sls")
    assert "PARAMETERS must be a non-empty tuple" in _refusal("Bare", {"TITLE": "t", "FORMULA": "f"}, "bare-test")
    assert "TITLE and FORMULA" in _refusal("Untitled", {"PARAMETERS": one["PARAMETERS"]}, "untitled-test")
    with pytest.raises(ValueError, match="a unit .* is required"):
        Parameter(name="E", unit=None, meaning="modulus")
    assert not {"bare-test", "untitled-test"} & set(REGISTRY) and REGISTRY["sls"].cls is models.SLS
    assert "material" not in _package_kinds()  # the refused classes are gone


# ----------------------------------------------------------------------------- tables outside the package
def test_the_schema_enum_names_the_configurable_models():
    schema = yaml.safe_load((ROOT / "workflow" / "schemas" / "config.schema.yaml").read_text())
    enum = schema["properties"]["materials"]["additionalProperties"]["properties"]["model"]["enum"]
    assert sorted(enum) == sorted(spec_models())


def test_the_cli_formula_table_is_the_registry():
    from vcor import cli

    expected = {kind: (fam.title, fam.formula, tuple((p.name, p.unit) for p in fam.parameters))
                for kind, fam in REGISTRY.items() if fam.configurable}
    assert expected == cli.MODEL_FORMULAS
