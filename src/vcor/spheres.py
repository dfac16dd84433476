"""Viscoelastic spheres (Ramirez, Poeschel, Brilliantov & Schwager 1999; Mueller & Poeschel 2011).

The equation of motion of two colliding viscoelastic spheres (Ramirez Eq. 5),

.. math:: \\ddot\\xi + (\\rho/m_{eff}) (\\xi^{3/2} + \\tfrac32 A \\sqrt\\xi \\dot\\xi) = 0,
          \\quad \\xi(0) = 0, \\ \\dot\\xi(0) = g,

is vcor's model with a Kelvin-Voigt kernel (tau = A) and a rigid target (alpha = 0). Everything
depends on one dimensionless group

.. math:: b = \\tfrac32 A (\\rho/m_{eff})^{2/5} g^{1/5}

(``rho`` = 2 Y sqrt(R_eff) / (3 (1 - nu^2)), Ramirez Eq. 2), and (g/g*)^{1/5} = C1 b with g* of Eq. 31.

Two separation rules: ``overlap`` (xi returns to zero; Ramirez, Schwager & Poeschel 1998) and
``force`` (the contact force returns to zero first: "delayed recovery", Schwager & Poeschel 2008,
fitted by the Pade of Mueller & Poeschel 2011 in v* = sqrt(b)).
"""

from __future__ import annotations

import math

import numpy as np

from .checks import positive
from .materials import models as _materials
from .solvers.common import richardson

__all__ = [
    "A_COEFFS",
    "C1_CLOSED_FORM",
    "MP_DEN",
    "MP_NUM",
    "TABLE_I",
    "C",
    "SolverFailure",
    "b_group",
    "cor_numeric",
    "cor_numeric_sls",
    "cor_pade",
    "cor_pade_force",
    "cor_root",
    "cor_series",
    "cor_spheres",
    "dissipative_constant",
    "g_star",
    "pade_coefficients",
]


class SolverFailure(RuntimeError):
    """The solver did not return an ok result; ``status`` holds its status (vcor.status)."""

    def __init__(self, status: str, message: str):
        super().__init__(f"spheres: solver status {status}: {message}")
        self.status = status

#: series coefficients of eps = 1 + sum_k C_k b^k (Ramirez Eqs. 6, 65, 67; Schwager & Poeschel 1998)
C = (-1.153449, 0.798267, -0.483582, 0.285279)
#: C1 in closed form (Eq. 30): sqrt(pi) Gamma(3/5) / (2^(1/5) 5^(2/5) Gamma(21/10)), evaluated with
#: scipy.special.gamma (tests/test_spheres.py recomputes it) and written out so that importing this
#: module, as the workflow's planning does, loads no scipy
C1_CLOSED_FORM = 1.1534488580952884
#: ``a_k = |C_k| / C1^k``, the coefficients of eps = 1 - a1 x + a2 x^2 - a3 x^3 + a4 x^4, x = (g/g*)^(1/5)
A_COEFFS = tuple(abs(c) / abs(C[0]) ** (k + 1) for k, c in enumerate(C))
#: Table I of Ramirez et al. (d1..d5 of the [1/4] Pade, Eq. 35), as printed
TABLE_I = (2.5839, 3.5839, 2.9839, 1.1487, 0.3265)
#: Mueller & Poeschel 2011 Pade for the force rule, in v* = sqrt(b): numerator, denominator
MP_NUM = (1.0, 1.07232, 0.574198, 0.141552)
MP_DEN = (1.0, 1.07232, 1.72765, 1.37842, 1.19449, 0.467273, 0.235585)


def _check_b(b):
    b = np.asarray(b, dtype=float)
    if np.any(~np.isfinite(b)) or np.any(b < 0):
        raise ValueError(f"b must be finite and in [0, inf), got {b}")
    return b


