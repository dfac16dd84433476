"""The config's ``dem:`` block: one entry per collision handed to DEM codes (:mod:`vcor.dem`).

::

    dem:
      <name>:
        sphere: {material: <name or spec>, r: 0.005, rho: 1200, nu: 0.45}   # material required
        target: {sphere: {...}}       # or rigid, or {plate: {material, h, rho, nu}}
        v0: {start: 0.1, stop: 10, num: 25, log: true}                      # or a list, m/s
        T: [0, 20, 40]                # optional, deg C: materials with a shift function
        models: [lammps-viscoelastic, ...]   # optional: every law of vcor.dem.laws.MODELS that applies
        solver: {...}                 # optional solver options (default method adaptive)

``sphere.material`` and a target body's ``material`` are names of the project's catalogue (preset,
config material, fit or calibration), inline specs ``{model: ...}`` or (a target's) ``rigid``; a
target sphere without ``material`` is the sphere's twin. With ``T``, every viscoelastic body's
material is taken at each temperature through its shift function. :func:`check_dem` checks an entry
before any job (every message names the key); :func:`run_dem` is the job: the collisions at every
temperature and the laws fitted to each. Without ``models``, an entry has every law of
:data:`vcor.dem.laws.MODELS`, less ``lammps-hereditary`` where vcor's plugin cannot take the collision
(:func:`hereditary_refusal`); listing it for such an entry is refused with the reason.
"""

from __future__ import annotations

import re

from ..contact.bodies import NU_DEFAULTS
from ..contact.impact import make_impact
from ..contact.pair import target_inputs
from ..dem.fit import collision, fit_laws
from ..dem.hereditary_law import REFUSALS
from ..dem.laws import HEREDITARY, MODELS
from ..materials.catalogue import Catalogue
from ..materials.shift import at_temperature
from ..materials.specs import from_spec, shift_function
from ..solvers.applicability import refusal
from ..solvers.options import DEFAULT_METHOD, solver_options
from .grid import axis_error, axis_values, first_below

__all__ = ["DEM_KEYS", "check_dem", "dem_material", "entry_models", "hereditary_refusal", "run_dem", "solver_method"]

#: keys of a dem entry
DEM_KEYS = {"sphere", "target", "v0", "T", "models", "solver"}


def solver_method(spec: dict) -> str:
    """The solver method of an entry's collisions: its ``solver.method``, else the default method."""
    return (spec.get("solver") or {}).get("method", DEFAULT_METHOD)


def _where(name: str) -> str:
    return f"dem.{name}"


def dem_material(spec: dict, catalogue: Catalogue, T: float | None = None, where: str = "dem"):
    """(material, shift function or None) of an entry's ``sphere.material`` at temperature T (deg C)."""
    return _body_material((spec.get("sphere") or {}).get("material"), catalogue, T, f"{where}.sphere")


def _body_material(value, catalogue: Catalogue, T: float | None, where: str):
    """(material, shift function or None) of a body's ``material`` value at temperature T (deg C); an
    elastic material without a shift function is the same at every temperature."""
    if isinstance(value, str):
        catalogue.check(value, f"{where}.material")
        shift = catalogue.shift(value)
        material = catalogue.material(value)
        name = value
    elif isinstance(value, dict):
        material = from_spec(value, name="body", base_dir=catalogue.base_dir, where=f"{where}.material")
        shift = shift_function(value, f"{where}.material") if "shift" in value else None
        name = f"{where}.material"
    else:
        raise ValueError(f"{where}.material: a material name or a spec {{model: ...}}, got {value!r}")
    if T is not None and not (shift is None and material.is_elastic):
        material = at_temperature(material, shift, T, name)
    return material, shift


def _target_at(spec: dict, catalogue: Catalogue, T: float | None, where: str):
    """The entry's target with a target body's named material (or spec) resolved to the material at T."""
    target = spec.get("target", "rigid")
    if not isinstance(target, dict):
        return target
    (kind, body), = target.items()
    value = (body or {}).get("material") if isinstance(body, dict) else None
    if value is None or value == "rigid":
        return target
    material, _ = _body_material(value, catalogue, T, f"{where}.target.{kind}")
    return {kind: {**body, "material": material}}


