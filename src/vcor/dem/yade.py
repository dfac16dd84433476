"""A ready-to-run Yade script of a ``dem:`` entry: ``collision.py``, a head-on collision of two spheres
or of a sphere with a flat wall under the dataset's ``yade-mindlin`` law.

``yade -n -x collision.py 2.5`` prints one line ``COR = <value>`` (the relative normal speed after the
contact over the approach speed 2.5 m/s). Optional ``key=value`` arguments: ``T=<deg C>`` picks a
temperature of a temperature sweep (default the first), ``steps=<n>`` the time steps per elastic
Hertz contact time (default :data:`STEPS`).

The script sets, as Yade's ``pkg/dem/HertzMindlin.cpp`` reads them:

* ``FrictMat(young, poisson, density, frictionAngle=0)`` per body, ``young`` = 2 (1 - nu^2) E_eff for
  both (a wall's too): Yade's E* = E_a E_b / ((1 - nu_a^2) E_b + (1 - nu_b^2) E_a) is then E_eff, and
  Yade's K = 4/3 E* sqrt(R*) is vcor's;
* ``Ig2_Wall_Sphere_ScGeom(hertzian=True)`` for a wall (its radius 1e8 R, so R* = R to 1e-8; without
  it Yade takes the wall's radius equal to the sphere's and R* = R/2);
* ``Ip2_FrictMat_FrictMat_MindlinPhys(en, vn)``: Yade inverts the Mueller & Poeschel Pade for v*,
  beta = v*^2 vn^(-1/5), A = 2/3 beta (K/m_eff)^(-2/5), the BSHP dashpot 3/2 A K sqrt(xi) xi'
  (``Law2_ScGeom_MindlinPhys_Mindlin``), the total normal force clipped at zero;
* no friction, no gravity, ``NewtonIntegrator(damping=0)``; the time step is the elastic Hertz
  contact time over ``steps``; the COR is read once the bodies no longer overlap.

It needs Yade >= 2024.02a (:data:`vcor.dem.export.YADE_VERSION`), where ``vn`` was added: an older
Yade has no ``vn`` (``AttributeError: No such attribute: vn``), and ``en`` alone would give
Thornton's constant-COR damping, the COR ``en`` at every speed. The script checks for ``vn`` first
and stops with that message (naming the Yade it found) on an older Yade.
"""

from __future__ import annotations

import json

from ..io.receipts import atomic_text
from .export import YADE_VERSION, quality_lines

__all__ = ["SCRIPT_NAME", "STEPS", "script_parameters", "write_script"]

#: the script's file name under ``results/dem/<name>/yade/``
SCRIPT_NAME = "collision.py"
#: default time steps per elastic Hertz contact time
STEPS = 1000

_HEADER = '''\
# vcor Yade script, entry {name}: {what}.
# Written by vcor.dem.yade from results/dem/{name}.nc (law yade-mindlin).
#   yade -n -x {script} <v0 m/s> [T=<deg C>] [steps=<n>]      prints one line: COR = <value>
# Requires Yade >= {version}: Ip2_FrictMat_FrictMat_MindlinPhys.vn (the velocity-dependent COR of
# Mueller & Poeschel 2011) was added there. An older Yade has no vn, and en alone would give
# Thornton's constant-COR damping (the COR en at every speed): this script stops with a message.
# Law: Hertz-Mindlin; FrictMat young = 2 (1 - nu^2) E_eff for both bodies (Yade's E* is then vcor's
# E_eff); en at vn; no friction, no gravity, no numerical damping; a wall with hertzian=True.
# Time step: the elastic Hertz contact time / steps (default {steps}).
{quality}import math
import sys

from yade import O, Vector3, config
from yade.utils import sphere, wall
from yade.wrapper import (Bo1_Sphere_Aabb, Bo1_Wall_Aabb, ForceResetter, FrictMat, Ig2_Sphere_Sphere_ScGeom,
                          Ig2_Wall_Sphere_ScGeom, InsertionSortCollider, InteractionLoop,
                          Ip2_FrictMat_FrictMat_MindlinPhys, Law2_ScGeom_MindlinPhys_Mindlin, NewtonIntegrator)

# ---- parameters written by vcor ---------------------------------------------------------------
REQUIRED = "{version}"
KIND = "{kind}"          # pair: two spheres, v0 = relative approach speed; wall: a sphere on a wall
POISSON = {nu!r}         # FrictMat.poisson of every body (1)
RADII = {radii!r}        # m
DENSITIES = {densities!r}    # kg/m^3
# per temperature (deg C; None without a temperature sweep): FrictMat.young (Pa), en (1), vn (m/s)
LAW = {law}
STEPS = {steps}
# ------------------------------------------------------------------------------------------------
HERTZ_TIME = 3.2180654597185065   # elastic Hertz contact time in units of (m_eff/K)^(2/5) v0^(-1/5)
'''

