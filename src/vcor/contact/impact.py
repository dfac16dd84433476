"""Impact set-up: geometry and case -> sphere mass m, contact kernel k(t), plate mobility alpha(t).

Green 2026, Eqs. 1, 3, 12 and Section 3 (SI units throughout):

* k(t) = 4/3 sqrt(r) E'(t) (N m^-1.5), E'(t) = c_case E(t) / (1 - nu^2)
* alpha(t) = sqrt(3 rho_b / E'_b(t)) / (16 rho_b h^2) (m N^-1 s^-1), Zener's point mobility of
  an infinite Kirchhoff plate of half-thickness h; ``rigid=True`` sets alpha = 0.

Cases (which body is viscoelastic, Eq. 1):

1. both elastic: the material must be elastic; treated like case 3 (sphere much stiffer).
2. sphere and plate of the same viscoelastic material: E' = E/(2 (1 - nu^2)), the plate
   mobility uses E'_b = E/(1 - nu^2).
3. (default, the paper's) stiff elastic sphere on a viscoelastic plate: E' = E'_b = E/(1-nu^2).
4. viscoelastic sphere on a stiff elastic plate: E' = E/(1 - nu^2); alpha is constant, from the
   plate's own modulus ``E_plate`` and ``nu_plate`` (defaults: steel, 200 GPa, 0.3).

Densities not given follow the case (``DENSITIES``): the viscoelastic body is the paper's polymer,
1100 kg/m^3, a stiff elastic one steel, 7800 kg/m^3.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from ..checks import interned, number
from ..materials import models as _materials
from ..materials.presets import get as _preset

__all__ = ["DENSITIES", "GEOMETRY_AXES", "GEOMETRY_DEFAULTS", "GLASSY_TIME_CAP", "RANGES", "RELAXED_TO_ZERO",
           "Geometry", "Impact", "make_impact"]

#: densities (kg/m^3) used when rho_a / rho_b are not given: the viscoelastic body is the paper's polymer
#: (1100), a stiff elastic one steel (7800). Case 1 and 3: steel sphere on a polymer plate; case 2: both
#: polymer; case 4: polymer sphere on a steel plate.
DENSITIES = {"polymer": 1100.0, "steel": 7800.0}
_SPHERE_IS_POLYMER = {1: False, 2: True, 3: False, 4: True}
_PLATE_IS_POLYMER = {1: True, 2: True, 3: True, 4: False}

#: allowed ranges (closed) of the geometry's and the impact's numbers, SI units (RANGE_UNITS)
RANGES = {"r": (1e-9, 1e3), "rho_a": (1e-3, 1e6), "rho_b": (1e-3, 1e6), "h": (1e-9, 1e3), "E_plate": (1e-3, 1e15),
          "v0": (1e-9, 1e5)}
RANGE_UNITS = {"r": "m", "rho_a": "kg/m^3", "rho_b": "kg/m^3", "h": "m", "E_plate": "Pa", "v0": "m/s"}
#: for a material that relaxes towards zero (a Maxwell fluid, rubbery modulus 0) the contact-time
#: estimate has no fixed point; it is then at most this many times the elastic contact time of the
#: glassy modulus (solids, rubbery modulus > 0, are bounded by their rubbery contact time and not capped)
GLASSY_TIME_CAP = 1024.0
#: a plate of a fluid (rubbery modulus 0) whose modulus has fallen below this fraction of its glassy value
#: has a mobility that no step follows (Zener's mobility grows as E'_b^-1/2): a march that fails there says
#: so (:meth:`Impact.unbounded_mobility`)
RELAXED_TO_ZERO = 1e-12

GEOMETRY_DEFAULTS = {
    "r": 0.010,  # sphere radius, m
    "rho_a": None,  # sphere density, kg/m^3 (None: by case, see DENSITIES)
    "rho_b": None,  # plate density, kg/m^3 (None: by case)
    "h": None,  # plate half-thickness, m (None -> 2 r, as in the paper)
    "nu": 0.5,  # Poisson ratio of the viscoelastic body
    "case": 3,
    "rigid": False,  # rigid, immovable target: alpha = 0
    "E_plate": 200e9,  # case 4 only: elastic plate modulus, Pa
    "nu_plate": 0.3,  # case 4, and the plate of plate_material
    # the plate's own material when it differs from the contact modulus (vcor.contact.bodies: Eq. 1 with two
    # deformable bodies); the plate's plane-strain modulus is then E_b(t) / (1 - nu_plate^2)
    "plate_material": None,
}
#: the geometry keywords that are numbers a sweep may vary (grid axes of role geometry,
#: vcor.study.grid); case, rigid and plate_material choose the set-up and are fixed per scene
GEOMETRY_AXES = tuple(k for k in GEOMETRY_DEFAULTS if k not in ("case", "rigid", "plate_material"))


@dataclass(frozen=True, kw_only=True)
class Geometry:
    """Sphere-plate geometry. Units: m, kg/m^3, Pa.

    Examples
    --------
    Densities and the plate's half-thickness not given follow the case (here 3: a steel sphere on a
    polymer plate) and the radius:

    >>> from vcor.contact.impact import Geometry
    >>> g = Geometry(r=0.005)
    >>> g.half_thickness, g.sphere_density, g.plate_density, f"{g.mass * 1e3:.2f} g"
    (0.01, 7800.0, 1100.0, '4.08 g')
    >>> Geometry(case=5)
    Traceback (most recent call last):
    ...
    ValueError: case must be one of 1, 2, 3, 4 (an integer), got 5
    """

    r: float = GEOMETRY_DEFAULTS["r"]
    rho_a: float | None = None
    rho_b: float | None = None
    h: float | None = None
    nu: float = GEOMETRY_DEFAULTS["nu"]
    case: int = 3
    rigid: bool = False
    E_plate: float = GEOMETRY_DEFAULTS["E_plate"]
    nu_plate: float = GEOMETRY_DEFAULTS["nu_plate"]
    plate_material: _materials.Material | None = None

    def __post_init__(self):
        # stated ranges, wide enough for dimensionless use (the Ramirez unit problem: r = 1 m,
        # rho_a = 0.24 kg/m^3), narrow enough that masses, stiffnesses and times stay floating-point
        values = {"r": number("r", self.r, *RANGES["r"], lo_open=False, hi_open=False, unit="m")}
        for name in ("rho_a", "rho_b", "h"):
            if getattr(self, name) is not None:
                values[name] = number(name, getattr(self, name), *RANGES[name], lo_open=False, hi_open=False,
                                      unit=RANGE_UNITS[name])
        values["nu"] = number("nu", self.nu, -1, 0.5, hi_open=False)
        values["nu_plate"] = number("nu_plate", self.nu_plate, -1, 0.5, hi_open=False)
        values["E_plate"] = number("E_plate", self.E_plate, *RANGES["E_plate"], lo_open=False, hi_open=False,
                                   unit="Pa")
        if isinstance(self.case, bool) or not isinstance(self.case, (int, np.integer)) or self.case not in (1, 2, 3, 4):
            raise ValueError(f"case must be one of 1, 2, 3, 4 (an integer), got {self.case!r}")
        values["case"] = int(self.case)
        if not isinstance(self.rigid, (bool, np.bool_)):
            raise ValueError(f"rigid must be true or false, got {self.rigid!r}")
        values["rigid"] = bool(self.rigid)
        if self.plate_material is not None:
            if not isinstance(self.plate_material, _materials.Material) or self.plate_material.viscosity > 0:
                raise ValueError(f"plate_material must be a material without a Dirac (Kelvin-Voigt) term, "
                                 f"got {self.plate_material!r}")
            if self.case != 3:
                raise ValueError(f"plate_material goes with case 3 (vcor.contact.bodies), got case {self.case}")
        for name, value in values.items():  # stored as plain floats, ints and bools
            object.__setattr__(self, name, value)

    @property
    def half_thickness(self) -> float:
        return 2.0 * self.r if self.h is None else float(self.h)

    @property
    def sphere_density(self) -> float:
        """rho_a, or by case (``DENSITIES``), kg/m^3."""
        if self.rho_a is not None:
            return float(self.rho_a)
        return DENSITIES["polymer" if _SPHERE_IS_POLYMER[self.case] else "steel"]

    @property
    def plate_density(self) -> float:
        """rho_b, or by case (``DENSITIES``), kg/m^3."""
        if self.rho_b is not None:
            return float(self.rho_b)
        return DENSITIES["polymer" if _PLATE_IS_POLYMER[self.case] else "steel"]

    @cached_property
    def mass(self) -> float:
        """Sphere mass, kg (computed once: the geometry is immutable)."""
        return 4.0 / 3.0 * math.pi * self.r**3 * self.sphere_density

    @cached_property
    def kernel_scale(self) -> float:
        """kappa, m^0.5: the contact kernel k(t) = kappa E(t) (``Impact.kappa``; computed once: the geometry is
        immutable)."""
        c = 0.5 if self.case == 2 else 1.0
        return 4.0 / 3.0 * math.sqrt(self.r) * c / (1.0 - self.nu**2)


@dataclass(frozen=True)
class Impact:
    """One impact problem: material, geometry and impact speed v0 (m/s).

    Exposes the mass ``m`` (kg), the kernel scale ``kappa`` (k(t) = kappa E(t), m^0.5),
    and the plate mobility ``alpha(t)`` / ``alpha_rate(t)``.

    Examples
    --------
    >>> from vcor.contact.impact import make_impact
    >>> imp = make_impact("sls", 1.0, {"r": 0.01})
    >>> f"m = {imp.m * 1e3:.1f} g", f"k(0) = {float(imp.kernel(0.0)):.4g} N/m^1.5"
    ('m = 32.7 g', 'k(0) = 2.667e+06 N/m^1.5')
    >>> f"alpha(0) = {float(imp.alpha(0.0)):.4g} m/(N s)"
    'alpha(0) = 0.001825 m/(N s)'
    """

    material: _materials.Material
    v0: float
    geometry: Geometry = field(default_factory=Geometry)

    def __post_init__(self):
        object.__setattr__(self, "v0", number("v0", self.v0, *RANGES["v0"], lo_open=False, hi_open=False, unit="m/s"))
        g = self.geometry
        if g.case == 1 and not self.material.is_elastic:
            raise ValueError(f"case 1 (both bodies elastic) needs an elastic material (constant E(t), no "
                             f"viscosity), got {self.material.kind!r} {self.material.params()}; use case 2, 3 or 4")

    @property
    def m(self) -> float:
        return self.geometry.mass

    @property
    def kappa(self) -> float:
        """k(t) = kappa E(t), m^0.5 (``Geometry.kernel_scale``: computed once per geometry, which a sweep's
        points and repeated calls share)."""
        return self.geometry.kernel_scale

    def kernel(self, t):
        """k(t) = kappa E(t) in N m^-1.5 (regular part)."""
        return self.kappa * self.material.relaxation_modulus(t)

    @property
    def mobility_scale(self) -> float:
        """alpha(t) sqrt(E'_b(t)) = sqrt(3 rho_b) / (16 rho_b h^2), m N^-1 s^-1 Pa^0.5."""
        g = self.geometry
        h = g.half_thickness
        rho = g.plate_density
        return math.sqrt(3.0 * rho) / (16.0 * rho * h * h)

    def _plate_modulus(self, t):
        """E'_b(t) in Pa (plane-strain modulus of the plate)."""
        g = self.geometry
        t = np.asarray(t, dtype=float)
        if g.case == 4:
            return np.full_like(t, g.E_plate / (1.0 - g.nu_plate**2))
        if g.plate_material is not None:
            return g.plate_material.relaxation_modulus(t) / (1.0 - g.nu_plate**2)
        return self.material.relaxation_modulus(t) / (1.0 - g.nu**2)

    def alpha(self, t):
        """Plate mobility alpha(t), m N^-1 s^-1 (0 for a rigid target)."""
        t = np.asarray(t, dtype=float)
        if self.geometry.rigid:
            return np.zeros_like(t)
        with np.errstate(divide="ignore"):
            return self.mobility_scale / np.sqrt(self._plate_modulus(t))

    def alpha_rate(self, t):
        """d alpha/dt, m N^-1 s^-2. 0 at t = 0 where it is singular but multiplies J(0) = 0."""
        t = np.asarray(t, dtype=float)
        g = self.geometry
        if g.rigid or g.case == 4:
            return np.zeros_like(t)
        eb = self._plate_modulus(t)
        if g.plate_material is not None:
            deb = g.plate_material.relaxation_rate(t) / (1.0 - g.nu_plate**2)
        else:
            deb = self.material.relaxation_rate(t) / (1.0 - g.nu**2)
        with np.errstate(divide="ignore", invalid="ignore"):
            out = -0.5 * self.mobility_scale * deb / eb**1.5
        return np.where(t > 0, out, 0.0)

    def mobility(self, t: float) -> tuple[float, float]:
        """(alpha(t), alpha'(t)) at one time, as floats (:meth:`mobility_function` at ``t``)."""
        return self.mobility_function()(t)

    def mobility_function(self):
        """t -> (alpha(t), alpha'(t)) as floats, in m/(N s) and m/(N s^2); for a Prony plate a fast
        scalar path with the plate's constants computed once (the internal-variable solver calls it in
        every right-hand-side evaluation). Where the plate's modulus has relaxed to zero (a Maxwell
        fluid) alpha is inf (:meth:`unbounded_mobility` says so)."""
        g = self.geometry
        if g.rigid:
            return lambda t: (0.0, 0.0)
        if g.case == 4:
            return lambda t: (float(self.alpha(t)), 0.0)
        own = g.plate_material is not None
        mat = g.plate_material if own else self.material
        if not mat.is_prony:
            return lambda t: (float(self.alpha(t)), float(self.alpha_rate(t)))
        e_inf, e, b = mat.prony_terms()
        c = 1.0 / (1.0 - (g.nu_plate if own else g.nu) ** 2)
        scale = self.mobility_scale
        modes = bool(e.size)

        def prony_plate(t):
            ex = e * np.exp(-b * t) if modes else e
            eb = c * (e_inf + float(ex.sum()))
            if not eb > 0.0:
                return math.inf, math.inf
            deb = -c * float((ex * b).sum())
            a = scale / math.sqrt(eb)
            return a, (-0.5 * a * deb / eb if t > 0 else 0.0)

        return prony_plate

    @cached_property
    def mobility_is_constant(self) -> bool:
        """alpha'(t) = 0: a rigid target, case 4, or a plate whose modulus does not relax (elastic, or the
        regular part of a Kelvin-Voigt modulus)."""
        g = self.geometry
        if g.rigid or g.case == 4:
            return True
        plate = g.plate_material if g.plate_material is not None else self.material
        if plate.is_elastic:  # (a fractional or CERF law with E1 = 0 too)
            return True
        if not plate.is_prony:
            return False
        _, e, b = plate.prony_terms()
        return not np.any(e * b)  # a term of rate 0 (SLS(E, 0, 0)) is a constant too

    def unbounded_mobility(self, t: float) -> str:
        """Why the plate's mobility is not finite at time t (s), or "" when it is: the plate's modulus has
        relaxed to zero (a Maxwell fluid, rubbery modulus 0), where Zener's mobility
        sqrt(3 rho_b / E'_b) / (16 rho_b h^2) has no bound."""
        g = self.geometry
        if g.rigid or g.case == 4 or not math.isfinite(t):
            return ""
        plate = g.plate_material if g.plate_material is not None else self.material
        now, glassy = float(self._plate_modulus(t)), float(self._plate_modulus(0.0))
        # zero in floating point, or (a fluid: rubbery modulus 0, finite glassy modulus) below RELAXED_TO_ZERO
        # of its glassy value, where the mobility outgrows any step
        if now > 0.0 and not (plate.rubbery == 0.0 and math.isfinite(glassy) and now <= RELAXED_TO_ZERO * glassy):
            return ""
        return (f"the plate's modulus E'_b(t) has relaxed to zero ({now:.3g} Pa) by t = {t:.6g} s (plate material "
                f"{plate.kind} "
                f"{plate.params()}, rubbery modulus {plate.rubbery:g} Pa: a Maxwell fluid, e.g. SLS alpha = 0), "
                f"where Zener's plate mobility sqrt(3 rho_b / E'_b) / (16 rho_b h^2) is unbounded: give the plate "
                f"a rubbery modulus > 0 (SLS alpha > 0), or take a rigid target (rigid=True) or case 4")

    def contact_time_estimate(self) -> float:
        """Hertz contact time on a rigid target, t_c = 2.9432 s_max / v0, s_max = (5 m v0^2 / (4 k))^(2/5),
        with k evaluated at a quarter of that time (fixed point), in s. An estimate, not a bound:
        relaxation and the plate's motion change the real contact time both ways (in the paper's SLS case
        t0/t_c = 0.845; thin plates make it far longer). A material whose modulus relaxes towards zero (a
        Maxwell fluid, rubbery modulus 0) has no fixed point: the estimate is then capped at GLASSY_TIME_CAP
        times the elastic contact time of its glassy modulus. Used to choose dt, the adaptive steps and T_max.

        Examples
        --------
        >>> import vcor
        >>> from vcor.contact.impact import make_impact
        >>> tc = make_impact("sls", 1.0, {}).contact_time_estimate()
        >>> f"estimate {tc * 1e3:.2f} ms", f"solved t0 {vcor.simulate('sls', 1.0).t0 * 1e3:.2f} ms"
        ('estimate 2.74 ms', 'solved t0 2.19 ms')
        """
        t = 1e-3
        kappa, modulus_at, v0 = self.kappa, self.material.modulus_at, self.v0
        energy = 5.0 * self.m * v0**2  # (the same operations as inside the loop before: the same t)
        glassy, rubbery = self.material.glassy, self.material.rubbery
        cap = (GLASSY_TIME_CAP * 2.9432 * (energy / (4.0 * kappa * glassy)) ** 0.4 / v0
               if not rubbery > 0.0 and math.isfinite(glassy) and kappa * glassy > 0 else math.inf)
        for _ in range(8):
            stiffness = kappa * modulus_at(t / 4)
            if not stiffness > 0.0:  # relaxed (or underflowed) to zero at t/4: the estimate is beyond the cap
                t = cap
                break
            t = 2.9432 * (energy / (4.0 * stiffness)) ** 0.4 / v0
            if not t < cap:
                t = cap
                break
        if not (math.isfinite(t) and t > 0.0):
            raise ValueError(f"the contact time of this impact cannot be estimated (t_c = {t!r} s): material "
                             f"{self.material.kind} {self.material.params()}, v0 = {v0} m/s, sphere mass "
                             f"{self.m:.3g} kg; moduli, sizes and speed must keep it within floating-point range")
        return t


def make_impact(material, v0, geometry: dict) -> Impact:
    """The validated :class:`~vcor.contact.impact.Impact` of a material (a preset name, a spec ``{model: ...}``
    or a Material),
    an impact speed (m/s) and geometry keywords.

    Examples
    --------
    >>> from vcor.contact.impact import make_impact
    >>> imp = make_impact("butyl-fc", 2.0, {"r": 0.005, "rigid": True})
    >>> imp.v0, imp.geometry.rigid, float(imp.alpha(1e-3))
    (2.0, True, 0.0)
    >>> make_impact("sls", 1.0, {"radius": 0.01})
    Traceback (most recent call last):
    ...
    ValueError: unknown geometry keyword(s) ['radius']; allowed: [...]
    """
    unknown = set(geometry) - set(GEOMETRY_DEFAULTS) if geometry else ()  # (no sets built for no keywords)
    if unknown:
        raise ValueError(f"unknown geometry keyword(s) {sorted(unknown)}; allowed: {sorted(GEOMETRY_DEFAULTS)}")
    if isinstance(material, dict):  # a spec {model: ...}, as a config's materials: block and the bodies take it
        from ..materials.specs import from_spec

        material = from_spec(material, where="material")
    mat = _preset(material) if isinstance(material, str) else material
    if not isinstance(mat, _materials.Material):
        raise ValueError(f"material must be a preset name, a spec {{model: ...}} or a vcor.materials.Material, "
                         f"got {material!r}")
    geo = _geometry(**geometry)
    # a value other than the default where it is not used would be ignored (a flat curve over an axis of it);
    # settings that spell out every keyword at its default pass
    if geo.E_plate != GEOMETRY_DEFAULTS["E_plate"] and geo.case != 4:
        raise ValueError(f"E_plate is the elastic plate's modulus of case 4 only; this impact is case {geo.case}, "
                         f"whose plate is of the material: give case=4 (a viscoelastic sphere on an elastic "
                         f"plate), or leave E_plate out")
    if geo.rigid and (geo.h is not None or geo.rho_b is not None):
        given = [k for k in ("h", "rho_b") if getattr(geo, k) is not None]
        raise ValueError(f"{' and '.join(given)} describe{'s' if len(given) == 1 else ''} a plate, and rigid=True is "
                         f"an immovable target without one: "
                         f"give rigid or the plate, not both")
    if geo.nu_plate != GEOMETRY_DEFAULTS["nu_plate"] and geo.case != 4 and geo.plate_material is None:
        raise ValueError(f"nu_plate is the Poisson ratio of a plate of its own material (case 4, or a plate "
                         f"body); this impact is case {geo.case}, whose plate takes nu: give nu, or leave nu_plate "
                         f"out")
    return Impact(mat, v0, geo)


#: Geometry(**keywords), validated once per distinct keyword set (immutable: a sweep's points share it)
_geometry = interned(Geometry)
