"""Figures: one function per figure, datasets in, Figure out.

``FIGURES[name] = (function, needs)`` where ``needs`` names the datasets the function takes
(``sweep``, ``moduli``, ``histories``, ...), so the workflow builds only those. Every function takes
``opts`` (the scene's figure options). Points whose status is not ok are drawn as red crosses on
the axis and counted in the title, never silently dropped. Ok points outside the model's stated range
(a non-zero ``validity`` flag, :mod:`vcor.solvers.validity`) are drawn open, on dashed segments, with a
legend entry naming the reasons and a count in the title (:func:`vcor.plots.common.sweep_line`).
"""

from __future__ import annotations

from .calibration import calibration
from .common import save
from .dem import dem
from .paper import fig1, fig2, fig3, fig4, fig5, fig6, fig7, fig8, fig9, prony_terms
from .spheres import spheres_eps, spheres_hereditary, spheres_ice
from .studies import stability_map, work_precision
from .temperature import cor_temperature, cor_v0_temperature, master_curve

__all__ = ["AXIS_OPTIONS", "FIGURES", "FIGURE_OPTIONS", "NEEDS_AXIS", "OPTION_DEFAULTS", "calibration", "dem", "draw",
           "needs", "options_of", "save"]

FIGURES = {
    "cor_temperature": (cor_temperature, ("sweep",)),
    "cor_v0_temperature": (cor_v0_temperature, ("sweep",)),
    "master_curve": (master_curve, ("material_fit", "material_samples")),
    "fig1": (fig1, ("sweep", "moduli")),
    "fig2": (fig2, ("histories",)),
    "fig3": (fig3, ("histories",)),
    "fig4": (fig4, ("sweep",)),
    "fig5": (fig5, ("sweep", "moduli")),
    "fig6": (fig6, ("histories",)),
    "fig7": (fig7, ("histories",)),
    "fig8": (fig8, ("sweep",)),
    "fig9": (fig9, ("sweep",)),
    "prony_terms": (prony_terms, ("sweep",)),
    "spheres_eps": (spheres_eps, ("spheres",)),
    "spheres_ice": (spheres_ice, ("spheres",)),
    "spheres_hereditary": (spheres_hereditary, ("spheres",)),
    "work_precision": (work_precision, ("convergence",)),
    "stability_map": (stability_map, ("sweep",)),
}


#: the options each figure takes, option -> what its value is: ``material`` (a material of the scene),
#: ``fits`` (a list of the project's fits), ``runs`` (a list of the scene's history runs,
#: "<material>/<method>"), ``v0`` / ``beta`` (a value on that grid axis, m/s / 1/s), ``v0 list`` /
#: ``T list`` (values on that axis), ``number``, ``text``, ``pattern`` (text with {n}, the number of
#: Prony terms). Figures in AXIS_OPTIONS also take any other grid axis, naming the value drawn.
FIGURE_OPTIONS = {
    "cor_temperature": {"v0s": "v0 list"},
    "cor_v0_temperature": {"T": "T list"},
    "master_curve": {"materials": "fits"},
    "fig1": {"material": "material", "v0": "v0", "beta": "beta"},
    "fig2": {"runs": "runs"},
    "fig3": {"runs": "runs"},
    "fig4": {"material": "material"},
    "fig5": {"reference": "material", "v0": "v0"},
    "fig6": {"runs": "runs"},
    "fig7": {"runs": "runs"},
    "fig8": {},
    "fig9": {"material": "material"},
    "prony_terms": {"reference": "material", "v0": "v0", "pattern": "pattern"},
    "spheres_eps": {},
    "spheres_ice": {"g_star_cm_s": "number", "g_min_cm_s": "number", "g_max_cm_s": "number"},
    "spheres_hereditary": {},
    "work_precision": {},
    "stability_map": {"title": "text"},
}
#: figures that take any grid axis as an option (the value the lines are drawn at)
AXIS_OPTIONS = {"cor_temperature", "cor_v0_temperature"}
#: option values a figure uses when the scene does not give them (fig4 without material: the first)
OPTION_DEFAULTS = {
    "fig1": {"material": "sls", "v0": 10.0, "beta": 1200.0},
    "fig5": {"reference": "butyl-fc", "v0": 10.0},
    "fig9": {"material": "butyl-fc"},
    "prony_terms": {"reference": "butyl-fc", "v0": 10.0, "pattern": "butyl-prony-n{n}"},
    "spheres_ice": {"g_star_cm_s": 0.32, "g_min_cm_s": 0.05, "g_max_cm_s": 5.0},
    "stability_map": {"title": "Stability map: status and estimated COR error"},
}
#: grid axes (besides v0) a figure's sweep must have
NEEDS_AXIS = {"cor_temperature": ("T",), "cor_v0_temperature": ("T",), "fig4": ("beta",)}


def options_of(name, opts) -> dict:
    """The figure's options: the scene's, completed by OPTION_DEFAULTS."""
    return {**OPTION_DEFAULTS.get(name, {}), **dict(opts or {})}


def draw(name, data, opts):
    """Figure ``name`` from its datasets ``data`` (a dict: need -> Dataset, or list of Datasets for
    ``material_fit`` and ``material_samples``, the latter possibly empty) and the scene's options for it
    (completed by OPTION_DEFAULTS)."""
    fn, need = FIGURES[name]
    return fn(*(data[n] for n in need), options_of(name, opts))


def needs(figures) -> set[str]:
    """Datasets the given figures need."""
    out = set()
    for f in figures:
        if f not in FIGURES:
            raise ValueError(f"unknown figure {f!r}; allowed: {sorted(FIGURES)}")
        out.update(FIGURES[f][1])
    return out
