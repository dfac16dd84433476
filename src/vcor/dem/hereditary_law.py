"""vcor's own contact law for a DEM code: the Prony series that ``pair_style vcor/hereditary`` (and
``fix vcor/wall/hereditary``) of vcor's LAMMPS plugin (``plugins/lammps/``) takes, and its time step.

The plugin integrates the two-sphere model of :mod:`vcor.contact.pair` (Green 2026 with a rigid
target, DESIGN 1.1):

.. math::

    F = \\tfrac43 \\sqrt{R_\\mathrm{eff}}\\,\\Big[E_\\infty u + \\sum_i q_i\\Big]_+, \\quad u = \\delta^{3/2},
    \\quad \\dot q_i = -\\beta_i q_i + E_i \\dot u,

with the contact's relaxation modulus :math:`E_c(t) = E_\\infty + \\sum_i E_i e^{-\\beta_i t}` in the
effective (plane-strain) form vcor's contact uses: ``factor`` times the material's E(t), where factor
is 1/(2 (1 - nu^2)) for two spheres of one material and 1/(1 - nu^2) for a sphere on a rigid wall or
a rigid sphere. A Prony-type material (SLS, Prony presets, config materials, fits, calibrations) is its
own series. A fractional or CERF material is taken through its sum of exponentials
(:mod:`vcor.materials.expsums`) on [t_min, t_max] = [SOE_START x vcor's shortest contact time,
SOE_SPAN x its longest], with relative error at most SOE_TOL on the transient there (the error found
is ``soe_error``). Before t_min the sum stays finite where the fractional kernel is singular: the
COR error this leaves grows as sqrt(t_min / t0) (for the Butyl pair: 2.5e-3 at t_min = 1e-3 t0,
1.7e-5 at 1e-7 t0, the default; the dataset gives the error for each entry). Refused, with the
reason (:func:`refusal`): a Kelvin-Voigt dashpot, two bodies that vcor combines by Eq. 1 pointwise
in time (two different materials or Poisson ratios: a fitted sum whose terms may be negative), a plate target.

The time step (:func:`time_step`): dt = t_H(Ebar(dt)) / nsteps, where t_H(E) = 3.2181 (m_eff / K)^(2/5)
v0^(-1/5) is the Hertz contact time with the modulus E (K = 4/3 E sqrt(R_eff)) and
Ebar(h) = E_inf + sum E_i (1 - exp(-beta_i h)) / (beta_i h) the modulus one step of the plugin's
update responds with (:func:`step_modulus`). The fastest rates enter through Ebar: a term with
beta_i dt << 1 is a spring of modulus E_i, one with beta_i dt >> 1 a dashpot that adds only
E_i / (beta_i dt) to the step's stiffness, so it does not shorten the step; the update is exact for a
linear change of u over the step, stable and accurate for any beta_i dt (the COR within 2e-6 of
vcor's for beta dt from 4e-5 to 160, tests/dem/test_hereditary.py).
For a Prony series whose rates are slow against the step, Ebar is the glassy modulus E_c(0) and
t_H the shortest contact the law can have at v0; for a fractional kernel's sum of exponentials,
Ebar(dt) does not depend on how far its fastest modes reach.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["FIXED_POINT_ITERATIONS", "HERTZ_TIME", "NSTEPS", "REFUSALS", "SERIES_BELOW", "SOE_SPAN", "SOE_START",
           "SOE_TOL", "HereditaryLaw", "collision_law", "contact_law", "refusal", "step_modulus", "time_step"]

#: t_H = HERTZ_TIME (m_eff / K)^(2/5) v0^(-1/5): the elastic Hertz contact time (the constant of in.pair)
HERTZ_TIME = 3.2180654597185065
#: below this beta h, (1 - exp(-beta h)) / (beta h) is summed from its series 1 - x/2 + x^2/6
SERIES_BELOW = 1e-4
#: iterations of the time step's fixed point (it contracts by a factor <= 0.2 per iteration)
FIXED_POINT_ITERATIONS = 30
#: default time steps per glassy Hertz contact time (the COR of the plugin is then within ~1e-6 of vcor's)
NSTEPS = 1000
#: the relative error bound of a fractional or CERF material's sum of exponentials on [t_min, t_max]
SOE_TOL = 1e-4
#: t_min of the sum of exponentials: this fraction of vcor's shortest contact time
SOE_START = 1e-7
#: t_max of the sum of exponentials: this many times vcor's longest contact time (the force of a
#: contact is needed until the bodies part, after the force has returned to zero)
SOE_SPAN = 10.0

#: why the plugin cannot take a collision, by cause
REFUSALS = {
    "kelvin-voigt": "a Kelvin-Voigt dashpot is a Dirac term in E(t), not a sum of exponentials; its hereditary law is "
                    "the Brilliantov law, which lammps-viscoelastic fits exactly",
    "eq1": "two bodies of different materials (or Poisson ratios) combine by Green 2026 Eq. 1 pointwise in time, which "
           "vcor's solvers carry as a fitted exponential sum with terms of either sign; the plugin takes one Prony "
           "series of non-negative moduli per type pair",
    "plate": "a plate target's flexural mobility (Zener's plate) is not a contact law; the plugin models a sphere on a "
             "second sphere or on a rigid wall",
}


@dataclass(frozen=True, kw_only=True)
class HereditaryLaw:
    """The contact's relaxation modulus as the plugin takes it: ``e_inf`` (Pa), ``e`` (Pa) and
    ``beta`` (1/s) per term, in the effective plane-strain form; ``soe_error``: the relative error of
    the representation of the material's transient (0 for a Prony-type material); ``source``: in
    words, where the series comes from.

    Examples
    --------
    Two spheres of the paper's SLS (E_g = 15 MPa, nu = 0.5): the contact modulus is E/(2 (1 - nu^2)):

    >>> from vcor.dem.hereditary_law import contact_law
    >>> law = contact_law("sls", 1.0 / 1.5)
    >>> law.e_inf, law.e, law.beta, law.glassy
    (2500000.0, (7500000.0,), (1200.0,), 10000000.0)
    """

    e_inf: float
    e: tuple
    beta: tuple
    soe_error: float = 0.0
    source: str = ""

    @property
    def glassy(self) -> float:
        """E_c(0) = E_inf + sum E_i, Pa."""
        return self.e_inf + float(sum(self.e))

    def coefficients(self) -> list[float]:
        """The ``pair_coeff`` numbers after the type pair: E_inf E_1 beta_1 E_2 beta_2 ... (Pa, 1/s)."""
        out = [self.e_inf]
        for e, b in zip(self.e, self.beta):
            out += [e, b]
        return out


def refusal(material=None, target_kind: str = "sphere") -> str:
    """Why the plugin cannot take this collision (module docstring), or "" when it can: ``material``
    is the contact material (:func:`vcor.contact.pair.target_inputs`; its ``kind``), ``target_kind``
    ``sphere``, ``rigid`` or ``plate``.

    Examples
    --------
    >>> from vcor.dem.hereditary_law import refusal
    >>> refusal(target_kind="plate").split(";")[0]
    "a plate target's flexural mobility (Zener's plate) is not a contact law"
    """
    if target_kind == "plate":
        return REFUSALS["plate"]
    if material is None:
        return ""
    if material.kind == "eq1":
        return REFUSALS["eq1"]
    if material.viscosity > 0:
        return REFUSALS["kelvin-voigt"]
    return ""


def _terms(material, t_min: float, t_max: float) -> tuple[float, np.ndarray, np.ndarray, float, str]:
    """(E_inf, E, beta, relative error, source) of the material's own series or its sum of exponentials."""
    if material.is_prony:
        e_inf, e, b = material.prony_terms()
        return float(e_inf), np.asarray(e, float), np.asarray(b, float), 0.0, f"the {material.kind} series itself"
    from ..materials.expsums import soe  # scipy.special on use

    rep = soe(material, t_min, t_max, SOE_TOL)
    p = rep.material
    source = (f"the {material.kind} law as a sum of {rep.n_terms} exponentials on [{rep.t_min:.3g}, {rep.t_max:.3g}] s "
              f"(vcor.materials.expsums), relative error of the transient {rep.checked_error:.2g}")
    return float(p.E_inf), np.asarray(p.E, float), np.asarray(p.beta, float), float(rep.checked_error), source


