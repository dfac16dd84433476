"""Sphinx extension of the vcor documentation: tables generated from the package and the schema.

Directives (MyST: ```` ```{vcor-solver-options} ````):

``vcor-solver-options``
    every solver option from :mod:`vcor.solvers.options` (``SolverOptions.names``, ``default_of``,
    ``allowed_of``, ``methods_of``, ``OPTION_HELP``, ``OPTION_UNITS``).
``vcor-statuses``
    the status vocabulary of :mod:`vcor.status` (codes from ``STATUS_CODES``, meanings from the
    module's table).
``vcor-result-fields``
    the fields of a :class:`vcor.solvers.common.Result` with units (``UNITS``, ``LONG_NAMES``).
``vcor-layers``
    the architecture's layers as ``tests/test_architecture.py`` enforces them (``LAYERS``).
``vcor-grid-axes``
    the grid axes a scene may sweep with their units (``vcor.study.scene.AXIS_UNITS``).
``vcor-presets``
    the preset materials (``vcor.materials.PRESETS``) with their parameters.
``vcor-figures``
    the figure registry (``vcor.plots.FIGURES``) with the datasets each needs and its report caption
    (``workflow/report/figures/<name>.rst``).
``vcor-value`` (a role)
    the value of a constant of the package, e.g. ``{vcor-value}`vcor.solvers.adaptive.FLOOR_BITS```.
``TableCodeBreaks`` (a post-transform)
    break opportunities in code inside table cells, so that long names wrap inside the page.
``vcor-config-reference``
    every key of ``workflow/schemas/config.schema.yaml`` with its type, allowed values and default; the
    directive's body (YAML: key path -> meaning) gives the meaning. A schema key without a meaning, or
    a meaning for a key the schema lacks, fails the build.
"""

from __future__ import annotations

import importlib
import re
from pathlib import Path

import yaml
from docutils import nodes
from docutils.parsers.rst import Directive
from docutils.statemachine import StringList
from sphinx.transforms.post_transforms import SphinxPostTransform

from vcor.io.yamlfile import load_yaml

ROOT = Path(__file__).resolve().parents[2]
SCHEMA = ROOT / "workflow" / "schemas" / "config.schema.yaml"
CAPTIONS = ROOT / "workflow" / "report" / "figures"

#: modules left out of the API reference (not public API: the command line is documented in the guide)
HIDDEN_MODULES = ["vcor.cli", "vcor.version"]


# ----------------------------------------------------------------------------- docutils helpers
def _inline(text: str) -> list[nodes.Node]:
    """Text with ``code`` spans (single backticks) as literal nodes."""
    out: list[nodes.Node] = []
    for i, part in enumerate(re.split(r"`([^`]*)`", str(text))):
        if part:
            out.append(nodes.literal(part, part) if i % 2 else nodes.Text(part))
    return out


def _plain(rst: str) -> str:
    """A docstring's reStructuredText reduced to text with `code` spans (roles and ``literals``)."""
    rst = re.sub(r":[\w:]+:`~?([^`<]+?)(?:\s*<[^>]+>)?`", r"`\1`", rst)
    return rst.replace("``", "`")


def _table(headers, rows, widths=None, state=None, offset=0) -> nodes.table:
    """A table node; with ``state`` (a directive's), each body cell is parsed as the page's markup
    (roles such as {doc} work), else only `code` spans are recognised."""
    table = nodes.table(classes=["vcor-generated", "colwidths-given"])
    group = nodes.tgroup(cols=len(headers))
    table += group
    for w in widths or [1] * len(headers):
        group += nodes.colspec(colwidth=w)
    head = nodes.thead()
    group += head
    body = nodes.tbody()
    group += body
    for target, cells in ((head, [headers]), (body, rows)):
        for cells_of_row in cells:
            row = nodes.row()
            for cell in cells_of_row:
                entry = nodes.entry()
                if state is not None and target is body:
                    state.nested_parse(StringList(str(cell).splitlines() or [""]), offset, entry)
                else:
                    for para in str(cell).split("\n\n"):
                        entry += nodes.paragraph("", "", *_inline(para))
                row += entry
            target += row
    return table