_BODY = '''

def check_yade():
    """Stop on a Yade without Ip2_FrictMat_FrictMat_MindlinPhys.vn (older than 2024.02a), saying why."""
    if not hasattr(Ip2_FrictMat_FrictMat_MindlinPhys(), "vn"):
        have = str(getattr(config, "version", "unknown"))
        sys.exit(f"this script needs Yade >= {REQUIRED} (found {have}): Ip2_FrictMat_FrictMat_MindlinPhys.vn, "
                 "the velocity-dependent COR, was added in 2024.02a; with en alone an older Yade uses Thornton's "
                 "constant-COR damping and its COR would be en at every speed, not the fitted curve")


def arguments(argv):
    """(v0 in m/s, the law of the chosen temperature, steps) from the command line."""
    usage = "usage: yade -n -x collision.py <v0 m/s> [T=<deg C>] [steps=<n>]"
    if len(argv) < 2:
        sys.exit(usage)
    try:
        v0 = float(argv[1])
        options = dict(arg.split("=", 1) for arg in argv[2:])
    except ValueError:
        sys.exit(usage)
    unknown = sorted(set(options) - {"T", "steps"})
    if unknown or not v0 > 0:
        sys.exit(f"{usage} (v0 > 0; keys T, steps), got {argv[1:]}")
    temps = list(LAW)
    if "T" in options:
        if temps == [None]:
            sys.exit("this entry has no temperature sweep: drop T=")
        chosen = [t for t in temps if abs(t - float(options["T"])) <= 1e-9 * max(1.0, abs(t))]
        if not chosen:
            sys.exit(f"T must be one of {temps} deg C, got {options['T']}")
        law = LAW[chosen[0]]
    else:
        law = LAW[temps[0]]
    steps = int(options.get("steps", STEPS))
    if steps < 10:
        sys.exit(f"steps must be >= 10, got {steps}")
    return v0, law, steps


def build(v0, law, steps):
    """The bodies, the engines and the time step; returns the contact time estimate (s)."""
    O.reset()
    mats = [FrictMat(young=law["young"], poisson=POISSON, density=rho, frictionAngle=0.0) for rho in DENSITIES]
    for mat in mats:
        O.materials.append(mat)
    e_star = law["young"] / (2.0 * (1.0 - POISSON**2))   # Yade's E* of two bodies of this young, poisson
    if KIND == "pair":
        r1, r2 = RADII
        one = O.bodies.append(sphere((-r1, 0.0, 0.0), r1, material=mats[0]))
        two = O.bodies.append(sphere((r2, 0.0, 0.0), r2, material=mats[1]))
        m1, m2 = O.bodies[one].state.mass, O.bodies[two].state.mass
        m_eff, r_eff = m1 * m2 / (m1 + m2), r1 * r2 / (r1 + r2)
    else:
        r1 = RADII[0]
        O.bodies.append(wall(0.0, axis=0, sense=1, material=mats[0]))
        one = O.bodies.append(sphere((r1, 0.0, 0.0), r1, material=mats[0]))
        m_eff, r_eff = O.bodies[one].state.mass, r1 * 1e8 * r1 / (r1 + 1e8 * r1)
    stiffness = 4.0 / 3.0 * e_star * math.sqrt(r_eff)
    t_c = HERTZ_TIME * (m_eff / stiffness) ** 0.4 * v0 ** -0.2
    O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
        InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom(hertzian=True)],
                        [Ip2_FrictMat_FrictMat_MindlinPhys(en=law["en"], vn=law["vn"])],
                        [Law2_ScGeom_MindlinPhys_Mindlin()]),
        NewtonIntegrator(damping=0.0, gravity=Vector3(0.0, 0.0, 0.0)),
    ]
    O.dt = t_c / steps
    gap = 10.0 * v0 * O.dt
    if KIND == "pair":
        O.bodies[0].state.pos = Vector3(-(RADII[0] + 0.5 * gap), 0.0, 0.0)
        O.bodies[1].state.pos = Vector3(RADII[1] + 0.5 * gap, 0.0, 0.0)
        O.bodies[0].state.vel = Vector3(0.5 * v0, 0.0, 0.0)
        O.bodies[1].state.vel = Vector3(-0.5 * v0, 0.0, 0.0)
    else:
        O.bodies[1].state.pos = Vector3(RADII[0] + gap, 0.0, 0.0)
        O.bodies[1].state.vel = Vector3(-v0, 0.0, 0.0)
    return t_c


def overlap():
    """The bodies' overlap (m), > 0 in contact."""
    if KIND == "pair":
        return RADII[0] + RADII[1] - (O.bodies[1].state.pos[0] - O.bodies[0].state.pos[0])
    return RADII[0] - O.bodies[1].state.pos[0]


def cor(v0):
    """The relative normal speed after the contact over v0."""
    if KIND == "pair":
        return (O.bodies[1].state.vel[0] - O.bodies[0].state.vel[0]) / v0
    return O.bodies[1].state.vel[0] / v0


def main(argv):
    check_yade()
    v0, law, steps = arguments(argv)
    build(v0, law, steps)
    O.run(int(1.5 * steps) + 20, True)
    more = 0
    while overlap() > 0.0:
        if more >= 200:
            sys.exit(f"the bodies still overlap after {more + 1.5:g} contact times: no separation")
        O.run(steps, True)
        more += 1
    print(f"COR = {cor(v0):.12g}")


main(sys.argv)
'''


