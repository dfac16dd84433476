"""Richardson extrapolation of the adaptive method's nested grids, and when not to trust it.

The adaptive method (:mod:`vcor.solvers.adaptive`) replays its accepted grid with every step divided by
2, 4, ... and combines the grids' outcomes with weights that remove the leading error terms. The
combination is a guess unless the grids are in the asymptotic range; :func:`extrapolate` checks that
first, for t0 and the COR each: either the coarse and the finest grid agree to RICHARDSON_GAP relative (the
COR too, however small: a COR of a few COR_FLOOR, where a creeping thin plate releases the sphere, can have grids
per cents apart), or the ratio of successive differences of the three
finest grids, (x_h - x_h/2) / (x_h/2 - x_h/4), is in RICHARDSON_RATIO (4 for the leading h^2 error;
measured 3.6..4.4 on thin plates, whose grids differ by up to 1 %; with two error terms of opposite sign
the ratio alone can leave the band where the grids agree closely, which the gap test covers). Grids further
apart than RICHARDSON_MAX_GAP in t0 (relative) are never extrapolated, whatever their ratio: the
expansion's later terms are then not small against its first (a Kelvin-Voigt gel whose dashpot holds the
sphere while the force creeps to 1e-10 of its peak: grids 10-20 % apart with ratios 4.0-4.4, extrapolated
0.5-1.2 % off). A COR of a few 1e-6 can have grids tens of per cent apart and still extrapolate well (its
error is absolute, of the order of the step error in the sphere's speed), so the COR's gap does not count here.
Otherwise (e.g. a force creeping to zero over hours, t0 ill-conditioned: grids tens of per cent apart,
erratic ratios) the values of the finest grid are kept, the message says so, and the flag is
``grids_disagree``. So they are where the
finest grid's COR is below COR_FLOOR, whatever the grids: the sphere then leaves slower than the step
control follows (its motion scale is at least ``_records.MOTION_FLOOR`` v0) and t0 is where a force of the
order of the rounding of its history sum meets zero (a captured sphere: an elastic sphere on a 1 mm plate
of 10 kg/m^3 leaves at 2.7e-13 m/s; its t0 moves by 1e-3 with step_tol, not as any power of the step).

Grids that pass these checks are extrapolated. Two tighter checks on t0 then say whether the result is held
to the method's accuracy; where either fails, the values stay extrapolated (they are closer than the finest
grid's) and the flag is ``uncertain_extrapolation``. A smaller step_tol reduces their error but need not clear
the flag: where the step control misjudges the march, the spread does not shrink in proportion to step_tol:

* the t0 spread, ``|t0 finest - t0 coarse| / t0``, is at most RICHARDSON_MAX_GAP_STEPS times the step tolerance:
  the step control holds each step's error to step_tol, so a march whose grids differ by far more has an
  error its step control did not see;
* t0's difference ratio is in RICHARDSON_T0_RATIO (4 within a factor 1.25) where the spread is above
  RICHARDSON_T0_GAP (closer grids can have erratic ratios: two error terms of opposite sign, or differences at
  the rounding of t0).

Measured (``benchmarks/bench_extrapolation.py``, ``docs/_generated/extrapolation.md``): on the 668 impacts within
1e-7 of their references (of 695: six presets at 40 speeds on plate and rigid targets, the stability scenes but
their thin plates, 32 Kelvin-Voigt gels) the largest spread is 5.5 step_tol and no t0 ratio is outside the band
with a spread above RICHARDSON_T0_GAP, so neither check flags any of them; of the 27 more than 1e-7 off, 13 are
``grids_disagree`` and 13 ``uncertain_extrapolation``: Kelvin-Voigt gels held by their dashpot (spreads of 27
step_tol and more, 1e-6 .. 6.4e-4 off), an SLS of rubbery modulus 1e-3 of its glassy one at 1 mm/s (54 step_tol,
1.8e-5 off) and SLS laws relaxing at 1e6-1e7 1/s (spreads of 0.2 and 0.8 step_tol but t0 ratios 2.96 and 7.7,
inside RICHARDSON_RATIO; 2.8e-6 and 5.3e-6 off). One carries neither: a gel at 6.7 step_tol, 1.1e-7 off.
"""

from __future__ import annotations

import math

import numpy as np

from .common import OUTCOME

__all__ = ["COR_FLOOR", "RICHARDSON_GAP", "RICHARDSON_MAX_GAP", "RICHARDSON_MAX_GAP_STEPS", "RICHARDSON_RATIO",
           "RICHARDSON_T0_GAP", "RICHARDSON_T0_RATIO", "difference_ratio", "extrapolate", "weights_for"]

RICHARDSON_GAP = 1e-3
RICHARDSON_RATIO = (2.5, 8.0)
RICHARDSON_T0_GAP = 1e-5
RICHARDSON_T0_RATIO = (3.2, 5.0)
RICHARDSON_MAX_GAP = 0.05
RICHARDSON_MAX_GAP_STEPS = 8.0
COR_FLOOR = 1e-9
_DISAGREE, _UNCERTAIN = "grids_disagree", "uncertain_extrapolation"  # the validity flags the checks set
_COR, _T0 = OUTCOME.index("cor"), OUTCOME.index("t0")


def weights_for(exponents) -> tuple:
    """Weights of the values on grids h, h/2, h/4, ... (one more grid than exponents) that sum to 1 and
    remove the error terms h^p of ``exponents`` (solved, not inverted: they sum to 1 to rounding)."""
    n = len(exponents) + 1
    rows = np.array([[1.0] + [2.0 ** (-p * j) for p in exponents] for j in range(n)])
    return tuple(float(w) for w in np.linalg.solve(rows.T, np.eye(n)[0]))


