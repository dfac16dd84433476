"""The sphere limit fitted to a measured law: g* of Ramirez et al. (1999) from eps(g).

Ramirez et al. fit their viscoelastic-sphere COR (the Pade approximant, Eq. 35) to the Bridges et al.
(1984) law for ice, eps = 0.32 g^-0.234 (g the impact speed in cm/s), for the material constant g*.
:func:`fit_g_star` does the same with vcor's exact eps (``vcor.spheres.cor_numeric``) or the Pade, by
least squares in ln g*.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["BRIDGES_ICE", "GStarFit", "bridges_ice", "fit_g_star"]

#: Bridges et al. (1984) ice law as Ramirez et al. (1999) quote it: eps = 0.32 g^-0.234, g in cm/s
BRIDGES_ICE = (0.32, -0.234)


def bridges_ice(g_cm_s):
    """eps of the Bridges et al. ice law as Ramirez et al. quote it (g in cm/s)."""
    return BRIDGES_ICE[0] * np.asarray(g_cm_s, float) ** BRIDGES_ICE[1]


@dataclass(frozen=True, kw_only=True)
class GStarFit:
    """g* (in the units of g) of the Ramirez model fitted to eps(g): ``model`` "numeric" (vcor's exact
    eps, separation ``rule``) or "pade" (Ramirez Eq. 35, the paper's procedure); ``stderr`` from the
    residual scatter (the misfit of the model's shape, since a law is not noisy data), ``rms`` the rms
    residual in eps."""

    g_star: float
    stderr: float
    rms: float
    model: str
    rule: str
    g_range: tuple
    n_points: int


def fit_g_star(g, eps, *, model: str = "numeric", rule: str = "overlap", start: float = 0.32) -> GStarFit:
    """Least squares in ln g* of eps_model(b = (g / g*)^(1/5) / C1) to ``eps`` at speeds ``g``
    (vcor.spheres: x = (g/g*)^(1/5) = C1 b). The exact numerical eps uses ``spheres.cor_numeric``
    (Kelvin-Voigt, rigid target, Richardson-extrapolated, error ~1e-9)."""
    from scipy.optimize import least_squares

    from .. import spheres as S

    g, eps = np.asarray(g, float), np.asarray(eps, float)
    if g.ndim != 1 or g.size < 2 or g.shape != eps.shape or np.any(g <= 0) or not np.all(np.isfinite(eps)):
        raise ValueError("fit_g_star: g (> 0) and eps must be 1-D arrays of equal length >= 2, finite")
    if model not in ("numeric", "pade"):
        raise ValueError(f"fit_g_star: model must be 'numeric' or 'pade', got {model!r}")
    c1 = abs(S.C[0])

    def eps_model(ln_gs):
        b = (g / math.exp(ln_gs)) ** 0.2 / c1
        return S.cor_pade(b) if model == "pade" else np.array([S.cor_numeric(x, rule) for x in b])

    fit = least_squares(lambda x: eps_model(x[0]) - eps, [math.log(start)], jac="3-point", diff_step=1e-4,
                        xtol=1e-12, ftol=1e-12, gtol=1e-12)
    r = fit.fun
    dof = g.size - 1
    s2 = float(r @ r) / dof
    J = fit.jac
    sx = math.sqrt(s2 / float(J[:, 0] @ J[:, 0]))
    gs = math.exp(fit.x[0])
    return GStarFit(g_star=gs, stderr=gs * sx, rms=float(np.sqrt(np.mean(r**2))), model=model,
                    rule=rule if model == "numeric" else "-", g_range=(float(g.min()), float(g.max())),
                    n_points=int(g.size))