def script_parameters(ds) -> dict:
    """What the script of the DEM dataset ``ds`` (:func:`vcor.dem.export.dem_dataset`) holds: ``kind``,
    ``nu``, ``radii`` (m), ``densities`` (kg/m^3) and ``law``: {T (deg C) or None: {young (Pa), en (1),
    vn (m/s)}}, per temperature in the dataset's order."""
    if "en" not in ds or "young" not in ds:
        raise ValueError(f"dataset {ds.attrs.get('dem', '?')}: no yade-mindlin parameters (en, vn, young); "
                         "the entry's models must include yade-mindlin")
    contact = json.loads(ds.attrs["contact"])
    has_t = "T" in ds.dims
    temps = [float(t) for t in ds["T"].values] if has_t else [None]
    law = {}
    for i, T in enumerate(temps):
        pick = (lambda v, i=i: float(ds[v].values[i] if has_t else ds[v].values))
        law[T] = {"young": pick("young"), "en": pick("en"), "vn": pick("vn")}
    return {"kind": contact["kind"], "nu": float(contact["nu"]), "radii": tuple(float(r) for r in contact["radii_m"]),
            "densities": tuple(float(d) for d in contact["densities_kg_m-3"]), "law": law}


def _law_literal(law: dict) -> str:
    rows = [f"    {T!r}: {{'young': {p['young']!r}, 'en': {p['en']!r}, 'vn': {p['vn']!r}}}," for T, p in law.items()]
    return "{\n" + "\n".join(rows) + "\n}"


def write_script(path, ds, *, steps: int = STEPS) -> None:
    """The Yade script of the DEM dataset ``ds`` at ``path`` (module docstring); the first temperature's
    law is the default."""
    if int(steps) < 10:
        raise ValueError(f"steps: time steps per contact time, >= 10, got {steps}")
    p = script_parameters(ds)
    what = ("two spheres, head-on, v0 = relative approach speed" if p["kind"] == "pair"
            else "a sphere on a flat wall, v0 = approach speed")
    text = _HEADER.format(name=ds.attrs["dem"], what=what, script=SCRIPT_NAME, version=YADE_VERSION,
                          kind=p["kind"], nu=p["nu"], radii=p["radii"], densities=p["densities"],
                          law=_law_literal(p["law"]), steps=int(steps),
                          quality="".join(f"# {line}\n" for line in quality_lines(ds, ["yade-mindlin"])))
    atomic_text(path, text + _BODY)
