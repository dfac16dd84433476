"""The Yade script of a dem: entry (docs, "DEM codes"): its numbers, integrated here independently
of vcor with Yade's own formulas, give the dataset's ``cor_model(yade-mindlin)``; and the script run
in Yade itself (a Yade >= 2024.02a on PATH as ``yade``, importable as ``yade``, or named by
``VCOR_YADE``) prints that COR.

The independent integration reads the script's parameters (``ast``, not vcor) and applies what
Yade's ``pkg/dem/HertzMindlin.cpp`` computes: E* = E_a E_b / ((1 - nu_a^2) E_b + (1 - nu_b^2) E_a),
R* = R_a R_b / (R_a + R_b) (a wall with ``hertzian=True``: R_a = 1e8 R), kno = 4/3 E* sqrt(R*), v*
from the 3/6 Pade e(v*) = en, beta = v*^2 vn^(-1/5), A = 2/3 beta (kno/m)^(-2/5), the normal force
kno (xi^(3/2) + 3/2 A xi^(1/2) xi') clipped at zero; the COR is the rebound speed where it vanishes.
"""

import ast
import json
import math
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from vcor.dem import export, fit, yade

#: the five speeds (m/s) of the acceptance, across the default entries' range 0.1..10 m/s
SPEEDS = np.geomspace(0.1, 10.0, 5)
#: the acceptance bound on abs(Yade's COR - cor_model(yade-mindlin))
BOUND = 2e-3
#: Yade's Pade coefficients (Mueller & Poeschel 2011, 3/6), as in HertzMindlin.cpp
PADE_NUM = (1.0, 1.07232, 0.574198, 0.141552)
PADE_DEN = (1.0, 1.07232, 1.72765, 1.37842, 1.19449, 0.467273, 0.235585)
#: the wall's radius factor of Ig2_Wall_Sphere_ScGeom(hertzian=True)
HERTZ_FAC = 1e8

CASES = {
    "sls-pair": ("sls", {"sphere": {}}),
    "butyl-wall": ("butyl-prony3", "rigid"),
}


def _dataset(case, speeds=SPEEDS):
    material, target = CASES[case]
    col = fit.collision(material, speeds, sphere={"r": 0.005}, target=target)
    return export.dem_dataset(case, [col], [fit.fit_laws(col)])


def script_values(path) -> dict:
    """The upper-case constants the script assigns, read as literals."""
    out = {}
    for node in ast.parse(path.read_text()).body:
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
            name = node.targets[0].id
            if name.isupper():
                try:
                    out[name] = ast.literal_eval(node.value)
                except ValueError:
                    continue
    return out


def _pade(v):
    return np.polyval(PADE_NUM[::-1], v) / np.polyval(PADE_DEN[::-1], v)


def yade_contact(values, T=None) -> dict:
    """kno (N m^-3/2), mbar (kg) and A (s) as Yade derives them from the script's values."""
    law = values["LAW"][T]
    young, nu = law["young"], values["POISSON"]
    e_star = young * young / ((1 - nu**2) * young + (1 - nu**2) * young)
    masses = [4.0 / 3.0 * math.pi * r**3 * rho for r, rho in zip(values["RADII"], values["DENSITIES"])]
    if values["KIND"] == "pair":
        (ra, rb), mbar = values["RADII"], masses[0] * masses[1] / (masses[0] + masses[1])
    else:
        rb = values["RADII"][0]
        ra, mbar = HERTZ_FAC * rb, masses[0]
    kno = 4.0 / 3.0 * e_star * math.sqrt(ra * rb / (ra + rb))
    vstar = 0.0 if law["en"] == 1.0 else brentq(lambda v: _pade(v) - law["en"], 0.0, 1e3, xtol=1e-15)
    beta = vstar**2 * law["vn"] ** -0.2
    return {"kno": kno, "mbar": mbar, "A": 2.0 / 3.0 * beta * (kno / mbar) ** -0.4}


def clipped_cor(kno, mbar, A, v0) -> float:
    """The COR of kno (xi^1.5 + 1.5 A sqrt(xi) xi'), clipped at zero, for a head-on approach at v0
    (m/s): integrated until xi + 1.5 A xi' = 0 (the force vanishes; past it the bodies fly apart)."""
    scale = (mbar * v0**2 / kno) ** 0.4  # overlap scale, m

    def rhs(_t, y):
        xi, rate = max(y[0], 0.0), y[1]
        return [rate, -kno / mbar * math.sqrt(xi) * (xi + 1.5 * A * rate)]

    def force_zero(_t, y):
        return y[0] + 1.5 * A * y[1]

    force_zero.terminal, force_zero.direction = True, -1
    t_end = 50.0 * scale / v0
    sol = solve_ivp(rhs, (0.0, t_end), [0.0, v0], method="DOP853", events=force_zero, rtol=1e-11,
                    atol=[1e-14 * scale, 1e-14 * v0])
    assert sol.status == 1, sol.message
    return -float(sol.y_events[0][0][1]) / v0


