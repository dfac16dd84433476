"""Targets: a second sphere (particle-particle collisions), a rigid target or a plate.

Two spheres colliding head-on are one sphere on an immovable target: the reduced radius
R_eff = R_a R_b / (R_a + R_b), the reduced mass m_eff = m_a m_b / (m_a + m_b) (the sphere's density is
then m_eff over the volume of a sphere of radius R_eff), no plate mobility, and the contact modulus of
Green 2026 Eq. 1:

* both of one material and Poisson ratio: E'/2 with E' = E / (1 - nu^2) (the paper's case 2, on an
  immovable target), exact in every method;
* one of them rigid: the other's E';
* both elastic: E'_a E'_b / (E'_a + E'_b), a constant;
* otherwise Eq. 1 pointwise in time (:class:`vcor.materials.EqOne`), which every method solves
  (:mod:`vcor.contact.bodies`).

The COR is that of the relative normal velocity: (v_b - v_a after) / (v_a - v_b before).

:func:`target_inputs` is what ``vcor.simulate(..., target=...)`` calls: ``target`` is ``"plate"``
(the default geometry keywords), ``"rigid"``, ``{"sphere": {material, r, rho, nu}}`` or
``{"plate": {material, h, rho, nu}}`` (:mod:`vcor.contact.bodies`); a target body without
``material`` is of the impacting sphere's material, and a target sphere without ``material`` is
the impacting sphere's twin (its r, rho and nu by default).
"""

from __future__ import annotations

import math

from ..materials import models as _materials
from .bodies import BODY_KEYS, Body, body_from_spec, eq_one, impact_inputs
from .impact import RANGES

__all__ = ["PLATE_KEYWORDS", "TARGET_KINDS", "sphere_pair", "target_inputs", "twin_defaults"]

#: what a target may be
TARGET_KINDS = ("plate", "rigid", "sphere")
#: geometry keywords that describe the plate (or the case): not with a sphere or body target
PLATE_KEYWORDS = ("h", "rho_b", "case", "rigid", "E_plate", "nu_plate", "plate_material")


def _volume(r: float) -> float:
    return 4.0 / 3.0 * math.pi * r**3


def sphere_pair(a: Body, b: Body,
                names: tuple[str, str] = ("sphere", "target.sphere")) -> tuple[_materials.Material, dict]:
    """(contact material, geometry keywords) of sphere ``a`` hitting sphere ``b`` head-on (module
    docstring); ``names``: what the caller calls the two spheres (messages name them so).

    Examples
    --------
    Two equal SLS spheres: the paper's case 2 on an immovable target, with the reduced radius:

    >>> from vcor.contact.bodies import body_from_spec
    >>> from vcor.contact.pair import sphere_pair
    >>> a = body_from_spec("sphere", {"material": "sls", "r": 0.01})
    >>> material, geometry = sphere_pair(a, a)
    >>> geometry["r"], geometry["case"], geometry["rigid"]
    (0.005, 2, True)
    """
    if a.rigid and b.rigid:
        raise ValueError("target.sphere: both spheres are rigid: no contact modulus (give one a material)")
    ra, rb = a.size, b.size
    r_eff = ra * rb / (ra + rb)
    ma, mb = a.rho * _volume(ra), b.rho * _volume(rb)
    m_eff = ma * mb / (ma + mb)
    geometry = {"r": r_eff, "rho_a": m_eff / _volume(r_eff), "rigid": True}
    (r_lo, r_hi), (rho_lo, rho_hi) = RANGES["r"], RANGES["rho_a"]
    if not (r_lo <= r_eff <= r_hi and rho_lo <= geometry["rho_a"] <= rho_hi):
        # each sphere is in range; their equivalent sphere (half the radius, four times the density of two
        # equal ones) may not be, and it is what the solver takes
        raise ValueError(f"{names[0]} and {names[1]}: their equivalent sphere (reduced radius {r_eff:.3g} m, density "
                         f"{geometry['rho_a']:.3g} kg/m^3) is outside the solver's geometry ranges, r in [{r_lo:g}, "
                         f"{r_hi:g}] m and rho_a in [{rho_lo:g}, {rho_hi:g}] kg/m^3")
    if b.rigid:
        return a.material, {**geometry, "nu": a.nu, "case": 3}
    if a.rigid:
        return b.material, {**geometry, "nu": b.nu, "case": 3}
    if a.material == b.material and a.nu == b.nu:
        return a.material, {**geometry, "nu": a.nu, "case": 2}
    if a.material.is_elastic and b.material.is_elastic:
        ea, eb = a.c * a.material.glassy, b.c * b.material.glassy
        return _materials.Elastic(ea * eb / (ea + eb)), {**geometry, "nu": 0.0, "case": 3}
    return eq_one(a, b, names), {**geometry, "nu": 0.0, "case": 3}