def pade_coefficients(a=A_COEFFS):
    """d1..d5 of eps = (1 + d1 x) / (1 + d2 x + d3 x^2 + d4 x^3 + d5 x^4) from a1..a4.

    eps * denominator = numerator, with eps = 1 - a1 x + a2 x^2 - a3 x^3 + a4 x^4 - a5 x^5, matched
    through x^5 with the unknown a5 set to 0: five linear equations for d1..d5. With the a_k from the
    printed C_k this reproduces Table I to all printed digits (truncated to four decimals); with the
    exact a2 = 3/5 the d_k move by 2e-5.

    Examples
    --------
    >>> from vcor.spheres import TABLE_I, pade_coefficients
    >>> [round(d, 4) for d in pade_coefficients()]
    [2.584, 3.584, 2.984, 1.1487, 0.3265]
    >>> TABLE_I
    (2.5839, 3.5839, 2.9839, 1.1487, 0.3265)
    """
    a1, a2, a3, a4 = a
    M = np.array([
        [1.0, -1.0, 0.0, 0.0, 0.0],  # x^1: d1 = d2 - a1
        [0.0, -a1, 1.0, 0.0, 0.0],  # x^2: d3 - a1 d2 + a2 = 0
        [0.0, a2, -a1, 1.0, 0.0],  # x^3: d4 - a1 d3 + a2 d2 - a3 = 0
        [0.0, -a3, a2, -a1, 1.0],  # x^4: d5 - a1 d4 + a2 d3 - a3 d2 + a4 = 0
        [0.0, a4, -a3, a2, -a1],  # x^5: -a1 d5 + a2 d4 - a3 d3 + a4 d2 - a5 = 0, a5 = 0
    ])
    rhs = np.array([-a1, -a2, a3, -a4, 0.0])
    return tuple(float(x) for x in np.linalg.solve(M, rhs))


def cor_series(b, order: int = 4):
    """Truncated series eps = 1 + sum_{k <= order} C_k b^k (order 0..4).

    Examples
    --------
    >>> from vcor.spheres import cor_series
    >>> round(float(cor_series(0.1)), 4), round(float(cor_series(0.1, order=1)), 4)
    (0.8922, 0.8847)
    """
    if order not in (0, 1, 2, 3, 4):
        raise ValueError(f"order must be 0..4, got {order!r}")
    b = _check_b(b)
    return 1.0 + sum(C[k] * b ** (k + 1) for k in range(order))


def cor_pade(b, d=None):
    """Ramirez Eq. 35 with x = (g/g*)^(1/5) = C1 b and d_k derived from the a_k (default).

    Examples
    --------
    >>> import numpy as np
    >>> from vcor.spheres import cor_pade
    >>> np.round(cor_pade([0.0, 0.1, 1.0, 10.0]), 4)
    array([1.    , 0.8922, 0.3478, 0.0039])
    """
    b = _check_b(b)
    d1, d2, d3, d4, d5 = pade_coefficients() if d is None else d
    x = abs(C[0]) * b
    return (1 + d1 * x) / (1 + d2 * x + d3 * x**2 + d4 * x**3 + d5 * x**4)


def cor_pade_force(b):
    """Mueller & Poeschel 2011 Pade (force rule) in v* = sqrt(b).

    Examples
    --------
    >>> from vcor.spheres import cor_pade_force
    >>> round(float(cor_pade_force(0.1)), 4)
    0.8929
    """
    v = np.sqrt(_check_b(b))
    return np.polyval(MP_NUM[::-1], v) / np.polyval(MP_DEN[::-1], v)


def cor_root(b):
    """Root of Ramirez Eq. 27, eps + 2 delta d eps^(3/5) = 1 with 2 delta d = C1 b (= continued
    fraction Eq. 28); the approximate theory, exact to O(b^2).

    Examples
    --------
    >>> from vcor.spheres import cor_root
    >>> round(float(cor_root(0.1)), 4)
    0.8923
    """
    b = _check_b(b)
    x = abs(C[0]) * np.atleast_1d(b)

    from scipy.optimize import brentq

    def root(xi):
        return brentq(lambda e: e + xi * e**0.6 - 1.0, 0.0, 1.0, xtol=1e-15)

    out = np.array([1.0 if xi == 0 else root(xi) for xi in x])
    return out.reshape(np.shape(b))


# ----------------------------------------------------------------------------- numerics
# Unit problem: rho/m_eff = 1 and g = 1, so b = 3A/2. Realised as a rigid target with
# r = 1 m, nu = 0 (kappa = 4/3), E = 3/4 Pa (k = 1), rho_a = 3/(4 pi) kg/m^3 (m = 1 kg), v0 = 1 m/s.
_UNIT = {"r": 1.0, "nu": 0.0, "rho_a": 3.0 / (4.0 * math.pi), "rigid": True}
#: elastic contact time of the unit problem (2.9432 (5/4)^(2/5))
T_C_UNIT = 2.9432 * 1.25**0.4