@pytest.mark.parametrize("case", sorted(CASES))
def test_the_scripts_numbers_give_the_datasets_yade_cor(tmp_path, case):
    """Independent of vcor's fit and COR code: the script's young, poisson, radii, densities, en and
    vn, taken through Yade's formulas, give cor_model(yade-mindlin) at five speeds within 2e-3."""
    ds = _dataset(case)
    path = tmp_path / yade.SCRIPT_NAME
    yade.write_script(path, ds)
    values = script_values(path)
    assert values["REQUIRED"] == export.YADE_VERSION == "2024.02a"
    c = yade_contact(values)
    got = np.array([clipped_cor(c["kno"], c["mbar"], c["A"], v) for v in SPEEDS])
    want = ds["cor_model"].sel(model="yade-mindlin").values
    print(f"\n{case}: largest |script's law - cor_model(yade-mindlin)| {np.max(np.abs(got - want)):.1e}")
    np.testing.assert_array_less(np.abs(got - want), BOUND)
    # the contact Yade builds is vcor's: K = 4/3 E_eff sqrt(R_eff) (to the wall's 1e-8) and the mass
    contact = json.loads(ds.attrs["contact"])
    k_vcor = 4.0 / 3.0 * float(ds["E_eff"]) * math.sqrt(contact["r_eff_m"])
    assert c["kno"] == pytest.approx(k_vcor, rel=1e-8) and c["mbar"] == pytest.approx(contact["m_eff_kg"], rel=1e-12)


def test_a_temperature_entry_has_one_law_per_temperature(tmp_path):
    """A temperature sweep: the script lists the law of every temperature; each gives that
    temperature's cor_model(yade-mindlin)."""
    from vcor.materials import SLS
    from vcor.materials.shift import at_temperature
    from vcor.materials.specs import shift_function

    spec = {"model": "sls", "E_glassy": 15e6, "alpha": 300, "beta": 1200,
            "shift": {"model": "wlf", "C1": 8.0, "C2": 120.0, "T_ref": 20.0}}
    shift = shift_function(spec, "t")
    temps = [0.0, 40.0]
    cols = [fit.collision(at_temperature(SLS(15e6, 300.0, 1200.0), shift, T, "t"), SPEEDS, sphere={"r": 0.005},
                          target="rigid") for T in temps]
    ds = export.dem_dataset("hot", cols, [fit.fit_laws(c) for c in cols], temps)
    path = tmp_path / yade.SCRIPT_NAME
    yade.write_script(path, ds)
    values = script_values(path)
    assert list(values["LAW"]) == temps
    for T in temps:
        c = yade_contact(values, T)
        got = np.array([clipped_cor(c["kno"], c["mbar"], c["A"], v) for v in SPEEDS])
        want = ds["cor_model"].sel(model="yade-mindlin", T=T).values
        np.testing.assert_array_less(np.abs(got - want), BOUND)


def test_a_dataset_without_the_yade_law_has_no_script(tmp_path):
    col = fit.collision("sls", SPEEDS, sphere={"r": 0.005}, target="rigid")
    ds = export.dem_dataset("t", [col], [fit.fit_laws(col, ["lammps-viscoelastic", "table"])])
    with pytest.raises(ValueError, match="yade-mindlin"):
        yade.write_script(tmp_path / "c.py", ds)
    with pytest.raises(ValueError, match="steps"):
        yade.write_script(tmp_path / "c.py", _dataset("butyl-wall"), steps=3)


def _yade_command():
    """The command that runs a script in Yade, or None: VCOR_YADE, ``yade`` on PATH, or the Python
    module ``yade``."""
    given = os.environ.get("VCOR_YADE") or shutil.which("yade")
    if given:
        return [given, "-n", "-x"]
    probe = subprocess.run([sys.executable, "-c", "import yade"], capture_output=True, timeout=120, check=False)
    return [sys.executable] if probe.returncode == 0 else None


