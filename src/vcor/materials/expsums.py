"""Sums of exponentials (SOE) for the relaxation kernels: every material as internal variables.

A material's transient E(t) - E(inf) is written as sum_k E_k exp(-beta_k t) on [t_min, t_max]:

* Prony and SLS: exact, their own terms. Elastic and Kelvin-Voigt: no transient (Kelvin-Voigt's
  viscosity is a local term of the march).
* The fractional law E0 + E1/sqrt(pi t) and CERF E0 + E1 erfcx(b1 sqrt t) are completely monotone
  with known relaxation spectra:

      1/sqrt(pi t)      = 1/pi   int_0^inf s^-1/2 e^-st ds,
      erfcx(b1 sqrt t)  = b1/pi  int_0^inf e^-st / (s^1/2 (s + b1^2)) ds.

  With s = e^x each is an integral over the real line of a function analytic in the strip
  ``|Im x| < pi/2``, so the trapezoid rule in x (step h) converges exponentially (Trefethen & Weideman
  2014; the construction of McLean 2018 and Jiang et al. 2017 for t^-beta). The nodes run from
  s_min to s_max; the nodes below s_min, where e^-st ~ 1 on [0, t_max], are summed into a constant
  added to E(inf); the nodes above s_max, whose modes have decayed before t_min, are dropped.

A-priori relative error bound of the fractional transient on [t_min, t_max] (the sum of three parts,
each held below tol/3 by the choice of h, s_max and s_min):

* discretisation: 2 sum_j cosh(2 pi^2 j / h)^-1/2 (from ``|Gamma(1/2 + i w)|^2 = pi / cosh(pi w)``);
* dropped fast modes: erfc(sqrt(s_max t_min e^-h));
* slow modes as a constant: (s_min t_max)^3/2 h e^-3h/2 / ((1 - e^-3h/2) sqrt(pi)).

The CERF spectrum is the fractional one times b1^2/(s + b1^2) <= 1 (analytic in the same strip);
its SOE uses the same nodes, and both are checked a posteriori on log-spaced times (32 per
period h of the error in log t)
(:attr:`SOE.checked_error`); :func:`soe` raises if the check exceeds ``tol``.

* The pointwise Eq. 1 combination of two bodies (:class:`~vcor.materials.eq_one.EqOne`) has no known
  spectrum and is in general not completely monotone: it is fitted by least squares on the window
  (:mod:`vcor.materials.expfit`), and its contract is the relative error of the modulus itself,
  <= ``tol``, checked a posteriori on times ten times denser than the fit's; where no fit reaches ``tol``,
  the best one within FIT_ACCEPT (1e-8) is taken and its error reported (``checked_error``). A modulus
  that relaxes below RELAXED of its start on the window (a fluid body) and has no fit there is fitted up
  to that point and held in absolute terms beyond (:func:`_fit_relaxed`).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from ..checks import number
from . import models as _materials
from .expfit import ExponentialSum, FitError, fit_exponential_sum

__all__ = ["FIT_ACCEPT", "MAX_SOE_TOL", "MIN_SOE_TOL", "RELAXED", "SOE", "fractional_bound", "soe"]

#: a posteriori check: log-spaced times, this many per period h of the trapezoid error in log t
CHECKS_PER_PERIOD = 32
#: the two-body modulus of Eq. 1 has no spectrum to build its sum from, and some pairs cannot be fitted to
#: the default 1e-10 in double precision (a modulus that falls by orders of magnitude within microseconds
#: against a soft partner: a sigmoid in t, whose fit loses the rest to the cancellation of its weights):
#: the best fit is then taken when its checked error is at most this, a tenth of the solvers' own default
#: accuracy (1e-7), and the result reports it (soe_error, and a message: vcor.solvers.validity)
FIT_ACCEPT = 1e-8
#: soe's largest tolerance (its argument's upper bound)
MAX_SOE_TOL = 1e-2
#: soe's smallest tolerance: a sum's relative error, checked in double precision, is of order 1e-14 at best
MIN_SOE_TOL = 1e-13


@dataclass(frozen=True, kw_only=True)
class SOE:
    """An exponential-sum representation: ``material`` (a Prony with E(inf) + slow-mode constant,
    moduli E_k in Pa, rates beta_k in 1/s: the material's own terms where it is Prony-type, else an
    :class:`~vcor.materials.expfit.ExponentialSum`, not bound by a material's largest modulus: the sum of a
    fractional law's modes grows as t_min^-1/2; a fitted two-body modulus's terms may be negative), the interval
    [t_min, t_max] in s, the a-priori bound (NaN where none is derived: exact representations have 0),
    and the largest relative error found on the check's log-spaced times (0 for exact
    representations): of the transient E(t) - E(inf) for the completely monotone laws, of the modulus
    E(t) for a fit."""

    material: _materials.Prony | ExponentialSum
    t_min: float
    t_max: float
    bound: float
    checked_error: float
    exact: bool

    @property
    def n_terms(self) -> int:
        return len(self.material.E)


def _erfc(x: float) -> float:
    """:func:`scipy.special.erfc` as a float (scipy.special loads on first use: a sweep of Prony materials
    never needs it, and its import costs a job's start a sixth of a second)."""
    from scipy.special import erfc

    return erfc(x)


def _cosh_sum(h: float) -> float:
    return 2.0 * sum(math.cosh(2 * math.pi**2 * j / h) ** -0.5 for j in range(1, 6))


def fractional_bound(h: float, s_min: float, s_max: float, t_min: float, t_max: float) -> float:
    """A-priori bound on the relative error of the SOE of 1/sqrt(pi t) on [t_min, t_max]
    (see the module docstring)."""
    q = math.exp(-1.5 * h)
    slow = (s_min * t_max) ** 1.5 * h * q / ((1 - q) * math.sqrt(math.pi))
    fast = float(_erfc(math.sqrt(s_max * t_min * math.exp(-h))))
    return _cosh_sum(h) + fast + slow


def _choose(tol: float, t_min: float, t_max: float):
    """h, s_min, s_max with each part of :func:`fractional_bound` below tol / 3."""
    h = 1.0
    while _cosh_sum(h) > tol / 3:
        h *= 0.97
    s_max = 1.0 / t_min
    while _erfc(math.sqrt(s_max * t_min * math.exp(-h))) > tol / 3:
        s_max *= 1.25
    q = math.exp(-1.5 * h)
    s_min = (tol / 3 * (1 - q) * math.sqrt(math.pi) / (h * q)) ** (2.0 / 3.0) / t_max
    return h, s_min, s_max


def _transient(material):
    """(callable transient(t), spectral density rho(s)) of a completely monotone material
    (:meth:`vcor.materials.base.Material.relaxation_spectrum`)."""
    spectrum = material.relaxation_spectrum()
    if spectrum is not None:
        return spectrum
    raise ValueError(f"no exponential-sum (SOE) construction for material kind {material.kind!r}: method "
                     f"'direct' solves any kernel")


def soe(material, t_min: float, t_max: float, tol: float = 1e-10, from_zero: bool = False) -> SOE:
    """SOE of ``material``'s relaxation modulus on [t_min, t_max] (s) with relative error <= ``tol``
    for the transient (see the module docstring). Prony-type materials are returned exactly; the Eq. 1
    combination of two bodies is fitted, with relative error <= ``tol`` for the modulus (or, where no fit
    reaches it, the best within FIT_ACCEPT: ``checked_error`` says which), on [0, t_max] with
    ``from_zero`` (the internal-variable methods integrate the kernel from t = 0; the sums of the
    completely monotone laws are not accurate there and refuse it).

    The interval is widened to powers of two (t_min down, t_max up) and the result cached, so a sweep
    whose points have nearby steps and horizons shares one construction."""
    t_min = number("t_min", t_min, 0.0, math.inf, lo_open=True, hi_open=True, unit="s")
    t_max = number("t_max", t_max, t_min, math.inf, lo_open=True, hi_open=True, unit="s")
    tol = number("tol", tol, MIN_SOE_TOL, MAX_SOE_TOL, lo_open=False, unit="(relative)")
    if material.is_prony:
        if type(material) is _materials.Prony:  # already the sum (a sweep builds one per point: no copy)
            exact = material
        else:
            e_inf, e, b = material.prony_terms()
            exact = _materials.Prony(float(e_inf), tuple(map(float, e)), tuple(map(float, b)))
        return SOE(material=exact, t_min=t_min, t_max=t_max, bound=0.0, checked_error=0.0, exact=True)
    if material.is_elastic:  # a law with no transient (a fractional or CERF law with E1 = 0): its constant
        return SOE(material=_materials.Prony(float(material.relaxation_modulus(t_max)), (), ()), t_min=t_min,
                   t_max=t_max, bound=0.0, checked_error=0.0, exact=True)
    lo, hi = math.floor(math.log2(t_min)), math.ceil(math.log2(t_max))
    if isinstance(material, _materials.EqOne):
        return _fit_cached(material, lo, hi, tol, bool(from_zero))
    if from_zero:
        raise ValueError(f"the exponential sum of material kind {material.kind!r} is built for t > 0 only: its "
                         f"modulus is not a finite sum of exponentials down to t = 0")
    return _soe_cached(material, lo, hi, tol)


@functools.lru_cache(maxsize=256)
def _fit_cached(material, lo: int, hi: int, tol: float, from_zero: bool) -> SOE:
    t_min, t_max = 2.0**lo, 2.0**hi
    accept = max(tol, FIT_ACCEPT)
    try:
        try:
            fitted, checked = fit_exponential_sum(material.relaxation_modulus, material.summed_rates, t_min, t_max,
                                                  tol, from_zero, accept=accept)
        except FitError as exc:
            t_cut = _relaxed_by(material, t_min, t_max)
            if t_cut is None:
                raise
            fitted, checked = _fit_relaxed(material, t_min, t_cut, t_max, (tol, from_zero, accept), exc)
    except ValueError as exc:
        best = getattr(exc, "best", math.inf)
        advice = f"raise soe_tol above {best:.2g}, or " if best < MAX_SOE_TOL else ""
        raise ValueError(f"the contact modulus of {material.describe_bodies()} (Green 2026 Eq. 1, pointwise): "
                         f"{exc}; {advice}use method 'direct' (it takes the modulus as it is)") from None
    return SOE(material=fitted, t_min=t_min, t_max=t_max, bound=math.nan, checked_error=checked, exact=False)


#: a two-body modulus that relaxes by orders of magnitude on the window (a body that is a fluid: a Maxwell
#: SLS, alpha = 0, whose e^-beta t tail falls to 1e-160 within it) has no fit in the relative error there:
#: the weights' rounding, ``eps * sum(abs(w)) / min(E')``, exceeds any tolerance. Where the fit on the whole
#: window fails, such a modulus is fitted where it is above this fraction of its value at the window's start
#: (the rounding stays below 1e-10 there), and beyond the sum is held to the modulus in absolute terms,
#: relative to that value (a relative error there may be larger: the reported error is this mixed one)
RELAXED = 1e-5


def _relaxed_by(material, t_min: float, t_max: float) -> float | None:
    """The first time (s) on a grid of 64 per octave of (t_min, t_max] where ``material``'s modulus is at most
    RELAXED of its value at t_min, or None."""
    t = np.geomspace(t_min, t_max, 64 * math.ceil(math.log2(t_max / t_min)) + 1)
    below = np.flatnonzero(material.relaxation_modulus(t) <= RELAXED * float(material.relaxation_modulus(t_min)))
    return float(t[below[0]]) if below.size and below[0] > 0 else None


def _fit_relaxed(material, t_min, t_cut, t_max, settings, whole):
    """(ExponentialSum, error) of a modulus that falls below RELAXED of its value at ``t_min`` by ``t_cut``:
    fitted on [t_min, t_cut]; its error the larger of that fit's relative error and the largest
    |sum - modulus| on [t_cut, t_max] over the modulus at t_min. ``settings``: (tol, from_zero, accept);
    ``whole``: the whole window's FitError, raised where this one's error exceeds ``accept`` too."""
    tol, from_zero, accept = settings
    try:
        fitted, checked = fit_exponential_sum(material.relaxation_modulus, material.summed_rates, t_min, t_cut, tol,
                                              from_zero, accept=accept)
    except FitError:
        raise whole from None
    tail = np.geomspace(t_cut, t_max, 64 * math.ceil(math.log2(t_max / t_cut)) + 1)
    error = float(np.max(np.abs(fitted.relaxation_modulus(tail) - material.relaxation_modulus(tail))))
    checked = max(checked, error / float(material.relaxation_modulus(t_min)))
    if not checked <= accept:
        raise whole
    return fitted, checked


@functools.lru_cache(maxsize=256)
def _soe_cached(material, lo: int, hi: int, tol: float) -> SOE:
    t_min, t_max = 2.0**lo, 2.0**hi
    transient, rho = _transient(material)
    h, s_min, s_max = _choose(tol, t_min, t_max)
    # the trapezoid error is periodic in log t with period h: CHECKS_PER_PERIOD times per period
    t = np.geomspace(t_min, t_max, int(CHECKS_PER_PERIOD * math.log(t_max / t_min) / h) + 2)
    exact_tr = transient(t)
    for _ in range(LOW_CUT_LOWERINGS + 1):
        approx, constant, s, weights = _trapezoid_sum(material.E0, rho, h, s_min, s_max)
        approx_tr = constant + np.exp(-np.outer(t, s)) @ weights  # not E(t) - E0: E0 may dwarf the transient
        checked = float(np.max(np.abs(approx_tr / exact_tr - 1)))
        if checked <= tol:
            break
        s_min /= LOW_CUT_FACTOR
    exact_bound = isinstance(material, _materials.FractionalPower)  # the bound is derived for 1/sqrt(pi t)
    bound = fractional_bound(h, s_min, s_max, t_min, t_max) if exact_bound else math.nan
    if not checked <= tol:
        raise ValueError(f"SOE of {material.kind!r} on [{t_min:g}, {t_max:g}] s: relative error {checked:.2e} "
                         f"exceeds tol = {tol:g}")
    return SOE(material=approx, t_min=t_min, t_max=t_max, bound=bound, checked_error=checked, exact=False)


#: the nodes' low end s_min is chosen for the fractional law's spectrum; a spectrum that holds more of its
#: weight at rates far below 1/t_max (a CERF law whose b1^2 is far slower than the window: rho(s) ~
#: 1/(pi b1 sqrt(s)) there) needs it lower: where the sum misses tol, s_min is divided by LOW_CUT_FACTOR,
#: up to LOW_CUT_LOWERINGS times (each takes about 60 times off the error at t_max of such a law)
LOW_CUT_FACTOR = 16.0
LOW_CUT_LOWERINGS = 8


def _trapezoid_sum(e0: float, rho, h: float, s_min: float, s_max: float):
    """(ExponentialSum of E0 + the trapezoid sum of the spectrum ``rho`` on nodes h apart in log s from s_min to s_max,
    the constant of the nodes below s_min, the nodes s (1/s), their weights (Pa)): the nodes below s_min
    continue the grid, where e^-st ~ 1 on [0, t_max]."""
    x = np.arange(math.log(s_min), math.log(s_max) + 0.5 * h, h)
    s = np.exp(x)
    weights = h * rho(s) * s
    below = s[0] * np.exp(-h * np.arange(1, 400))
    constant = float(np.sum(h * rho(below) * below))
    return (ExponentialSum(e0 + constant, tuple(map(float, weights)), tuple(map(float, s))), constant, s,
            weights)
