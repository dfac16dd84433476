"""vcor: the viscoelastic coefficient of restitution (Green 2026; Ramirez et al. 1999).

The public surface: :func:`simulate` (one impact, method ``adaptive`` by default), :class:`Result`,
:class:`SolverOptions`; the study functions, one per capability of the workflow (:mod:`vcor.study.api`):
:func:`sweep` (a scene's grid, in parallel, the dataset the workflow archives), :func:`fit`,
:func:`calibrate`, :func:`dem_export`, :func:`histories`, :func:`moduli`, :func:`viscoelastic_spheres` and
:func:`convergence`; and the subpackages :mod:`~vcor.materials`, :mod:`~vcor.contact`,
:mod:`~vcor.solvers`, :mod:`~vcor.fitting`, :mod:`~vcor.study`, :mod:`~vcor.io`, :mod:`~vcor.plots`
and the modules :mod:`~vcor.spheres` and :mod:`~vcor.status`.

Names are loaded on first use (PEP 562), so that a process that only draws figures or fits a
material does not import the numba solvers (workflow jobs start faster).
"""

from importlib import import_module
from typing import TYPE_CHECKING

from .version import __version__

if TYPE_CHECKING:  # what the lazy names are, for type checkers (loaded on first use otherwise)
    from .solvers.common import Result
    from .solvers.options import SolverOptions
    from .solvers.simulate import simulate
    from .study.api import calibrate, convergence, dem_export, fit, histories, moduli, sweep, viscoelastic_spheres

__all__ = ["Result", "SolverOptions", "__version__", "calibrate", "convergence", "dem_export", "fit", "histories",
           "materials", "moduli", "simulate", "sweep", "viscoelastic_spheres"]

_NAMES = {"Result": "vcor.solvers.common", "simulate": "vcor.solvers.simulate", "SolverOptions": "vcor.solvers.options",
          **dict.fromkeys(("sweep", "fit", "calibrate", "dem_export", "histories", "moduli", "viscoelastic_spheres",
                           "convergence"), "vcor.study.api")}
_SUBMODULES = ("checks", "cli", "cli_study", "contact", "fitting", "io", "materials", "plots", "provenance", "solvers",
               "spheres", "status", "study")


def __getattr__(name):
    if name in _NAMES:
        value = getattr(import_module(_NAMES[name]), name)
        globals()[name] = value  # loaded once: later look-ups do not come here (~1 us per vcor.simulate call)
        return value
    if name in _SUBMODULES:
        return import_module(f"vcor.{name}")
    raise AttributeError(f"module 'vcor' has no attribute {name!r}")


def __dir__():
    """The public names, the lazy ones included (tab completion in IPython and Jupyter lists them)."""
    loaded = (k for k in globals() if not k.startswith("_") and k not in ("TYPE_CHECKING", "import_module"))
    return sorted({*__all__, *_SUBMODULES, *loaded})
