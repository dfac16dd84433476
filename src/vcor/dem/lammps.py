"""Ready-to-run LAMMPS decks of a ``dem:`` entry: ``in.pair`` (two spheres, ``pair_style granular``)
or ``in.wall`` (a sphere on a flat wall, ``fix wall/gran granular``), ``units si``.

``lmp -in in.pair -var v0 2.5 -log none`` prints LAMMPS's own lines (its warnings and errors among them)
and then one line ``COR = <value>`` (``grep '^COR ='`` picks it out): the relative normal speed after
the contact over the approach speed v0 (m/s). The line goes to LAMMPS's screen, standard output as
LAMMPS holds it, so that several runs whose output a shell collects in one file keep every line (a deck
that opened /dev/stdout again would write at its own offset); ``-screen none`` would hide it. The deck holds the
dataset's ``hertz/material`` modulus E (Pa), Poisson ratio and the fitted parameters; ``-var model
viscoelastic`` (the default: ``damping viscoelastic`` with eta_n0 and ``limit_damping``) or ``-var
model coeff_restitution`` (the constant e, without ``limit_damping``, where its COR is e exactly)
picks the law, and ``-var E``, ``-var eta_n0``, ``-var e`` override the values (a temperature sweep
lists all three per temperature in the header: the deck's defaults are the first temperature's, and
the modulus changes with the temperature as the damping does). The time step is the elastic Hertz
contact time over ``nsteps`` (default 2000: the COR then agrees with the law's to a few 1e-5;
LAMMPS's velocity-Verlet step evaluates the dashpot at the half-step velocity, an error about
0.04 / nsteps).
"""

from __future__ import annotations

from ..io.receipts import atomic_text
from .export import quality_lines

__all__ = ["DECK_NAMES", "MAX_CONTACT_TIMES", "NSTEPS", "PAIR_ATOMS", "PAIR_MASSES", "PAIR_RUN", "V0_CHECK",
           "WALL_ATOMS", "WALL_MASSES", "WALL_RUN", "deck_name", "write_deck"]

#: the deck of each contact kind
DECK_NAMES = {"pair": "in.pair", "wall": "in.wall"}
#: the first lines of every collision deck (this module's and vcor.dem.hereditary's; ``{deck}`` its name):
#: no default speed, so a misspelt -var V0 runs nothing; v0 <= 0 stops it (one line on standard error, exit 2)
V0_CHECK = """\
if "$(!is_defined(variable,v0))" then &
   "print '{deck} needs -var v0 <m/s> (the approach speed; LAMMPS names are case-sensitive)' &
append /dev/stderr screen no" "quit 2"
if "$(!(v_v0 > 0.0))" then &
   "print 'v0 must be > 0 m/s (the approach speed), got ${{v0}}' append /dev/stderr screen no" "quit 2"
"""
#: default time steps per elastic contact time
NSTEPS = 2000

_HEADER = """\
# vcor DEM deck, entry {name}: {what}. Written by vcor.dem.lammps; units si.
#   lmp -in {deck} -var v0 <m/s> -log none     prints LAMMPS's lines, then one: COR = <value>
{usage}# Parameters fitted by vcor (results/dem/{name}.nc){t_note}:
{table}
{quality}"""

_COMMON = """\
{v0_check}{t_check}variable model   index {model}
variable E       index {E:.12g}
variable nu      index {nu:.12g}
{law_vars}variable nsteps  index {nsteps}
units            si
atom_style       sphere
dimension        3
boundary         f f f
comm_modify      vel yes
atom_modify      map array
{choice}
variable Eeff    equal v_E/(2.0*(1.0-v_nu^2))
"""
#: the header line of each LAMMPS law
_USAGE = {
    "lammps-viscoelastic": "# -var model viscoelastic       damping viscoelastic, eta_n0, limit_damping "
                           "(the force clipped at zero;\n"
                           "#                               vcor's separation where the force vanishes)"
                           "            [default]\n",
    "lammps-coeff-restitution": "# -var model coeff_restitution  damping coeff_restitution, the constant e, no "
                                "limit_damping\n",
}
#: per LAMMPS law of the dataset: the deck's model name, its coefficient variable, the tail keyword
_LAWS = {"lammps-viscoelastic": ("viscoelastic", "eta_n0", "limit_damping"),
         "lammps-coeff-restitution": ("coeff_restitution", "e", " ")}
#: the contact law of both decks (pair_coeff, fix wall/gran): Hertz with the chosen damping
_HERTZ = "hertz/material ${E} ${coef} ${nu} tangential linear_nohistory 0.0 0.0 damping ${model} ${tail}"

