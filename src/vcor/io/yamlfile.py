"""Reading YAML and JSON files strictly: a key given twice in one mapping is an error.

PyYAML, Python's ``json`` and Snakemake's config loader all keep the last of two equal keys of a mapping
without a word, so a config with two ``v0:`` lines in one grid silently loses the first. Every YAML or
JSON file vcor reads (configs, the config schema, material files) goes through this module, which
refuses such a file in one line naming the file, the key, both lines and the second one's column::

    config file config.yaml, line 14, column 5: key 'v0' is given twice in one mapping (lines 12 and 14): only
    the last would be read; remove or rename one

Equal means equal once read (``1`` and ``1.0`` are the same key, ``'v0'`` and ``v0`` too); the same key in
two different mappings is of course allowed, and so is a key that overrides one brought in by a YAML
merge key (``<<: *defaults``). Values are read as ``yaml.safe_load`` (libyaml's parser when PyYAML has it)
and ``json.loads`` read them.
"""

from __future__ import annotations

import functools
import json
from pathlib import Path

__all__ = ["RepeatedKeyError", "load_json", "load_yaml", "loads_yaml"]


class RepeatedKeyError(ValueError):
    """A key given twice in one mapping; the message names the file, the key and both lines."""


def _message(where: str, key, first: int | None, second: int | None, column: int | None = None) -> str:
    if first is None:
        return f"{where}: key {key!r} is given twice in one object: only the last would be read; remove or rename one"
    lines = f"lines {first} and {second}" if first != second else f"both on line {second}"
    at = f", line {second}" + (f", column {column}" if column is not None else "")
    return (f"{where}{at}: key {key!r} is given twice in one mapping ({lines}): only the last would be read; "
            f"remove or rename one")


class _Repeated(Exception):
    """A repeated key found while reading: the key and the lines of both (None: not known)."""

    def __init__(self, key, first=None, second=None, column=None):
        super().__init__(key)
        self.key, self.first, self.second, self.column = key, first, second, column


@functools.cache
def _strict_loader():
    """A safe YAML loader class whose mappings refuse a repeated key (:class:`_Repeated`)."""
    import yaml

    class StrictLoader(getattr(yaml, "CSafeLoader", yaml.SafeLoader)):
        pass

    def construct_mapping(loader, node, deep=False):
        seen = {}
        for key_node, _ in node.value:
            if key_node.tag == "tag:yaml.org,2002:merge":  # '<<': the keys it brings may be overridden
                continue
            key, mark = loader.construct_object(key_node, deep=True), key_node.start_mark
            line = mark.line + 1
            try:
                if key in seen:
                    raise _Repeated(key, seen[key], line, mark.column + 1)
                seen[key] = line
            except TypeError:  # an unhashable key: the safe constructor refuses it with its own message
                break
        return yaml.SafeLoader.construct_mapping(loader, node, deep=deep)

    StrictLoader.add_constructor("tag:yaml.org,2002:map", construct_mapping)
    return StrictLoader


def _yaml(text: str, where: str):
    import yaml

    try:
        return yaml.load(text, Loader=_strict_loader())  # a SafeLoader with stricter mappings
    except _Repeated as rep:
        raise RepeatedKeyError(_message(where, rep.key, rep.first, rep.second, rep.column)) from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        at = f", line {mark.line + 1}, column {mark.column + 1}" if mark is not None else ""
        problem = getattr(exc, "problem", None) or str(exc).splitlines()[0]
        raise ValueError(f"{where}{at}: not valid YAML ({problem})") from None


def _pairs(pairs):
    out = {}
    for key, value in pairs:
        if key in out:
            raise _Repeated(key)
        out[key] = value
    return out


def _json(text: str, where: str):
    """The JSON ``text``; a repeated key is located by reading the text as YAML (JSON is YAML's flow
    style; a tab, which JSON allows between tokens and never inside a string, is read as a space)."""
    try:
        return json.loads(text, object_pairs_hook=_pairs)
    except _Repeated as rep:
        try:
            _yaml(text.replace("\t", " "), where)
        except RepeatedKeyError:
            raise
        except ValueError:
            pass
        raise RepeatedKeyError(_message(where, rep.key, None, None)) from None


def _read(path, what: str) -> tuple[str, str]:
    path = Path(path)
    where = f"{what} {str(path)}"
    try:
        return path.read_text(encoding="utf-8-sig"), where
    except FileNotFoundError:
        raise ValueError(f"{where} does not exist") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ValueError(f"{where} cannot be read ({exc})") from None


def load_yaml(path, *, what: str = "config file"):
    """The content of the YAML or JSON file at ``path`` (tried as JSON first, then as YAML, as Snakemake
    reads a config file). ``what`` names the file's role in the errors: :class:`RepeatedKeyError` for a
    key given twice in one mapping (the key, both lines and the second's column), ValueError for a file
    that is missing or not valid YAML (line and column).

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from vcor.io.yamlfile import load_yaml
    >>> path = Path(tempfile.mkdtemp()) / "config.yaml"
    >>> _ = path.write_text("scenes:\\n  s:\\n    grid:\\n      v0: [1, 2]\\n      v0: [3]\\n")
    >>> try:
    ...     load_yaml(path)
    ... except ValueError as exc:
    ...     print(exc)
    config file ...config.yaml, line 5, column 7: key 'v0' is given twice in one mapping (lines 4 and 5): only
    the last would be read; remove or rename one
    """
    text, where = _read(path, what)
    try:
        return _json(text, where)
    except json.JSONDecodeError:
        return _yaml(text, where)


def loads_yaml(text: str, where: str):
    """The YAML ``text`` (a command-line value), read as :func:`load_yaml` reads a file: a key given twice in
    one mapping is :class:`RepeatedKeyError`, text that is not YAML ValueError, each naming ``where``."""
    return _yaml(text, where)


def load_json(path, *, what: str = "JSON file"):
    """The content of the JSON file at ``path``; :class:`RepeatedKeyError` for a key given twice in one
    object (naming both lines when the file reads as YAML too, as JSON files almost always do),
    ValueError for a file that is missing or not valid JSON (line and column)."""
    text, where = _read(path, what)
    try:
        return _json(text, where)
    except json.JSONDecodeError as exc:
        raise ValueError(f"{where}, line {exc.lineno}, column {exc.colno}: not valid JSON ({exc.msg})") from None
