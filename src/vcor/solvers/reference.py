"""Reference implementations of the numba marches (``_fixed_kernels``, ``_adaptive_kernels``,
``_separation``), in plain NumPy/SciPy.

Read this file to understand the scheme; run it to check the kernels. Each public function solves one
impact with the discretisation of one numba march, written for clarity rather than speed:

* the hereditary force is an explicit NumPy dot product over the whole history (O(N^2)), also for the
  methods whose kernels carry the history recursively (``soe``, ``adaptive``); only
  :func:`prony_reference` keeps internal variables, because they are its subject;
* the implicit trapezoidal step is solved by :func:`scipy.optimize.brentq` in a bracket, to ~1e-15
  relative (the kernels use Newton's method with their own stopping rules);
* the separation is the root (brentq) of the cubic through four nodes (:class:`numpy.polynomial.Polynomial`),
  the work integrals are :func:`numpy.trapezoid`.

From the package they take only the model, not the march: the material's exact step integrals and
moments (``Material.step_integrals``, ``step_moments``, ``first_step``, ``antiderivative``,
``relaxation_modulus``), the impact's mass, kernel scale and plate mobility (``Impact.m``, ``kappa``,
``alpha``, ``alpha_rate``, ``mobility_scale``), the exponential sums of :func:`vcor.materials.expsums.soe` and the
adaptive method's constants (``vcor.solvers.adaptive``: step floor, start level, horizon).

Contents (reference: numba kernel)
----------------------------------
::

    direct_reference               march_direct (form a, optional Volterra term; form b)
    prony_reference                march_prony (method ive-numba)
    soe_reference                  march_soe
    paper_reference                march_paper
    adaptive_reference             march_adaptive (a controlled grid, or the replay of a level plan)
    adaptive_richardson_reference  adaptive_grids (four or three grids, Richardson extrapolation)
    separation_reference           separation_point / locate_separation

Units (SI)
----------
t, dt, h: s; s (interference): m; g = s': m/s; u = s^{3/2}: m^1.5; F: N; J = int F dt: N s;
k(t) = kappa E(t): N m^-1.5 (kappa in m^0.5, E in Pa); eta = kappa x viscosity: N s m^-1.5;
alpha: m N^-1 s^-1, alpha': m N^-1 s^-2; m: kg; v0: m/s; works: J.

The model (Green 2026, Eq. 2 in first-order form)
-------------------------------------------------
::

    s' = g = v0 - J/m - alpha'(t) J - alpha(t) F,        J' = F,        s(0) = J(0) = 0,
    F(t) = int_0^t k(t - tau) u'(tau) dtau + eta u'(t),  u = sgn(s) |s|^{3/2}

(eta u' is the Dirac part of a Kelvin-Voigt kernel; u is extended oddly for s < 0.)

The trapezoidal step (every method but ``paper``)
-------------------------------------------------
::

    s_n = s_{n-1} + h/2 (g_{n-1} + g_n),     J_n = J_{n-1} + h/2 (F_{n-1} + F_n),
    g_n = v0 - J_n/m - alpha'(t_n) J_n - alpha(t_n) F_n,
    F_n = A_n(u_n) + eta u'_n,                u'_n = 3/2 |s_n|^{1/2} g_n,

A_n(u_n) being the method's discrete convolution with the unknown u_n = u(s_n) in it. Given s_n, the
last three lines are linear in (F_n, g_n, J_n); s_n is the root of R(s) = s - s_{n-1} - h/2 (g_{n-1} + g_n(s)).

Separation
----------
The march stops N_EXTRA = 2 steps after the first node n at which, once loaded (F > 0 and s > 0 at
some earlier or the same node), F_n <= 0 (rule "force") or s_n <= 0 (rule "overlap");
:func:`separation_reference` then finds t0 in [t_{n-1}, t_n].
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import partial

import numpy as np
from numpy.polynomial import Polynomial
from scipy.integrate import quad
from scipy.optimize import brentq

from ..materials.expsums import soe
from . import _adaptive_kernels as _kernels
from . import adaptive as _adaptive
from .nearly_elastic import glassy_stiffness

__all__ = [
    "OUTCOME",
    "AdaptiveGrid",
    "Body",
    "ExponentialSumHistory",
    "FoldedProductIntegration",
    "InternalVariables",
    "LinearFormB",
    "Nodes",
    "QuadraticProductIntegration",
    "SeparationWatch",
    "StepControl",
    "adaptive_reference",
    "adaptive_richardson_reference",
    "direct_reference",
    "mean_parabola",
    "paper_reference",
    "parabola_peak",
    "prony_reference",
    "richardson_weights",
    "separation_reference",
    "soe_reference",
    "soe_weights",
    "trapezoidal_step",
]

#: steps marched past the separation step (the separation's cubic uses nodes n - 2 .. n + 1)
N_EXTRA = 2
#: steps of exact local history of the ``soe`` method (lags 0..SOE_LOCAL_LAGS; vcor.solvers.soe.N_LOCAL)
SOE_LOCAL_LAGS = 8
#: the separation scalars, in the order of ``vcor.solvers.common.OUTCOME``
OUTCOME = ("cor", "t0", "s_residual", "w_h", "w_plate", "sphere_velocity", "energy_residual", "s_max", "f_max")
#: relative tolerance of brentq: the smallest it accepts (4 machine epsilons)
_RTOL = 4.0 * np.finfo(float).eps


# ---------------------------------------------------------------------------------------------------
# shared pieces: the bodies, the nodes, the implicit step, the separation watch
# ---------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Body:
    """What the step needs of the impact: sphere mass ``m`` (kg), impact speed ``v0`` (m/s), Dirac
    weight ``eta`` of the kernel (N s m^-1.5; 0 but for Kelvin-Voigt)."""

    m: float
    v0: float
    eta: float

    @classmethod
    def of(cls, impact):
        return cls(float(impact.m), float(impact.v0), float(impact.kappa * impact.material.viscosity))


@dataclass
class Nodes:
    """The solution at the nodes t_0 = 0, t_1, ...: t (s), s (m), g = s' (m/s), F (N), J (N s), u (m^1.5)."""

    t: list = field(default_factory=lambda: [0.0])
    s: list = field(default_factory=lambda: [0.0])
    g: list = field(default_factory=list)
    F: list = field(default_factory=lambda: [0.0])
    J: list = field(default_factory=lambda: [0.0])
    u: list = field(default_factory=lambda: [0.0])

    @classmethod
    def at_impact(cls, v0):
        return cls(g=[float(v0)])

    def last(self):
        """(s, g, F, J) at the newest node."""
        return self.s[-1], self.g[-1], self.F[-1], self.J[-1]

    def append(self, t, s, g, F, J, u):
        for name, value in zip(["t", "s", "g", "F", "J", "u"], (t, s, g, F, J, u)):
            getattr(self, name).append(float(value))

    def arrays(self):
        return {name: np.array(getattr(self, name)) for name in ["t", "s", "g", "F", "J", "u"]}