@pytest.mark.parametrize("case", sorted(CASES))
def test_yade_runs_the_script(tmp_path, case):
    """In Yade >= 2024.02a, the script's COR equals cor_model(yade-mindlin) within 2e-3 at five speeds."""
    command = _yade_command()
    if command is None:
        pytest.skip("no Yade: neither VCOR_YADE, `yade` on PATH nor an importable yade module "
                    "(Debian 12 ships Yade 2023.02a, which lacks Ip2_FrictMat_FrictMat_MindlinPhys.vn)")
    ds = _dataset(case)
    path = tmp_path / yade.SCRIPT_NAME
    yade.write_script(path, ds)
    worst = 0.0
    for v0, want in zip(SPEEDS, ds["cor_model"].sel(model="yade-mindlin").values):
        out = subprocess.run([*command, path.name, repr(float(v0))], cwd=tmp_path, capture_output=True, text=True,
                             timeout=600, check=False)
        if out.returncode != 0 and "needs Yade >=" in out.stderr + out.stdout:
            pytest.skip(f"the Yade found is too old for the export: {(out.stderr + out.stdout).strip()[-300:]}")
        lines = [x for x in out.stdout.splitlines() if x.startswith("COR = ")]
        assert out.returncode == 0 and len(lines) == 1, out.stdout[-2000:] + out.stderr[-2000:]
        got = float(lines[0].split("=")[1])
        worst = max(worst, abs(got - want))
        assert abs(got - want) <= BOUND, (v0, got, want)
    print(f"\n{case}: largest |Yade - cor_model(yade-mindlin)| {worst:.1e}")


#: A stand-in for the part of Yade's Python API the script calls (yade, yade.utils, yade.wrapper), with
#: Yade's semantics as its sources give them: NewtonIntegrator's leapfrog (forces from the positions at
#: t and the velocities at t - dt/2), Ip2_FrictMat_FrictMat_MindlinPhys's beta from (en, vn), and
#: Law2_ScGeom_MindlinPhys_Mindlin's normal force clipped at zero. It runs the script's control flow
#: (arguments, bodies, signs, time step, the loop to separation, the refusal of an old Yade) here,
#: where no Yade >= 2024.02a exists; it is no substitute for test_yade_runs_the_script.
STUB = '''
import math, sys, types

class Vector3(list):
    def __init__(self, x, y, z):
        super().__init__([float(x), float(y), float(z)])

class _State:
    def __init__(self, pos, mass):
        self.pos, self.vel, self.mass = Vector3(*pos), Vector3(0, 0, 0), mass

class _Body:
    def __init__(self, kind, pos, radius, material, fixed):
        mass = 0.0 if fixed else 4.0 / 3.0 * math.pi * radius**3 * material.density
        self.kind, self.radius, self.material, self.fixed = kind, radius, material, fixed
        self.state = _State(pos, mass)

class _List(list):
    def append(self, item):
        super().append(item)
        return len(self) - 1

class _Omega:
    def reset(self):
        self.bodies, self.materials, self.engines, self.dt, self._phys = _List(), _List(), [], 0.0, None
    def run(self, n, wait):
        loop = [e for e in self.engines if isinstance(e, InteractionLoop)][0]
        newton = [e for e in self.engines if isinstance(e, NewtonIntegrator)][0]
        assert wait and newton.damping == 0.0 and list(newton.gravity) == [0.0, 0.0, 0.0]
        ip2 = loop.functors[1][0]
        for _ in range(int(n)):
            forces = self._forces(ip2, loop.functors[0])
            for body, f in zip(self.bodies, forces):
                if not body.fixed:
                    body.state.vel[0] += f / body.state.mass * self.dt
                    body.state.pos[0] += body.state.vel[0] * self.dt
    def _forces(self, ip2, ig2s):
        a, b = self.bodies[0], self.bodies[1]
        if a.kind == "wall":
            hertzian = [g for g in ig2s if isinstance(g, Ig2_Wall_Sphere_ScGeom)][0].hertzian
            ra, rb, un = (1e8 if hertzian else 1.0) * b.radius, b.radius, b.radius - (b.state.pos[0] - a.state.pos[0])
            mbar = b.state.mass
        else:
            ra, rb, un = a.radius, b.radius, a.radius + b.radius - (b.state.pos[0] - a.state.pos[0])
            mbar = a.state.mass * b.state.mass / (a.state.mass + b.state.mass)
        if un < 0:
            self._phys = None
            return [0.0, 0.0]
        if self._phys is None:
            self._phys = ip2._physics(a.material, b.material, ra, rb)
        kno, beta = self._phys
        fn, kn = kno * un**1.5, 1.5 * kno * math.sqrt(un)
        cn = 2.0 * beta * (kno / mbar) ** -0.4 / 3.0 * kn
        total = fn - cn * (b.state.vel[0] - a.state.vel[0])
        total = max(total, 0.0)
        return [-total, total]

def _vstar(en):
    num = (1.0, 1.07232, 0.574198, 0.141552)
    den = (1.0, 1.07232, 1.72765, 1.37842, 1.19449, 0.467273, 0.235585)
    e = lambda v: sum(c * v**i for i, c in enumerate(num)) / sum(c * v**i for i, c in enumerate(den))
    lo, hi = 0.0, 1e3
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if e(mid) > en else (lo, mid)
    return 0.5 * (lo + hi)

class _Functor:
    def __init__(self, *args, **kw):
        self.functors = list(args)
        for k, v in kw.items():
            setattr(self, k, v)

class ForceResetter(_Functor): pass
class InsertionSortCollider(_Functor): pass
class Bo1_Sphere_Aabb(_Functor): pass
class Bo1_Wall_Aabb(_Functor): pass
class InteractionLoop(_Functor): pass
class Ig2_Sphere_Sphere_ScGeom(_Functor): pass
class Ig2_Wall_Sphere_ScGeom(_Functor):
    hertzian = False
class Law2_ScGeom_MindlinPhys_Mindlin(_Functor): pass
class NewtonIntegrator(_Functor):
    damping = 0.2
    gravity = Vector3(0, 0, -9.81)

class FrictMat:
    def __init__(self, young, poisson, density, frictionAngle):
        assert frictionAngle == 0.0
        self.young, self.poisson, self.density = young, poisson, density

class Ip2_FrictMat_FrictMat_MindlinPhys:
    def __init__(self, **kw):
        for k, v in kw.items():
            if k not in ("en", "vn") or (k == "vn" and OLD):
                raise AttributeError("No such attribute: " + k)
            setattr(self, k, v)
    def __getattr__(self, name):
        if name == "vn" and not OLD:
            return None
        raise AttributeError(name)
    def _physics(self, ma, mb, ra, rb):
        ea, eb, va, vb = ma.young, mb.young, ma.poisson, mb.poisson
        e_star = ea * eb / ((1 - va**2) * eb + (1 - vb**2) * ea)
        kno = 4.0 / 3.0 * e_star * math.sqrt(ra * rb / (ra + rb))
        return kno, _vstar(self.en) ** 2 * self.vn ** -0.2

O = _Omega()
O.reset()
config = types.SimpleNamespace(version=VERSION)

def sphere(center, radius, material):
    return _Body("sphere", center, radius, material, False)

def wall(position, axis, sense, material):
    assert axis == 0 and sense == 1
    return _Body("wall", (position, 0.0, 0.0), 0.0, material, True)
'''


