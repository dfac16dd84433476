"""Bodies instead of a case number: a sphere and a plate, each with its own
material, size, density and Poisson ratio, combined as Green 2026 Eq. 1 says.

* ``sphere: {material, r, rho, nu}``, ``plate: {material, h, rho, nu}``; ``material`` is a
  material (a preset name, a config material's name (the workflow inlines its parameters:
  :mod:`vcor.study.project`; a fit or calibration, which the workflow resolves through its
  catalogue), an inline spec ``{model: ...}`` as in the config's ``materials:``
  block, ``rigid``, or ``{model: elastic, E: ...}``); in a scene a body without ``material`` takes the
  scene's swept material (its ``materials`` list). h is the plate's half-thickness (default 2 r).
* Defaults: a rigid or elastic body is steel (rho 7800 kg/m^3, nu 0.3), a viscoelastic one the
  paper's polymer (rho 1100 kg/m^3, nu 0.5) (``vcor.contact.impact.DENSITIES``).
* Contact modulus, Eq. 1 as written: E'(t) = E'_a E'_b / (E'_a + E'_b) pointwise in time, E'_i =
  E_i / (1 - nu_i^2); a rigid body drops out (E' = E'_other). Plate mobility (Zener): from the
  plate's own E'_b(t), rho and h; a rigid plate is an immovable target (alpha = 0).

What :func:`impact_inputs` returns is an ordinary (material, geometry) pair for ``simulate``:

* one body rigid: the other body's material and Poisson ratio, case 3 (or a rigid target): every
  method works and the result equals the case form (the paper's case 3 is a rigid-contact steel
  sphere with steel density);
* both the same material and Poisson ratio: the paper's case 2 (E'/2; the plate mobility from E');
* otherwise an :class:`vcor.materials.EqOne` contact modulus (already plane strain: geometry nu = 0)
  and the plate's modulus in ``plate_material`` / ``nu_plate``; unless both bodies are elastic (then E'
  is a constant). Every method solves it: ``direct`` takes E' as it is, ``adaptive`` and ``soe`` its
  exponential sum on their time window (:mod:`vcor.materials.expfit`, error reported as
  ``soe_error``), ``ive`` and ``ive-numba`` the same sum from t = 0 when E'(0) is finite; the plate's
  mobility comes from the plate's own modulus. A Kelvin-Voigt (Dirac) body has no pointwise
  combination with a deformable body of another material: refused, naming the two bodies.

:func:`series_modulus` is the alternative for comparison: the compliances of the two
bodies added in the Laplace domain (the correspondence principle applied to 1/E' = 1/E'_a + 1/E'_b),
exact for Prony bodies (the result is again a Prony series).
"""

from __future__ import annotations

import functools
import json
from dataclasses import dataclass

import numpy as np

from ..checks import number
from ..materials import models as _materials
from ..materials.presets import PRESETS, get
from ..materials.specs import from_spec
from .impact import DENSITIES, GEOMETRY_DEFAULTS, RANGES

__all__ = ["BODY_KEYS", "Body", "body_from_spec", "eq_one", "impact_inputs", "scene_bodies", "series_modulus"]

#: keys of a body mapping (size: r for the sphere, h for the plate)
BODY_KEYS = {"sphere": {"material", "r", "rho", "nu"}, "plate": {"material", "h", "rho", "nu"}}
#: default Poisson ratios: stiff (rigid, elastic) bodies are steel, viscoelastic ones rubber-like
NU_DEFAULTS = {"steel": 0.3, "polymer": 0.5}


@dataclass(kw_only=True, frozen=True)
class Body:
    """One body: ``material`` (a Material, or None for a rigid body), ``size`` (sphere radius r or
    plate half-thickness h, m; None: the plate's default 2 r), density ``rho`` (kg/m^3) and Poisson
    ratio ``nu``.

    Examples
    --------
    >>> from vcor.contact.bodies import body_from_spec
    >>> wall = body_from_spec("plate", {"material": "rigid"})
    >>> wall.rigid, wall.rho, wall.nu, round(wall.c, 4)
    (True, 7800.0, 0.3, 1.0989)
    """

    material: _materials.Material | None
    size: float | None
    rho: float
    nu: float

    @property
    def rigid(self) -> bool:
        return self.material is None

    @property
    def c(self) -> float:
        """1 / (1 - nu^2), the plane-strain factor of E (Eq. 1)."""
        return 1.0 / (1.0 - self.nu**2)


def _material_of(value, where, swept):
    if value is None:
        if swept is None:
            raise ValueError(f"{where}.material: give a material (a preset name, an inline spec, or rigid)")
        return swept
    if isinstance(value, _materials.Material):
        return value
    if value == "rigid":
        return None
    if isinstance(value, str):
        if value not in PRESETS:
            raise ValueError(f"{where}.material: {value!r} is not a preset ({sorted(PRESETS)}) or 'rigid'; "
                             f"another material inline as {{model: ...}} (in a workflow config, a body also "
                             f"takes the names of config materials, fits and calibrations)")
        return get(value)
    if isinstance(value, dict):
        return from_spec(value, where=f"{where}.material")
    raise ValueError(f"{where}.material: a preset name, 'rigid' or a mapping {{model: ...}}, got {value!r}")