def overlap_power(s):
    """``u = sgn(s) |s|^{3/2}`` in m^1.5 (s in m)."""
    return math.copysign(abs(s) ** 1.5, s)


def trapezoidal_step(prev, h, mobility, body, convolution):
    """One implicit trapezoidal step of the model (see the module docstring).

    Parameters
    ----------
    prev : tuple
        (s, g, F, J) at t_{n-1}: m, m/s, N, N s.
    h : float
        Step t_n - t_{n-1}, s.
    mobility : tuple
        (alpha(t_n), alpha'(t_n)): m N^-1 s^-1, m N^-1 s^-2.
    body : Body
    convolution : callable
        A_n(u_n): the discrete convolution in N for u_n = u(s_n) in m^1.5 (Dirac term excluded).

    Returns
    -------
    (s_n, g_n, F_n, J_n, u_n)

    Notes
    -----
    With J_b = J_{n-1} + h/2 F_{n-1}, kin = 1/m + alpha'_n, B = v0 - kin J_b (m/s) and
    c = alpha_n + h/2 kin (m N^-1 s^-1) the step's linear part is J_n = J_b + h/2 F_n, g_n = B - c F_n,
    F_n = A_n + eta p g_n (``p = 3/2 |s_n|^{1/2}``), so that F_n = (A_n + eta p B) / (1 + eta p c).
    s_n is the root of R(s) = s - s_{n-1} - h/2 (g_{n-1} + g_n(s)), by brentq (relative tolerance
    4 eps) in a bracket grown around the explicit Euler value s_{n-1} + h g_{n-1}.
    """
    s0, g0, F0, J0 = prev
    alpha, alpha_rate = mobility
    J_b = J0 + 0.5 * h * F0
    kin = 1.0 / body.m + alpha_rate
    B = body.v0 - kin * J_b
    c = alpha + 0.5 * h * kin

    def force_and_rate(s):
        u = overlap_power(s)
        p = 1.5 * math.sqrt(abs(s))
        F = (convolution(u) + body.eta * p * B) / (1.0 + body.eta * p * c)
        return u, F, B - c * F

    def residual(s):
        return s - s0 - 0.5 * h * (g0 + force_and_rate(s)[2])

    scale = h * (abs(g0) + body.v0)  # one step's motion, m
    s = _root_near(residual, s0 + h * g0, 1e-3 * scale, xtol=1e-17 * scale)
    u, F, g = force_and_rate(s)
    return s, g, F, J_b + 0.5 * h * F, u


def _root_near(f, guess, width, xtol):
    """Root of f by brentq in [guess - w, guess + w], w = width, 4 width, 16 width, ... until f changes sign."""
    for _ in range(60):
        lo, hi = guess - width, guess + width
        f_lo, f_hi = f(lo), f(hi)
        if f_lo == 0.0:
            return lo
        if f_hi == 0.0:
            return hi
        if (f_lo < 0.0) != (f_hi < 0.0):
            return brentq(f, lo, hi, xtol=xtol, rtol=_RTOL, maxiter=500)
        width *= 4.0
    raise RuntimeError(f"no sign change of the step residual around s = {guess!r}")


class SeparationWatch:
    """Loading and separation along a march: loaded from the first node with F > 0 and s > 0;
    separation at the first node after (or at) loading with F <= 0 (rule "force") or s <= 0 ("overlap")."""

    def __init__(self, rule):
        if rule not in ("force", "overlap"):
            raise ValueError(f"rule must be 'force' or 'overlap', got {rule!r}")
        self.rule = rule
        self.loaded = False
        self.n_sep = None

    def separates(self, s, F):
        """Would a node (s, F) be the separation node?"""
        return self.loaded and (F <= 0.0 if self.rule == "force" else s <= 0.0)

    def update(self, n, s, F):
        """Record node n; True when the march may stop (N_EXTRA nodes past the separation node)."""
        if self.n_sep is None:
            self.loaded = self.loaded or (F > 0.0 and s > 0.0)
            if self.separates(s, F):
                self.n_sep = n
        return self.n_sep is not None and n >= self.n_sep + N_EXTRA


def _outcome(impact, nodes, n_sep, rule, glassy=0.0):
    """The node arrays, the separation index and the separation scalars of a finished march (``glassy``:
    :func:`separation_reference`)."""
    out = nodes.arrays()
    out["n_sep"] = n_sep
    out.update(separation_reference(out["t"], out["s"], out["g"], out["F"], out["J"], n_sep, rule,
                                    impact.m, impact.v0, impact.mobility_is_constant, glassy))
    return out


def _mobility(impact, t):
    """(alpha(t), alpha'(t)) of the impact's plate (the model's own functions)."""
    return float(impact.alpha(t)), float(impact.alpha_rate(t))


# ---------------------------------------------------------------------------------------------------
# fixed-step marches (direct form a / b, soe, prony): one loop, the discrete convolution differs
# ---------------------------------------------------------------------------------------------------
def _fixed_step_march(impact, dt, n_steps, rule, history):
    """March t_n = n dt with ``history.force(n, u_known, u_n)`` as A_n (u_known = u_0..u_{n-1}) and
    ``history.accept(u)`` after each step (u = u_0..u_n)."""
    body = Body.of(impact)
    nodes = Nodes.at_impact(body.v0)
    watch = SeparationWatch(rule)
    for n in range(1, n_steps + 1):
        t_n = n * dt
        u_known = np.array(nodes.u)
        step = trapezoidal_step(nodes.last(), dt, _mobility(impact, t_n), body,
                                partial(history.force, n, u_known))
        nodes.append(t_n, *step)
        history.accept(np.array(nodes.u))
        if watch.update(n, step[0], step[2]):
            return _outcome(impact, nodes, watch.n_sep, rule)
    raise RuntimeError(f"no separation within {n_steps} steps of {dt:.3g} s")


def _increments(u_known, u_n):
    """du_j = u_{j+1} - u_j, j = 0..n-1 (m^1.5), with u_n the trial value."""
    return np.diff(np.append(u_known, u_n))