def _fmt(value) -> str:
    if value is None:
        return "not set"
    if isinstance(value, bool):
        return "`true`" if value else "`false`"
    if isinstance(value, str):
        return f"`{value}`"
    if isinstance(value, float):
        return f"`{value:g}`"
    if isinstance(value, (list, tuple)):
        return "`[" + ", ".join(str(v) for v in value) + "]`"
    if isinstance(value, dict):
        return "`{}`" if not value else f"`{value}`"
    return f"`{value}`"


# ----------------------------------------------------------------------------- solver options
class SolverOptionsTable(Directive):
    """Every solver option: methods, default (and per-method defaults), unit, allowed values, meaning."""

    def run(self):
        from vcor.solvers.options import (
            DEFAULT_METHOD,
            FIXED_STEP_METHODS,
            METHOD_NAMES,
            OPTION_HELP,
            OPTION_UNITS,
            SolverOptions,
        )

        rows = []
        for name in SolverOptions.names():
            methods = SolverOptions.methods_of(name)
            default = SolverOptions.default_of(name)
            text = "automatic" if default is None else _fmt(default)
            groups: dict = {}
            for m in methods:
                d = SolverOptions.default_of(name, m)
                if d != default:
                    groups.setdefault(_fmt(d), []).append(f"`{m}`")
            if groups:
                text += "; " + "; ".join(f"{d} for {', '.join(ms)}" for d, ms in groups.items())
            if name == "method":
                text = f"`{DEFAULT_METHOD}`"
            if set(methods) == set(METHOD_NAMES):
                used = "all"
            elif set(methods) == set(FIXED_STEP_METHODS):
                used = "fixed-step: " + ", ".join(f"`{m}`" for m in methods)
            else:
                used = ", ".join(f"`{m}`" for m in methods)
            unit = {"none": "–", "1": "1"}.get(OPTION_UNITS[name], OPTION_UNITS[name])
            allowed = SolverOptions.allowed_of(name)
            meaning = OPTION_HELP[name] + ("\n\nallowed: " + ", ".join(f"`{a}`" for a in allowed) if allowed else "")
            rows.append([f"`{name}`", used, text, unit, meaning])
        return [_table(["option", "used by", "default", "unit", "meaning"], rows, [5, 4, 4, 1, 12])]


# ----------------------------------------------------------------------------- statuses
class StatusTable(Directive):
    def run(self):
        from vcor import status

        meanings = {}
        for line in (status.__doc__ or "").splitlines():
            m = re.match(r"^(\S+)\s+(\d+)\s+(.+)$", line.strip())
            if m and m.group(1) in status.STATUS_CODES:
                meanings[m.group(1)] = (int(m.group(2)), m.group(3))
        rows = []
        for name, code in sorted(status.STATUS_CODES.items(), key=lambda kv: kv[1]):
            if name not in meanings or meanings[name][0] != code:
                raise self.error(f"vcor.status: the module docstring's table has no row {name!r} with code {code}")
            rows.append([f"`{name}`", str(code), meanings[name][1]])
        return [_table(["status", "code", "meaning"], rows, [3, 1, 12])]


# ----------------------------------------------------------------------------- result fields
class ResultFields(Directive):
    def run(self):
        from vcor.solvers.common import LONG_NAMES, UNITS

        rows = [[f"`{k}`", UNITS[k], LONG_NAMES.get(k, "")] for k in UNITS]
        return [_table(["field", "unit (UDUNITS)", "meaning"], rows, [3, 2, 10])]


# ----------------------------------------------------------------------------- architecture
ARCHITECTURE_TEST = ROOT / "tests" / "test_architecture.py"


class LayerTable(Directive):
    """The layers of ``tests/test_architecture.py`` (``LAYERS``, bottom first), each unit with the first
    line of its docstring."""

    def run(self):
        import ast

        tree = ast.parse(ARCHITECTURE_TEST.read_text())
        layers = next((ast.literal_eval(n.value) for n in ast.walk(tree) if isinstance(n, ast.Assign)
                       and any(isinstance(t, ast.Name) and t.id == "LAYERS" for t in n.targets)), None)
        if layers is None:
            raise self.error(f"{ARCHITECTURE_TEST}: no LAYERS")
        rows = []
        for i, units in enumerate(layers, 1):
            parts = []
            for unit in units:
                mod = importlib.import_module(f"vcor.{unit}")
                summary = " ".join((mod.__doc__ or "").strip().split("\n\n")[0].split())
                parts.append(f"`vcor.{unit}`: {_plain(summary)}")
            rows.append([str(i), "\n\n".join(parts)])
        return [_table(["layer", "units (a module may import its own layer and the ones below)"], rows, [1, 12])]