def contact_law(material, factor: float, t_min: float = 1e-7, t_max: float = 1e-2) -> HereditaryLaw:
    """The plugin's series of ``material`` (a Material or a preset name) scaled by ``factor`` (the
    effective plane-strain factor, module docstring); [t_min, t_max] (s) is where a fractional or CERF
    material's sum of exponentials holds. A term with beta = 0 joins E_inf, a term with E = 0 is
    dropped. ValueError with the reason (:func:`refusal`) for a material the plugin cannot take."""
    if isinstance(material, str):
        from ..materials.presets import get

        material = get(material)
    why = refusal(material)
    if why:
        raise ValueError(f"lammps-hereditary: {why}")
    e_inf, e, b, err, source = _terms(material, t_min, t_max)
    keep = (e > 0) & (b > 0)
    e_inf += float(np.sum(e[(e > 0) & (b == 0)]))
    return HereditaryLaw(e_inf=factor * e_inf, e=tuple(float(factor * x) for x in e[keep]),
                         beta=tuple(float(x) for x in b[keep]), soe_error=err, source=source)


def collision_law(material, factor: float, target_kind: str, t0) -> HereditaryLaw:
    """The plugin's series of one collision: its contact ``material`` and ``factor`` (module
    docstring), the target's kind (``sphere``, ``rigid``, ``plate``) and vcor's contact times ``t0``
    (s; NaN where not solved) that set a sum of exponentials' interval. ValueError with the reason
    where the plugin cannot take the collision."""
    why = refusal(material, target_kind)
    if why:
        raise ValueError(f"lammps-hereditary: {why}")
    t0 = np.asarray(t0, dtype=float)
    t0 = t0[np.isfinite(t0)]
    if not t0.size:
        raise ValueError("lammps-hereditary: no speed of the collision ended ok (no contact time for the series)")
    return contact_law(material, factor, SOE_START * float(t0.min()), SOE_SPAN * float(t0.max()))