class QuadraticProductIntegration:
    """The direct scheme's convolution (form a), u quadratic on every step but the first.

    On step j, [t_j, t_{j+1}], u' is the slope of the parabola through u_{j-1}, u_j, u_{j+1}:
    u' = du_j/dt + (du_j - du_{j-1}) (tau - t_{j+1/2}) / dt^2 (j >= 1), u' = du_0/dt on step 0. With the
    lag i = n - 1 - j and sigma = t_n - tau,

        A_n = sum_{j=0}^{n-1} du_j w_i + sum_{j=1}^{n-1} (du_j - du_{j-1}) v_i,
        w_i = (1/dt) int_{i dt}^{(i+1) dt} k(sigma) dsigma              (N m^-1.5),
        v_i = (1/dt^2) int_{i dt}^{(i+1) dt} k(sigma) (sigma_i - sigma) dsigma   (sigma_i the step's middle),

    from the material's exact step integrals W_i and moments V_i: w_i = kappa W_i / dt, v_i = -kappa V_i / dt^2.

    Volterra term (form a, h2(t1, t2) = c2 k(t1 + t2), c2 in m^-1.5), with u linear on every step:

        A2_n = c2/dt^2 sum_{i,j < n} du_i du_j Q_{2n-1-i-j},
        Q_c = int int_{cell} k(sigma_1 + sigma_2) = K2((c+1) dt) - 2 K2(c dt) + K2((c-1) dt)  (N m^-1.5 s^2),

    K2 = kappa x the second antiderivative of E.
    """

    def __init__(self, impact, dt, n_steps, c2=None):
        mat, kappa = impact.material, impact.kappa
        self.w = kappa * mat.step_integrals(dt, n_steps) / dt
        self.v = -kappa * mat.step_moments(dt, n_steps) / dt**2
        self.c2 = c2
        if c2 is not None:
            k2 = kappa * mat.antiderivative(dt * np.arange(2 * n_steps + 2, dtype=float), 2)
            self.q = np.zeros(2 * n_steps + 1)
            self.q[1:] = k2[2:] - 2.0 * k2[1:-1] + k2[:-2]
            self.scale = c2 / dt**2
            self._cells = (None, None)

    def force(self, n, u_known, u_n):
        du = _increments(u_known, u_n)
        lag = n - 1 - np.arange(n)
        slope_change = np.diff(du, prepend=du[0])  # du_j - du_{j-1}; 0 for j = 0
        total = du @ self.w[lag] + slope_change @ self.v[lag]
        if self.c2 is not None:
            total += self.scale * (du @ self._cell_weights(n) @ du)
        return total

    def _cell_weights(self, n):
        """The matrix Q_{2n-1-i-j}, i, j = 0..n-1 (built once per step)."""
        if self._cells[0] != n:
            j = np.arange(n)
            self._cells = (n, self.q[2 * n - 1 - np.add.outer(j, j)])
        return self._cells[1]

    def accept(self, u):
        pass


class LinearFormB:
    """Form b, k(0) u + int u kdot, with u linear on every step (Green Eq. 8b):

        A_n = k_0 u_n + int_0^{t_n} kdot(t_n - tau) u(tau) dtau
            = k_0 u_n + sum_{j=0}^{n-1} [u_j (k_{i+1} - k_i) + du_j (W_i/dt - k_i)],   i = n - 1 - j,

    k_i = k(i dt) (N m^-1.5), W_i = kappa int_{step i} E (N m^-1.5 s): the step's integral of kdot
    against the linear u, by parts. Algebraically the linear product integration of form a.
    """

    def __init__(self, impact, dt, n_steps):
        mat, kappa = impact.material, impact.kappa
        if not math.isfinite(mat.glassy):
            raise ValueError(f"form b needs a finite k(0); {mat.kind!r} is singular at t = 0")
        self.k = kappa * mat.relaxation_modulus(dt * np.arange(n_steps + 1, dtype=float))
        self.w = kappa * mat.step_integrals(dt, n_steps) / dt

    def force(self, n, u_known, u_n):
        du = _increments(u_known, u_n)
        lag = n - 1 - np.arange(n)
        return (self.k[0] * u_n + u_known @ (self.k[lag + 1] - self.k[lag])
                + du @ (self.w[lag] - self.k[lag]))

    def accept(self, u):
        pass


class FoldedProductIntegration:
    """The quadratic product integration written with folded weights, per lag i:

        A_n = sum_{j=0}^{n-1} du_j wt_i - du_0 v_{n-1}   (n >= 2),     A_1 = du_0 w_0,
        wt_0 = w_0 + v_0,  wt_i = w_i + v_i - v_{i-1}   (regrouping the slope changes of
        :class:`QuadraticProductIntegration` by du_j).

    The ``soe`` method splits the lags: i <= L (= SOE_LOCAL_LAGS) the exact kernel's wt_i, v_i; i > L the
    weights of the kernel's exponential sum k~ (folded with k~'s own v_{i-1}, also at i = L + 1). Here
    every lag's weight is in the two arrays and the sum is a dot product over the whole history.
    """

    def __init__(self, wt, v):
        self.wt, self.v = wt, v

    def force(self, n, u_known, u_n):
        du = _increments(u_known, u_n)
        if n == 1:
            return du[0] * (self.wt[0] - self.v[0])
        return du @ self.wt[n - 1 - np.arange(n)] - du[0] * self.v[n - 1]

    def accept(self, u):
        pass


class InternalVariables:
    """Prony kernel k(t) = G_inf + sum_k G_k e^{-b_k t} (N m^-1.5; b_k in 1/s) as internal variables:
    A_n = G_inf u_n + sum_k Q_k(t_n), Q_k' = -b_k Q_k + G_k u', u linear on the step, exactly:

        Q_k(t_n) = e^{-b_k dt} Q_k(t_{n-1}) + G_k (1 - e^{-b_k dt}) / (b_k dt) (u_n - u_{n-1})

    (the weight -> G_k for b_k -> 0): the recursive form of the *linear* product integration.
    """

    def __init__(self, impact, dt):
        e_inf, e, b = impact.material.prony_terms()
        self.G_inf = impact.kappa * e_inf
        self.decay = np.exp(-b * dt)
        bdt = b * dt
        self.weight = impact.kappa * e * np.where(bdt > 0, -np.expm1(-bdt) / np.where(bdt > 0, bdt, 1.0), 1.0)
        self.Q = np.zeros(e.size)

    def _advanced(self, du):
        return self.decay * self.Q + self.weight * du

    def force(self, n, u_known, u_n):
        return self.G_inf * u_n + self._advanced(u_n - u_known[-1]).sum()

    def accept(self, u):
        self.Q = self._advanced(u[-1] - u[-2])


def direct_reference(impact, dt, n_steps, rule="force", volterra=False, c2=0.0, form="a"):
    """The ``direct`` method (``_fixed_kernels.march_direct``; drivers ``vcor.solvers.direct.run_direct``).

    Parameters
    ----------
    impact : vcor.contact.impact.Impact
    dt : float
        Time step, s.
    n_steps : int
        Most steps marched (RuntimeError if the impact has not separated by then).
    rule : {"force", "overlap"}
    volterra : bool
        Add the second-order Volterra term (form a only), coefficient ``c2`` in m^-1.5.
    form : {"a", "b"}
        "a": :class:`QuadraticProductIntegration`; "b": :class:`LinearFormB`.

    Returns
    -------
    dict
        Node arrays t (s), s (m), g (m/s), F (N), J (N s), u (m^1.5) up to the separation node
        ``n_sep`` + N_EXTRA, ``n_sep``, and the separation scalars of :func:`separation_reference`.
    """
    if form == "b":
        if volterra:
            raise ValueError("the Volterra term is implemented for form a only")
        history = LinearFormB(impact, dt, n_steps)
    elif form == "a":
        history = QuadraticProductIntegration(impact, dt, n_steps, c2=float(c2) if volterra else None)
    else:
        raise ValueError(f"form must be 'a' or 'b', got {form!r}")
    return _fixed_step_march(impact, dt, n_steps, rule, history)


