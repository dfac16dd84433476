r"""Fewer modes: a smooth spectrum's fine grid merged into a Prony series of a few modes per decade,
and what the merge changes in E', E'' and tan delta."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import nnls

from .model import complex_modulus, relative_errors, tan_delta_extrema
from .smooth import SpectrumFit

__all__ = ["ReducedModes", "reduce_modes"]

#: fewest points of the dense comparison and refit grids
MIN_DENSE = 50


@dataclass(frozen=True, kw_only=True)
class ReducedModes:
    """A Prony series with fewer modes than a :class:`~vcor.fitting.spectrum.smooth.SpectrumFit`, and what
    the reduction changed.

    Attributes
    ----------
    tau, E, E_inf : ndarray, ndarray, float
        Relaxation times (s), moduli (Pa), equilibrium modulus (Pa).
    change : dict
        Relative change against the smooth fit over its data range (dense grid): ``E_stor_max``,
        ``E_stor_rms``, ``E_loss_max``, ``E_loss_rms``, ``tan_delta_max``, ``tan_delta_rms``;
        and ``tan_delta_extrema`` of the reduced model on the same grid as the fit's
        (:data:`vcor.fitting.spectrum.model.N_DENSE` points).
    """

    tau: np.ndarray
    E: np.ndarray
    E_inf: float
    change: dict

    @property
    def n_modes(self) -> int:
        return int(self.E.size)

    def prony_terms(self):
        """(E_inf [Pa], E [Pa], beta = 1/tau [1/s])."""
        return float(self.E_inf), self.E.copy(), 1.0 / self.tau


def _merged(fit: SpectrumFit, per_decade):
    """(tau, E) of consecutive blocks of the fine grid: strength and strength-weighted mean log time."""
    decades = float(np.log10(fit.tau[-1] / fit.tau[0]))       # a float: numpy < 2 rounds float64 to float64
    n_blocks = min(fit.tau.size, max(1, round(decades * per_decade) + 1))
    blocks = np.array_split(np.arange(fit.tau.size), n_blocks)
    E = np.array([fit.E[b].sum() for b in blocks])
    tau = np.array([math.exp(float(np.sum(fit.E[b] * np.log(fit.tau[b])) / fit.E[b].sum())) for b in blocks])
    return tau, E


def _refit(fit: SpectrumFit, tau, n_dense_per_decade):
    """(E_inf, tau, E): NNLS moduli at the merged times against the smooth fit's E', E'' (relative
    residuals) over the data range widened by the fit's margins; modes refitted to 0 dropped."""
    f_lo, f_hi = fit.f_range
    span = math.log10(f_hi / f_lo)
    # fit on the data range widened by the fit's margins so the end modes stay physical
    m_lo = max(math.log10(fit.tau[-1] * 2 * math.pi * f_lo), 0.0)
    m_hi = max(math.log10(1.0 / (fit.tau[0] * 2 * math.pi * f_hi)), 0.0)
    f_fit = np.geomspace(f_lo / 10**m_lo, f_hi * 10**m_hi,
                         max(int((span + m_lo + m_hi) * n_dense_per_decade), MIN_DENSE))
    wf = 2 * math.pi * f_fit
    target = fit.complex_modulus(wf)
    wt = np.multiply.outer(wf, tau)
    A = np.vstack([np.column_stack([np.ones(wf.size), wt**2 / (1 + wt**2)]) / target.real[:, None],
                   np.column_stack([np.zeros(wf.size), wt / (1 + wt**2)]) / target.imag[:, None]])
    x, _ = nnls(A, np.ones(2 * wf.size), maxiter=50 * (tau.size + 1))
    E_inf, E = float(x[0]), x[1:]
    keep = E > 0
    return E_inf, tau[keep], E[keep]


def reduce_modes(fit: SpectrumFit, per_decade=1.0, *, refit=True, n_dense_per_decade=20) -> ReducedModes:
    r"""Merge the fine grid's modes into about ``per_decade`` modes per decade.

    The fine grid is split into round(span * per_decade) + 1 consecutive blocks (span: decades of the
    grid), each merged into one mode, keeping the block's strength and its
    strength-weighted mean log time: :math:`E = \sum_{j\in b} E_j`,
    :math:`\ln\tau = \sum_{j\in b} E_j \ln\tau_j / E`.  With ``refit`` the merged moduli (and
    :math:`E_\infty`) are then re-fitted by non-negative least squares to the smooth fit's
    :math:`E'` and :math:`E''` (relative residuals) on a dense grid over the data range widened by
    the fit's margin, which removes most of the ripple a coarse discrete spectrum adds; modes whose
    refitted modulus is 0 are dropped.

    Parameters
    ----------
    fit : SpectrumFit
    per_decade : float
        Target modes per decade (e.g. 1, 1.5, 2).
    refit : bool
        NNLS re-fit of the merged moduli (keeps the merged times).
    n_dense_per_decade : int
        Density of the comparison grid.

    Returns
    -------
    ReducedModes
    """
    tau, E = _merged(fit, per_decade)
    E_inf = fit.E_inf
    if refit:
        E_inf, tau, E = _refit(fit, tau, n_dense_per_decade)
    f_lo, f_hi = fit.f_range
    f_dense = np.geomspace(f_lo, f_hi, max(int(math.log10(f_hi / f_lo) * n_dense_per_decade), MIN_DENSE))
    w_dense = 2 * math.pi * f_dense
    change = relative_errors(complex_modulus(w_dense, E_inf, E, tau), fit.complex_modulus(w_dense))
    change["tan_delta_extrema"] = tan_delta_extrema(E_inf, E, tau, f_lo, f_hi)
    return ReducedModes(tau=tau, E=E, E_inf=E_inf, change=change)