def _stub(tmp_path, version):
    pkg = tmp_path / "stub" / "yade"
    pkg.mkdir(parents=True)
    old = version.startswith("2023")
    (pkg / "__init__.py").write_text(f"VERSION = {version!r}\nOLD = {old!r}\n" + STUB)
    (pkg / "utils.py").write_text("from yade import sphere, wall\n")
    (pkg / "wrapper.py").write_text("from yade import *\nfrom yade import _Functor\n")
    return {**os.environ, "PYTHONPATH": str(tmp_path / "stub")}


def _run(env, path, *args):
    return subprocess.run([sys.executable, path.name, *args], cwd=path.parent, env=env, capture_output=True,
                          text=True, timeout=300, check=False)


@pytest.mark.parametrize("case", sorted(CASES))
def test_the_script_under_a_yade_stand_in(tmp_path, case):
    """The script's bodies, speeds, time step and loop, under the stand-in (``STUB``): its COR equals
    cor_model(yade-mindlin) within 2e-3 at five speeds; bad arguments are refused in one line."""
    ds = _dataset(case)
    path = tmp_path / yade.SCRIPT_NAME
    yade.write_script(path, ds)
    env = _stub(tmp_path, "2025.2.0")
    worst = 0.0
    for v0, want in zip(SPEEDS, ds["cor_model"].sel(model="yade-mindlin").values):
        out = _run(env, path, repr(float(v0)))
        lines = [x for x in out.stdout.splitlines() if x.startswith("COR = ")]
        assert out.returncode == 0 and len(lines) == 1, out.stdout[-2000:] + out.stderr[-2000:]
        worst = max(worst, abs(float(lines[0].split("=")[1]) - want))
    print(f"\n{case}: largest |stand-in Yade - cor_model(yade-mindlin)| {worst:.1e} (1000 steps per contact)")
    assert worst <= BOUND
    for bad in (["-1"], ["2.0", "T=20"], ["2.0", "speed=3"], []):
        out = _run(env, path, *bad)
        assert out.returncode != 0 and "COR" not in out.stdout and len(out.stderr.strip().splitlines()) == 1, bad


def test_an_old_yade_is_refused_with_the_reason(tmp_path):
    """On Yade 2023.02a (no vn) the script stops before any step, naming the version it needs and why."""
    path = tmp_path / yade.SCRIPT_NAME
    yade.write_script(path, _dataset("butyl-wall"))
    out = _run(_stub(tmp_path, "2023.02a"), path, "1.0")
    assert out.returncode != 0 and "COR = " not in out.stdout
    for words in ("needs Yade >= 2024.02a", "found 2023.02a", "Thornton", "en at every speed"):
        assert words in out.stderr, (words, out.stderr)