# ----------------------------------------------------------------------------- grid axes
class GridAxes(Directive):
    def run(self):
        from vcor.study.scene import AXIS_UNITS

        rows = [[f"`{k}`", unit, meaning] for k, (unit, meaning) in AXIS_UNITS.items()]
        return [_table(["axis", "unit (UDUNITS)", "meaning"], rows, [2, 2, 10])]


# ----------------------------------------------------------------------------- presets
class PresetTable(Directive):
    def run(self):
        from vcor import materials

        rows = []
        for name in materials.PRESETS:
            mat = materials.get(name)
            params = ", ".join(f"{k} = {v:g}" if isinstance(v, float) else
                               f"{k} = ({', '.join(f'{x:g}' for x in v)})" if isinstance(v, (list, tuple)) else
                               f"{k} = {v}" for k, v in mat.params().items())
            rows.append([f"`{name}`", f"`{type(mat).__name__}`", params])
        return [_table(["preset", "class", "parameters (SI: Pa, 1/s, s, Pa s^0.5, s^-1/2)"], rows, [3, 3, 12])]


# ----------------------------------------------------------------------------- figures
class FigureTable(Directive):
    def run(self):
        from vcor import plots

        schema = load_yaml(SCHEMA, what="config schema")
        enum = schema["properties"]["scenes"]["additionalProperties"]["properties"]["figures"]["propertyNames"]["enum"]
        rows = []
        for name, (_, needs) in plots.FIGURES.items():
            path = CAPTIONS / f"{name}.rst"
            if not path.is_file():
                raise self.error(f"figure {name!r} has no caption {path}")
            caption = " ".join(path.read_text().split())
            caption = re.sub(r"\s*\(scene \{\{[^}]*\}\}\)", "", caption)
            caption = re.sub(r"\{\{[^}]*\}\}", "…", caption).replace("**", "")
            options = plots.FIGURE_OPTIONS[name]
            defaults = plots.OPTION_DEFAULTS.get(name, {})
            opts = [f"`{o}` ({kind}" + (f", default `{defaults[o]}`" if o in defaults else "") + ")"
                    for o, kind in options.items()]
            if name in plots.AXIS_OPTIONS:
                opts.append("any other grid axis (the value drawn)")
            axes = ", ".join(f"`{a}`" for a in plots.NEEDS_AXIS.get(name, ()))
            rows.append([f"`{name}`", ", ".join(f"`{n}`" for n in needs) + (f"; grid axis {axes}" if axes else ""),
                         "; ".join(opts) or "none", caption])
        missing = set(plots.FIGURES) ^ set(enum)
        if missing:
            raise self.error(f"figures in the schema enum and vcor.plots.FIGURES differ: {sorted(missing)}")
        return [_table(["figure", "needs", "options (what the value names)", "caption (from the report)"], rows,
                       [3, 3, 5, 10])]


# ----------------------------------------------------------------------------- validity flags
class ValidityTable(Directive):
    def run(self):
        from vcor.solvers import extrapolation, validity

        limits = {"large_indentation": f"s_max / r > {validity.MAX_INDENTATION:g}",
                  "fast_impact": f"v0 > {validity.MAX_SPEED_FRACTION:g} sqrt(E(t0/4) / rho)",
                  "energy_residual": f"abs(energy residual) > {validity.MAX_ENERGY_RESIDUAL:g}",
                  "under_resolved": f"fixed step, Kelvin-Voigt, t_d / dt < {validity.MIN_DAMPING_STEPS}",
                  "no_rebound": "sphere_velocity z'(t0) > 0 (still towards the target)",
                  "grids_disagree": (f"adaptive: grids differ by > {extrapolation.RICHARDSON_GAP:g}, their differences "
                                     f"not shrinking as h^2 (ratio not in {extrapolation.RICHARDSON_RATIO}), or differ "
                                     f"in t0 by > {extrapolation.RICHARDSON_MAX_GAP:g}, or an extrapolated COR < 0, or "
                                     f"a COR < {extrapolation.COR_FLOOR:g}"),
                  "uncertain_extrapolation": (f"adaptive: extrapolated grids apart in t0 by > "
                                              f"{extrapolation.RICHARDSON_MAX_GAP_STEPS:g} step_tol, or by > "
                                              f"{extrapolation.RICHARDSON_T0_GAP:g} with a t0 ratio not in "
                                              f"{extrapolation.RICHARDSON_T0_RATIO}")}
        if set(limits) != set(validity.FLAGS):
            raise self.error(f"validity flags differ from the table: {sorted(set(limits) ^ set(validity.FLAGS))}")
        rows = [[f"`{name}`", str(mask), f"`{limits[name]}`"] for name, mask in validity.FLAGS.items()]
        return [_table(["flag", "mask", "set when"], rows, [3, 1, 8])]