def step_modulus(law: HereditaryLaw, h):
    """Ebar(h) = (1/h) int_0^h E_c(t) dt = E_inf + sum E_i (1 - exp(-beta_i h)) / (beta_i h), Pa: the
    modulus the plugin's update over a step h (s) responds with (its discrete stiffness). Below
    beta h = SERIES_BELOW the fraction is summed from its series (as the deck does)."""
    x = np.multiply.outer(np.asarray(h, dtype=float), np.asarray(law.beta, dtype=float))
    safe = np.where(x < SERIES_BELOW, 1.0, x)
    fraction = np.where(x < SERIES_BELOW, 1.0 - 0.5 * x + x * x / 6.0, (1.0 - np.exp(-safe)) / safe)
    return law.e_inf + (np.asarray(law.e, dtype=float) * fraction).sum(axis=-1)


def time_step(law: HereditaryLaw, m_eff: float, r_eff: float, v0, nsteps: int = NSTEPS):
    """dt (s) at the speeds ``v0`` (m/s): the fixed point of dt = t_H(Ebar(dt)) / nsteps (module
    docstring), from dt = t_H(E_c(0)) / nsteps in FIXED_POINT_ITERATIONS steps; the deck and
    :mod:`vcor.dem.mirror` use it.

    Examples
    --------
    >>> from vcor.dem.hereditary_law import contact_law, time_step
    >>> law = contact_law("sls", 1.0 / 1.5)
    >>> f"{float(time_step(law, 2.88e-4, 0.0025, 1.0)):.4e} s"
    '5.7787e-07 s'
    """
    scale = HERTZ_TIME * (m_eff / (4.0 / 3.0 * math.sqrt(r_eff))) ** 0.4 * np.asarray(v0, dtype=float) ** -0.2 / nsteps
    h = scale * law.glassy**-0.4
    for _ in range(FIXED_POINT_ITERATIONS):
        h = scale * step_modulus(law, h) ** -0.4
    return h
