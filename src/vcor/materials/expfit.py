"""Exponential-sum fits of relaxation moduli that have no known spectrum: Green 2026 Eq. 1, the pointwise
combination of two bodies' moduli (:class:`vcor.materials.eq_one.EqOne`).

E'(t) = c_a E_a(t) c_b E_b(t) / (c_a E_a(t) + c_b E_b(t)) is smooth for t > 0 but in general not
completely monotone (an elastic body on an SLS body gives the series sum_n a_n e^{-n beta t} with
alternating signs), so the trapezoid construction of :mod:`vcor.materials.expsums` does not apply.
It is fitted instead, on [t_min, t_max], by linear least squares in the relative error:

    E'(t) ~ c_0 + sum_j c_j e^{-s_j t},   minimise  sum_i ((c_0 + sum_j c_j e^{-s_j t_i}) / E'(t_i) - 1)^2

over log-spaced times t_i, with rates s_j chosen, in order of increasing cost, from

* the sums of up to ``order`` rates of the bodies' own Prony terms (the exact spectrum of E' when both
  bodies are Prony-type: E' is then a rational function of their exponentials, and for an elastic
  body on a Prony body a few such terms reproduce it to rounding), and
* a geometric grid of spacing ``step`` in ln s from 0.01 / t_max to 20 / t_min (a continuous spectrum,
  and the fractional and CERF laws' sqrt(t) behaviour near t = 0).

The least-squares problem is solved by QR with column pivoting (LAPACK ``geqp3``): the columns beyond
the numerical rank (1e-15 of the largest pivot) are dropped, which keeps the weights moderate. A fit is
accepted when its relative error, checked on times ten times denser than the samples, is <= ``tol``
and the weights lose no more than that to rounding (``(|c_0| + sum |c_j|) / min E' * eps <= tol``); else
the next, richer rate set is tried (:data:`ATTEMPTS`). Where none reaches ``tol``, the caller may take the
best within a looser ``accept`` (``vcor.materials.expsums.FIT_ACCEPT``), whose error is then the larger of
the check's and the rounding's. The weights may be negative, so the result is an
:class:`ExponentialSum` (a Prony with signed terms), not a material.

The fit runs with one BLAS thread (:func:`vcor.threads.one_blas_thread`): its linear algebra is a few small
QR factorisations, which a multi-threaded BLAS slows down by orders of magnitude on a busy machine, and
whose last digits would depend on the number of threads.

Why not a general-purpose fit (scipy.optimize on rates and weights): the problem is linear once the
rates are fixed, and the rates that matter are known (the bodies' own, and a grid dense enough that the
check passes); a nonlinear fit of ~50 rates would be slower and could stall.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ..threads import one_blas_thread
from .base import Parameter
from .prony import Prony

__all__ = ["ATTEMPTS", "ExponentialSum", "FitError", "fit_exponential_sum", "sample_times", "summed_rates"]


class FitError(ValueError):
    """No exponential sum within the accepted error: ``best``, the smallest error reached."""

    def __init__(self, message: str, best: float):
        super().__init__(message)
        self.best = best


#: the rate sets tried in turn: (grid spacing in ln s, or None for the bodies' rates alone; the largest
#: number of the bodies' rates summed)
ATTEMPTS = ((None, 3), (0.7, 3), (0.5, 3), (0.35, 4), (0.25, 4), (0.18, 4), (0.12, 4))
#: samples per unit of ln t: at least SAMPLES_PER_LOG, and SAMPLES_PER_RATE per rate of the grid (the
#: finer grids; 0.25 takes 24, 0.18 takes 33, 0.12 takes 50)
SAMPLES_PER_LOG = 24.0
SAMPLES_PER_RATE = 6.0
#: the check: this many times the samples, log-spaced and offset from them
CHECK_FACTOR = 10
#: relative size, against the largest pivot of the QR factorisation, of a column kept in the fit
RANK_CUTOFF = 1e-15
#: the grid's slowest and fastest rates, times 1 / t_max and 1 / t_min
GRID_SLOWEST = 0.01
GRID_FASTEST = 20.0
#: at most this many of the bodies' summed rates (the combinations of many Prony terms grow fast)
MAX_COMBINED = 400


@dataclass(frozen=True)
class ExponentialSum(Prony, kind="exponential-sum"):
    """E(t) = E_inf + sum_i E_i exp(-beta_i t) with terms of either sign (Pa; rates beta_i in 1/s): a
    fitted representation of a modulus over a time window, used by the solvers like a Prony series
    (its step integrals and moments are the Prony closed forms, which hold for any sign). It is not a
    material a user gives: a negative term would make a material's modulus increase somewhere, and
    this one is only checked on the window it was fitted on.

    Examples
    --------
    >>> from vcor.materials.expfit import ExponentialSum
    >>> s = ExponentialSum(2.0, (1.0, -0.5), (10.0, 20.0))
    >>> float(s.relaxation_modulus(0.0))
    2.5
    """

    TITLE: ClassVar[str] = "exponential sum with terms of either sign (a fitted modulus, not a material)"
    FORMULA: ClassVar[str] = "E(t) = E_inf + sum_i E_i exp(-beta_i t), E_inf and E_i of either sign"
    PARAMETERS: ClassVar[tuple] = (Parameter(name="E_inf", unit="Pa", meaning="constant term"),
                                   Parameter(name="E", unit="Pa", meaning="term weights (either sign)",
                                             shape="terms"),
                                   Parameter(name="beta", unit="s-1", meaning="rates", shape="terms"))
    #: fitted by the solvers, never named by a config spec
    CONFIGURABLE: ClassVar[bool] = False

    def __post_init__(self):
        e = tuple(float(x) for x in self.E)
        b = tuple(float(x) for x in self.beta)
        if len(e) != len(b):
            raise ValueError(f"ExponentialSum: E and beta must have equal length, got {len(e)} and {len(b)}")
        if not (math.isfinite(self.E_inf) and all(map(math.isfinite, e)) and all(x >= 0 and math.isfinite(x)
                                                                                  for x in b)):
            raise ValueError("ExponentialSum: E_inf and E must be finite, beta finite and >= 0")
        object.__setattr__(self, "E_inf", float(self.E_inf))
        object.__setattr__(self, "E", e)
        object.__setattr__(self, "beta", b)
        object.__setattr__(self, "_term_arrays", (np.asarray(e, float), np.asarray(b, float)))
        object.__setattr__(self, "_term_pairs", tuple(zip(e, b)))  # for modulus_at

    @property
    def is_elastic(self) -> bool:
        return not any(self.E)


def _rate_set(combined, step, t_min, t_max) -> np.ndarray:
    lo, hi = GRID_SLOWEST / t_max, GRID_FASTEST / t_min
    rates = [x for x in combined if lo < x < hi]
    if step is not None:
        rates.extend(np.exp(np.arange(math.log(lo), math.log(hi) + 0.5 * step, step)))
    return np.unique(np.asarray(rates, dtype=float))


def _least_squares(rates, t, e):
    """(weights, rates) of the columns kept (rate 0: the constant): the relative-error least-squares fit
    by QR with column pivoting, the columns beyond the numerical rank dropped."""
    from scipy.linalg import qr, solve_triangular  # on use: only two-body contacts fit

    a = np.hstack([np.ones((t.size, 1)), np.exp(-np.multiply.outer(t, rates))]) / e[:, None]
    q, r, piv = qr(a, mode="economic", pivoting=True)
    diag = np.abs(np.diag(r))
    rank = int(np.sum(diag > RANK_CUTOFF * diag[0]))
    coef = solve_triangular(r[:rank, :rank], q[:, :rank].T @ np.ones(t.size))
    keep = np.sort(piv[:rank])
    weights = np.zeros(rates.size + 1)
    weights[piv[:rank]] = coef
    return weights[keep], np.concatenate(([0.0], rates))[keep]


def fit_exponential_sum(modulus, combined, t_min: float, t_max: float, tol: float, from_zero: bool = False,
                        accept: float | None = None):
    """(ExponentialSum, checked relative error) of the callable ``modulus`` (E(t) in Pa, t in s, > 0 on
    the window) on [t_min, t_max] (s), with the bodies' summed rates ``combined(order)`` (1/s) as the
    first candidates (module docstring); ``from_zero``: t = 0 is a sample and a check point too (for
    the internal-variable methods, which integrate the kernel from t = 0). The first rate set of
    :data:`ATTEMPTS` that reaches ``tol`` is taken; when none does, the best of them if it is within
    ``accept`` (default: ``tol``), with the larger of its checked error and its rounding loss as its error,
    else :class:`FitError` (the message gives the best error reached). Runs with one BLAS thread."""
    with one_blas_thread():
        return _fit(modulus, combined, t_min, t_max, tol, from_zero, accept)


def _fit(modulus, combined, t_min, t_max, tol, from_zero, accept):
    """:func:`fit_exponential_sum`'s work, within its BLAS thread limit."""
    samples = {}  # per density: (t, E(t), check times, E there)
    best = math.inf
    for step, order in ATTEMPTS:
        rates = _rate_set(combined(order), step, t_min, t_max)
        if rates.size == 0:
            continue
        per_log = max(SAMPLES_PER_LOG, SAMPLES_PER_RATE / step) if step is not None else SAMPLES_PER_LOG
        if per_log not in samples:
            t, t_check = sample_times(t_min, t_max, per_log, from_zero)
            samples[per_log] = (t, modulus(t), t_check, modulus(t_check))
            if not (np.all(np.isfinite(samples[per_log][3])) and np.all(samples[per_log][3] > 0)):
                raise FitError("the modulus to fit must be finite and > 0 on the window", math.inf)
        t, e, t_check, e_check = samples[per_log]
        weights, kept_rates = _least_squares(rates, t, e)
        terms = np.exp(-np.multiply.outer(t_check, kept_rates)) @ weights
        error = float(np.max(np.abs(terms / e_check - 1.0)))
        rounding = float(np.sum(np.abs(weights)) / np.min(e_check) * np.finfo(float).eps)
        if max(error, rounding) < best:
            best, best_fit = max(error, rounding), (weights, kept_rates)
        if error <= tol and rounding <= tol:
            return _exponential_sum(weights, kept_rates), error
    if best <= (tol if accept is None else accept):
        weights, kept_rates = best_fit
        return _exponential_sum(weights, kept_rates), best
    window = f"[0, {t_max:.3g}]" if from_zero else f"[{t_min:.3g}, {t_max:.3g}]"
    raise FitError(f"no exponential sum reaches a relative error of {tol:g} on {window} s (best {best:.2g})", best)