# ----------------------------------------------------------------------------- config reference
_PLACEHOLDER = {"materials": "<material>", "calibrations": "<calibration>", "fits": "<fit>", "scenes": "<scene>",
                "grid": "<axis>", "tie": "<parameter>", "figures": "<figure>", "free": "<parameter>"}


def _bounds(s: dict) -> str:
    parts = []
    for key, op in (("minimum", ">="), ("exclusiveMinimum", ">"), ("maximum", "<="), ("exclusiveMaximum", "<")):
        if key in s:
            parts.append(f"{op} {s[key]:g}")
    return (" " + ", ".join(parts)) if parts else ""


def _kind(s: dict) -> str:
    if "const" in s:
        return _fmt(s["const"])
    if "enum" in s:
        return "one of " + ", ".join("`null`" if v is None else _fmt(v) for v in s["enum"])
    if "oneOf" in s:
        return " or ".join(_kind(x) for x in s["oneOf"])
    if s.get("type") == "object" and "properties" in s and "required" in s:
        keys = [k if k in s["required"] else f"[{k}]" for k in s["properties"]]
        return "mapping `{" + ", ".join(keys) + "}`"
    t = s.get("type", "mapping" if "properties" in s or "additionalProperties" in s else "any")
    if isinstance(t, list):
        text = " or ".join("`null`" if x == "null" else {"object": "mapping"}.get(x, x) for x in t)
    else:
        text = {"object": "mapping", "array": "list"}.get(t, t)
    if t == "array" and "items" in s:
        n = ""
        if "minItems" in s and s.get("minItems") == s.get("maxItems"):
            n = f" of {s['minItems']}"
        text = f"list{n} of {_kind(s['items'])}"
    return text + _bounds(s)


def schema_rows(schema: dict, prefix: str = "", parent: str = ""):
    """(path, schema node) of every key, depth first; children of ``scenes.<scene>.solver`` excluded (the
    solver options table documents them)."""
    for name, sub in schema.get("properties", {}).items():
        path = f"{prefix}.{name}" if prefix else name
        yield path, sub
        if path.endswith(".solver"):
            continue
        yield from schema_rows(sub, path, name)
    extra = schema.get("additionalProperties")
    if isinstance(extra, dict):
        path = f"{prefix}.{_PLACEHOLDER.get(parent, '<name>')}"
        if "properties" in extra or "additionalProperties" in extra:
            yield path, extra
            yield from schema_rows(extra, path, "")
        elif parent in ("grid", "free"):
            yield path, extra


class ConfigReference(Directive):
    has_content = True

    def run(self):
        from vcor.solvers.options import SolverOptions

        schema = load_yaml(SCHEMA, what="config schema")
        meanings = yaml.safe_load("\n".join(self.content)) or {}
        rows, seen = [], set()
        for path, node in schema_rows(schema):
            if path == "scenes.<scene>.solver":
                got = set(node.get("properties", {}))
                if got != set(SolverOptions.names()):
                    raise self.error(f"{path}: schema keys {sorted(got)} differ from the solver options "
                                     f"{sorted(SolverOptions.names())}")
            if path not in meanings:
                raise self.error(f"config reference: no meaning for schema key {path!r} (add it to the directive)")
            seen.add(path)
            default = _fmt(node["default"]) if "default" in node else "–"
            rows.append([f"`{path}`", _kind(node), default, str(meanings[path])])
        unknown = set(meanings) - seen
        if unknown:
            raise self.error(f"config reference: meanings for keys the schema does not have: {sorted(unknown)}")
        headers = ["key", "type and allowed values", "schema default", "meaning and unit"]
        return [_table(headers, rows, [5, 4, 2, 10], self.state, self.content_offset)]


