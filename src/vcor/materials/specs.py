"""Materials from config specs (the ``materials:`` block of ``config.yaml``).

A spec is a mapping with ``model`` (a registered kind a config may name,
:data:`vcor.materials.base.REGISTRY`) and the model's parameters as its registry entry names them (SI;
the entry gives their units). The Prony model takes one of three forms (a table may
instead come from a CSV ``file``, see below):

* ``{E_inf, E: [...], beta: [...]}``     moduli Pa, rates 1/s (the class's own form),
* ``{E_inf, E: [...], tau: [...]}``      relaxation times s (beta = 1/tau),
* ``{E_0, g: [...], tau: [...]}``        normalised finite-element form (Abaqus, Ansys):
  E(t) = E_0 (1 - sum g_i (1 - e^{-t/tau_i})), instantaneous modulus E_0 (Pa), relative moduli
  g_i >= 0 with sum g_i < 1 (E_inf = E_0 (1 - sum g_i), E_i = E_0 g_i).

Optional ``shift: {model: wlf, C1, C2 [K], T_ref [deg C]}`` or ``{model: arrhenius, E_a [J/mol],
T_ref}`` (any model): the material is then E(t; T) = E(t / a_T(T)) at temperature T
(:mod:`vcor.materials.shift`), and a scene may use ``T`` (deg C) as a grid axis.

A Prony table from a file: ``{model: prony, E_inf or E_0, file: table.csv}``; the CSV has a header row
with ``tau`` or ``beta`` and ``E`` or ``g`` (``g`` needs ``E_0``, ``E`` needs ``E_inf``), one term per
row; a relative path is taken from the project folder. Errors name the key (``materials.<name>.<key>``;
for an unknown key, the keys the model takes and the closest of them) or the file, line and column, with
the allowed range; the classes check the values (positive moduli:
a non-increasing E(t)).
"""

from __future__ import annotations

import difflib
import math
from pathlib import Path

from ..checks import number
from ..io.csvfile import cell_number, data_rows, named_by, project_file, read_rows
from ..io.csvfile import header as column_names
from . import models as _materials
from .base import MAX_MODULUS, modulus
from .shift import ShiftFunction

__all__ = ["PRONY_SPEC_KEYS", "canonical", "from_spec", "read_prony_csv", "shift_function", "spec_models"]

#: the keys of a Prony spec, each optional: its class's own form, relaxation times tau, the normalised form
#: (E_0, g) or a CSV file
PRONY_SPEC_KEYS = frozenset({"E_inf", "E", "beta", "tau", "E_0", "g", "file"})


def spec_models() -> dict:
    """model -> (required keys, optional keys) of every registered model a config may name
    (:data:`vcor.materials.base.REGISTRY`): its parameters, except the Prony model, whose forms
    (:data:`PRONY_SPEC_KEYS`) are all optional keys."""
    return {kind: (set(), set(PRONY_SPEC_KEYS)) if fam.cls is _materials.Prony else (set(fam.names), set())
            for kind, fam in _materials.REGISTRY.items() if fam.configurable}


def _numbers(where, values, unit, lo=0.0, hi=math.inf, *, lo_open=False, hi_open=True):
    """Each of ``values`` (a non-empty list) a number in [lo, hi) (or (lo, hi) with ``lo_open``, [lo, hi] with
    ``hi_open`` False); the errors name ``where[i]`` and that range with ``unit``."""
    if not isinstance(values, (list, tuple)) or not values:
        raise ValueError(f"{where} must be a non-empty list of numbers{f' ({unit})' if unit else ''}, got {values!r}")
    return [number(f"{where}[{i}]", v, lo, hi, lo_open=lo_open, hi_open=hi_open, unit=unit)
            for i, v in enumerate(values)]


#: the ranges of a Prony table's columns, as a config's inline lists have them (:func:`_prony`)
_TABLE_RANGES = {"tau": "(0, inf) s", "beta": "[0, inf) 1/s", "E": f"[0, {MAX_MODULUS:g}] Pa", "g": "[0, 1)"}


