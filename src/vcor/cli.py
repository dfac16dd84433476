"""``vcor`` command line: one impact, scalars printed as text or JSON (thin wrapper)."""

from __future__ import annotations

import argparse
import json
import sys

from . import materials
from .contact.impact import GEOMETRY_DEFAULTS
from .solvers.options import BOOLEAN_OPTIONS, OPTION_HELP, SolverOptions
from .solvers.simulate import simulate
from .solvers.common import UNITS

_INTEGER_OPTIONS = ("steps_per_contact", "max_steps", "max_adaptive_steps")


def build_parser():
    """The argument parser; its solver flags come from vcor.options.SolverOptions."""
    p = argparse.ArgumentParser(prog="vcor", description="Viscoelastic coefficient of restitution")
    sub = p.add_subparsers(dest="command", required=True)
    imp = sub.add_parser("impact", help="simulate one sphere-plate impact")
    imp.add_argument("--material", default="sls",
                     help=f"preset ({', '.join(sorted(materials.PRESETS))}), a fitted material file, or a "
                          "name in the materials block of --config")
    imp.add_argument("--config", default=None,
                     help="a config.yaml whose materials block defines --material (relative CSV paths from its folder)")
    imp.add_argument("--v0", type=float, required=True, help="impact speed, m/s")
    # solver options: names, allowed values and help from vcor.options (unset ones keep their defaults)
    for name in SolverOptions.names():
        if name == "ghost":
            continue  # histories only; the command prints scalars
        flag = f"--{name.replace('_', '-')}"
        default = SolverOptions.default_of(name)
        help_text = f"{OPTION_HELP[name]} (default {default})"
        if name == "volterra":
            imp.add_argument(flag, action="store_true", default=None, help=help_text)
        elif name in BOOLEAN_OPTIONS:
            imp.add_argument(flag, action=argparse.BooleanOptionalAction, default=None, help=help_text)
        elif SolverOptions.allowed_of(name) is not None:
            imp.add_argument(flag, dest=name, choices=SolverOptions.allowed_of(name), default=None, help=help_text)
        else:
            kind = int if name in _INTEGER_OPTIONS else float
            imp.add_argument(flag, dest=name, type=kind, default=None, help=help_text)
    for key in ("r", "rho_a", "rho_b", "h", "nu", "E_plate", "nu_plate"):
        default = GEOMETRY_DEFAULTS[key] if GEOMETRY_DEFAULTS[key] is not None else "by case: polymer 1100, steel 7800"
        imp.add_argument(f"--{key}", type=float, default=None, help=f"geometry (default {default})")
    imp.add_argument("--case", type=int, default=None, choices=(1, 2, 3, 4))
    imp.add_argument("--rigid", action="store_true", help="rigid, immovable target (alpha = 0)")
    imp.add_argument("--json", action="store_true", help="print JSON with units")
    return p


def _config_material(path, name):
    """Material ``name`` of the ``materials:`` block of the YAML config ``path``."""
    from pathlib import Path

    import yaml

    from .materials.specs import from_spec

    path = Path(path)
    if not path.is_file():
        raise ValueError(f"--config {str(path)!r} does not exist")
    block = (yaml.safe_load(path.read_text()) or {}).get("materials") or {}
    if name not in block:
        raise ValueError(f"material {name!r} is neither a preset nor in the materials block of {path} "
                         f"(names there: {sorted(block)})")
    return from_spec(block[name], name=name, base_dir=path.parent)


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    geometry = {k: getattr(args, k) for k in GEOMETRY_DEFAULTS if getattr(args, k, None) is not None}
    if args.rigid:
        geometry["rigid"] = True
    material = args.material
    options = {k: getattr(args, k) for k in SolverOptions.names() if getattr(args, k, None) is not None}
    try:
        if args.config is not None and material not in materials.PRESETS:
            material = _config_material(args.config, material)
        elif material not in materials.PRESETS and (material.endswith(".nc") or material.endswith(".json")):
            material = materials.from_file(material)
        res = simulate(material, args.v0, options=options, **geometry)
    except ValueError as exc:
        print(f"vcor: error: {exc}", file=sys.stderr)
        return 2
    if args.json:
        print(json.dumps(res.with_units(), indent=2))
    else:
        for key, value in res.scalars().items():
            unit = UNITS.get(key)
            print(f"{key:16s} {value}" + (f" {unit}" if unit and unit != "1" else ""))
    return 0 if res.ok else 1


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
