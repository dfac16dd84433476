"""The deck ``in.hereditary`` of a ``dem:`` entry: the entry's collision in LAMMPS with vcor's own
contact law, ``pair_style vcor/hereditary`` (two spheres) or ``fix vcor/wall/hereditary`` (a sphere
on a rigid wall) of vcor's plugin (``plugins/lammps/``, GPL-2.0; :mod:`vcor.dem.hereditary_law`).

::

    vcor lammps-plugin build --out plugin        # its last line: the path of vcorplugin.so
    lmp -in in.hereditary -var v0 2.5 -var plugin plugin/vcorplugin.so -log none

prints LAMMPS's own lines (its warnings and errors among them) and then ``COR = <value>``: the relative
normal speed after the contact over the approach speed v0 (m/s), like ``in.pair``
(:mod:`vcor.dem.lammps`). The deck holds the contact's series from the dataset
(``hereditary_E_inf``, ``hereditary_E``, ``hereditary_beta``; per temperature with ``-var T <deg C>``,
one of the entry's, the first by default) and the time step of
:func:`vcor.dem.hereditary_law.time_step` (the fixed point of dt = t_H(Ebar(dt)) / nsteps, solved in
the deck; ``-var nsteps`` changes nsteps). :func:`vcor.dem.mirror.plugin_cor` computes the same COR
without LAMMPS.
"""

from __future__ import annotations

import json

import numpy as np

from ..io.receipts import atomic_text
from .hereditary_law import FIXED_POINT_ITERATIONS, HERTZ_TIME, SERIES_BELOW, HereditaryLaw
from .lammps import PAIR_ATOMS, PAIR_MASSES, PAIR_RUN, V0_CHECK, WALL_ATOMS, WALL_MASSES, WALL_RUN

__all__ = ["DECK_NAME", "laws_of", "write_deck"]

#: the deck's file name (results/dem/<name>/lammps/)
DECK_NAME = "in.hereditary"

_HEADER = """\
# vcor DEM deck, entry {name}: {what}, vcor's own contact law (the hereditary Hertz contact of
# vcor.contact.pair: Prony internal variables, the force clipped at zero) in LAMMPS. Written by
# vcor.dem.hereditary; units si.
#   vcor lammps-plugin build --out <DIR>     builds vcor's plugin (GPL-2.0); its last line is the .so
#   lmp -in in.hereditary -var v0 <m/s> -var plugin <path to vcorplugin.so> -log none
#                                            prints LAMMPS's lines, then one: COR = <value>
# The contact's relaxation modulus E_c(t) = E_inf + sum_i E_i exp(-beta_i t) (Pa, 1/s), effective
# plane-strain form ({form}), from results/dem/{name}.nc: {source}.
# Time step: the fixed point of dt = t_H(Ebar(dt)) / nsteps, t_H(E) = 3.2181 (m_eff/K)^(2/5) v0^(-1/5),
# K = 4/3 E sqrt(R_eff), Ebar(h) = E_inf + sum_i E_i (1 - exp(-beta_i h))/(beta_i h) (vcor.dem.hereditary_law);
# -var nsteps <n>, an integer >= 1 (default {nsteps}; the plugin warns below n = 10). -var v0 > 0 m/s.{t_note}
# A value out of its range stops the deck with one line on standard error naming it (exit 2); a word
# that is not a number stops LAMMPS with its own line naming the variable ("Non-numeric variable value").
{v0_check}variable plugin  index NONE
variable nsteps  index {nsteps}
{t_var}if "$(!(v_nsteps >= 1 && v_nsteps == floor(v_nsteps)))" then &
   "print 'nsteps must be an integer >= 1 (time steps per Hertz contact time, default {nsteps}), got ${{nsteps}}' &
append /dev/stderr screen no" "quit 2"
units            si
atom_style       sphere
dimension        3
boundary         f f f
atom_modify      map array
variable found   equal is_file(${{plugin}})
if "${{found}} == 0" then &
   "print 'in.hereditary needs -var plugin <the path of vcorplugin.so> (vcor lammps-plugin build prints it), &
got ${{plugin}}' append /dev/stderr screen no" "quit 1"
variable folder  equal is_file(${{plugin}}/.)
if "${{folder}} == 1" then &
   "print 'in.hereditary needs -var plugin <the path of vcorplugin.so>, got the folder ${{plugin}}: give the file &
in it (vcor lammps-plugin build prints its path)' append /dev/stderr screen no" "quit 1"
plugin           load ${{plugin}}
"""
#: the time step's fixed point, solved in the deck (the same iteration as hereditary_law.time_step)
_TIME_STEP = """\
variable scale   equal {hertz!r}*(v_{mass}/(4.0/3.0*sqrt(v_{radius})))^0.4*v_v0^(-0.2)/v_nsteps
variable h       equal $(v_scale*v_Eg^(-0.4):%.17g)
variable it      loop {iterations}
label            dtfix
variable hnew    equal $(v_scale*v_Ebar^(-0.4):%.17g)
variable h       equal ${{hnew}}
next             it
jump             SELF dtfix
variable dt      equal ${{h}}
"""


def _ebar(law: HereditaryLaw) -> str:
    """Ebar(v_h) as a LAMMPS equal-style formula (hereditary_law.step_modulus, term by term)."""
    parts = [repr(law.e_inf)]
    for e, b in zip(law.e, law.beta):
        x = f"{b!r}*v_h"
        parts.append(f"{e!r}*ternary({x}<{SERIES_BELOW!r},1.0-0.5*{x}+({x})^2/6.0,(1.0-exp(-{x}))/({x}))")
    return " + &\n   ".join(parts)


