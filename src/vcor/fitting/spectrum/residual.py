r"""The one residual of every spectrum fit, and its Jacobian.

For points :math:`i` with data :math:`E'_i, E''_i` (Pa), multiplicities :math:`m_i` and component
weights :math:`a', a''` the data rows are

.. math:: r'_i = \sqrt{m_i a'}\,\Big(\frac{\mathrm{Re}\,M_i}{E'_i} - 1\Big), \qquad
          r''_i = \sqrt{m_i a''}\,\Big(\frac{\mathrm{Im}\,M_i}{E''_i} - 1\Big), \qquad
          M_i = E^*(\omega_i)\,e^{\,i\varphi_i},

the Prony model :math:`E^*(\omega) = E_\infty + \sum_j E_j\,i\omega\tau_j/(1 + i\omega\tau_j)` as an
instrument with a phase error :math:`\varphi_i` measures it (0 without one), optionally followed by
relaxation rows :math:`\sqrt{a_t}\,(E(t_l)/E_l - 1)`.  The parameters are :math:`\ln E_\infty` and
:math:`H_j = \ln E_j`; the smooth fit (:mod:`vcor.fitting.spectrum.smooth`) uses exactly these, the
joint fit (:mod:`vcor.fitting.dma.joint`) and the leverages (:mod:`vcor.fitting.spectrum.leverage`) add
columns for the shift of every set (:meth:`Residual.shift_columns`,
:math:`\partial E^*(\omega 10^{s})/\partial s = \ln 10\;\omega\,\partial E^*/\partial\omega`) and for
an instrument lag (:meth:`Residual.lag_column`).
"""

from __future__ import annotations

import numpy as np

from .model import shift_derivative

__all__ = ["Design", "Residual", "second_differences"]


def second_differences(n):
    """The (n - 2) x n second-difference matrix D2 (rows 1, -2, 1)."""
    D = np.zeros((n - 2, n))
    i = np.arange(n - 2)
    D[i, i], D[i, i + 1], D[i, i + 2] = 1.0, -2.0, 1.0
    return D


class Design:
    """The model's kernels at given kernel arguments ``wt`` (:math:`\\omega\\tau`, points x modes) and
    instrument phase (rad per point, or None): E'_m = E_inf cp + Ks E, E''_m = E_inf sp + Kl E."""

    def __init__(self, wt, phase=None, t=None, tau=None):
        n = wt.shape[0]
        w2 = wt**2
        d = 1 + w2
        ks, kl = w2 / d, wt / d
        # the model as measured: E* rotated by the instrument's phase error, E*_m = E* e^{i phase}
        cp, sp = (np.ones(n), np.zeros(n)) if phase is None else (np.cos(phase), np.sin(phase))
        self.wt, self.cp, self.sp = wt, cp, sp
        if phase is None:      # cos 0 = 1, sin 0 = 0: the rotation below would return ks, kl unchanged
            self.Ks, self.Kl = ks, kl
        else:
            self.Ks, self.Kl = cp[:, None] * ks - sp[:, None] * kl, sp[:, None] * ks + cp[:, None] * kl
        self.Kt = None if t is None else np.exp(-np.divide.outer(t, tau))

    def measured(self, E_inf, E):
        """(Re, Im) of the model as measured, Pa."""
        return E_inf * self.cp + self.Ks @ E, E_inf * self.sp + self.Kl @ E


class Residual:
    """The data rows (module docstring) of points with data ``E_stor``, ``E_loss`` (Pa), multiplicities
    ``weight`` and component weights ``components`` = (a', a'', a_t); ``relaxation`` = (t [s], E [Pa])."""

    def __init__(self, E_stor, E_loss, weight, components, relaxation=None):
        sw = np.sqrt(weight)
        self.rows_s, self.rows_l = sw * np.sqrt(components[0]), sw * np.sqrt(components[1])
        self.cs = self.rows_s / E_stor                    # row scale of the E' residuals
        self.cl = self.rows_l / E_loss
        self.n = np.size(E_stor)
        self.has_t = relaxation is not None
        if self.has_t:
            t, E_relax = relaxation
            self.rows_t = np.broadcast_to(np.sqrt(components[2]), t.shape).astype(float)
            self.ct = self.rows_t / E_relax

    def value(self, design: Design, E_inf, E):
        """The data rows at moduli ``E_inf``, ``E`` (Pa)."""
        r = [self.cs * (E_inf * design.cp + design.Ks @ E) - self.rows_s,
             self.cl * (E_inf * design.sp + design.Kl @ E) - self.rows_l]
        if self.has_t:
            r.append(self.ct * (E_inf + design.Kt @ E) - self.rows_t)
        return np.concatenate(r)

    def spectrum_columns(self, design: Design, E_inf, E):
        """Jacobian of the data rows in (ln E_inf, H_1..H_n)."""
        blocks = [np.column_stack([self.cs * E_inf * design.cp, (self.cs[:, None] * design.Ks) * E]),
                  np.column_stack([self.cl * E_inf * design.sp, (self.cl[:, None] * design.Kl) * E])]
        if self.has_t:
            blocks.append(np.column_stack([self.ct * E_inf, (self.ct[:, None] * design.Kt) * E]))
        return np.vstack(blocks)

    def shift_columns(self, design: Design, E, index, n_shifts):
        """Jacobian of the E' and E'' rows in the shifts s_k (decades) of the sets, point i moving with
        shift ``index[i]`` (-1: held), (2n, n_shifts)."""
        d1, d2 = shift_derivative(design.wt, E)
        cp, sp = design.cp, design.sp
        J = np.zeros((2 * self.n, n_shifts))
        rows = np.flatnonzero(index >= 0)
        J[rows, index[rows]] = (self.cs * (cp * d1 - sp * d2))[rows]
        J[self.n + rows, index[rows]] = (self.cl * (sp * d1 + cp * d2))[rows]
        return J

    def lag_column(self, design: Design, E_inf, E, g):
        """Jacobian of the E' and E'' rows in a phase p with phase_i = g_i p (rad), (2n,)."""
        m1, m2 = design.measured(E_inf, E)
        return np.concatenate([-self.cs * g * m2, self.cl * g * m1])