def twin_defaults(sphere: Body, kind: str, spec) -> dict:
    """A target sphere without its own material is a twin of the impacting sphere: its radius, density
    and Poisson ratio default to the sphere's (a plate's keys keep their own defaults).

    Examples
    --------
    >>> from vcor.contact.bodies import body_from_spec
    >>> from vcor.contact.pair import twin_defaults
    >>> ball = body_from_spec("sphere", {"material": "sls", "r": 0.01})
    >>> twin_defaults(ball, "sphere", {"r": 0.02})
    {'r': 0.02, 'rho': 1100.0, 'nu': 0.5}
    """
    if spec is not None and not isinstance(spec, dict):
        raise ValueError(f"target.{kind}: a mapping with keys {sorted(BODY_KEYS[kind])}, got {spec!r}")
    spec = dict(spec or {})
    if kind != "sphere" or "material" in spec:
        return spec
    return {"r": sphere.size, "rho": sphere.rho, "nu": sphere.nu, **spec}


def target_inputs(material, target, geometry: dict) -> tuple[_materials.Material, dict]:
    """(material, geometry keywords) for ``simulate`` of ``material`` hitting ``target`` (module
    docstring); ``geometry`` holds the impacting sphere's keywords (r, rho_a, nu).

    Examples
    --------
    ``vcor.simulate(..., target=...)`` calls it; two equal SLS spheres head-on at 1 m/s (the COR of
    the relative velocity) and an SLS sphere on a rigid wall:

    >>> import vcor
    >>> f"{vcor.simulate('sls', 1.0, target={'sphere': {}}).cor:.3f}"
    '0.656'
    >>> from vcor.contact.pair import target_inputs
    >>> target_inputs("sls", "rigid", {"r": 0.01})
    ('sls', {'r': 0.01, 'rigid': True})
    """
    if target == "plate":
        return material, geometry
    if target == "rigid":
        if geometry.get("rigid", True) is not True:
            raise ValueError(f"target 'rigid' with rigid={geometry['rigid']!r}: give one of them (target='plate' is "
                             f"the plate of the geometry keywords)")
        return material, {**geometry, "rigid": True}
    if not isinstance(target, dict) or len(target) != 1 or next(iter(target)) not in ("sphere", "plate"):
        raise ValueError(f"target must be one of 'plate', 'rigid', {{'sphere': {{...}}}} or {{'plate': {{...}}}} (one "
                         f"kind), got {target!r}")
    (kind, spec), = target.items()
    clash = sorted(set(geometry) & set(PLATE_KEYWORDS))
    if clash:
        raise ValueError(f"target: a {kind} target takes its own size, density and Poisson ratio; the geometry "
                         f"keywords {clash} describe the default plate and do not go with it")
    unknown = sorted(set(geometry) - {"r", "rho_a", "nu"})
    if unknown:
        raise ValueError(f"target: unknown keyword(s) {unknown} with a {kind} target (the sphere takes r, rho_a, nu)")
    swept = material if isinstance(material, _materials.Material) else None
    sphere_spec = {"material": material,
                   **{k: geometry[g] for k, g in (("r", "r"), ("rho", "rho_a"), ("nu", "nu")) if g in geometry}}
    sphere = body_from_spec("sphere", sphere_spec, where="sphere")
    other = body_from_spec(kind, twin_defaults(sphere, kind, spec), swept=swept or sphere.material,
                           where=f"target.{kind}")
    if kind == "sphere":
        return sphere_pair(sphere, other, ("sphere", "target.sphere"))
    return impact_inputs(sphere, other, ("sphere", "target.plate"))