def _law_lines(law: HereditaryLaw) -> str:
    coeffs = " ".join(repr(float(c)) for c in law.coefficients())
    return (f"variable coeffs  string \"{coeffs}\"\n"
            f"variable Eg      equal {law.glassy!r}\n"
            f"variable Ebar    equal &\n   {_ebar(law)}\n")


def laws_of(ds) -> list[tuple[float | None, HereditaryLaw]]:
    """(temperature in deg C or None, the plugin's series) of each temperature of the DEM dataset
    ``ds`` (:func:`vcor.dem.export.dem_dataset`) with the law ``lammps-hereditary``."""
    if "hereditary_E_inf" not in ds:
        raise ValueError(f"dataset {ds.attrs.get('dem', '?')}: no lammps-hereditary law (its models must include it "
                         f"for the deck {DECK_NAME})")
    temps = [float(t) for t in ds["T"].values] if "T" in ds.dims else [None]
    out = []
    for i, T in enumerate(temps):
        pick = (lambda v, i=i, T=T: np.atleast_1d(ds[v].values[i] if T is not None else ds[v].values))
        e, b = pick("hereditary_E"), pick("hereditary_beta")
        keep = np.isfinite(e) & np.isfinite(b)
        out.append((T, HereditaryLaw(e_inf=float(pick("hereditary_E_inf")[0]), e=tuple(map(float, e[keep])),
                                     beta=tuple(map(float, b[keep])),
                                     soe_error=float(pick("hereditary_soe_error")[0]))))
    return out


def _selection(laws: list) -> str:
    """The series of the chosen temperature (``-var T``), or the one series."""
    if laws[0][0] is None:  # one series: a -var T would be ignored, so it is refused (asked with
        # is_defined, whatever its value: an if comparing it as text takes 20.5 or -3 for arithmetic)
        return ("if \"$(is_defined(variable,T))\" then \"print 'T: this entry has no temperatures (no T in its dem "
                "config), got ${T}' append /dev/stderr screen no\" \"quit 2\"\n" + _law_lines(laws[0][1]))
    # compared in a formula ($(v_T == ...)): a word that is not a number stops LAMMPS naming T (the if
    # command's own comparison of a word with a number is an error that names neither)
    allowed = " ".join(f"{T:g}" for T, _ in laws)
    branches = [f'"$(v_T == {T!r})"{" then" if i == 0 else ""} "jump SELF series_{i + 1}"'
                for i, (T, _) in enumerate(laws)]
    text = ("if " + " &\n   elif ".join(branches)
            + f" &\n   else \"print 'T must be one of: {allowed} (deg C), got ${{T}}' append /dev/stderr screen no\" "
              f"\"quit 2\"\n")
    for i, (_, law) in enumerate(laws):
        text += f"label            series_{i + 1}\n{_law_lines(law)}jump             SELF series_chosen\n"
    return text + "label            series_chosen\n"


def write_deck(path, ds) -> None:
    """The deck ``in.hereditary`` (module docstring) of the DEM dataset ``ds`` at ``path``: two spheres
    head-on for a pair entry, a sphere on the wall x = 0 for a rigid target."""
    contact = json.loads(ds.attrs["contact"])
    kind = contact["kind"]
    laws = laws_of(ds)
    radii, dens = contact["radii_m"], contact["densities_kg_m-3"]
    values = {"r1": radii[0], "rho1": dens[0], "r2": radii[-1], "rho2": dens[-1]}
    temps = [T for T, _ in laws if T is not None]
    t_note = (f"\n# -var T <deg C>: the series at one of the entry's temperatures: {' '.join(f'{T:g}' for T in temps)}"
              f" (default {temps[0]:g})" if temps else "")
    header = _HEADER.format(
        name=ds.attrs["dem"], nsteps=int(ds.attrs.get("hereditary_nsteps", 1000)), t_note=t_note,
        what=("two spheres, head-on, v0 = relative approach speed" if kind == "pair"
              else "a sphere on a flat rigid wall, v0 = approach speed"),
        form="E/(2 (1 - nu^2)) of the spheres' material" if kind == "pair" else "E/(1 - nu^2) of the sphere's material",
        source=ds.attrs.get("hereditary_series", "vcor"),
        t_var=f"variable T       index {temps[0]!r}\n" if temps else "", v0_check=V0_CHECK.format(deck=DECK_NAME))
    step = _TIME_STEP.format(hertz=HERTZ_TIME, iterations=FIXED_POINT_ITERATIONS,
                             mass="meff" if kind == "pair" else "m", radius="Reff" if kind == "pair" else "R")
    if kind == "pair":
        body = (PAIR_MASSES.format(**values) + _selection(laws) + step + PAIR_ATOMS.format()
                + "pair_style       vcor/hereditary\npair_coeff       * * ${coeffs}\n" + PAIR_RUN.format())
    else:
        body = (WALL_MASSES.format(**values) + _selection(laws) + step + WALL_ATOMS.format()
                + "pair_style       zero ${R}\npair_coeff       * *\n"
                + "fix              wall all vcor/wall/hereditary xplane 0.0 NULL ${coeffs}\n" + WALL_RUN.format())
    atomic_text(path, header + body)