def prony_reference(impact, dt, n_steps, rule="force"):
    """The ``ive-numba`` method (``_fixed_kernels.march_prony``): :class:`InternalVariables` in the
    trapezoidal step. Prony kernels only (sls, butyl-prony3, elastic, kelvin-voigt, prony). It is the
    linear product integration: direct form b's numbers, not form a's (quadratic u).
    Returns the dict of :func:`direct_reference`."""
    if not impact.material.is_prony:
        raise ValueError(f"prony_reference needs a Prony kernel, got {impact.material.kind!r}")
    return _fixed_step_march(impact, dt, n_steps, rule, InternalVariables(impact, dt))


def soe_weights(impact, dt, n_steps, t_max, tol=1e-10):
    """Folded weights (wt, v) of the ``soe`` method for lags 0..n_steps-1 (N m^-1.5).

    Lags i <= L = SOE_LOCAL_LAGS: the exact kernel's (as in the direct scheme). Lags i > L: those of the
    exponential sum k~(t) = kappa (E~_inf + sum_k E_k e^{-beta_k t}) of :func:`vcor.materials.expsums.soe` on
    [(L + 1) dt, max(t_max, 2 (L + 1) dt)] with relative error <= ``tol`` (t_max in s: the method's horizon,
    ``vcor.solvers.soe.run_soe``: (max_steps + 8) dt, times 1 + ghost with histories).
    """
    mat, kappa = impact.material, impact.kappa
    lag = SOE_LOCAL_LAGS + 1
    approx = soe(mat, lag * dt, max(t_max, 2 * lag * dt), tol).material

    def folded(material):
        w = kappa * material.step_integrals(dt, n_steps) / dt
        v = -kappa * material.step_moments(dt, n_steps) / dt**2
        return w + v - np.concatenate(([0.0], v[:-1])), v

    wt_exact, v_exact = folded(mat)
    wt_sum, v_sum = folded(approx)
    local = np.arange(n_steps) <= SOE_LOCAL_LAGS
    return np.where(local, wt_exact, wt_sum), np.where(local, v_exact, v_sum)


def soe_reference(impact, dt, n_steps, t_max, rule="force", tol=1e-10):
    """The ``soe`` method (``_fixed_kernels.march_soe``) with its history as the full sum
    (:class:`FoldedProductIntegration` with :func:`soe_weights`), not as recursive mode variables.
    ``t_max`` (s) as in :func:`soe_weights`. Returns the dict of :func:`direct_reference`."""
    wt, v = soe_weights(impact, dt, n_steps, t_max, tol)
    return _fixed_step_march(impact, dt, n_steps, rule, FoldedProductIntegration(wt, v))


# ---------------------------------------------------------------------------------------------------
# the paper-like explicit baseline
# ---------------------------------------------------------------------------------------------------
#: Adams-Bashforth coefficients of f_{n-1}, f_{n-2}, ... for orders 1..4
ADAMS_BASHFORTH = {1: (1.0,), 2: (3 / 2, -1 / 2), 3: (23 / 12, -16 / 12, 5 / 12),
                   4: (55 / 24, -59 / 24, 37 / 24, -9 / 24)}


def paper_reference(impact, dt, n_steps, rule="force"):
    """The ``paper`` baseline (``_fixed_kernels.march_paper``): explicit Adams-Bashforth of order min(n, 4)
    for (s, J) and the kernel clamped at dt, evaluated at points:

        (s, J)_n = (s, J)_{n-1} + dt sum_{i=1}^{min(n,4)} beta_i (g, F)_{n-i},
        F_n = sum_{j=1}^{n} k(max((n - j) dt, dt)) (u_j - u_{j-1}),
        g_n = v0 - J_n/m - alpha'(t_n) J_n - alpha(t_n) F_n.

    No Dirac term (Kelvin-Voigt refused). Returns the dict of :func:`direct_reference`.
    """
    if impact.material.viscosity > 0:
        raise ValueError("the paper baseline has no Dirac (Kelvin-Voigt) term")
    clamped = impact.kernel(dt * np.maximum(np.arange(n_steps + 1, dtype=float), 1.0))
    nodes = Nodes.at_impact(impact.v0)
    watch = SeparationWatch(rule)
    for n in range(1, n_steps + 1):
        beta = np.array(ADAMS_BASHFORTH[min(n, 4)])
        rates = np.array([nodes.g[-len(beta):], nodes.F[-len(beta):]])[:, ::-1]  # newest first
        s, J = np.array([nodes.s[-1], nodes.J[-1]]) + dt * (rates @ beta)
        u = overlap_power(s)
        du = np.diff(np.append(nodes.u, u))
        F = du @ clamped[n - 1 - np.arange(n)]
        alpha, alpha_rate = _mobility(impact, n * dt)
        g = impact.v0 - J / impact.m - alpha_rate * J - alpha * F
        nodes.append(n * dt, s, g, F, J, u)
        if watch.update(n, s, F):
            return _outcome(impact, nodes, watch.n_sep, rule)
    raise RuntimeError(f"no separation within {n_steps} steps of {dt:.3g} s")


# ---------------------------------------------------------------------------------------------------
# the adaptive march
# ---------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class AdaptiveGrid:
    """The adaptive method's constants for one impact (``vcor.solvers.adaptive``).

    Steps are h_base 2^(level - split), split 0 for the accepted grid (1, 2, ...: every step divided by
    2, 4, ...); levels ``floor`` .. ``top``; the first step on ``start_level``. ``horizon`` (s) is the
    first time horizon; ``representation`` the exponential sum (a Prony series, or a fitted
    exponential sum) of the kernel on ``window`` = (h_base / 2^SPLIT_LEVELS, 2 horizon, soe_tol); a
    separation is located on a step <= ``sep_frac`` t. ``singular``: the kernel has a t^-1/2 singularity
    (a fractional or CERF law but of E1 = 0, elastic) and the method's cubic scheme is on
    (``vcor.solvers.adaptive.CUBIC``): the newest step's cubic term (:class:`ExponentialSumHistory`), the
    graded start and the unloading hold (:class:`StepControl`), the first step on
    ``vcor.solvers.adaptive.first_level`` (START_LEVEL_FRACTIONAL, START_LEVEL_SINGULAR) and three Richardson grids
    (:func:`adaptive_richardson_reference`).
    """

    h_base: float
    start_level: int
    floor: int
    top: int
    horizon: float
    sep_frac: float
    representation: object
    window: tuple
    singular: bool = False

    @classmethod
    def of(cls, impact, tc, soe_tol=1e-10, step_tol=4e-4):
        """``tc``: the contact-time estimate (s) the method was given."""
        a = _adaptive
        top_power = 2.0 ** math.floor(math.log2(tc))
        h_base = top_power * 2.0**-a.FLOOR_BITS
        horizon = a.HORIZON_START * 2.0 * top_power
        n_levels = round(math.log2(a.MAX_STEP_FRACTION * horizon / h_base)) + 1
        window = (h_base * 2.0**-a.SPLIT_LEVELS, 2.0 * horizon, soe_tol)
        rep = soe(impact.material, *window).material
        sep = a.separation_steps(a.exact_rate(impact, a.plate_kind(impact)), tc)
        mat = impact.material
        singular = bool(a.CUBIC) and not mat.is_elastic and (mat.sqrt_law() is not None or mat.erfcx_law() is not None)
        start = a.first_level(mat, step_tol) if singular else a.START_LEVEL
        return cls(h_base, start, 0, n_levels - 1, horizon, 1.0 / sep, rep, window, singular)