def _viscous(value, catalogue: Catalogue) -> str:
    """"elastic", "kelvin-voigt" (with a dashpot) or "other": a body's material value (a name or an
    inline spec), known before a fit's or calibration's file exists (a fit is a Prony or CERF law; a
    calibration has its start material's kind)."""
    if isinstance(value, str) and value in catalogue.fits:
        return "other"
    if isinstance(value, str) and value in catalogue.calibrations:
        return _viscous(catalogue.calibrations[value].get("material"), catalogue)
    material, _ = _body_material(value, catalogue, None, "dem")
    return "elastic" if material.is_elastic else ("kelvin-voigt" if material.viscosity > 0 else "other")


def hereditary_refusal(spec: dict, catalogue: Catalogue) -> str:
    """Why vcor's own law (``lammps-hereditary``) cannot take an entry's collision, or "": a plate
    target, a Kelvin-Voigt sphere, or a target sphere of another material or Poisson ratio that is not
    rigid (:data:`vcor.dem.hereditary_law.REFUSALS`; two elastic bodies combine into one modulus)."""
    target = spec.get("target", "rigid")
    if isinstance(target, dict) and "plate" in target:
        return REFUSALS["plate"]
    sphere = spec["sphere"]
    mine = _viscous(sphere["material"], catalogue)
    if mine == "kelvin-voigt":
        return REFUSALS["kelvin-voigt"]
    body = (target.get("sphere") or {}) if isinstance(target, dict) else {}
    other = body.get("material")
    if other == "rigid":
        return ""
    default_nu = NU_DEFAULTS["steel" if mine == "elastic" else "polymer"]  # one material: one family's default
    nu = sphere.get("nu", default_nu)
    twin = other is None  # the sphere's twin (vcor.contact.pair.twin_defaults): its material, and its nu unless set
    other = sphere["material"] if twin else other
    same = other == sphere["material"] and body.get("nu", nu if twin else default_nu) == nu
    if not same and (mine != "elastic" or _viscous(other, catalogue) != "elastic"):
        return REFUSALS["eq1"]
    return ""


def entry_models(spec: dict, catalogue: Catalogue) -> list[str]:
    """The entry's DEM laws (module docstring)."""
    if "models" in spec:
        return list(spec["models"])
    return [m for m in MODELS if m != HEREDITARY or not hereditary_refusal(spec, catalogue)]


def _speeds(spec, where):
    try:
        v0 = axis_values(spec["v0"])
    except (ValueError, KeyError, TypeError) as exc:
        raise ValueError(axis_error(f"{where}.v0", exc)) from None
    if isinstance(spec["v0"], dict) and float(spec["v0"]["stop"]) <= float(spec["v0"]["start"]):
        raise ValueError(f"{where}.v0: a range from low to high speed (stop > start), got {spec['v0']!r}")
    if v0[0] <= 0:
        raise ValueError(f"{where}.v0{first_below(spec['v0'], 0.0)}: impact speeds must be > 0 m/s, got {v0[0]}")
    if len(v0) < 2:
        raise ValueError(f"{where}.v0: at least two speeds (the laws are fitted over a range), got {v0}")
    return v0