#: the pieces of a two-sphere deck: the bodies' masses and radii, the atoms (they need ${{dt}}), the run
#: (it needs the interaction); also used by the hereditary deck (vcor.dem.hereditary)
PAIR_MASSES = """\
variable R1      index {r1:.12g}
variable R2      index {r2:.12g}
variable rho1    index {rho1:.12g}
variable rho2    index {rho2:.12g}
variable m1      equal 4.0/3.0*PI*v_R1^3*v_rho1
variable m2      equal 4.0/3.0*PI*v_R2^3*v_rho2
variable meff    equal v_m1*v_m2/(v_m1+v_m2)
variable Reff    equal v_R1*v_R2/(v_R1+v_R2)
"""
PAIR_ATOMS = """\
variable L       equal 100.0*(v_R1+v_R2)
region           box block -${{L}} ${{L}} -${{L}} ${{L}} -${{L}} ${{L}} units box
create_box       1 box
variable gap     equal 10.0*v_v0*v_dt
variable x1      equal -(v_R1+0.5*v_gap)
variable x2      equal v_R2+0.5*v_gap
create_atoms     1 single ${{x1}} 0.0 0.0 units box
create_atoms     1 single ${{x2}} 0.0 0.0 units box
variable D1      equal 2.0*v_R1
variable D2      equal 2.0*v_R2
set              atom 1 diameter ${{D1}} density ${{rho1}}
set              atom 2 diameter ${{D2}} density ${{rho2}}
variable vh      equal 0.5*v_v0
variable mvh     equal -0.5*v_v0
velocity         all set 0.0 0.0 0.0 units box
set              atom 1 vx ${{vh}}
set              atom 2 vx ${{mvh}}
"""
#: contact times the decks run past their first run before they give up on a separation
MAX_CONTACT_TIMES = 64
#: after the first run (1.5 contact times): runs of one contact time while the bodies touch, at most
#: MAX_CONTACT_TIMES of them; then one line on standard error and exit 3 (no COR: a captured sphere, or
#: moduli that are not in Pa, where the bodies sink into each other, would otherwise run until LAMMPS loses
#: the atoms, minutes later). A template as the runs below ({{ }} for LAMMPS's braces).
_MORE = ("variable more    loop " + str(MAX_CONTACT_TIMES) + "\n"
         "label            more\n"
         'if "${{sep}} > 0.0" then "jump SELF separated"\n'
         "run              ${{nsteps}}\n"
         "next             more\n"
         "jump             SELF more\n"
         'print            "no separation within ' + f"{MAX_CONTACT_TIMES + 1.5:g}" + " contact times of ${{nsteps}} "
         'steps: the bodies stay in contact (a captured sphere, or moduli not in Pa), no COR" '
         "append /dev/stderr screen no\n"
         "quit             3\n"
         "label            separated\n")
PAIR_RUN = """\
neighbor         ${{R1}} bin
neigh_modify     delay 0 every 1 check yes
fix              integ all nve/sphere
timestep         ${{dt}}
thermo           0
variable sep     equal x[2]-x[1]-(v_R1+v_R2)
variable nrun    equal ceil(1.5*v_nsteps)+20
run              ${{nrun}}
""" + _MORE + """variable cor     equal (vx[2]-vx[1])/v_v0
variable corf    format cor %.12g
print            "COR = ${{corf}}" universe no
"""
#: the pieces of a sphere-on-a-wall deck (as PAIR_MASSES, PAIR_ATOMS, PAIR_RUN)
WALL_MASSES = """\
variable R       index {r1:.12g}
variable rho     index {rho1:.12g}
variable m       equal 4.0/3.0*PI*v_R^3*v_rho
"""
WALL_ATOMS = """\
variable L       equal 100.0*v_R
region           box block -${{L}} ${{L}} -${{L}} ${{L}} -${{L}} ${{L}} units box
create_box       1 box
variable gap     equal 10.0*v_v0*v_dt
variable x1      equal v_R+v_gap
create_atoms     1 single ${{x1}} 0.0 0.0 units box
variable D       equal 2.0*v_R
set              atom 1 diameter ${{D}} density ${{rho}}
variable mv      equal -v_v0
velocity         all set 0.0 0.0 0.0 units box
set              atom 1 vx ${{mv}}
"""
WALL_RUN = """\
neighbor         ${{R}} bin
neigh_modify     delay 0 every 1 check yes
fix              integ all nve/sphere
timestep         ${{dt}}
thermo           0
variable sep     equal x[1]-v_R
variable nrun    equal ceil(1.5*v_nsteps)+20
run              ${{nrun}}
""" + _MORE + """variable cor     equal vx[1]/v_v0
variable corf    format cor %.12g
print            "COR = ${{corf}}" universe no
"""
#: the time step of in.pair / in.wall: the elastic Hertz contact time of E_lammps over nsteps
_PAIR_DT = """\
variable K       equal 4.0/3.0*v_Eeff*sqrt(v_Reff)
variable tc      equal 3.2180654597185065*(v_meff/v_K)^0.4*v_v0^(-0.2)
variable dt      equal v_tc/v_nsteps
"""
_WALL_DT = """\
variable K       equal 4.0/3.0*v_Eeff*sqrt(v_R)
variable tc      equal 3.2180654597185065*(v_m/v_K)^0.4*v_v0^(-0.2)
variable dt      equal v_tc/v_nsteps
"""
_PAIR = (PAIR_MASSES + _PAIR_DT + PAIR_ATOMS + """\
pair_style       granular
pair_coeff       * * {hertz}
""" + PAIR_RUN)
_WALL = (WALL_MASSES + _WALL_DT + WALL_ATOMS + """\
pair_style       zero ${{R}}
pair_coeff       * *
fix              wall all wall/gran granular {hertz} xplane 0.0 NULL
""" + WALL_RUN)