class ExponentialSumHistory:
    """Product integration on a variable grid (``_adaptive_kernels.march_adaptive``).

    Step j spans [t_{j-1}, t_j], h_j = t_j - t_{j-1}, middle tau_j; d_j = (u_j - u_{j-1}) / h_j
    (m^1.5/s) is the mean of u' over it. On the newest step n, u' is the parabola
    d_n + c_n (tau - tau_n) + q_n ((tau - tau_n)^2 - h_n^2/12) whose means over steps n, n-1, n-2 are
    d_n, d_{n-1}, d_{n-2} (solved here as a 3 x 3 linear system, :func:`mean_parabola`); on step 2 the
    line through the means of steps 1 and 2, c_2 = 2 (d_2 - d_1) / (h_2 + h_1), q_2 = 0; on step 1
    c_1 = q_1 = 0. Once older, a step keeps d_j + c_j (tau - tau_j). The newest step uses the exact
    kernel, the older ones the exponential sum k~(x) = kappa (E~_inf + sum_k E_k e^{-b_k x}) (exact
    for Prony kernels)::

        A_n = d_n I0(h_n) + c_n M(h_n) + q_n Q(h_n)
              + sum_{j<n} sum_k e^{-b_k (t_n - t_j)} (d_j GA_k(h_j) + c_j GB_k(h_j)),
        I0(h) = int_0^h k,  M(h) = int_0^h k(x) (h/2 - x) dx,  Q(h) = int_0^h k(x) ((x - h/2)^2 - h^2/12) dx,
        GA_k(h) = kappa E_k int_0^h e^{-b_k x} dx,  GB_k(h) = kappa E_k int_0^h e^{-b_k x} (h/2 - x) dx,

    (mode 0: b = 0, E~_inf). Here the double sum is evaluated in full at every trial step.

    ``cubic`` (a kernel with a t^-1/2 singularity, :attr:`AdaptiveGrid.singular`): from step 4 on, while the
    mean of the step before the newest is positive (d_{n-1} > 0: u' > 0), the newest step's u' is the cubic
    d_n + c_n x + q_n (x^2 - h_n^2/12) + r_n (x^3 - 0.15 h_n^2 x), x = tau - tau_n, whose means over steps
    n..n-3 are d_n..d_{n-3} (:func:`mean_cubic`; the added polynomial has zero mean and zero first moment on
    the step, so d_n and c_n keep their meaning, and an older step keeps d_j + c_j (tau - tau_j) as before),
    and A_n gains r_n R(h_n), R(h) = int_0^h k(x) P3(h/2 - x) dx, P3(z) = z^3 - 0.15 h^2 z
    (:meth:`cubic_weight`).
    """

    def __init__(self, impact, representation, cubic=False):
        self.kappa = impact.kappa
        self.material = impact.material
        self.exp_sum = representation
        self.cubic = cubic
        self._cubic_weights = {}  # R(h) per step size h
        e_inf, _, b = representation.prony_terms()
        self.e_inf = e_inf
        self.rates = np.concatenate(([0.0], b))
        self.t_end = []  # t_j of the accepted steps
        self.parts = []  # per accepted step, d_j GA(h_j) + c_j GB(h_j) per mode
        self.means = []  # (h_j, d_j) of the accepted steps

    def _mode_weights(self, h):
        """(GA, GB) per mode for a step h (N m^-1.5 s, N m^-1.5 s^2)."""
        ga = self.kappa * np.concatenate(([self.e_inf * h], self.exp_sum.term_step_integrals(h, 1)[0]))
        gb = -self.kappa * np.concatenate(([0.0], self.exp_sum.term_step_moments(h, 1)[0]))
        return ga, gb

    def _newest_weights(self, h):
        """(I0, M, Q) of the exact kernel for a step h (N m^-1.5 s, N m^-1.5 s^2, N m^-1.5 s^3)."""
        integral, moment = self.material.first_step(h)
        curvature = self.material.first_step_second_moment(h)
        return self.kappa * float(integral), -self.kappa * float(moment), self.kappa * float(curvature)

    def cubic_weight(self, h):
        """R(h) = int_0^h k(x) P3(h/2 - x) dx, P3(z) = z^3 - 0.15 h^2 z (N m^-1.5 s^4), by adaptive quadrature
        (:func:`scipy.integrate.quad`) in y = sqrt(x / h), where a t^-1/2 kernel is smooth:
        R = kappa h^4 int_0^1 (E(h y^2) - E(0)) 2 y P3(1/2 - y^2)|_{h=1} dy (P3 has zero mean: a finite E(0)
        is taken out, and with it the cancellation of a kernel that barely relaxes on the step). Cached per
        step size."""
        if h not in self._cubic_weights:
            glassy = self.material.glassy
            e0 = glassy if math.isfinite(glassy) else 0.0

            def integrand(y):
                z = 0.5 - y * y
                return 2.0 * y * (float(self.material.relaxation_modulus(h * y * y)) - e0) * (z**3 - 0.15 * z)

            value, _ = quad(integrand, 0.0, 1.0, epsabs=0.0, epsrel=1e-11, limit=200)
            self._cubic_weights[h] = self.kappa * h**4 * value
        return self._cubic_weights[h]

    def slopes(self, h, u_prev, u_n):
        """(d_n, c_n, q_n, r_n) of a step h from u_{n-1} to u_n (r_n = 0 but on the cubic steps)."""
        d = (u_n - u_prev) / h
        if not self.means:
            return d, 0.0, 0.0, 0.0
        h1, d1 = self.means[-1]
        if len(self.means) == 1:
            return d, 2.0 * (d - d1) / (h + h1), 0.0, 0.0
        h2, d2 = self.means[-2]
        if self.cubic and len(self.means) >= 3 and d1 > 0.0:
            h3, d3 = self.means[-3]
            return (d, *mean_cubic((h, h1, h2, h3), (d, d1, d2, d3))[1:])
        return (d, *mean_parabola((h, h1, h2), (d, d1, d2))[1:], 0.0)

    def older_steps(self, t_n):
        """sum_{j<n} sum_k e^{-b_k (t_n - t_j)} (d_j GA_k + c_j GB_k), N."""
        if not self.t_end:
            return 0.0
        decay = np.exp(-np.multiply.outer(t_n - np.array(self.t_end), self.rates))
        return float(np.sum(decay * np.array(self.parts)))

    def convolution(self, t_n, h, u_prev):
        """A_n(u_n) for a trial step h ending at t_n (u_prev = u_{n-1})."""
        older = self.older_steps(t_n)
        i0, moment, curvature = self._newest_weights(h)
        cubic = self.cubic_weight(h) if self.cubic else 0.0

        def force(u_n):
            d, c, q, r = self.slopes(h, u_prev, u_n)
            return older + d * i0 + c * moment + q * curvature + r * cubic

        return force

    def accept(self, t_n, h, u_prev, u_n):
        d, c, _, _ = self.slopes(h, u_prev, u_n)
        ga, gb = self._mode_weights(h)
        self.t_end.append(t_n)
        self.parts.append(d * ga + c * gb)
        self.means.append((h, d))


