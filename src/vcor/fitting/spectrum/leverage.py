r"""Leverages of the data points of a spectrum fit: the diagonal of its linearised hat matrix."""

from __future__ import annotations

import math

import numpy as np

from .residual import Design, Residual, second_differences
from .smooth import SpectrumFit, component_weights

__all__ = ["leverage"]

#: relative ridge on the (penalised) Gauss-Newton matrix: a parameter the data do not inform stays finite
RIDGE = 1e-12


def _columns(fit, moduli, residual, design, shift_index, lag):
    """Jacobian of the data rows: the spectrum's own parameters, then the fitted shifts and lag."""
    cols = [residual.spectrum_columns(design, *moduli)]
    if shift_index is not None:
        k = np.asarray(shift_index, int)
        cols.append(residual.shift_columns(design, fit.E, k, max(int(k.max()) + 1, 0)))
    if lag is not None and lag[2]:
        f_meas = np.asarray(lag[0], float)
        cols.append(residual.lag_column(design, *moduli, f_meas / f_meas.max())[:, None])
    return np.hstack(cols)


def leverage(fit: SpectrumFit, f, E_stor, E_loss, *, weight=None, components=(1.0, 1.0, 1.0), lag=None,
             shift_index=None, curvature=False):
    r"""Leverages of data points in a spectrum fit: the diagonal of the linearised hat matrix
    :math:`A_\lambda = J (J^\top J + \lambda L^\top L)^{-1} J^\top` at the fit's solution, for the E' and
    the E'' residual of every point; in [0, 1).

    A point of leverage :math:`h` pulls the fit towards itself: its fitted residual is about
    :math:`(1 - h)` times its error, so residuals alone understate the scatter where few points
    decide the fit (the ends of the data). Scale-free (the row weights cancel).

    The parameters are those of the spectrum, and with ``shift_index`` the shift of every set that was
    fitted too (:func:`vcor.fitting.dma.joint.fit_with_shifts`: a shift is one more parameter that
    each of its set's points informs, so a set's residuals shrink by more than the spectrum alone
    explains), and with ``lag`` the instrument's time lag, fitted or held.

    With ``curvature`` (the spectrum's own parameters only) the residuals' curvature
    :math:`\sum_i r_i \nabla^2 r_i` joins the Gauss-Newton matrix,
    :math:`J (J^\top J + \mathrm{diag}(J^\top r) + \lambda L^\top L)^{-1} J^\top` (exact for
    moduli :math:`e^{H_j}`: each residual's second derivative in :math:`H_j` equals its first): the
    linear response of the fitted value to its own data value, which a refit follows within a few per
    cent where the Gauss-Newton value is up to 18 % off (``tests/fitting/test_resample.py``); it is not bounded
    by 1 where the fit is barely determined, so the bootstrap's residual correction takes the
    Gauss-Newton value, the one that correction is defined with.

    Parameters
    ----------
    fit : SpectrumFit
    f : array_like
        Frequencies of the points, Hz (reduced, as fitted).
    E_stor, E_loss : array_like
        The data, Pa.
    weight : array_like, optional
        Point multiplicities, as in the fit (default 1).
    components : tuple
        Weights a', a'' of the E' and E'' residuals, as in the fit.
    lag : (array_like, float, bool), optional
        (measured frequency of every point [Hz], the instrument's time lag [s], whether it was fitted):
        the model is compared as measured (``phase`` of
        :func:`vcor.fitting.spectrum.smooth.fit_spectrum`); a fitted lag is a parameter.
    shift_index : array_like of int, optional
        For every point the index (0, 1, ...) of its set's shift among the fitted shifts, -1 where the
        shift was held (the reference set, given shifts).
    curvature : bool
        Include the residuals' curvature (above).

    Returns
    -------
    (h_stor, h_loss) : tuple of ndarray
        In [0, 1) (Gauss-Newton); the exact response with ``curvature``.
    """
    f = np.asarray(f, float)
    es, el = np.asarray(E_stor, float), np.asarray(E_loss, float)
    n = f.size
    fit_E_inf = fit.E_inf > 0
    w = np.ones(n) if weight is None else np.asarray(weight, float)
    if curvature and (shift_index is not None or (lag is not None and lag[2])):
        raise ValueError("curvature is exact for the spectrum's own parameters only: give no shift_index or fitted lag")
    phase = None if lag is None else 2 * math.pi * np.asarray(lag[0], float) * float(lag[1])
    residual = Residual(es, el, w, component_weights(components, es, el))
    design = Design(np.multiply.outer(2 * math.pi * f, fit.tau), phase)
    # the moduli as the fit's parameters give them: exp(ln E)
    th = np.concatenate([[math.log(fit.E_inf) if fit_E_inf else 0.0], np.log(fit.E)])
    moduli = (float(np.exp(th[0])) if fit_E_inf else 0.0), np.exp(th[1:])
    J = _columns(fit, moduli, residual, design, shift_index, lag)
    m = fit.tau.size + 1
    A = J.T @ J
    D = second_differences(fit.tau.size)
    A[1:m, 1:m] += fit.lam * (D.T @ D)
    if curvature:
        # sum_i r_i d2r_i: for moduli e^theta diagonal and equal to J^T r (d2 r_i / d theta_j^2 = d r_i / d theta_j)
        A += np.diag(J.T @ residual.value(design, *moduli))
    if not fit_E_inf:
        J, A = J[:, 1:], A[1:, 1:]
    A += RIDGE * np.trace(A) / A.shape[0] * np.eye(A.shape[0])
    h = np.einsum("ij,ji->i", J, np.linalg.solve(A, J.T))
    if not curvature:
        h = np.clip(h, 0.0, 1.0 - 1e-9)
    return h[:n], h[n:]
