"""The config's shape, checked against its JSON schema, refused in one line.

``workflow/schemas/config.schema.yaml`` says which keys a config may have, their types, ranges and
defaults (a ``description`` per key). :func:`check_schema` validates a config against it, filling in
the defaults (as ``snakemake.utils.validate(..., set_default=True)`` does), and turns the most
relevant of jsonschema's error objects into one line built from the error's path and validator (not
its text, which for ``oneOf``/``anyOf`` quotes the whole schema):

    scenes.my-study.figure: unknown key; allowed: [...]; did you mean 'figures'?
    scenes.s.grid.v0: got '1,2,3'; allowed: a list of numbers, or a range {start, stop, step} ...

It uses jsonschema directly (Snakemake's ``validate`` raises the first error only, and only as text
wrapped in its own message), with the same default-filling recipe.
"""

from __future__ import annotations

import copy
import difflib
import functools
from pathlib import Path

from ..checks import text_hint

__all__ = ["SchemaError", "check_keys", "check_schema", "explain", "load_schema"]


class SchemaError(ValueError):
    """A config that does not have the schema's shape; the message is one line naming the key."""


@functools.lru_cache(maxsize=4)
def _load(path: str) -> dict:
    from ..io.yamlfile import load_yaml

    return load_yaml(path, what="config schema")


def load_schema(path) -> dict:
    """The schema at ``path`` (YAML), read once per process."""
    return _load(str(Path(path).resolve()))


def _validator(schema: dict):
    from jsonschema import Draft202012Validator, validators

    properties = Draft202012Validator.VALIDATORS["properties"]

    def set_defaults(validator, props, instance, sub):
        if isinstance(instance, dict):
            for name, subschema in props.items():
                if isinstance(subschema, dict) and "default" in subschema:
                    instance.setdefault(name, subschema["default"])
        yield from properties(validator, props, instance, sub)

    cls = validators.extend(Draft202012Validator, {"properties": set_defaults})
    return cls(schema)


def check_schema(config: dict, schema_path) -> dict:
    """``config`` with the schema's defaults filled in; :class:`SchemaError` (one line) when it does
    not have the schema's shape."""
    if config is None:
        config = {}
    if not isinstance(config, dict):
        raise SchemaError(f"the config must be a mapping of sections (scenes, fits, calibrations, dem, "
                          f"materials, ...), got {type(config).__name__} {_short(config)}")
    check_keys(config)
    schema = load_schema(schema_path)
    given = copy.deepcopy(config)  # the validator fills defaults in as it goes: a refusal shows what was given
    errors = list(_validator(schema).iter_errors(config))
    if errors:
        error = _most_relevant(errors)
        error.instance = _given(given, error.absolute_path, error.instance)
        raise SchemaError(explain(error, schema))
    return config


def _given(config, path, instance):
    """A refused mapping ``instance`` (at ``path``) as ``config`` gave it, without the defaults the validator
    filled in; ``instance`` itself where it is not a mapping (a refused key name, a value)."""
    value = config
    for key in path:
        try:
            value = value[key]
        except (KeyError, IndexError, TypeError):
            return instance
    return value if isinstance(instance, dict) and isinstance(value, dict) and set(value) <= set(instance) else instance


def check_keys(value, path=()) -> None:
    """Every key of the config is text: YAML reads an unquoted 2026 as a number and on, off, yes, no, true
    and false as booleans, which no name or key of a config can be (a scene 2026, a material called on).
    SchemaError naming the key and the fix (quote it)."""
    if isinstance(value, dict):
        for key, item in value.items():
            if not isinstance(key, str):
                if isinstance(key, bool):
                    read = ("a boolean (YAML reads an unquoted on, off, yes, no, true or false so); names and keys "
                            "are text: quote the word as written, e.g. 'on'")
                elif key is None:
                    read = "null (YAML reads an empty key, ~ or null so); names and keys are text: name it"
                elif isinstance(key, (int, float)):
                    read = f"a number; names and keys are text: quote it, '{key}'"
                else:  # a date (YAML reads 2026-01-01 so), or another YAML type
                    read = f"a {type(key).__name__}; names and keys are text: quote it as written, e.g. '{key}'"
                raise SchemaError(f"{_where(path)}: the key {key!r} is read as {read}")
            check_keys(item, (*path, key))
    elif isinstance(value, list):
        for i, item in enumerate(value):
            check_keys(item, (*path, i))


def _most_relevant(errors):
    from jsonschema.exceptions import relevance

    return sorted(errors, key=relevance)[-1] if len(errors) > 1 else errors[0]


# -- one line per error -----------------------------------------------------------------------------
def _where(path) -> str:
    out = ""
    for p in path:
        out += f"[{p}]" if isinstance(p, int) else (f".{p}" if out else str(p))
    return out or "the config"


def _short(value, n: int = 60) -> str:
    text = repr(value)
    return text if len(text) <= n else text[: n - 3] + "..."


def _hint(word, choices) -> str:
    close = difflib.get_close_matches(str(word), [str(c) for c in choices], n=1, cutoff=0.6)
    return f"; did you mean {close[0]!r}?" if close else ""


def _allowed_keys(schema: dict) -> list[str]:
    return sorted(schema.get("properties", {}))


#: JSON schema types in a config writer's words
TYPE_WORDS = {"object": "a mapping", "array": "a list", "number": "a number", "integer": "an integer",
              "string": "a text", "boolean": "true or false", "null": "null"}