def mean_parabola(sizes, means):
    """(a, c, q) of p(x) = a + c x + q (x^2 - h_0^2/12), x the time from the middle of the newest of
    consecutive steps of ``sizes`` (h_0, h_1, h_2: newest first, s), whose means over the steps are
    ``means`` (d_0, d_1, d_2): the 3 x 3 system of the exact means of 1, x and x^2 over each step,
    solved in units of h_0 (``_adaptive_kernels.slope_weights`` in closed form)."""
    h = np.asarray(sizes, dtype=float) / sizes[0]
    right = 0.5 - np.concatenate(([0.0], np.cumsum(h[:-1])))  # each step's right end, x / h_0
    left = right - h
    mean_x = 0.5 * (left + right)
    mean_x2 = (right**3 - left**3) / (3.0 * h)
    rows = np.column_stack([np.ones(3), mean_x, mean_x2 - 1.0 / 12.0])
    a, c, q = np.linalg.solve(rows, np.asarray(means, dtype=float))
    return float(a), float(c) / sizes[0], float(q) / sizes[0] ** 2


def mean_cubic(sizes, means):
    """(a, c, q, r) of p(x) = a + c x + q (x^2 - h_0^2/12) + r (x^3 - 0.15 h_0^2 x), x the time from the
    middle of the newest of four consecutive steps of ``sizes`` (h_0..h_3: newest first, s), whose means over
    the steps are ``means`` (d_0..d_3): as :func:`mean_parabola`, the 4 x 4 system of the exact means of 1,
    x, x^2 and x^3 over each step, solved in units of h_0 (``_adaptive_kernels.cubic_weights`` in closed
    form)."""
    h = np.asarray(sizes, dtype=float) / sizes[0]
    right = 0.5 - np.concatenate(([0.0], np.cumsum(h[:-1])))  # each step's right end, x / h_0
    left = right - h
    mean_x = 0.5 * (left + right)
    mean_x2 = (right**3 - left**3) / (3.0 * h)
    mean_x3 = (right**4 - left**4) / (4.0 * h)
    rows = np.column_stack([np.ones(4), mean_x, mean_x2 - 1.0 / 12.0, mean_x3 - 0.15 * mean_x])
    a, c, q, r = np.linalg.solve(rows, np.asarray(means, dtype=float))
    return float(a), float(c) / sizes[0], float(q) / sizes[0] ** 2, float(r) / sizes[0] ** 3


def _adaptive_mobility(impact, representation, window):
    """(alpha, alpha') as the adaptive march evaluates them: 0 or constant (rigid target, case 4, an
    elastic plate of its own material), the exact law for a fractional or CERF plate, else from the plate
    modulus of an exponential sum, E_b = (E~_inf + sum_k E_k e^{-b_k t}) / (1 - nu^2): alpha =
    S / sqrt(E_b), alpha' = -S E_b' / (2 E_b^1.5). The sum is the kernel's ``representation`` when the
    plate is of the contact's material, else the plate material's own (exact for Prony, its
    exponential sum on ``window`` = (t_min, t_max, tol) otherwise)."""
    g = impact.geometry
    own = g.plate_material is not None
    if g.rigid or g.case == 4 or (own and g.plate_material.is_elastic):
        alpha = 0.0 if g.rigid else float(impact.alpha(0.0))
        return lambda t: (alpha, 0.0)
    plate = g.plate_material if own else impact.material
    if plate.sqrt_law() is not None or plate.erfcx_law() is not None:
        return lambda t: _mobility(impact, t)
    if own:
        representation = soe(plate, *window).material
    factor, scale = 1.0 / (1.0 - (g.nu_plate if own else g.nu) ** 2), impact.mobility_scale

    def mobility(t):
        e_b = factor * float(representation.relaxation_modulus(t))
        e_b_rate = factor * float(representation.relaxation_rate(t))
        return scale / math.sqrt(e_b), -0.5 * scale * e_b_rate / e_b**1.5

    return mobility


def local_error(h, h_prev, g_n, g_prev, g_prev2):
    """The trapezoidal rule's local error per unit step, ``h^2 |g''| / 12`` (m/s), g'' from the second
    divided difference of g over the last three nodes."""
    g2 = 2.0 * ((g_n - g_prev) / h - (g_prev - g_prev2) / h_prev) / (h + h_prev)
    return h * h * abs(g2) / 12.0


def retry_level(level, ratio, floor):
    """Level of the retry of a step whose error is ``ratio`` times the tolerance: one level down per
    factor 4 (the error per unit step falls as h^2), 1 to 4 levels, not below ``floor``."""
    drop = next(d for d in (1, 2, 3, 4) if ratio <= 4.0**d or d == 4 or level - d == floor)
    return level - drop


def grown_level(level, error, tol, top):
    """Level after an accepted step: up by the largest of 0, 1, 2 levels with error 4^up < tol / 2,
    not above ``top``."""
    return level + max(up for up in (0, 1, 2) if up == 0 or (error * 4.0**up < 0.5 * tol and level + up <= top))


@dataclass(frozen=True)
class StepControl:
    """The adaptive method's acceptance rules for a trial step n on ``level`` (step h, ending at t_n).

    * error = ``h^2 |g''| / 12`` (:func:`local_error`, n >= 2) against
      tol = ``step_tol min(v0, max(|g_n| + |s_n| / max(t_n, tc), MOTION_FLOOR v0))``: the motion's own
      scale (m/s);
      error > tol: retry on :func:`retry_level` (at the floor level the step is accepted);
    * a step that would separate with h > sep_frac t_n: retry one level down (not below the floor);
    * after an accepted step (n >= 2, not separated) the next level is :func:`grown_level`; on a
      ``singular`` grid (:class:`AdaptiveGrid`) only up to steps h with GRADE h <= t_n (a graded start:
      near t = 0 u' ~ t^1/2, which the newest step's cubic does not fit on steps comparable to t), and not
      at all while unloading (s' < 0) within UNLOAD_HOLD contact-time estimates (:meth:`grown`;
      ``_adaptive_kernels.GRADE``, ``UNLOAD_HOLD``).
    """

    grid: AdaptiveGrid
    step_tol: float
    tc: float
    v0: float

    def tolerance(self, s, g, t_n):
        scale = abs(g) + abs(s) / max(t_n, self.tc)
        return self.step_tol * min(self.v0, max(scale, _adaptive.MOTION_FLOOR * self.v0))

    def retry(self, level, error, tol, separates, h, t_n):
        """The level on which to retry the trial step, or None to accept it (error None: n = 1)."""
        floor = self.grid.floor
        if error is not None and error > tol and level > floor:
            return retry_level(level, error / tol, floor)
        if separates and h > self.grid.sep_frac * t_n and level > floor:
            return level - 1
        return None

    def grown(self, level, error, tol, g, t_n, split):
        """The level after an accepted step (error, tol: its own) ending at t_n with s' = g, on a grid of
        steps h_base 2^(level - split)."""
        top = self.grid.top
        if self.grid.singular:
            if g < 0.0 and t_n <= _kernels.UNLOAD_HOLD * self.tc:
                return level
            while top > level and self.grid.h_base * 2.0 ** (top - split) * _kernels.GRADE > t_n:
                top -= 1
        return grown_level(level, error, tol, top)


