"""The ``vcor`` command line: one impact, the materials a project can name, a dataset as a table.

::

    vcor impact --material sls --v0 10 [--json]         one impact (method adaptive unless --method)
    vcor materials [--config config.yaml] [--json]      presets and a config's materials
    vcor export results/sls/sweep.nc [--csv FILE]       a dataset as a tidy table (one row per point)
    vcor --version

Exit codes: 0 ok; 1 the impact ended with a status other than ok (its message says what to change);
2 bad input (the message names the parameter and the allowed range).
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from .contact.impact import GEOMETRY_DEFAULTS
from .solvers.options import BOOLEAN_OPTIONS, OPTION_HELP, OPTION_UNITS, SolverOptions
from .version import __version__

__all__ = ["GEOMETRY_FLAGS", "build_parser", "impact_options", "main"]

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


def _flags(name: str) -> list[str]:
    """``--name-with-dashes`` and, where it differs, the old spelling ``--name_with_underscores``."""
    dashed = f"--{name.replace('_', '-')}"
    return [dashed] if "_" not in name else [dashed, f"--{name}"]


def _unit_text(unit: str) -> str:
    return "no unit" if unit in ("none", "1") or unit.startswith("none") else f"unit {unit}"


def _add_impact(sub) -> list:
    """Add the impact subcommand to ``sub``; returns its options (argparse actions)."""
    actions = []
    imp = sub.add_parser("impact", help="simulate one sphere-plate impact and print its outcome with units",
                         description="Simulate one impact (vcor.simulate) and print the result with units.")
    _add(actions, imp, "--material", required=True,
                     help="a preset (vcor materials lists them), a material file (.nc or .json), or a name of "
                          "--config's materials, fits or calibrations [no unit; required]")
    _add(actions, imp, "--config", default=None, help="a config.yaml whose materials block defines --material "
                     "(relative paths from its folder) [no unit; default: none]")
    _add(actions, imp, "--v0", type=float, required=True, help="impact speed, > 0 [unit m/s; required]")
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
            _add(actions, imp, *_flags(name), dest=name, type=int if name in _INTEGER_OPTIONS else float, default=None,
                             help=help_text)
    for key, (text, unit, default) in GEOMETRY_FLAGS.items():
        _add(actions, imp, *_flags(key), dest=key, type=float, default=None,
                         help=f"{text} [{_unit_text(unit)}; default {default}]")
    _add(actions, imp, "--case", type=int, default=None, choices=(1, 2, 3, 4),
                     help="which body is viscoelastic (Green 2026, Sec. 3): 1 both elastic, 2 sphere and plate of "
                          "the material, 3 a stiff sphere on a plate of the material, 4 a sphere of the material on "
                          "a stiff plate [no unit; default 3]")
    _add(actions, imp, "--rigid", action="store_true", help="rigid, immovable target (plate mobility 0) [no unit; "
                     "default off]")
    _add(actions, imp, "--json", action="store_true", help="print JSON, every number with its unit [no unit; "
         "default off]")
    return actions


def _add(actions, parser, *flags, **kwargs):
    actions.append(parser.add_argument(*flags, **kwargs))


def impact_options() -> list:
    """The options of ``vcor impact`` (argparse actions; tests check their help texts)."""
    return _add_impact(argparse.ArgumentParser().add_subparsers())


def build_parser() -> argparse.ArgumentParser:
    """The argument parser; the solver flags come from :class:`vcor.solvers.options.SolverOptions`."""
    p = argparse.ArgumentParser(prog="vcor", description="vcor: the viscoelastic coefficient of restitution. "
                                "SI units throughout.")
    p.add_argument("--version", action="version", version=f"vcor {__version__}")
    sub = p.add_subparsers(dest="command", required=True, metavar="{impact,materials,export}")
    _add_impact(sub)
    mats = sub.add_parser("materials", help="list the presets and a config's materials with their parameters",
                          description="List the materials a project can name: presets, and with --config its "
                                      "materials, fits and calibrations.")
    mats.add_argument("--config", default=None, help="a config.yaml [no unit; default: presets only]")
    mats.add_argument("--json", action="store_true", help="print JSON [no unit; default off]")
    exp = sub.add_parser("export", help="write a dataset as a tidy CSV table (one row per point, units in the header)",
                         description="Write the point variables of a vcor dataset (a sweep: one row per grid point) "
                                     "as CSV, each column headed 'name [unit]', statuses by name.")
    exp.add_argument("dataset", help="a NetCDF dataset written by vcor (e.g. results/sls/sweep.nc)")
    exp.add_argument("--csv", default=None, help="output file [no unit; default: standard output]")
    return p


def _catalogue(config):
    """The Catalogue of a config file (None: presets only)."""
    from .materials.catalogue import Catalogue

    if config is None:
        return Catalogue()
    import yaml

    from .study.config import load_project

    path = Path(config)
    if not path.is_file():
        raise ValueError(f"--config {str(path)!r} does not exist")
    cfg = yaml.safe_load(path.read_text()) or {}
    if not isinstance(cfg, dict):
        raise ValueError(f"--config {str(path)!r}: not a mapping of config keys")
    cfg.setdefault("scenes", {})
    base = path.parent
    return load_project({**cfg, "scenes": {}}, base_dir=base).catalogue


def _impact(args) -> int:
    from .materials.files import from_file
    from .solvers.common import UNITS
    from .solvers.simulate import simulate

    geometry = {k: getattr(args, k) for k in GEOMETRY_DEFAULTS if getattr(args, k, None) is not None}
    if args.rigid:
        geometry["rigid"] = True
    options = {k: getattr(args, k) for k in SolverOptions.names() if getattr(args, k, None) is not None}
    catalogue = _catalogue(args.config)
    name = args.material
    if name.endswith((".nc", ".json")) and Path(name).is_file():
        material = from_file(name)
    else:
        catalogue.check(name, "--material")
        material = catalogue.material(name)
    res = simulate(material, args.v0, options=options, **geometry)
    if args.json:
        print(json.dumps(res.with_units(), indent=2))
    else:
        for key, value in res.scalars().items():
            unit = UNITS.get(key)
            print(f"{key:16s} {value}" + (f" {unit}" if unit and unit != "1" else ""))
    if not res.ok:
        print(f"vcor: status {res.status}: {res.message}", file=sys.stderr)
    return 0 if res.ok else 1


def _materials(args) -> int:
    catalogue = _catalogue(args.config)
    rows = []
    from .materials.presets import PRESETS

    for name in [*PRESETS, *catalogue.specs, *catalogue.fits, *catalogue.calibrations]:
        source = catalogue.source(name)
        try:
            d = catalogue.material(name).to_dict()
            shift = catalogue.shift(name)
        except ValueError as exc:  # a fit or calibration not computed yet
            d, shift = {"kind": "(not computed yet)", "note": str(exc)}, None
        rows.append({"name": name, "source": source, "model": d.pop("kind"), "parameters": d,
                     "shift": shift.to_dict() if shift else None})
    if args.json:
        print(json.dumps(rows, indent=2))
        return 0
    print("# parameters in SI: moduli Pa, rates 1/s, times s (the model's own names: vcor.materials)")
    print(f"{'name':24s} {'source':12s} {'model':14s} parameters")
    for row in rows:
        params = ", ".join(f"{k}={v}" for k, v in row["parameters"].items())
        shift = f"; shift {row['shift']}" if row["shift"] else ""
        print(f"{row['name']:24s} {row['source']:12s} {row['model']:14s} {params}{shift}")
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
    args = build_parser().parse_args(argv)
    run = {"impact": _impact, "materials": _materials, "export": _export}[args.command]
    try:
        return run(args)
    except ValueError as exc:
        print(f"vcor: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
