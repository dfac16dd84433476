"""Nearly elastic kernels: those that barely relax within the contact, whose separation needs care.

Such a contact's force F ~ u = s^{3/2} returns to zero at a tiny residual overlap, where it falls
steeply: the cubic through F misses the root by far more than the march's error (and on a coarse grid
the step that holds it also holds the zero of s, another time). The ``adaptive`` method locates the
separation of a kernel :func:`glassy_stiffness` names on k(0) u(s) + (F - k(0) u), the second part
smooth (``_separation.separation_point``), and takes all its Richardson grids
(``adaptive.smooth_step``), as for an elastic kernel.
"""

from __future__ import annotations

import functools
import math

__all__ = ["NEARLY_ELASTIC", "contact_octave", "glassy_stiffness", "octave_stiffness"]


def glassy_stiffness(impact, tc: float | None = None) -> float:
    """k(0) = kappa E(0) (N m^-1.5) of a nearly elastic kernel, else 0: one whose modulus relaxes by at most
    NEARLY_ELASTIC of E(0) within the power of two at or below the contact-time estimate, with E(0) finite
    and no Dirac term, and not elastic (whose separation is the root of s itself). Its separation is
    located on k(0) u(s) + (F - k(0) u) (``_separation.separation_point``): the force returns to zero at
    a small residual overlap, where the cubic through F is rough; and it takes all Richardson grids (as an
    elastic kernel: ``adaptive.smooth_step``). One decision per impact, the same on every Richardson grid.
    ``tc``: the impact's contact-time estimate (s), where the caller has it."""
    return octave_stiffness(impact.material, float(impact.kappa), contact_octave(
        impact.contact_time_estimate() if tc is None else tc))


def contact_octave(tc: float) -> float:
    """The power of two at or below the contact-time estimate ``tc`` (s): the window of the decision."""
    return 2.0 ** math.floor(math.log2(tc))


@functools.lru_cache(maxsize=256)
def octave_stiffness(material, kappa: float, top: float) -> float:
    """(Cached.) :func:`glassy_stiffness` of ``material`` with k = ``kappa`` E (m^0.5) over the window ``top``
    (s, :func:`contact_octave`): the form the adaptive method's cached tables take it in."""
    if material.viscosity != 0.0 or material.is_elastic:
        return 0.0
    e0 = float(material.relaxation_modulus(0.0))
    if not (math.isfinite(e0) and e0 > 0.0):
        return 0.0
    relaxed = 1.0 - float(material.relaxation_modulus(top)) / e0
    return kappa * e0 if relaxed <= NEARLY_ELASTIC else 0.0


#: a kernel that relaxes by at most this fraction of E(0) within a contact-time estimate is nearly elastic
#: (:func:`glassy_stiffness`). One-mode Prony laws (E_inf 10 MPa, E_1 50 MPa) on the paper's plate, t0 from
#: the cubic through F against ive at rtol 1e-12: relaxing by 1.6e-3 within the contact, within 1e-9; by
#: 5e-4, 3e-7 off; by 5e-5, 1.5e-4 off (``tests/solvers/test_adaptive.py::
#: test_a_nearly_elastic_contact_separates_where_its_force_vanishes`` checks the split's result)
NEARLY_ELASTIC = 1e-3