def adaptive_reference(impact, tc, step_tol=4e-4, rule="force", plan=None, split=0, soe_tol=1e-10):
    """The ``adaptive`` method's march (``_adaptive_kernels.march_adaptive``): :class:`ExponentialSumHistory`
    in the trapezoidal step, steps h_base 2^(level - split) (:class:`AdaptiveGrid`), the levels chosen
    by :class:`StepControl` on every step not in ``plan`` and before the separation node (after it the
    level is frozen).

    Parameters
    ----------
    impact : vcor.contact.impact.Impact
    tc : float
        The contact-time estimate given to the method (s): sets h_base and the tolerance's scale.
    step_tol : float
    rule : {"force", "overlap"}
    plan : sequence of int, optional
        Levels of the first len(plan) steps (a replay: no error control, no separation refinement);
        after the plan the control resumes from its last level.
    split : int
        0: steps h_base 2^level; 1, 2, ...: every step divided by 2, 4, ... (the Richardson grids).
    soe_tol : float

    Returns
    -------
    dict
        As :func:`direct_reference`, plus ``levels`` (level of step j + 1 at index j) and ``rejected``
        (trial steps retried).
    """
    grid = AdaptiveGrid.of(impact, tc, soe_tol, step_tol)
    history = ExponentialSumHistory(impact, grid.representation, grid.singular)
    mobility = _adaptive_mobility(impact, grid.representation, grid.window)
    body = Body.of(impact)
    control = StepControl(grid, step_tol, tc, body.v0)
    nodes = Nodes.at_impact(body.v0)
    watch = SeparationWatch(rule)
    plan = [] if plan is None else [int(x) for x in plan]
    level, levels, rejected, n = grid.start_level, [], 0, 1
    while True:
        if n <= len(plan):
            level = plan[n - 1]
        controlled = n > len(plan) and watch.n_sep is None
        h = grid.h_base * 2.0 ** (level - split)
        t_n = nodes.t[-1] + h
        if t_n >= grid.horizon:
            raise RuntimeError("adaptive_reference: beyond the first time horizon (not implemented)")
        u_prev = nodes.u[-1]
        s, g, F, J, u = trapezoidal_step(nodes.last(), h, mobility(t_n), body, history.convolution(t_n, h, u_prev))
        error = tol = None
        if controlled and n >= 2:
            error = local_error(h, nodes.t[-1] - nodes.t[-2], g, nodes.g[-1], nodes.g[-2])
            tol = control.tolerance(s, g, t_n)
        retry = control.retry(level, error, tol, watch.separates(s, F), h, t_n) if controlled else None
        if retry is not None:
            level, rejected = retry, rejected + 1
            continue
        history.accept(t_n, h, u_prev, u)
        nodes.append(t_n, s, g, F, J, u)
        levels.append(level)
        if watch.update(n, s, F):
            out = _outcome(impact, nodes, watch.n_sep, rule,
                           glassy_stiffness(impact, tc))
            if rule == "force":  # s'(t0) = z'0 - alpha'(t0) J(t0) where F(t0) = 0 (the method's COR)
                z0 = out["sphere_velocity"]
                out["cor"] = abs(z0 - mobility(out["t0"])[1] * body.m * (body.v0 - z0)) / body.v0
            out.update(levels=np.array(levels), rejected=rejected)
            return out
        if error is not None and watch.n_sep is None:
            level = control.grown(level, error, tol, g, t_n, split)
        n += 1


#: the Richardson grids' error exponents (vcor.solvers.adaptive.RICHARDSON_EXPONENTS)
RICHARDSON_EXPONENTS = (2.0, 3.5, 4.0)


def richardson_weights(exponents=RICHARDSON_EXPONENTS):
    """Weights w of the values on grids h, h/2, h/4, ... (one more grid than exponents) with
    sum_j w_j x_j = x when x_j = x + sum_p a_p h_j^p: the solution of
    sum_j w_j (1, 2^{-p1 j}, 2^{-p2 j}, ...) = (1, 0, 0, ...)."""
    n = len(exponents) + 1
    rows = np.array([[1.0] + [2.0 ** (-p * j) for p in exponents] for j in range(n)])
    return np.linalg.solve(rows.T, np.eye(n)[0])


#: the exponents of the three grids of a smooth exponential kernel (vcor.solvers.adaptive.SMOOTH_EXPONENTS)
SMOOTH_EXPONENTS = (2.0, 4.0)


def smooth_kernel_rates(impact):
    """The relaxation rates (1/s) of the kernel's and the plate's exponential terms when both are exact
    sums of exponentials with no Dirac term and the kernel relaxes (a rigid target, a plate of constant
    mobility or a plate material that does not relax, of any law, count as such), else None: the cases in which
    ``adaptive`` takes three Richardson grids once every rate times its accepted grid's largest step
    is at most vcor.solvers.adaptive.RESOLVED_DECAY."""
    g = impact.geometry
    if impact.material.is_elastic:
        return None  # its force vanishes with the overlap, |t - t0|^1.5: four grids (vcor.solvers.adaptive.smooth_step)
    bodies = [impact.material]
    constant = g.rigid or g.case == 4 or (g.plate_material is not None and g.plate_material.is_elastic)
    if not constant:
        bodies.append(impact.material if g.plate_material is None else g.plate_material)
    rates = []
    for body in bodies:
        if not body.is_prony or body.viscosity != 0.0:
            return None
        rates.extend(float(b) for b in body.prony_terms()[2])
    return rates