def _numeric(material, rule, steps_per_contact, extrapolate):
    # Kelvin-Voigt and SLS kernels are Prony kernels: the fixed-step internal-variable march is the
    # same second-order scheme in O(N), which matters for the long, creeping contacts at large b.
    from .solvers.simulate import simulate  # the kernels load on use: the closed forms need none

    kw = dict(rule=rule, method="ive-numba", **_UNIT)
    r1 = simulate(material, 1.0, steps_per_contact=steps_per_contact, **kw)
    if r1.status != "ok":
        raise SolverFailure(r1.status, r1.message)
    if not extrapolate:
        return r1.cor
    r2 = simulate(material, 1.0, steps_per_contact=2 * steps_per_contact, **kw)
    if r2.status != "ok":
        raise SolverFailure(r2.status, r2.message)
    return richardson(r1.cor, r2.cor)[0]  # second order


def cor_numeric(b, rule: str = "overlap", *, steps_per_contact: int = 2000, richardson: bool = True):
    """eps(b) from vcor's direct solver: Kelvin-Voigt kernel, rigid target, unit problem.

    ``richardson`` combines dt and dt/2 (the scheme is second order), error ~1e-9 at the default.

    Examples
    --------
    The exact eps against the Pade approximant (both rules):

    >>> from vcor.spheres import cor_numeric, cor_pade, cor_pade_force
    >>> round(cor_numeric(0.1), 5), round(float(cor_pade(0.1)), 5)
    (0.89215, 0.89218)
    >>> round(cor_numeric(0.1, "force"), 5), round(float(cor_pade_force(0.1)), 5)
    (0.89286, 0.89286)
    """
    if rule not in ("overlap", "force"):
        raise ValueError(f"rule must be 'overlap' or 'force', got {rule!r}")
    bs = _check_b(b)
    out = [(_numeric(_materials.KelvinVoigt(0.75, 2.0 * float(x) / 3.0), rule, steps_per_contact, richardson)
            if x > 0 else 1.0) for x in np.atleast_1d(bs)]
    return np.array(out).reshape(np.shape(bs)) if np.ndim(bs) else out[0]


def sls_equivalent(b, tau_ratio):
    """SLS (Prony) solid with the same rubbery modulus and the same viscosity E A as the
    Kelvin-Voigt solid of b, relaxation time tau = tau_ratio * T_C_UNIT (unit problem):
    E(t) = E + (E A / tau) exp(-t / tau) -> E (1 + A delta(t)) as tau -> 0."""
    if not (tau_ratio > 0):
        raise ValueError(f"tau_ratio must be > 0, got {tau_ratio!r}")
    A = 2.0 * float(b) / 3.0
    tau = tau_ratio * T_C_UNIT
    return _materials.Prony(0.75, (0.75 * A / tau,), (1.0 / tau,))


def cor_numeric_sls(b, tau_ratio, rule: str = "overlap", *, steps_per_contact: int = 2000):
    """Hereditary extension: eps for the SLS of :func:`sls_equivalent` (Kelvin-Voigt as tau -> 0).

    Examples
    --------
    >>> from vcor.spheres import cor_numeric, cor_numeric_sls
    >>> [round(cor_numeric_sls(0.1, tau), 4) for tau in (0.001, 0.1)], round(cor_numeric(0.1), 4)
    ([0.8921, 0.9126], 0.8921)
    """
    bs = _check_b(b)
    out = [(_numeric(sls_equivalent(x, tau_ratio), rule, steps_per_contact, True) if x > 0 else 1.0)
           for x in np.atleast_1d(bs)]
    return np.array(out).reshape(np.shape(bs)) if np.ndim(bs) else out[0]


# ----------------------------------------------------------------------------- dimensional
def dissipative_constant(eta1, eta2, E, nu):
    """Ramirez Eq. 4: A = (3 eta2 - eta1)^2 / (3 (3 eta2 + 2 eta1)) (1 - nu^2)(1 - 2 nu) / (E nu^2), in s.
    eta1, eta2 are the viscous constants (Pa s), E the Young modulus (Pa), nu in (0, 0.5).

    Examples
    --------
    >>> from vcor.spheres import dissipative_constant
    >>> f"A = {dissipative_constant(1.0, 2.0, 1e7, 0.3):.4g} s"
    'A = 4.213e-07 s'
    """
    eta1 = float(eta1)
    eta2 = float(eta2)
    if eta1 < 0 or eta2 < 0 or not (3 * eta2 + 2 * eta1 > 0):
        raise ValueError("viscosities eta1, eta2 must be >= 0 Pa s and not both 0")
    E = positive("E", E)
    if not (0 < nu < 0.5):
        raise ValueError(f"nu must be in (0, 0.5) for Eq. 4, got {nu!r}")
    return (3 * eta2 - eta1) ** 2 / (3 * (3 * eta2 + 2 * eta1)) * (1 - nu**2) * (1 - 2 * nu) / (E * nu**2)