def _exponential_sum(weights, rates) -> ExponentialSum:
    """The fit's columns (rate 0: the constant) as an :class:`ExponentialSum`."""
    decaying = rates > 0
    return ExponentialSum(float(np.sum(weights[~decaying])), tuple(map(float, weights[decaying])),
                          tuple(map(float, rates[decaying])))


def sample_times(t_min: float, t_max: float, per_log: float, from_zero: bool = False):
    """(samples, check times) of a fit on [t_min, t_max] (s): ``per_log`` log-spaced samples per unit of
    ln t (plus 40), and CHECK_FACTOR times as many check times, offset from them; with ``from_zero``
    t = 0 leads both."""
    t = np.geomspace(t_min, t_max, int(per_log * math.log(t_max / t_min)) + 40)
    t_check = np.geomspace(t_min, t_max, CHECK_FACTOR * t.size + 1)
    if from_zero:
        return np.concatenate(([0.0], t)), np.concatenate(([0.0], t_check))
    return t, t_check


def summed_rates(rates, order: int) -> list:
    """The sums of 1 to ``order`` of ``rates`` (1/s, with repetition), at most MAX_COMBINED of them, the
    smallest first: the rates of the products of the exponentials, the spectrum of a rational function
    of them.

    Examples
    --------
    >>> from vcor.materials.expfit import summed_rates
    >>> summed_rates([1.0, 10.0], 2)
    [1.0, 2.0, 10.0, 11.0, 20.0]
    """
    out = set()
    base = sorted({float(r) for r in rates if r > 0})
    for n in range(1, order + 1):
        out.update(sum(c) for c in itertools.combinations_with_replacement(base, n))
        if len(out) > MAX_COMBINED:
            break
    return sorted(out)[:MAX_COMBINED]