def read_prony_csv(path) -> dict:
    """{column: [floats]} of a Prony table (header ``tau`` or ``beta``, ``E`` or ``g``). Errors name the
    file, the line (1-based, the header is line 1) and the column."""
    path = Path(path)
    rows = read_rows(path, "Prony table")
    header = column_names(path, rows)
    time_cols = [c for c in ("tau", "beta") if c in header]
    mod_cols = [c for c in ("E", "g") if c in header]
    unknown = [h for h in header if h not in ("tau", "beta", "E", "g")]
    if unknown or len(time_cols) != 1 or len(mod_cols) != 1:
        raise ValueError(f"{path}, line 1: header {header} must name exactly one of tau (s) or beta (1/s) and "
                         f"one of E (Pa) or g (1); unknown columns: {unknown}")
    out = {time_cols[0]: [], mod_cols[0]: []}
    for lineno, row in data_rows(path, rows, header, 1):
        for col, cell in zip(header, row):
            value = cell_number(path, lineno, col, cell)
            if (value < 0 or (col == "tau" and value == 0) or (col == "g" and value >= 1)
                    or (col == "E" and value > MAX_MODULUS)):
                raise ValueError(f"{path}, line {lineno}, column {col!r}: {cell.strip()} is outside "
                                 f"{_TABLE_RANGES[col]}")
            out[col].append(value)
    if not out[time_cols[0]]:
        raise ValueError(f"{path}: no terms below the header")
    return out


def _table_path(key: str, value, base_dir) -> Path:
    """The path of a Prony table ``value`` (relative: to ``base_dir``, the project folder); ValueError naming
    ``key`` and the folder it was looked for in when there is no such file."""
    if not isinstance(value, (str, Path)) or not str(value).strip():
        raise ValueError(f"{key}: the path of a CSV file (tau or beta, E or g), got {value!r}")
    return project_file(key, value, base_dir, "the Prony table")


def _prony(where, spec, base_dir):
    keys = set(spec) - {"model"}
    table = dict(spec)
    if "file" in keys:
        clash = keys & {"E", "beta", "tau", "g"}
        if clash:
            raise ValueError(f"{where}: give the terms either in file or as {sorted(clash)}, not both")
        path = _table_path(f"{where}.file", spec["file"], base_dir)
        with named_by(f"{where}.file"):
            table.update(read_prony_csv(path))
    if "tau" in table and "beta" in table:
        raise ValueError(f"{where}: give relaxation times tau (s) or rates beta (1/s), not both")
    if "tau" in table:
        beta = [1.0 / t for t in _numbers(f"{where}.tau", table["tau"], "s", lo_open=True)]
    elif "beta" in table:
        beta = _numbers(f"{where}.beta", table["beta"], "1/s")
    else:
        raise ValueError(f"{where}: a prony material needs rates beta (1/s) or times tau (s), or a file")
    if "g" in table:  # normalised finite-element form
        if "E_0" not in spec or "E_inf" in spec or "E" in table:
            raise ValueError(f"{where}: the normalised form needs E_0 (instantaneous modulus, Pa) and g, "
                             f"without E_inf or E")
        e0 = modulus(f"{where}.E_0", spec["E_0"])
        g = _numbers(f"{where}.g", table["g"], "", 0.0, 1.0)
        if any(x < 0 for x in g) or not sum(g) < 1:
            raise ValueError(f"{where}.g: relative moduli must be >= 0 with sum < 1 (the long-term modulus "
                             f"E_0 (1 - sum g) must stay > 0), got {g} (sum {sum(g):g})")
        e_inf, moduli = e0 * (1.0 - sum(g)), [e0 * x for x in g]
    else:
        if "E_0" in spec:
            raise ValueError(f"{where}.E_0 belongs to the normalised form (with g); with moduli E give E_inf")
        if "E" not in table or "E_inf" not in spec:
            raise ValueError(f"{where}: a prony material needs E_inf (Pa) and moduli E (Pa), or E_0 and g")
        e_inf = modulus(f"{where}.E_inf", spec["E_inf"], allow_zero=True)
        moduli = _numbers(f"{where}.E", table["E"], "Pa", hi=MAX_MODULUS, hi_open=False)
    if len(moduli) != len(beta):
        raise ValueError(f"{where}: {len(moduli)} moduli but {len(beta)} relaxation times/rates")
    try:
        return _materials.Prony(e_inf, tuple(moduli), tuple(beta))
    except ValueError as exc:
        raise ValueError(_named(where, str(exc), ("E_inf", "E", "beta"))) from None


