"""Figures: one function per figure, datasets in, Figure out.

``FIGURES[name] = (function, needs)`` where ``needs`` names the datasets the function takes
(``sweep``, ``moduli``, ``histories``, ...), so the workflow builds only those. Every function takes
``opts`` (the scene's figure options). Points whose status is not ok are drawn as red crosses on
the axis and counted in the title, never silently dropped.
"""

from __future__ import annotations

from .calibration import calibration
from .common import save
from .paper import fig1, fig2, fig3, fig4, fig5, fig6, fig7, fig8, fig9, prony_terms
from .spheres import spheres_eps, spheres_hereditary, spheres_ice
from .studies import stability_map, work_precision
from .temperature import cor_temperature, cor_v0_temperature, master_curve

__all__ = ["FIGURES", "NEEDS_AXIS", "calibration", "draw", "needs", "save"]

FIGURES = {
    "cor_temperature": (cor_temperature, ("sweep",)),
    "cor_v0_temperature": (cor_v0_temperature, ("sweep",)),
    "master_curve": (master_curve, ("material_fit",)),
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


def draw(name, data, opts):
    """Figure ``name`` from its datasets ``data`` (a dict: need -> Dataset, or list of Datasets for
    ``material_fit``) and the scene's options for it."""
    fn, need = FIGURES[name]
    return fn(*(data[n] for n in need), dict(opts or {}))


#: figures that need a grid axis besides v0
NEEDS_AXIS = {"cor_temperature": "T", "cor_v0_temperature": "T"}


def needs(figures) -> set[str]:
    """Datasets the given figures need."""
    out = set()
    for f in figures:
        if f not in FIGURES:
            raise ValueError(f"unknown figure {f!r}; allowed: {sorted(FIGURES)}")
        out.update(FIGURES[f][1])
    return out
