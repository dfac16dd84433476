r"""The Prony model on a fixed log grid of relaxation times: E*(omega), E(t), the derivative for a
shift of the frequency, and how well a model meets data (relative errors, tan delta extrema).

Units: frequencies Hz (angular frequency :math:`\omega = 2\pi f`), times s, moduli Pa.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["MARGIN", "N_DENSE", "PER_DECADE", "complex_modulus", "count_extrema", "fit_metrics", "margins",
           "relaxation_modulus", "shift_derivative", "tau_grid"]

#: relaxation times per decade of the fixed grid: twice the merged series' two modes per decade
#: (vcor.fitting.dma.MODES_PER_DECADE), so that every merged mode is a block of two fine ones (with 5
#: per decade the blocks alternate 3, 2, 3, ..., the merged modes are unevenly spaced and their tan delta
#: ripples more; the merging table of benchmarks/bench_dma.py gives the change the merge makes)
PER_DECADE = 4.0
#: decades (below the data's lowest frequency, above its highest) that the relaxation-time grid reaches
#: beyond the data. Within a margin the log-spectrum continues the data's trend as a power law (zero second
#: difference); beyond it the series ends and tan delta falls to zero. An impact (contact 10 us .. 1 ms:
#: f = 1/(2 t0) = 0.5 .. 50 kHz) at the coldest set's temperature lies up to 2.7 decades above a DMA's usual
#: top frequency of 100 Hz, so the high side reaches 3 decades (with less, the COR there follows the end of
#: the grid, not the data's trend); impacts at the hottest set lie above its lowest frequency, and on the low
#: side a long power-law continuation would invent flow (tan delta >> 1) where the data end on a plateau.
MARGIN = (1.5, 3.0)
#: log-spaced frequencies on which tan delta extrema are counted: with 4 modes per decade over up to 25
#: decades, 2000 points put 20 or more between neighbouring modes, so no ripple between them is missed
N_DENSE = 2000


def margins(margin, extra=0.0):
    """(low-frequency, high-frequency) margin in decades from a number (both sides) or a pair, plus ``extra``."""
    lo, hi = (margin, margin) if np.ndim(margin) == 0 else margin
    return float(lo) + extra, float(hi) + extra


def tau_grid(f_min, f_max, per_decade=PER_DECADE, margin=MARGIN):
    """Fixed log grid of relaxation times, s: from 1/(2 pi f_max) / 10^m_hi to 1/(2 pi f_min) * 10^m_lo,
    ``per_decade`` points per decade (rounded to fit the span); ``margin``: decades m_lo = m_hi, or
    (m_lo, m_hi) below the lowest and above the highest frequency."""
    if not (0 < f_min < f_max):
        raise ValueError(f"need 0 < f_min < f_max (Hz), got {f_min!r}, {f_max!r}")
    m_lo, m_hi = margins(margin)
    lo = math.log10(1.0 / (2 * math.pi * f_max)) - m_hi
    hi = math.log10(1.0 / (2 * math.pi * f_min)) + m_lo
    n = round((hi - lo) * per_decade) + 1
    return np.logspace(lo, hi, max(n, 3))


def complex_modulus(omega, E_inf, E, tau):
    r"""Prony complex modulus :math:`E^*(\omega) = E_\infty + \sum_j E_j\, i\omega\tau_j/(1+i\omega\tau_j)`
    (omega rad/s, moduli Pa, tau s)."""
    iwt = 1j * np.multiply.outer(np.asarray(omega, float), np.asarray(tau, float))
    return E_inf + (iwt / (1 + iwt)) @ np.asarray(E, float)


def shift_derivative(wt, E):
    r"""(dE'/ds, dE''/ds) of a Prony model at kernel arguments ``wt`` (:math:`\omega\tau`, points x modes)
    for a shift :math:`s = \log_{10} a_T` of the frequency, :math:`\ln 10\;\omega\,\partial E^*/\partial\omega`
    (Pa; moduli ``E`` in Pa)."""
    q = 1 + wt**2
    return math.log(10) * ((2 * wt**2 / q**2) @ E), math.log(10) * ((wt * (1 - wt**2) / q**2) @ E)


def relaxation_modulus(t, E_inf, E, tau):
    r""":math:`E(t) = E_\infty + \sum_j E_j e^{-t/\tau_j}` (t s, moduli Pa)."""
    return E_inf + np.exp(-np.divide.outer(np.asarray(t, float), np.asarray(tau, float))) @ np.asarray(E, float)


def count_extrema(y, rtol=1e-10):
    """Number of strict local extrema of a sampled curve: sign changes of its first difference,
    differences below ``rtol`` times the curve's scale counted as zero (flat steps are skipped)."""
    y = np.asarray(y, float)
    dy = np.diff(y)
    dy = dy[np.abs(dy) > rtol * np.max(np.abs(y))]
    return int(np.sum(np.sign(dy[1:]) != np.sign(dy[:-1])))


def tan_delta_extrema(E_inf, E, tau, f_lo, f_hi, n_dense=N_DENSE) -> int:
    """Local extrema of a Prony model's tan delta on ``n_dense`` log-spaced frequencies over [f_lo, f_hi] (Hz)."""
    e = complex_modulus(2 * np.pi * np.geomspace(f_lo, f_hi, n_dense), E_inf, E, tau)
    return count_extrema(e.imag / e.real)


def relative_errors(fit, data, weight=None) -> dict:
    """``{q}_rms`` (multiplicity-weighted) and ``{q}_max`` of fit / data - 1 for q = E_stor, E_loss, tan_delta;
    ``fit``, ``data``: complex moduli (Pa)."""
    w = np.ones(np.size(data)) if weight is None else np.asarray(weight, float)
    out = {}
    for name, a, b in (("E_stor", fit.real, data.real), ("E_loss", fit.imag, data.imag),
                       ("tan_delta", fit.imag / fit.real, data.imag / data.real)):
        r = a / b - 1
        out[f"{name}_rms"] = float(np.sqrt(np.average(r**2, weights=w)))
        out[f"{name}_max"] = float(np.max(np.abs(r[w > 0])))
    return out


def fit_metrics(E_inf, E, tau, f, E_stor, E_loss, weight=None, n_dense=N_DENSE, phase=None):
    """Relative errors of E', E'' and tan delta (rms and max, multiplicity-weighted) of a Prony
    model against data, and the number of local extrema of its tan delta on ``n_dense`` log-spaced
    frequencies over the data's range [min f, max f] (Hz). ``phase`` (rad, per point): the model is
    compared as measured, E* e^{i phase} (an instrument's phase error, :func:`fit_spectrum`); the extrema
    are the material's own."""
    e = complex_modulus(2 * np.pi * np.asarray(f), E_inf, E, tau)
    if phase is not None:
        e = e * np.exp(1j * np.asarray(phase, float))
    out = relative_errors(e, np.asarray(E_stor) + 1j * np.asarray(E_loss), weight)
    out["tan_delta_extrema"] = tan_delta_extrema(E_inf, E, tau, np.min(f), np.max(f), n_dense)
    return out