# ----------------------------------------------------------------------------- values from the package
def value_role(name, rawtext, text, lineno, inliner, options=None, content=None):
    """``{vcor-value}`vcor.solvers.adaptive.HORIZON_START``` -> the constant's value, as code; a dict's
    entry as ``{vcor-value}`vcor.contact.impact.DENSITIES[steel]```."""
    match = re.fullmatch(r"\s*([\w.]+)(?:\[([\w-]+)\])?\s*", text)
    try:
        if match is None:
            raise KeyError("expected a dotted name, optionally followed by [key]")
        path, key = match.groups()
        value = _resolve(path)
        if key is not None:
            value = value[key]
    except (ImportError, AttributeError, KeyError, TypeError) as exc:
        msg = inliner.reporter.error(f"vcor-value: cannot resolve {text!r}: {exc}", line=lineno)
        return [inliner.problematic(rawtext, rawtext, msg)], [msg]
    if isinstance(value, float):
        shown = f"{value:g}"
    elif isinstance(value, (tuple, list)):
        shown = ", ".join(f"{v:.4g}" if isinstance(v, float) else str(v) for v in value)
    else:
        shown = str(value)
    return [nodes.literal(rawtext, shown)], []


def _resolve(name: str):
    """The object a dotted name refers to (a module, then attributes; a class's own ``__dict__`` first)."""
    parts = name.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        for p in parts[i:]:
            obj = obj.__dict__[p] if isinstance(obj, type) and p in obj.__dict__ else getattr(obj, p)
        return obj
    raise ImportError(name)


# ----------------------------------------------------------------------------- code in tables
#: where a name in a table cell may break: after a path separator, a dot, an underscore, "::" or a comma
_BREAK_AFTER = re.compile(r"(?<=[/._,])(?=[^/._,])|(?<=::)")


class TableCodeBreaks(SphinxPostTransform):
    """Break opportunities (``<wbr>``, not copied with the text) in code inside table cells, so that a
    test id or a file name wraps at its separators instead of widening the table past the page."""

    default_priority = 900
    formats = ("html",)

    def run(self, **kwargs):
        for literal in list(self.document.findall(nodes.literal)):
            if not any(isinstance(a, nodes.entry) for a in _ancestors(literal)) or len(literal.children) != 1:
                continue
            text = literal.astext()
            pieces = _BREAK_AFTER.split(text)
            if len(pieces) < 2:
                continue
            literal.children = []
            for i, piece in enumerate(pieces):
                if i:
                    literal += nodes.raw("", "<wbr>", format="html")
                literal += nodes.Text(piece)


def _ancestors(node):
    while node.parent is not None:
        node = node.parent
        yield node


# ----------------------------------------------------------------------------- module data in the API
#: a module constant's value is shown in its signature when it reads as a value: short, and not the repr
#: of a function, class or object (a method table such as ``METHODS`` is described by its docstring)
MAX_VALUE_LENGTH = 100
_OBJECT_REPR = re.compile(r"<[\w.]+[ >]|object at 0x")


class HideReprValues(SphinxPostTransform):
    """Drop ``= value`` from the signature of module data and attributes whose value is a long table or
    holds Python reprs (``<function solve>``): the API reference then shows the name, the type and the
    docstring, not a dump."""

    default_priority = 800

    def run(self, **kwargs):
        from sphinx import addnodes

        for desc in self.document.findall(addnodes.desc):
            if desc.get("objtype") not in ("data", "attribute"):
                continue
            for sig in desc.findall(addnodes.desc_signature):
                for ann in list(sig.findall(addnodes.desc_annotation)):
                    text = ann.astext().strip()
                    if text.startswith("=") and (len(text) > MAX_VALUE_LENGTH or _OBJECT_REPR.search(text)):
                        ann.parent.remove(ann)


def setup(app):
    app.add_post_transform(TableCodeBreaks)
    app.add_post_transform(HideReprValues)
    app.config.autosummary_context = {"vcor_hidden_modules": HIDDEN_MODULES}
    app.add_role("vcor-value", value_role)
    app.add_directive("vcor-solver-options", SolverOptionsTable)
    app.add_directive("vcor-statuses", StatusTable)
    app.add_directive("vcor-result-fields", ResultFields)
    app.add_directive("vcor-presets", PresetTable)
    app.add_directive("vcor-grid-axes", GridAxes)
    app.add_directive("vcor-layers", LayerTable)
    app.add_directive("vcor-figures", FigureTable)
    app.add_directive("vcor-validity", ValidityTable)
    app.add_directive("vcor-config-reference", ConfigReference)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
