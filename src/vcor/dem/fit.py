"""One collision's hereditary COR against speed, and each DEM law fitted to it.

:func:`collision` solves the collision with vcor at every speed (the default method ``adaptive``, the
contact ends where the force vanishes) and describes it as a DEM :class:`~vcor.dem.laws.Contact`:

* ``m_eff`` and ``R_eff``: those of the pair (:mod:`vcor.contact.pair`), or the sphere's for a wall
  (a rigid target or a plate);
* ``E_eff``: the effective modulus of vcor's contact stiffness at a quarter of vcor's contact time
  at the reference speed (the geometric mean of the speeds), k(t0/4) = 4/3 E_eff sqrt(R_eff): the
  stiffness a Hertz spring needs to last about as long as the hereditary contact. It sets the DEM
  contact's duration and peak force; it does not change any law's COR (the Brilliantov COR depends
  on A K^(2/5), and A is fitted for this K). For a Kelvin-Voigt material it is exactly E'.

:func:`fit_laws` fits every law by least squares over the speeds whose vcor result is ``ok``: the
dissipation A (s) of the clipped Brilliantov law (bounded search over log A; the COR evaluated by
:func:`vcor.spheres.cor_numeric`, rule ``force``, which is how LAMMPS with ``limit_damping``,
MercuryDPM's BSHP and Yade end the contact); the constant e (the mean COR); the table (the COR).
Yade's (en, vn) is the pair that gives the fitted A at vn = the reference speed. ``lammps-hereditary``
is not fitted: it is vcor's own contact law (:mod:`vcor.dem.hereditary_law`), with the COR LAMMPS
computes with vcor's plugin and the deck's time step (:mod:`vcor.dem.mirror`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..contact.bodies import body_from_spec
from ..contact.impact import make_impact
from ..contact.pair import target_inputs, twin_defaults
from .hereditary_law import NSTEPS, collision_law, refusal
from .laws import HEREDITARY, MODELS, Contact, brilliantov_cor, eta_n0, lammps_modulus, yade_en, yade_young
from .mirror import plugin_cor

__all__ = ["B_RANGE", "Collision", "applicable", "collision", "fit_laws", "hereditary_refusal"]

#: the range of Ramirez's b the fit of A searches (the COR of the Brilliantov law goes from 0.9999 to
#: 0.0003 over it)
B_RANGE = (1e-6, 100.0)


@dataclass(kw_only=True)
class Collision:
    """vcor's COR of one collision at the speeds ``v0`` (m/s), with ``status``, ``message`` and
    ``soe_error`` (the relative error of the exponential sums the solve carried: ``Result.soe_error``)
    per speed, ``t0`` (s), and its DEM :class:`~vcor.dem.laws.Contact` (module docstring); ``v_ref`` is
    the reference speed (m/s)."""

    v0: np.ndarray
    cor: np.ndarray
    t0: np.ndarray
    status: list
    message: list
    contact: Contact
    v_ref: float
    #: per speed, as status and message (required: the dataset stores it)
    soe_error: list
    validity: list = field(default_factory=list)
    #: per speed, the sentence that says why a validity flag is set ("" where none is)
    validity_message: list = field(default_factory=list)
    #: the contact material, its effective modulus factor (E_c = factor E) and the target's kind
    #: (``sphere``, ``rigid``, ``plate``): what vcor's own law (lammps-hereditary) is built from
    material: object = None
    modulus_factor: float = math.nan
    target_kind: str = ""


def _bodies(material, sphere: dict, target):
    """(the impacting sphere, the target sphere or None) as bodies: sizes and densities explicit."""
    a = body_from_spec("sphere", {"material": material, **sphere}, where="dem.sphere")
    if isinstance(target, dict) and "sphere" in target:
        spec = twin_defaults(a, "sphere", target["sphere"])
        return a, body_from_spec("sphere", spec, swept=a.material, where="dem.target.sphere")
    return a, None


def _contact(a, b, target, t_ref: float, v_ref: float) -> tuple[Contact, object, float]:
    """The DEM view of the collision (module docstring), the contact material and its effective
    modulus factor."""
    mat, geo = target_inputs(a.material, target, {"r": a.size, "rho_a": a.rho, "nu": a.nu})
    impact = make_impact(mat, v_ref, geo)
    g = impact.geometry
    factor = impact.kappa / (4.0 / 3.0 * math.sqrt(g.r))
    e_eff = factor * float(impact.material.modulus_at(t_ref / 4.0))
    if b is not None:
        contact = Contact(kind="pair", m_eff=impact.m, r_eff=g.r, e_eff=e_eff, nu=a.nu, radii=(a.size, b.size),
                          densities=(a.rho, b.rho))
    else:
        contact = Contact(kind="wall", m_eff=impact.m, r_eff=g.r, e_eff=e_eff, nu=a.nu, radii=(a.size,),
                          densities=(a.rho,))
    return contact, impact.material, factor


def _target_kind(target) -> str:
    if isinstance(target, dict):
        return next(iter(target))
    return "rigid" if target == "rigid" else "plate"


def collision(material, v0, *, sphere: dict | None = None, target="rigid", options: dict | None = None) -> Collision:
    """vcor's COR of ``material`` (a preset name or a Material) in the sphere ``sphere`` ({r, rho, nu})
    hitting ``target`` (``"rigid"``, ``{"sphere": {...}}`` or ``{"plate": {...}}``) at the speeds
    ``v0`` (m/s), and its DEM contact (module docstring)."""
    a, b = _bodies(material, dict(sphere or {}), target)
    geometry = {"r": a.size, "rho_a": a.rho, "nu": a.nu}
    v0 = np.asarray(v0, dtype=float)
    from ..solvers.simulate import simulate  # the kernels load on use: the workflow's planning reads this module

    results = [simulate(a.material, float(v), target=target, options=options, **geometry) for v in v0]
    cor = np.array([r.cor if r.ok else math.nan for r in results])
    t0 = np.array([r.t0 if r.ok else math.nan for r in results])
    ok = np.isfinite(cor)
    v_ref = float(np.exp(np.mean(np.log(v0))))
    if not ok.any():
        raise ValueError(f"no speed of the collision ended ok: {results[0].status}: {results[0].message}")
    near = int(np.argmin(np.where(ok, np.abs(np.log(v0 / v_ref)), np.inf)))
    contact, mat, factor = _contact(a, b, target, float(t0[near]), v_ref)
    return Collision(v0=v0, cor=cor, t0=t0, status=[r.status for r in results], message=[r.message for r in results],
                     contact=contact, v_ref=v_ref, validity=[r.validity for r in results],
                     validity_message=[r.validity_message for r in results], material=mat,
                     modulus_factor=factor, target_kind=_target_kind(target),
                     soe_error=[float(r.soe_error) for r in results])


def _fit_dissipation(contact: Contact, v0, cor) -> float:
    """The A (s) of the clipped Brilliantov law that fits ``cor`` at ``v0`` in least squares."""
    from scipy.optimize import minimize_scalar  # on use: the workflow's planning imports this module

    scale = 1.5 * (contact.stiffness / contact.m_eff) ** 0.4
    lo = math.log(B_RANGE[0] / (scale * float(np.max(v0)) ** 0.2))
    hi = math.log(B_RANGE[1] / (scale * float(np.min(v0)) ** 0.2))

    def misfit(log_a):
        return float(np.sum((brilliantov_cor(contact, math.exp(log_a), v0) - cor) ** 2))

    best = minimize_scalar(misfit, bounds=(lo, hi), method="bounded", options={"xatol": 1e-7})
    return math.exp(best.x)


def hereditary_refusal(col: Collision) -> str:
    """Why vcor's own law (lammps-hereditary) cannot take the collision, or ""."""
    return refusal(col.material, col.target_kind)