def body_from_spec(kind: str, spec: dict, swept=None, where: str | None = None) -> Body:
    """A :class:`Body` from a config mapping (``kind`` sphere or plate); ``swept``: the scene's material
    for a body without ``material``. Errors name ``where.<key>``.

    Examples
    --------
    A viscoelastic body defaults to the paper's polymer, a rigid or elastic one to steel:

    >>> from vcor.contact.bodies import body_from_spec
    >>> plate = body_from_spec("plate", {"material": "sls", "h": 0.02})
    >>> plate.size, plate.rho, plate.nu
    (0.02, 1100.0, 0.5)
    >>> body_from_spec("sphere", {"material": "sls", "r": -1})
    Traceback (most recent call last):
    ...
    ValueError: sphere.r must be in [1e-09, 1000] m, got -1
    """
    where = where or kind
    if not isinstance(spec, dict):
        raise ValueError(f"{where}: a mapping with keys {sorted(BODY_KEYS[kind])}, got {spec!r}")  # noqa: TRY004 (config values: ValueError, like every bad input)
    unknown = set(spec) - BODY_KEYS[kind]
    if unknown:
        raise ValueError(f"{where}: unknown key(s) {sorted(unknown)}; allowed: {sorted(BODY_KEYS[kind])}")
    material = _material_of(spec.get("material"), where, swept)
    if material is not None and material.viscosity > 0 and kind == "plate":
        raise ValueError(f"{where}.material: a Kelvin-Voigt plate has no finite plate modulus for Zener's "
                         f"mobility; use it for the sphere, or a Prony/SLS plate")
    stiff = material is None or material.is_elastic
    family = "steel" if stiff else "polymer"
    size_key = "r" if kind == "sphere" else "h"
    size = spec.get(size_key, GEOMETRY_DEFAULTS["r"] if kind == "sphere" else None)
    lo, hi = RANGES[size_key]  # the ranges of the geometry's own r and h, and of its densities
    if size is not None:
        size = number(f"{where}.{size_key}", size, lo, hi, lo_open=False, hi_open=False, unit="m")
    lo, hi = RANGES["rho_a"]
    rho = number(f"{where}.rho", spec.get("rho", DENSITIES[family]), lo, hi, lo_open=False, hi_open=False,
                 unit="kg/m^3")
    nu = number(f"{where}.nu", spec.get("nu", NU_DEFAULTS[family]), -1, 0.5, hi_open=False)
    return Body(material=material, size=None if size is None else float(size), rho=float(rho), nu=float(nu))


@functools.lru_cache(maxsize=64)
def _fixed_body(kind: str, spec_json: str) -> Body:
    return body_from_spec(kind, json.loads(spec_json))


def scene_bodies(specs: dict, swept) -> tuple[Body, Body]:
    """(sphere, plate) of a scene's ``{sphere: ..., plate: ...}`` at a point whose swept material is
    ``swept``; a body that names its own material is built once per spec (cached), not per point."""
    out = []
    for kind in ("sphere", "plate"):
        spec = specs.get(kind) or {}
        material = spec.get("material")
        if material is None or isinstance(material, _materials.Material):
            out.append(body_from_spec(kind, spec, swept=swept))
        else:
            out.append(_fixed_body(kind, json.dumps(spec, sort_keys=True)))
    return out[0], out[1]


def eq_one(a: Body, b: Body, names: tuple[str, str]) -> _materials.EqOne:
    """The pointwise Eq. 1 contact modulus of two deformable bodies of different materials, its bodies
    called ``names`` as the user gave them (e.g. ``("sphere", "target.plate")``); a Kelvin-Voigt body is
    refused naming both.

    Examples
    --------
    >>> from vcor.contact.bodies import body_from_spec, eq_one
    >>> ball = body_from_spec("sphere", {"material": "kelvin-voigt"})
    >>> eq_one(ball, body_from_spec("plate", {"material": "sls"}), ("sphere", "plate"))
    Traceback (most recent call last):
    ...
    ValueError: sphere.material (kelvin-voigt) on plate.material (sls): ...
    """
    for body in (a, b):
        if body.material.viscosity > 0:
            raise ValueError(f"{names[0]}.material ({a.material.kind}) on {names[1]}.material ({b.material.kind}): "
                             f"a Kelvin-Voigt (Dirac) modulus has no pointwise Eq. 1 combination with a deformable "
                             f"body of another material, so no method solves the pair; make the other body rigid "
                             f"(material: rigid) or of the same material")
    return _materials.EqOne(a.material, a.c, b.material, b.c, names=names)