def from_spec(spec: dict, *, name: str = "material", base_dir=".", where: str | None = None) -> _materials.Material:
    """A material from a config spec (module docstring); errors name ``materials.<name>.<key>`` (or
    ``<where>.<key>``: an inline material, e.g. a scene's sphere)."""
    where = where or f"materials.{name}"
    if not isinstance(spec, dict):
        # a config value: reported as ValueError, like every bad input
        raise ValueError(f"{where} must be a mapping with 'model' and parameters, got {spec!r}")  # noqa: TRY004
    models = spec_models()
    model = spec.get("model")
    if not isinstance(model, str) or model not in models:
        raise ValueError(f"{where}.model must be one of {sorted(models)}, got {model!r}")
    required, optional = models[model]
    _check_keys(where, model, set(spec) - {"model", "shift"}, required, optional)
    if "shift" in spec:
        ShiftFunction.from_spec(spec["shift"], f"{where}.shift")  # checked here, applied per temperature
    spec = {k: v for k, v in spec.items() if k != "shift"}
    cls = _materials.REGISTRY[model].cls
    if cls is _materials.Prony:
        return _prony(where, spec, base_dir)
    # the constructor checks each parameter against its own range (and says so for a number written as text);
    # its message names the parameter, here with the config's path to it
    try:
        return cls(**{k: spec[k] for k in required})
    except ValueError as exc:
        raise ValueError(_named(where, str(exc), required)) from None


def _check_keys(where: str, model: str, keys: set, required: set, optional: set) -> None:
    """ValueError for a spec of ``model`` with an unknown key (naming ``<where>.<key>``, with the keys
    the model takes and a "did you mean" for a close one) or a missing one (naming ``where``)."""
    missing, unknown = required - keys, sorted(keys - required - optional, key=str)
    takes = f"a {model} material takes {sorted(required | optional)}"
    if unknown:
        key = unknown[0]
        close = difflib.get_close_matches(str(key), sorted(missing) or sorted(required | optional), n=1, cutoff=0.6)
        raise ValueError(f"{where}.{key}: unknown key" + (f" (also unknown: {unknown[1:]})" if unknown[1:] else "")
                         + f"; {takes}" + (f" (missing {sorted(missing)})" if missing else "")
                         + (f"; did you mean {close[0]!r}?" if close else ""))
    if missing:
        raise ValueError(f"{where} ({model}): missing {sorted(missing)}; {takes}")


def _named(where: str, text: str, names) -> str:
    """A constructor's message about one of its parameters ``names`` (``E_glassy must be ...``, or after the
    model's label, ``SLS alpha must be ...``) with the config's path to it (``<where>.E_glassy must be
    ...``); any other message after ``where: ``."""
    words = text.split(" ", 2)
    for i in (0, 1):
        if len(words) > i + 1 and words[i].split("[", 1)[0] in names:
            return f"{where}." + " ".join(words[i:])
    return f"{where}: {text}"


def canonical(spec):
    """``spec`` with every number (not a boolean) a float, in mappings and lists: YAML reads ``5000000`` as an
    integer and ``5.0e+6`` as a float, one value that a material spec (every parameter a real number in SI)
    must not tell apart: the workflow's jobs compare the specs they are given, and re-run on any difference."""
    if isinstance(spec, dict):
        return {k: canonical(v) for k, v in spec.items()}
    if isinstance(spec, list):
        return [canonical(v) for v in spec]
    return float(spec) if isinstance(spec, int) and not isinstance(spec, bool) else spec


def shift_function(spec: dict, name: str = "material") -> ShiftFunction | None:
    """The material's shift function (``shift:`` in its spec) or None."""
    return ShiftFunction.from_spec(spec["shift"], f"materials.{name}.shift") if "shift" in spec else None