def _pair(R1, R2, m1, m2, E, nu):
    """(R_eff, m_eff, rho) for two spheres of one material; R2 = m2 = inf is a sphere on an immovable
    half-space of the same material (rho = 2 E sqrt(R_eff) / (3 (1 - nu^2)), Ramirez Eq. 2)."""
    R1, m1, E = positive("R1", R1), positive("m1", m1), positive("E", E)
    R2 = math.inf if R2 == math.inf else positive("R2", R2)  # noqa: SIM300 (R2 is a radius, not a constant)
    m2 = math.inf if m2 == math.inf else positive("m2", m2)
    if not (-1 < nu <= 0.5):
        raise ValueError(f"nu must be in (-1, 0.5], got {nu!r}")
    r_eff = R1 * R2 / (R1 + R2) if math.isfinite(R2) else R1
    m_eff = m1 * m2 / (m1 + m2) if math.isfinite(m2) else m1
    rho = 2.0 * E * math.sqrt(r_eff) / (3.0 * (1.0 - nu**2))
    return r_eff, m_eff, rho


def b_group(*, R1, R2, m1, m2, E, nu, A, g):
    """b = 3/2 A (rho/m_eff)^(2/5) g^(1/5) for two spheres (R2 = m2 = inf: sphere on a rigid wall).
    Units: m, kg, Pa, s, m/s.

    Examples
    --------
    Two equal rubber-like spheres (r = 10 mm, 4.6 g) head-on at 1 m/s:

    >>> from vcor.spheres import b_group, cor_pade
    >>> b = b_group(R1=0.01, R2=0.01, m1=4.6e-3, m2=4.6e-3, E=1e7, nu=0.3, A=1e-4, g=1.0)
    >>> round(b, 4), round(float(cor_pade(b)), 3)
    (0.329, 0.693)
    """
    _, m_eff, rho = _pair(R1, R2, m1, m2, E, nu)
    if not (A >= 0):
        raise ValueError(f"A must be >= 0 s, got {A!r}")
    return 1.5 * A * (rho / m_eff) ** 0.4 * positive("g", g) ** 0.2


def g_star(*, R1, R2, m1, m2, E, nu, A):
    """Characteristic velocity g* (m/s) of Ramirez Eq. 31: (g*)^(-1/5) = C1 (3/2) A (rho/m_eff)^(2/5).

    Examples
    --------
    >>> from vcor.spheres import g_star
    >>> f"g* = {g_star(R1=0.01, R2=0.01, m1=4.6e-3, m2=4.6e-3, E=1e7, nu=0.3, A=1e-4):.1f} m/s"
    'g* = 127.1 m/s'
    """
    _, m_eff, rho = _pair(R1, R2, m1, m2, E, nu)
    return (C1_CLOSED_FORM * 1.5 * positive("A", A) * (rho / m_eff) ** 0.4) ** -5


def cor_spheres(*, R1, R2, m1, m2, E, nu, A, g, rule="overlap", options=None):
    """eps of a dimensional sphere pair, solved directly with vcor.simulate: Kelvin-Voigt E, tau = A;
    one material for both bodies (case 2, E' = E/(2(1 - nu^2))); the two-body problem reduced to
    m_eff and R_eff on an immovable target (alpha = 0). ``options``: further solver options (default
    method ``adaptive``). Units: m, kg, Pa, s, m/s.

    Examples
    --------
    The pair of :func:`b_group`'s example solved directly (b = 0.33; the Pade above gives 0.693):

    >>> from vcor.spheres import cor_spheres
    >>> round(cor_spheres(R1=0.01, R2=0.01, m1=4.6e-3, m2=4.6e-3, E=1e7, nu=0.3, A=1e-4, g=1.0), 3)
    0.692
    """
    from .solvers.simulate import simulate

    r_eff, m_eff, _ = _pair(R1, R2, m1, m2, E, nu)
    if not (A >= 0):
        raise ValueError(f"A must be >= 0 s, got {A!r}")
    res = simulate(_materials.KelvinVoigt(E, A), positive("g", g), options={"rule": rule, **(options or {})},
                   r=r_eff, rho_a=m_eff / (4.0 / 3.0 * math.pi * r_eff**3), nu=nu, case=2, rigid=True)
    if res.status != "ok":
        raise SolverFailure(res.status, res.message)
    return res.cor