def extrapolate(runs, weights, *, step_tol):
    """(values, message, flag): the OUTCOME values Richardson-extrapolated from ``runs`` (per grid, coarse to
    fine, its OUTCOME values in that order; further values ignored; lists of floats or an array) with
    ``weights`` (:func:`weights_for`, one per grid), and "" twice. Where the grids are not in the
    asymptotic range or the extrapolated COR is negative (module docstring), the finest grid's values, a
    message saying why and the validity flag ``grids_disagree`` (a name of ``vcor.solvers.validity.FLAGS``);
    where the extrapolation is not held to the method's accuracy (the t0 checks; ``step_tol``: the step
    tolerance the accepted grid was marched with), the extrapolated values, a message and
    ``uncertain_extrapolation`` (values: a list)."""
    rows = runs.tolist() if isinstance(runs, np.ndarray) else runs
    first, last = rows[0], rows[-1]
    n = len(OUTCOME)
    if len(weights) != len(rows):
        raise ValueError(f"{len(rows)} grids: the Richardson weights are for {len(weights)}")
    extrapolated = _weighted(weights, rows)[:n]
    cor = extrapolated[_COR]
    if cor < 0.0:
        # a COR of ~1e-11 (a creeping thin plate) within COR_FLOOR on every grid: the extrapolation
        # may leave the physical range; keep the finest grid's value rather than store a negative COR
        return last[:n], (f"not Richardson-extrapolated: the extrapolated COR {cor:.3g} is negative (grids "
                          f"{', '.join(f'{r[_COR]:.3g}' for r in rows)}); values of the finest grid"), _DISAGREE
    gap_t0, gap_cor = abs(last[_T0] - first[_T0]) / last[_T0], abs(last[_COR] - first[_COR])
    ratio_t0, ratio_cor = difference_ratio(rows, _T0), difference_ratio(rows, _COR)
    if gap_t0 > RICHARDSON_MAX_GAP:
        return last[:n], (
            f"not Richardson-extrapolated: {_pair(rows)} differ by {gap_t0:.2g} in t0 (relative), more than "
            f"{RICHARDSON_MAX_GAP:g}: too far apart for the error expansion's first terms to dominate, whatever the "
            f"ratios of their differences; values of the finest grid"), _DISAGREE
    lo, hi = RICHARDSON_RATIO
    if not ((gap_t0 <= RICHARDSON_GAP or lo <= ratio_t0 <= hi)
            and (gap_cor <= RICHARDSON_GAP * last[_COR] or lo <= ratio_cor <= hi)):
        # not in the asymptotic range: an extrapolation would be a guess; keep the finest grid's values
        return last[:n], (
            f"not Richardson-extrapolated: {_pair(rows)} differ by {gap_t0:.2g} (t0, relative) and {gap_cor:.2g} "
            f"(COR), and the differences between the three finest grids do not shrink as h^2 (ratios "
            f"{ratio_t0:.3g} for t0, {ratio_cor:.3g} for the COR; asymptotically 4); values of the finest "
            f"grid"), _DISAGREE
    if last[_COR] < COR_FLOOR:
        # the grids may agree or even shrink as h^2 by chance: their t0 is not held to the method's accuracy
        return last[:n], (
            f"not Richardson-extrapolated: the sphere leaves at a COR of {last[_COR]:.3g} (finest grid), below "
            f"{COR_FLOOR:g}, slower than the step control follows and at a force near the rounding of its "
            f"history sum, so t0 is not held to the method's accuracy (grids: t0 "
            f"{', '.join(f'{r[_T0]:.7g}' for r in rows)} s); values of the finest grid"), _DISAGREE
    lo_t0, hi_t0 = RICHARDSON_T0_RATIO
    spread = gap_t0 / step_tol
    if spread > RICHARDSON_MAX_GAP_STEPS or (gap_t0 > RICHARDSON_T0_GAP and not lo_t0 <= ratio_t0 <= hi_t0):
        why = (f"{spread:.3g} step_tol, more than {RICHARDSON_MAX_GAP_STEPS:g}: an error the step control did not see"
               if spread > RICHARDSON_MAX_GAP_STEPS else
               f"and the ratio of t0's differences on the three finest grids, {ratio_t0:.3g}, is outside "
               f"{RICHARDSON_T0_RATIO}: t0 is not yet in the asymptotic range")
        return extrapolated, (
            f"Richardson-extrapolated, but not held to the method's accuracy: {_pair(rows)} differ by {gap_t0:.2g} "
            f"in t0 (relative), {why} (a smaller step_tol reduces the error but need not clear this)"), _UNCERTAIN
    return extrapolated, "", ""


def _pair(rows) -> str:
    """The grids a message compares (built only where a message is: extrapolate runs on every result's path)."""
    return f"the grid and the finest grid (every step divided by {2**(len(rows) - 1)})"


def _weighted(weights, rows):
    """sum_j weights[j] rows[j], element by element (rows: lists of floats; written out for three and four
    grids, where numpy's call overhead would be most of the work)."""
    if len(rows) == 3:
        w0, w1, w2 = weights
        return [w0 * a + w1 * b + w2 * c for a, b, c in zip(*rows)]
    if len(rows) == 4:
        w0, w1, w2, w3 = weights
        return [w0 * a + w1 * b + w2 * c + w3 * d for a, b, c, d in zip(*rows)]
    return (np.array(weights) @ np.array(rows)).tolist()


def difference_ratio(rows, i):
    """(x0 - x1) / (x1 - x2) of the values ``rows[j][i]`` on the three finest grids h, h/2, h/4 (4 for h^2
    errors)."""
    a, b, c = rows[-3][i], rows[-2][i], rows[-1][i]  # (indexed, not a generator: on every result's path)
    d1, d2 = a - b, b - c
    return d1 / d2 if d2 != 0.0 else math.inf
