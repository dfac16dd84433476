r"""Shift laws fitted to per-set shift factors: WLF and Arrhenius, and the shift function a fit stores.

Both fits weigh each set's :math:`\log_{10} a_T` by :math:`1/\sigma^2`, its standard error floored at
:data:`SIGMA_FLOOR`; the residuals are fit minus data, in decades.
"""

from __future__ import annotations

import math

import numpy as np

from ...materials.shift import GAS_CONSTANT, ZERO_CELSIUS, ShiftFunction, wlf_log_aT

__all__ = ["SHIFT_LAWS", "SIGMA_FLOOR", "WLF_C1_STARTS", "WLF_C2_STARTS", "arrhenius_fit", "shift_function",
           "wlf_fit"]

#: smallest standard error of a per-set shift, decades: a shift held at 0 (the reference set) or given has
#: no error of its own, yet no law describes shifts to better than about 2 % in a_T
SIGMA_FLOOR = 0.01
#: starts of C1 (-): the "universal" WLF constants 17.44 (T_ref = T_g) and 8.86 (T_g + 50 K), and a steep one
WLF_C1_STARTS = (8.86, 17.44, 40.0)
#: starts of C2 (K): 51.6 (T_ref = T_g), 101.6 (T_g + 50 K), and flatter laws far above T_g
WLF_C2_STARTS = (51.6, 101.6, 300.0, 1000.0)
#: upper bounds of C1 (-) and C2 (K): far beyond any polymer's, they only keep the search finite
WLF_UPPER = (1e4, 1e5)
#: WLF needs C2 + T - T_ref > 0 at every set: by at least this (K)
WLF_MARGIN = 1e-3
#: the shift functions a fit may store
SHIFT_LAWS = ("table", "wlf", "arrhenius")


def _weights(y, sigma, power):
    return np.ones_like(y) if sigma is None else 1.0 / np.maximum(np.asarray(sigma, float), SIGMA_FLOOR) ** power


def wlf_fit(T, log_aT, T_ref, sigma=None):
    r"""Least-squares WLF constants through per-set shifts (several starts, best kept).

    Parameters
    ----------
    T, log_aT : array_like
        Temperatures (deg C) and log10 a_T.
    T_ref : float
        Reference temperature, deg C (the WLF curve is 0 there).
    sigma : array_like, optional
        Standard errors of log_aT, decades: weights 1/sigma^2, sigma floored at :data:`SIGMA_FLOOR`.

    Returns
    -------
    dict
        ``C1`` (-), ``C2`` (K), ``C1_std``, ``C2_std`` (linearised, from the residual scatter; ``inf`` where
        at most two sets lie away from T_ref, through which the two constants pass exactly), ``residual``
        (decades, fit - data) and its ``rms``.
    """
    from scipy.optimize import least_squares  # on use: planning a run imports the law names only

    T, y = np.asarray(T, float), np.asarray(log_aT, float)
    dT = T - T_ref
    w = _weights(y, sigma, 1)
    lo = max(WLF_MARGIN, -dT.min() + WLF_MARGIN)

    def res(p):
        return (wlf_log_aT(T, T_ref, p[0], p[1]) - y) * w

    best = None
    for c2 in WLF_C2_STARTS:
        for c1 in WLF_C1_STARTS:
            fit = least_squares(res, x0=[c1, max(c2, 2 * lo)], bounds=([0.0, lo], list(WLF_UPPER)), method="trf")
            if best is None or fit.cost < best.cost:
                best = fit
    # a set at T_ref lies on every WLF curve: it carries no degree of freedom
    dof = int(np.count_nonzero(dT != 0)) - 2
    if dof < 1:  # two constants through two shifts: their scatter says nothing of their errors
        c1_std = c2_std = math.inf
    else:
        cov = np.linalg.pinv(best.jac.T @ best.jac) * (2 * best.cost / dof)
        c1_std, c2_std = math.sqrt(max(cov[0, 0], 0)), math.sqrt(max(cov[1, 1], 0))
    r = wlf_log_aT(T, T_ref, *best.x) - y
    return {"C1": float(best.x[0]), "C2": float(best.x[1]), "C1_std": float(c1_std), "C2_std": float(c2_std),
            "residual": r, "rms": float(np.sqrt(np.mean(r**2)))}


def arrhenius_fit(T, log_aT, T_ref, sigma=None):
    r"""Arrhenius: :math:`\log_{10} a_T = \frac{E_a}{R \ln 10}\left(\frac1T - \frac1{T_\mathrm{ref}}\right)`
    (T in K inside), weighted least squares through the origin (``sigma`` as in :func:`wlf_fit`).

    Returns
    -------
    dict
        ``E_a`` (J/mol), ``E_a_std`` (``inf`` where one set lies away from T_ref: the line passes through it
        exactly), ``residual`` (decades, fit - data), ``rms``.
    """
    x = 1.0 / (np.asarray(T, float) + ZERO_CELSIUS) - 1.0 / (T_ref + ZERO_CELSIUS)
    y = np.asarray(log_aT, float)
    w = _weights(y, sigma, 2)
    slope = float(np.sum(w * x * y) / np.sum(w * x * x))
    r = slope * x - y
    dof = int(np.count_nonzero(x != 0)) - 1  # a set at T_ref lies on every Arrhenius line
    se = math.sqrt(float(np.sum(w * r**2)) / dof / float(np.sum(w * x * x))) if dof >= 1 else math.inf
    k = GAS_CONSTANT * math.log(10.0)
    return {"E_a": slope * k, "E_a_std": se * k, "residual": r, "rms": float(np.sqrt(np.mean(r**2)))}


def shift_function(fit, model: str = "table") -> ShiftFunction:
    """The shift function of a fit (:class:`vcor.fitting.dma.pipeline.DMAFit`): ``"table"`` (the per-set
    log10 a_T, PCHIP in T), ``"wlf"`` or ``"arrhenius"`` (fitted to them)."""
    if model == "table":
        return ShiftFunction.table(fit.T_ref, fit.T, fit.log_aT)
    if model == "wlf":
        return ShiftFunction(model="wlf", T_ref=fit.T_ref, C1=fit.wlf["C1"], C2=fit.wlf["C2"])
    if model == "arrhenius":
        return ShiftFunction(model="arrhenius", T_ref=fit.T_ref, E_a=fit.arrhenius["E_a"])
    raise ValueError(f"shift model must be one of {list(SHIFT_LAWS)}, got {model!r}")