def adaptive_richardson_reference(impact, tc, step_tol=4e-4, rule="force", soe_tol=1e-10):
    """The ``adaptive`` method with Richardson extrapolation (its default): the controlled grid, its
    replays with every step divided by 2, 4, ... (the levels of steps 1..n_sep + N_EXTRA, each repeated
    2, 4, ... times; vcor.solvers.adaptive.SPLIT_LEVELS replays, one fewer where
    :func:`smooth_kernel_rates` are all resolved on the controlled grid, or where the kernel has a t^-1/2
    singularity and the cubic scheme (:attr:`AdaptiveGrid.singular`) leaves its error no h^3.5 term to
    speak of; neither for a nearly elastic kernel) and the scalars extrapolated with
    :func:`richardson_weights` (``SMOOTH_EXPONENTS`` on three grids).

    Returns {"grids": [the dicts of :func:`adaptive_reference`], and each name of OUTCOME: the
    extrapolated value}. The method's guards (extrapolate only in the asymptotic range, never to a
    negative COR) are not reproduced.
    """
    first = adaptive_reference(impact, tc, step_tol, rule, soe_tol=soe_tol)
    plan = first["levels"][: first["n_sep"] + N_EXTRA]
    largest = float(np.max(np.diff(first["t"])))
    glassy = glassy_stiffness(impact, tc)  # (nearly elastic: all grids)
    rates = None if glassy else smooth_kernel_rates(impact)
    smooth = rates is not None and max(rates, default=0.0) * largest <= _adaptive.RESOLVED_DECAY
    smooth = smooth or (not glassy and AdaptiveGrid.of(impact, tc, soe_tol).singular)
    replays = _adaptive.SPLIT_LEVELS - 1 if smooth else _adaptive.SPLIT_LEVELS
    grids = [first] + [adaptive_reference(impact, tc, step_tol, rule, np.repeat(plan, 2**k), k, soe_tol)
                       for k in range(1, replays + 1)]
    weights = richardson_weights(SMOOTH_EXPONENTS if smooth else RICHARDSON_EXPONENTS)
    out = {"grids": grids}
    out.update({key: float(weights @ [grid[key] for grid in grids]) for key in OUTCOME})
    return out


# ---------------------------------------------------------------------------------------------------
# separation
# ---------------------------------------------------------------------------------------------------
def separation_reference(t, s, g, F, J, n, rule, m, v0, still_plate=False, glassy=0.0):
    """Separation inside [t_{n-1}, t_n] and the outcome there (``_separation.separation_point``).

    Parameters
    ----------
    t, s, g, F, J : arrays
        Node values (s, m, m/s, N, N s) of a march up to at least node n + 1 when it exists.
    n : int
        The separation node (the first with F <= 0, or s <= 0 for rule "overlap").
    rule : {"force", "overlap"}
    m, v0 : float
        Sphere mass (kg) and impact speed (m/s).
    glassy : float
        The kernel's finite k(0) without a Dirac term (N m^-1.5), or 0.

    Returns
    -------
    dict with the names of OUTCOME:
        t0 (s), the root in [t_{n-1}, t_n] of the cubic through the nodes lo..lo + 3
        (lo = max(0, min(n - 2, len(t) - 4))) of F, or of s for rule "overlap" or when s too
        crossed zero in step n and ``glassy`` is 0; with ``glassy``, of F as glassy u(s(t)) + R(t), s and
        R = F - glassy u by their cubics; s_residual = s(t0) (m), g0 = s'(t0) and J0 = J(t0) by the same
        cubics, except g0 when s crossed zero with F proportional to u = sgn(s)|s|^{3/2} on the
        nodes (an elastic kernel, to 1e-9) on a plate of constant mobility (``still_plate``):
        g0 = v0 - J0/m, the model's s' at F = 0;
        ``cor = |g0| / v0``; sphere_velocity z'0 = v0 - J0/m (m/s);
        w_h = int_0^t0 F s' dt and W_z = int_0^t0 F z' dt (J) by the trapezoid rule on nodes
        0..n-1 plus [t_{n-1}, t0] (F(t0) = 0 for rule "force", else its cubic); w_plate = W_z - w_h;
        energy_residual = (m v0^2/2 - m z'0^2/2 - W_z) / (m v0^2/2); s_max, f_max (m, N): the
        largest of samples 0..n, refined by the parabola through it and its neighbours.
    """
    t, s, g, F, J = (np.asarray(a, dtype=float) for a in (t, s, g, F, J))
    lo = max(0, min(n - 2, t.size - 4))
    window = slice(lo, lo + 4)

    def cubic(y):
        return Polynomial.fit(t[window], y[window], 3)

    def hertz(x):
        return np.sign(x) * np.abs(x) ** 1.5

    u = hertz(s[window])
    ref = int(np.argmax(np.abs(u)))
    elastic = u[ref] != 0.0 and np.max(np.abs(F[window] - F[window][ref] / u[ref] * u)) <= 1e-9 * abs(F[window][ref])
    glassy = 0.0 if rule == "overlap" else glassy
    by_overlap = rule == "overlap" or (glassy == 0.0 and s[n] <= 0.0 < s[n - 1])

    if by_overlap or glassy == 0.0:
        target = cubic(s if by_overlap else F)
    else:
        s_cubic, rest = cubic(s), cubic(F - glassy * hertz(s))

        def target(x):
            return glassy * hertz(s_cubic(x)) + rest(x)

    a, b = t[n - 1], t[n]
    if not target(a) > 0.0 >= target(b):
        raise RuntimeError(f"separation step {n}: the target does not change sign")
    t0 = b if target(b) == 0.0 else brentq(target, a, b, xtol=1e-18 * b, rtol=_RTOL, maxiter=500)
    s0, g0, J0 = (float(cubic(y)(t0)) for y in (s, g, J))
    if by_overlap and still_plate and elastic:
        g0 = v0 - J0 / m
    F0 = 0.0 if rule == "force" else float(cubic(F)(t0))
    z0 = v0 - J0 / m
    zdot = v0 - J / m
    w_h = np.trapezoid(F[:n] * g[:n], t[:n]) + 0.5 * (t0 - a) * (F[n - 1] * g[n - 1] + F0 * g0)
    w_z = np.trapezoid(F[:n] * zdot[:n], t[:n]) + 0.5 * (t0 - a) * (F[n - 1] * zdot[n - 1] + F0 * z0)
    e_in = 0.5 * m * v0 * v0
    return {"cor": abs(g0) / v0, "t0": float(t0), "s_residual": s0, "w_h": float(w_h), "w_plate": float(w_z - w_h),
            "sphere_velocity": z0, "energy_residual": float((e_in - 0.5 * m * z0 * z0 - w_z) / e_in),
            "s_max": parabola_peak(t[: n + 1], s[: n + 1]), "f_max": parabola_peak(t[: n + 1], F[: n + 1])}


def parabola_peak(t, y):
    """Largest sample of y(t), refined by the parabola through it and its neighbours (the sample
    itself at an end or where that parabola is not concave): its vertex value c0 - c1^2 / (4 c2)."""
    i = int(np.argmax(y))
    if i == 0 or i == y.size - 1:
        return float(y[i])
    near = slice(i - 1, i + 2)
    c0, c1, c2 = Polynomial.fit(t[near], y[near], 2).coef  # in the window's scaled variable
    if c2 >= 0.0:
        return float(y[i])
    return float(c0 - c1 * c1 / (4.0 * c2))