def applicable(col: Collision) -> list[str]:
    """Every model of :data:`~vcor.dem.laws.MODELS` that the collision can have: all, less
    lammps-hereditary where :func:`hereditary_refusal` gives a reason."""
    return [m for m in MODELS if m != HEREDITARY or not hereditary_refusal(col)]


def _hereditary(col: Collision, nsteps: int = NSTEPS) -> dict:
    """vcor's own law: the plugin's series and the COR LAMMPS computes with the deck's time step."""
    law = collision_law(col.material, col.modulus_factor, col.target_kind, col.t0)
    c = col.contact
    cor = plugin_cor(law, c.kind, c.radii, c.densities, col.v0, nsteps)
    return {"cor": cor, "hereditary_E_inf": law.e_inf, "hereditary_E": np.array(law.e),
            "hereditary_beta": np.array(law.beta), "hereditary_soe_error": law.soe_error, "source": law.source,
            "nsteps": nsteps}


def fit_laws(col: Collision, models=None) -> dict:
    """{model: {"cor": the law's COR at col.v0 (1), parameter: value, ...}} (module docstring); the
    parameters' units are those of :data:`vcor.dem.laws.PARAMETERS`. Speeds whose vcor result is not
    ok are left out of the fit (the law's COR is still given there). ``models``: a list of
    :data:`~vcor.dem.laws.MODELS` (ValueError naming the reason when lammps-hereditary cannot take the
    collision), or None: every applicable model (:func:`applicable`). lammps-hereditary is not fitted:
    its COR is the one LAMMPS computes with vcor's plugin (:mod:`vcor.dem.mirror`)."""
    models = applicable(col) if models is None else list(models)
    unknown = sorted(set(models) - set(MODELS))
    if unknown:
        raise ValueError(f"unknown DEM model(s) {unknown}; allowed: {list(MODELS)}")
    ok = np.isfinite(col.cor)
    v, c = col.v0[ok], col.cor[ok]
    contact = col.contact
    out = {}
    needs_a = {"lammps-viscoelastic", "mercurydpm-bshp", "yade-mindlin"} & set(models)
    if needs_a:
        A = _fit_dissipation(contact, v, c)
        curve = brilliantov_cor(contact, A, col.v0)
    for model in models:
        if model == "lammps-viscoelastic":
            out[model] = {"cor": curve, "eta_n0": eta_n0(contact, A), "E_lammps": lammps_modulus(contact)}
        elif model == "mercurydpm-bshp":
            out[model] = {"cor": curve, "A": A, "E_eff": contact.e_eff}
        elif model == "yade-mindlin":
            out[model] = {"cor": curve, "en": yade_en(contact, A, col.v_ref), "vn": col.v_ref,
                          "young": yade_young(contact)}
        elif model == HEREDITARY:
            out[model] = _hereditary(col)
        elif model == "lammps-coeff-restitution":
            e = float(np.mean(c))
            out[model] = {"cor": np.full(col.v0.shape, e), "e": e, "E_lammps": lammps_modulus(contact)}
        else:
            out[model] = {"cor": col.cor.copy()}
    return out