def check_dem(name: str, spec: dict, catalogue: Catalogue) -> None:
    """Everything about one entry that can be checked before its job (module docstring)."""
    where = _where(name)
    if not isinstance(spec, dict):
        raise ValueError(f"{where}: a mapping with keys {sorted(DEM_KEYS)}, got {spec!r}")  # noqa: TRY004 (config values)
    unknown = set(spec) - DEM_KEYS
    if unknown or "sphere" not in spec or "v0" not in spec:
        raise ValueError(f"{where}: keys {sorted(DEM_KEYS)} (sphere and v0 required); unknown {sorted(unknown)}")
    sphere = spec["sphere"]
    if not isinstance(sphere, dict) or "material" not in sphere:
        raise ValueError(f"{where}.sphere: a mapping {{material, r, rho, nu}} with a material, got {sphere!r}")
    target = spec.get("target", "rigid")
    if not (target == "rigid" or (isinstance(target, dict) and len(target) == 1
                                  and next(iter(target)) in ("sphere", "plate"))):
        raise ValueError(f"{where}.target: rigid, {{sphere: {{...}}}} or {{plate: {{...}}}} (one kind), got {target!r}")
    models = spec.get("models", list(MODELS))
    if not isinstance(models, list) or not models or not set(models) <= set(MODELS):
        raise ValueError(f"{where}.models: a list of DEM models of {list(MODELS)}, got {models!r}")
    if HEREDITARY in models and "models" in spec:
        why = hereditary_refusal(spec, catalogue)
        if why:
            raise ValueError(f"{where}.models: {HEREDITARY} cannot take this collision: {why}")
    v0 = _speeds(spec, where)
    try:
        options = solver_options(spec.get("solver") or {})  # checked now, used by the job
    except ValueError as exc:
        raise ValueError(f"{where}.solver: {exc}") from None
    temps = [None]
    if "T" in spec:
        try:
            temps = axis_values(spec["T"])
        except (ValueError, TypeError) as exc:
            raise ValueError(f"{where}.T: {exc}") from None
    targets = [(f"target.{k}", b) for k, b in target.items()] if isinstance(target, dict) else []
    bodies = [("sphere", sphere), *targets]
    names = [b.get("material") if isinstance(b, dict) else None for _, b in bodies]
    for (key, _), value in zip(bodies, names):
        if isinstance(value, str) and value != "rigid":
            catalogue.check(value, f"{where}.{key}.material")
    if any(isinstance(v, str) and v in catalogue.computed() for v in names):
        return  # a fit's or calibration's file is written by its rule: its values are checked by the job
    if temps != [None] and dem_material(spec, catalogue, where=where)[1] is None:
        raise ValueError(f"{where}.T: the sphere's material has no shift function (a temperature sweep needs "
                         f"one: materials.<name>.shift, or shift: in the inline spec)")
    for T in (temps[0], temps[-1]):
        try:
            material, _ = dem_material(spec, catalogue, T, where)
        except ValueError as exc:
            raise ValueError(f"{where}.T: {exc}" if T is not None else str(exc)) from None
        body = {k: sphere[k] for k in ("r", "rho", "nu") if k in sphere}
        geometry = {k: body[s] for k, s in (("r", "r"), ("rho_a", "rho"), ("nu", "nu")) if s in body}
        for v in (v0[0], v0[-1]):
            try:
                mat, geo = target_inputs(material, _target_at(spec, catalogue, T, where), geometry)
                impact = make_impact(mat, v, geo)
            except ValueError as exc:
                raise ValueError(_under(where, exc)) from None
            why = refusal(impact.material, options)
            if why:
                raise ValueError(f"{where}.solver.method: {why}")


def _under(where: str, exc: ValueError) -> str:
    """The message of a body's refusal under the entry's key ``where``: one that starts with the body's own
    key path (``target.plate.h must be ...``, ``target: ...``) as ``<where>.target.plate.h: must be ...``, so
    that a config file's refusal points at that key; others as ``<where>: ...``."""
    match = re.match(r"((?:sphere|target)(?:\.\w+)*)(?:: (.*)| (must .*))", str(exc), re.DOTALL)
    return f"{where}.{match.group(1)}: {match.group(2) or match.group(3)}" if match else f"{where}: {exc}"


def run_dem(name: str, spec: dict, catalogue: Catalogue):
    """(collisions, fitted laws, temperatures or None) of one entry: the job of the workflow's dem rule."""
    where = _where(name)
    v0 = _speeds(spec, where)
    temps = axis_values(spec["T"]) if "T" in spec else None
    sphere = {k: v for k, v in spec["sphere"].items() if k != "material"}
    models = entry_models(spec, catalogue)
    collisions, fits = [], []
    for T in temps or [None]:
        material, _ = dem_material(spec, catalogue, T, where)
        target = _target_at(spec, catalogue, T, where)
        col = collision(material, v0, sphere=sphere, target=target, options=spec.get("solver"))
        collisions.append(col)
        fits.append(fit_laws(col, models))
    return collisions, fits, temps

