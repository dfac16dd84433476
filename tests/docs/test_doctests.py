"""The ``Examples`` sections of the docstrings run as doctests: every module of the public surface has
examples and all of them pass; an example anywhere else in the package passes too
(docs/developer.md, "Documentation").

Run by pytest from this file (not ``--doctest-modules``, which would import every module as a test
module, including ``vcor.__main__``, which runs the command line, and could not require examples of the
public surface). Outputs are printed rounded, so the examples are stable to the solvers' accuracy."""

from __future__ import annotations

import doctest
import importlib
import pkgutil

import pytest

import vcor

#: the public surface (vcor.simulate, Result, SolverOptions, the sphere functions, the contact set-up, the
#: grid, the DEM laws and dataset, the calibration and fit entry points, the status vocabulary): each
#: module holds examples
PUBLIC = (
    "vcor.solvers.simulate",
    "vcor.solvers.common",
    "vcor.solvers.options",
    "vcor.spheres",
    "vcor.status",
    "vcor.contact.impact",
    "vcor.contact.pair",
    "vcor.contact.bodies",
    "vcor.study.grid",
    "vcor.dem.export",
    "vcor.dem.laws",
    "vcor.fitting.calibrate",
    "vcor.fitting.fits",
)
#: the options of every run: ``...`` stands for the rest of a long message or number, and line breaks
#: in a printed array or tuple do not matter
FLAGS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
#: modules that are not imported here: the command line's entry point runs the CLI when imported
NOT_IMPORTED = ("vcor.__main__",)


def _run(name: str) -> tuple[int, int, str]:
    """(examples tried, examples failed, the report of the failures) of module ``name``'s docstrings."""
    module = importlib.import_module(name)
    runner = doctest.DocTestRunner(optionflags=FLAGS)
    report = []
    for test in doctest.DocTestFinder().find(module, name):
        runner.run(test, out=report.append)
    return runner.tries, runner.failures, "".join(report)


def _other_modules() -> list[str]:
    names = [m.name for m in pkgutil.walk_packages(vcor.__path__, "vcor.")]
    return sorted(n for n in ["vcor", *names] if n not in PUBLIC and n not in NOT_IMPORTED)


@pytest.mark.parametrize("name", PUBLIC)
def test_the_public_surface_has_examples_that_pass(name):
    tried, failed, report = _run(name)
    assert tried > 0, f"{name}: no Examples section with a doctest"
    assert failed == 0, report


@pytest.mark.parametrize("name", _other_modules())
def test_every_other_example_passes(name):
    _, failed, report = _run(name)
    assert failed == 0, report