def deck_name(kind: str) -> str:
    """``in.pair`` for two spheres, ``in.wall`` for a sphere on a wall."""
    return DECK_NAMES[kind]


def _choice(present: list) -> str:
    """The deck's if-chain (``if ... then ... elif ... else``) that sets the coefficient and tail of the
    chosen law, over the fitted laws only."""
    branches = [f'"${{model}} == {_LAWS[m][0]}"{" then" if i == 0 else ""} '
                f'"variable coef string \'${{{_LAWS[m][1]}}}\'" "variable tail string \'{_LAWS[m][2]}\'"'
                for i, m in enumerate(present)]
    allowed = " or ".join(_LAWS[m][0] for m in present)
    return ("if " + " &\n   elif ".join(branches)
            + f' &\n   else "print \'model must be {allowed}\'" "quit 1"')


def write_deck(path, ds, *, nsteps: int = NSTEPS) -> None:
    """The deck of the DEM dataset ``ds`` (:func:`vcor.dem.export.dem_dataset`) at ``path`` (module
    docstring) with the LAMMPS laws the dataset holds; the first temperature's parameters are the
    defaults."""
    import json

    present = [m for m in _LAWS if m in ds["model"].values]
    if not present:
        raise ValueError(f"dataset {ds.attrs.get('dem', '?')}: no LAMMPS law (models {sorted(_LAWS)}); "
                         "the entry's models must include one for a deck")
    contact = json.loads(ds.attrs["contact"])
    kind = contact["kind"]
    first = (lambda v: float(ds[v].values.flat[0]))
    has_t = "T" in ds.dims
    rows = []
    for i in range(ds.sizes["T"] if has_t else 1):
        pick = (lambda v, i=i: float(ds[v].values[i] if has_t else ds[v].values))
        prefix = f"T = {float(ds['T'].values[i]):g} degC: " if has_t else ""
        coefs = "  ".join(f"-var {_LAWS[m][1]} {pick(_LAWS[m][1]):.10g}" for m in present)
        rows.append(f"#   {prefix}-var E {pick('E_lammps'):.10g}  {coefs}   (E in Pa)")
    radii, dens = contact["radii_m"], contact["densities_kg_m-3"]
    law_vars = "".join(f"variable {_LAWS[m][1]:<7s} index {first(_LAWS[m][1]):.12g}\n" for m in present)
    values = {"E": first("E_lammps"), "nu": contact["nu"], "model": _LAWS[present[0]][0], "law_vars": law_vars,
              "choice": _choice(present), "nsteps": int(nsteps), "r1": radii[0], "rho1": dens[0],
              "r2": radii[-1], "rho2": dens[-1], "hertz": _HERTZ, "v0_check": V0_CHECK.format(deck=DECK_NAMES[kind]),
              # -var T selects nothing in this deck (in.hereditary's does): refused rather than run at the first row
              "t_check": ("if \"$(is_defined(variable,T))\" then &\n"
                          f"   \"print '{DECK_NAMES[kind]} does not select a temperature with -var T: pass the -var "
                          "values of its row in the header' append /dev/stderr screen no\" \"quit 2\"\n")}
    what = ("two spheres, head-on, v0 = relative approach speed" if kind == "pair"
            else "a sphere on a flat wall, v0 = approach speed")
    usage = "".join(_USAGE[m] for m in present)
    if present[0] != "lammps-viscoelastic":
        usage = usage.replace("limit_damping\n", "limit_damping   [default]\n")
    quality = "".join(f"# {line}\n" for line in quality_lines(ds, present))
    text = _HEADER.format(name=ds.attrs["dem"], what=what, deck=DECK_NAMES[kind], table="\n".join(rows), usage=usage,
                          t_note=", per temperature" if has_t else "", quality=quality)
    text += _COMMON.format(**values) + (_PAIR if kind == "pair" else _WALL).format(**values)
    atomic_text(path, text)
