"""Where no fitted DEM law can follow the hereditary curve: the sense in which the COR changes with speed.

The trend of a COR curve is the sign of its change from the lowest to the highest speed whose vcor
result is ``ok``; a change of at most :data:`FLAT` (absolute COR) counts as flat. A law is flagged
where its trend is the opposite of vcor's (one rises with speed where the other falls) and it misses
vcor's COR by more than the dataset's bound (0.01, :data:`vcor.dem.export.WITHIN`) somewhere: no value
of its parameters follows the curve, the fit can only trade the error at one end of the range for
the other. (A law within the bound everywhere follows the curve whatever its trend.) The routes that
follow vcor's curve are then vcor's own contact law in LAMMPS (``lammps-hereditary``: the plugin's
``pair_style vcor/hereditary`` and the deck ``lammps/in.hereditary``, where the entry has it) and a
COR table (``table.csv``; in Aspherix ``hertz/vel_dependent`` with ``cor_lookup``). A constant law
(``lammps-coeff-restitution``) is flat and never flagged.
"""

from __future__ import annotations

import numpy as np

__all__ = ["FLAT", "HEREDITARY_ROUTE", "TABLE_ROUTE", "opposite", "trend", "warning"]

#: a change of the COR over the range at most this large (absolute) is no trend
FLAT = 1e-3
#: the route that follows the hereditary curve where no fitted law does
TABLE_ROUTE = "the COR table (table.csv; Aspherix hertz/vel_dependent with cor_lookup)"
#: vcor's own contact law in LAMMPS, where the dataset has it
HEREDITARY_ROUTE = ("vcor's own contact in LAMMPS (lammps-hereditary: pair_style vcor/hereditary of vcor's plugin, "
                    "the deck lammps/in.hereditary)")


def _ends(values, ok) -> tuple[float, float]:
    idx = np.flatnonzero(ok & np.isfinite(values))
    return (float(values[idx[0]]), float(values[idx[-1]])) if len(idx) >= 2 else (np.nan, np.nan)


def trend(values, ok) -> int:
    """+1 if ``values`` rises from the lowest to the highest ok speed by more than :data:`FLAT`, -1
    if it falls by more, 0 otherwise (flat, or fewer than two ok speeds)."""
    lo, hi = _ends(np.asarray(values, dtype=float), np.asarray(ok, dtype=bool))
    change = hi - lo
    return 0 if not np.isfinite(change) or abs(change) <= FLAT else int(np.sign(change))


def opposite(cor, cor_model, ok, bound: float) -> np.ndarray:
    """Per law (rows of ``cor_model``): True where its trend and that of ``cor`` are non-zero and of
    opposite sign and the law misses ``cor`` by more than ``bound`` at an ok speed (module docstring)."""
    ref = trend(cor, ok)
    cor, ok = np.asarray(cor, dtype=float), np.asarray(ok, dtype=bool) & np.isfinite(cor)
    return np.array([ref != 0 and trend(row, ok) == -ref and np.max(np.abs(row[ok] - cor[ok])) > bound
                     for row in np.atleast_2d(np.asarray(cor_model, dtype=float))], dtype=bool)


def _words(sign: int, many: bool = False) -> str:
    if many:
        return "rise" if sign > 0 else "fall"
    return "rises" if sign > 0 else "falls"


def warning(v0, cor, cor_model, ok, models, bound: float, prefix: str = "") -> str:
    """One sentence naming the laws flagged by :func:`opposite` at these speeds (m/s), with both
    curves' end values; empty when there is none. Laws with the same curve are named together."""
    v0, cor, ok = np.asarray(v0, dtype=float), np.asarray(cor, dtype=float), np.asarray(ok, dtype=bool)
    cor_model = np.atleast_2d(np.asarray(cor_model, dtype=float))
    bad = opposite(cor, cor_model, ok, bound)
    if not bad.any():
        return ""
    idx = np.flatnonzero(ok & np.isfinite(cor))
    v_lo, v_hi = v0[idx[0]], v0[idx[-1]]
    c_lo, c_hi = _ends(cor, ok)
    groups: dict[tuple, list] = {}
    for k in np.flatnonzero(bad):
        groups.setdefault(tuple(np.round(_ends(cor_model[k], ok), 4)), []).append(str(models[k]))
    laws = "; ".join(f"{', '.join(names)} {_words(-trend(cor, ok), len(names) > 1)} ({lo:.3f} to {hi:.3f})"
                     for (lo, hi), names in groups.items())
    route = (f"{HEREDITARY_ROUTE} and {TABLE_ROUTE} do" if "lammps-hereditary" in list(models)
             else f"{TABLE_ROUTE} does")
    return (f"{prefix}vcor's COR {_words(trend(cor, ok))} with speed ({c_lo:.3f} at {v_lo:g} m/s to {c_hi:.3f} "
            f"at {v_hi:g} m/s) while {laws}: no value of these laws' parameters follows the curve; {route}.")