def impact_inputs(sphere: Body, plate: Body,
                  names: tuple[str, str] = ("sphere", "plate")) -> tuple[_materials.Material, dict]:
    """(contact material, geometry keywords) of two bodies for ``vcor.simulate`` (module docstring);
    ``names``: what the caller calls the two bodies (messages name them so).

    Examples
    --------
    A rigid steel sphere on an SLS plate is the paper's case 3:

    >>> import vcor
    >>> from vcor.contact.bodies import body_from_spec, impact_inputs
    >>> ball = body_from_spec("sphere", {"material": "rigid", "r": 0.01})
    >>> material, geometry = impact_inputs(ball, body_from_spec("plate", {"material": "sls"}))
    >>> geometry["case"], f"{vcor.simulate(material, 1.0, **geometry).cor:.3f}"
    (3, '0.388')
    """
    if sphere.rigid and plate.rigid:
        raise ValueError("sphere and plate are both rigid: no contact modulus (give one body a material)")
    if sphere.size is None:
        raise ValueError("sphere.r: the sphere needs a radius")
    geometry = {"r": sphere.size, "h": plate.size, "rho_a": sphere.rho, "rho_b": plate.rho}
    if sphere.rigid:  # the paper's case 3: E' = E'_b, plate mobility from the same E'_b
        return plate.material, {**geometry, "nu": plate.nu, "case": 3}
    if plate.rigid:  # an immovable, rigid target: no plate density (a thickness given is refused by make_impact)
        return sphere.material, {**geometry, "rho_b": None, "nu": sphere.nu, "case": 3, "rigid": True}
    if sphere.material == plate.material and sphere.nu == plate.nu:  # case 2: E'/2, mobility from E'
        return sphere.material, {**geometry, "nu": sphere.nu, "case": 2}
    a, b = sphere.material, plate.material
    if a.is_elastic and b.is_elastic:
        ea, eb = sphere.c * a.glassy, plate.c * b.glassy
        contact = _materials.Elastic(ea * eb / (ea + eb))
    else:
        contact = eq_one(sphere, plate, names)
    return contact, {**geometry, "nu": 0.0, "case": 3, "plate_material": b, "nu_plate": plate.nu}


def series_modulus(a: _materials.Material, c_a: float, b: _materials.Material, c_b: float) -> _materials.Prony:
    """The series (Laplace-domain) combination of two Prony plane-strain moduli c_a E_a and c_b E_b:
    1/E*(s) = 1/E*_a(s) + 1/E*_b(s), E*(s) = s L[E](s). With E*_i = N_i / D_i (D_i = prod (s + beta_k)),
    E* = N_a N_b / (N_a D_b + N_b D_a): its poles (the denominator's roots, real and negative) are the
    relaxation rates of the result, and E(t) = E*(0) + sum_j Res_j e^(p_j t).

    Examples
    --------
    Two equal bodies in series have half the modulus at every time:

    >>> from vcor import materials
    >>> from vcor.contact.bodies import series_modulus
    >>> sls = materials.get("sls")
    >>> both = series_modulus(sls, 1.0, sls, 1.0)
    >>> [round(float(both.relaxation_modulus(t) / sls.relaxation_modulus(t)), 6) for t in (0.0, 1e-3, 1.0)]
    [0.5, 0.5, 0.5]
    """
    polys = []
    for m, c in ((a, c_a), (b, c_b)):
        if not m.is_prony or m.viscosity > 0:
            raise ValueError(f"series_modulus needs Prony (or SLS, elastic) bodies, got {m.kind!r}")
        e_inf, e, beta = m.prony_terms()
        den = np.poly1d([1.0])
        for bk in beta:
            den = den * np.poly1d([1.0, bk])
        num = den * float(c * e_inf)
        for k, ek in enumerate(e):
            others = np.poly1d([1.0])
            for j, bj in enumerate(beta):
                if j != k:
                    others = others * np.poly1d([1.0, bj])
            num = num + np.poly1d([float(c * ek), 0.0]) * others
        polys.append((num, den))
    (na, da), (nb, db) = polys
    num, den = na * nb, na * db + nb * da
    poles = np.roots(den.coeffs)
    if np.any(np.abs(poles.imag) > 1e-9 * np.abs(poles.real)) or np.any(poles.real >= 0):
        raise ValueError(f"series_modulus: poles {poles} are not real and negative")
    poles = np.sort(poles.real)
    dden = den.deriv()
    # L[E](s) = E*(s) / s: residue at p_j of num / (s den) -> coefficient of e^(p_j t)
    res = np.array([num(p) / (p * dden(p)) for p in poles])
    e_inf = float(num(0.0) / den(0.0))
    return _materials.Prony(e_inf, tuple(map(float, res)), tuple(map(float, -poles)))