#: the items of a list, in a config writer's words
_PLURALS = {"object": "mappings", "array": "lists", "number": "numbers", "integer": "integers", "string": "texts",
            "boolean": "true/false values"}


def _form(schema: dict) -> str:
    """A short description of what a (sub)schema accepts."""
    if "description" in schema and len(schema["description"]) <= 120:
        return schema["description"]
    if "const" in schema:
        return repr(schema["const"])
    if "enum" in schema:
        return f"one of {schema['enum']}"
    kind = schema.get("type")
    if kind is None and set(schema) == {"required"}:  # an alternative that only asks for keys
        return "a mapping with " + " and ".join(repr(k) for k in schema["required"])
    if kind == "object" and "properties" in schema:
        req = schema.get("required", [])
        opt = [k for k in schema["properties"] if k not in req]
        return "{" + ", ".join(req + [f"{k}?" for k in opt]) + "}"
    if kind == "array":
        item = schema.get("items", {})
        kind = item.get("type") if isinstance(item, dict) else None
        return f"a list of {_PLURALS.get(kind, 'values')}" if isinstance(kind, str) else "a list"
    if isinstance(kind, str):
        return TYPE_WORDS.get(kind, kind)
    return " or ".join(TYPE_WORDS.get(k, k) for k in kind) if isinstance(kind, list) else "a value"


def _alternatives(error):
    """The context errors of a oneOf/anyOf grouped by alternative, without the alternatives the value's
    type or keys rule out at once."""
    groups = {}
    for sub in error.context:
        groups.setdefault(sub.relative_schema_path[0], []).append(sub)
    near = {}
    for k, subs in groups.items():
        structural = any(len(s.path) == 0 and s.validator in ("type", "required", "additionalProperties", "const")
                         for s in subs)
        if not structural:
            near[k] = subs
    return near


def _unit_range(sub: dict) -> str:
    """" in m, > 0" for a property whose schema names its unit (its "units" annotation) and bounds; ""
    without: what a number there must be, in SI without a unit of its own (a value such as '3 mm' is text)."""
    limits = {"exclusiveMinimum": ">", "minimum": ">=", "maximum": "<=", "exclusiveMaximum": "<"}
    bounds = [f"{limits[k]} {sub[k]}" for k in limits if k in sub]
    said = ", ".join(([f"in {sub['units']}"] if sub.get("units") else []) + bounds)
    return f" ({said})" if said else ""


def explain(error, schema: dict) -> str:
    """One line for a jsonschema ``ValidationError`` (module docstring)."""
    where, given, rule = _where(error.absolute_path), error.instance, error.validator
    sub = error.schema if isinstance(error.schema, dict) else {}
    if "propertyNames" in error.absolute_schema_path and rule == "enum":  # a key that is not a known name
        names = error.validator_value
        return f"{where}.{given}: unknown name; allowed: {names}{_hint(given, names)}"
    if rule in ("oneOf", "anyOf"):
        near = _alternatives(error)
        if len(near) == 1:
            (subs,) = near.values()
            return explain(_most_relevant(subs), schema)
        forms = "; or ".join(_form(s) for s in error.validator_value)
        return f"{where}: got {_short(given)}; allowed: {sub.get('description') or forms}"
    if rule == "additionalProperties":
        allowed = _allowed_keys(sub)
        extra = [k for k in given if k not in allowed]
        key = extra[0] if extra else "?"
        return f"{where}.{key}: unknown key; allowed: {allowed}{_hint(key, allowed)}" if where != "the config" \
            else f"{key}: unknown section; allowed: {allowed}{_hint(key, allowed)}"
    if rule == "required":
        missing = [k for k in error.validator_value if k not in given]
        near = difflib.get_close_matches(missing[0], [str(k) for k in given], n=1, cutoff=0.5)
        written = f"; {near[0]!r} is written: did you mean {missing[0]!r}?" if near else ""
        return f"{where}: missing key {missing[0]!r} (required: {error.validator_value}){written}"
    if rule == "enum":
        return f"{where}: {_short(given)} is not allowed; allowed: {error.validator_value}" \
               f"{_hint(given, error.validator_value)}"
    if rule == "const":
        return f"{where}: {_short(given)} is not allowed; allowed: {error.validator_value!r}"
    if rule == "type":
        return (f"{where}: expected {_form({'type': error.validator_value})}{_unit_range(sub)}, got {_short(given)}"
                f"{text_hint(given)}")
    limits = {"minimum": ">=", "maximum": "<=", "exclusiveMinimum": ">", "exclusiveMaximum": "<"}
    if rule in limits:  # with the property's unit, where the schema names one (its "units" annotation)
        unit = f" {sub['units']}" if sub.get("units") else ""
        return f"{where}: must be {limits[rule]} {error.validator_value}{unit}, got {_short(given)}{unit}"
    if rule == "minItems" and given == []:
        return f"{where}: the list is empty; give at least {error.validator_value} value(s)"
    if rule in ("minItems", "maxItems", "minProperties", "maxProperties"):
        what = "item" if "Items" in rule else "entry"
        bound = "at least" if rule.startswith("min") else "at most"
        return f"{where}: {bound} {error.validator_value} {what}(s), got {_short(given)}"
    if rule == "uniqueItems":
        return f"{where}: each value at most once, got {_short(given)}"
    return f"{where}: {_short(given)} does not satisfy {rule} {_short(error.validator_value)}"
