"""``vcor`` command line: one impact, scalars printed as text or JSON (thin wrapper)."""

from __future__ import annotations

import argparse
import json
import sys

from . import materials
from .impact import GEOMETRY_DEFAULTS
from .solvers import METHODS, simulate
from .solvers.common import UNITS


def _parser():
    p = argparse.ArgumentParser(prog="vcor", description="Viscoelastic coefficient of restitution")
    sub = p.add_subparsers(dest="command", required=True)
    imp = sub.add_parser("impact", help="simulate one sphere-plate impact")
    imp.add_argument("--material", default="sls",
                     help=f"preset ({', '.join(sorted(materials.PRESETS))}) or a fitted material file")
    imp.add_argument("--v0", type=float, required=True, help="impact speed, m/s")
    imp.add_argument("--method", choices=METHODS, default="direct")
    imp.add_argument("--dt", type=float, default=None, help="time step, s (default: automatic)")
    imp.add_argument("--volterra", action="store_true", help="add the second-order Volterra term")
    imp.add_argument("--form", choices=("a", "b"), default="a")
    imp.add_argument("--rule", choices=("force", "overlap"), default="force")
    for key in ("r", "rho_a", "rho_b", "h", "nu", "E_plate", "nu_plate"):
        imp.add_argument(f"--{key}", type=float, default=None, help=f"geometry (default {GEOMETRY_DEFAULTS[key]})")
    imp.add_argument("--case", type=int, default=None, choices=(1, 2, 3, 4))
    imp.add_argument("--rigid", action="store_true", help="rigid, immovable target (alpha = 0)")
    imp.add_argument("--json", action="store_true", help="print JSON with units")
    return p


def main(argv=None) -> int:
    args = _parser().parse_args(argv)
    geometry = {k: getattr(args, k) for k in GEOMETRY_DEFAULTS if getattr(args, k, None) is not None}
    if args.rigid:
        geometry["rigid"] = True
    material = args.material
    if material not in materials.PRESETS and (material.endswith(".nc") or material.endswith(".json")):
        material = materials.from_file(material)
    try:
        res = simulate(material, args.v0, method=args.method, dt=args.dt, volterra=args.volterra,
                       form=args.form, rule=args.rule, **geometry)
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
