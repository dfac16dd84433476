"""The ``vcor`` commands of the study functions (:mod:`vcor.study.api`), for users without Snakemake::

    vcor sweep --config my.yaml --scene NAME --out sweep.nc [--workers N] [--no-progress]
    vcor fit --config my.yaml --name NAME --out NAME.nc [--table NAME.txt]
    vcor calibrate --config my.yaml --name NAME --out NAME.nc
    vcor dem --config my.yaml --name NAME [--project DIR]

Each writes what the workflow's rule writes for the entry (the same dataset, by the same function), and
refuses bad input with the workflow's one-line message naming the key, before any work (exit code 2).
A sweep's points that did not end ``ok`` are stored with their status, never an error: the command
writes the dataset, prints the counts and exits 0, or 1 when no point ended ``ok`` (nothing to use: the
statuses and messages in the file say why). ``vcor dem`` prints the files' paths on standard output and, on
standard error, the counts, one flagged speed's reason (every speed's: the dataset's ``validity_message``)
and the trend warning where a law goes the other way from vcor's COR. Ctrl-C stops a sweep at once, its
worker processes with it (exit code 130).
"""

from __future__ import annotations

import argparse
import sys

__all__ = ["COMMANDS", "add_commands"]


def _common(parser, what: str, name_flag: str) -> None:
    parser.add_argument("--config", required=True, help="the config file (YAML) that defines the entry; relative "
                        "paths in it are taken from its project folder (the nearest folder at or above it with "
                        "a Snakefile, else its own) [no unit; required]")
    parser.add_argument(name_flag, required=True, dest="name", help=f"the name of the {what} in the config [no unit; "
                        f"required]")


def _workers(text: str) -> int:
    """``--workers``: an integer >= 1 (argparse names the option in its error)."""
    try:
        n = int(text)
    except ValueError:
        n = 0
    if n < 1:
        raise argparse.ArgumentTypeError(f"must be an integer >= 1 (processes; leave --workers out for the cores "
                                         f"available), got {text!r}")
    return n


def add_commands(sub) -> None:
    """Add the commands of the module docstring to the subparsers ``sub`` of ``vcor``'s parser."""
    sw = sub.add_parser("sweep", help="solve a scene's grid into its sweep dataset (as results/<scene>/sweep.nc)",
                        description="Solve a scene of a config on this machine's cores and write its sweep dataset "
                                    "(vcor.sweep): the workflow's results/<scene>/sweep.nc, without Snakemake.")
    _common(sw, "scene (scenes.<name>)", "--scene")
    sw.add_argument("--out", required=True, help="the NetCDF file to write [no unit; required]")
    sw.add_argument("--workers", type=_workers, default=None, help="processes that solve, an integer >= 1 [no unit; "
                    "default: the cores available]")
    sw.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                    help="a progress bar on standard error [no unit; default: when it is a terminal]")
    ft = sub.add_parser("fit", help="fit a material of a config's fits block (as <material_dir>/<name>.nc)",
                        description="Fit a material of a config's fits: block (vcor.fit) and write its material file.")
    _common(ft, "fit (fits.<name>)", "--name")
    ft.add_argument("--out", required=True, help="the material file to write (NetCDF) [no unit; required]")
    ft.add_argument("--table", default=None, help="also write the fit's text table here [no unit; default: none]")
    cal = sub.add_parser("calibrate", help="calibrate a material of a config's calibrations block",
                         description="Calibrate a material to measured COR (vcor.calibrate) and write its record, "
                                     "which is also its material file.")
    _common(cal, "calibration (calibrations.<name>)", "--name")
    cal.add_argument("--out", required=True, help="the record to write (NetCDF) [no unit; required]")
    dem = sub.add_parser("dem", help="a dem: entry's dataset, COR table, parameters, LAMMPS deck and Yade script",
                         description="Export a dem: entry of a config (vcor.dem_export): its dataset, COR table, "
                                     "parameters file, LAMMPS deck and Yade script, laid out as the workflow does.")
    _common(dem, "DEM entry (dem.<name>)", "--name")
    dem.add_argument("--project", default=".", help="the folder the workflow's layout is written under "
                     "(results/dem/...) [no unit; default: the current folder]")


def _sweep(args) -> int:
    from .io.receipts import writable_file
    from .study.api import sweep_archive
    from .study.summary import outcome_of

    writable_file(args.out, "--out")
    try:
        archive = sweep_archive(args.name, config=args.config, workers=args.workers, progress=args.progress)
    except KeyboardInterrupt:
        print("vcor sweep: interrupted; nothing written", file=sys.stderr)
        return 130
    archive.write(args.out, command=f"vcor sweep --config {args.config} --scene {args.name}")
    done = outcome_of(archive.dataset)
    points = f"{done.points} point" + ("s" if done.points != 1 else "")
    print(f"vcor sweep: {points}, {done.text()}: {args.out}", file=sys.stderr)
    if done.ok + done.flagged == 0:
        print(f"vcor sweep: no point ended ok (exit code 1); the status and message variables of {args.out} say "
              f"why", file=sys.stderr)
        return 1
    return 0


def _fit(args) -> int:
    from .io.receipts import writable_file
    from .study.api import fit

    writable_file(args.out, "--out")
    if args.table:
        writable_file(args.table, "--table")
    fitted = fit(args.name, config=args.config)
    fitted.write(args.out, table=args.table)
    print(f"vcor fit: {args.name}: {fitted.material.to_dict()}: {args.out}", file=sys.stderr)
    return 0


def _calibrate(args) -> int:
    from .io.receipts import writable_file
    from .study.api import calibrate

    writable_file(args.out, "--out")
    calibrated = calibrate(args.name, config=args.config)
    sys.stderr.write(calibrated.report())
    calibrated.write(args.out)
    print(f"vcor calibrate: {args.name}: {args.out}", file=sys.stderr)
    return 0


def _dem(args) -> int:
    from .study.api import dem_export
    from .study.summary import outcome_of

    exported = dem_export(args.name, config=args.config)
    written = exported.write(args.project)
    for path in written.values():
        print(path)
    ds = exported.dataset
    done = outcome_of(ds)
    print(f"vcor dem: {args.name}: {done.points} points, {done.text()}: {written['nc']}", file=sys.stderr)
    if done.flagged:
        flagged = ds["validity"].values.ravel() != 0
        first = str(ds["validity_message"].values.ravel()[flagged][0])
        print(f"vcor dem: a flagged speed: {first} (every speed's reason: the dataset's validity_message)",
              file=sys.stderr)
    if ds.attrs.get("trend_warning"):
        print(f"vcor dem: WARNING: {ds.attrs['trend_warning']}", file=sys.stderr)
    return 0


#: command -> its function (args -> exit code)
COMMANDS = {"sweep": _sweep, "fit": _fit, "calibrate": _calibrate, "dem": _dem}
