r"""Raw DMA sets to a Prony material and its shift factors: the measured-data fit (``method: spectrum``).

:func:`fit_dma` runs the chain on raw isothermal frequency sweeps (f in Hz, E', E'' in Pa, T in deg C):

1. start-free shift factors of all sets at once (:func:`vcor.fitting.superpose.global_shifts`: one
   P-spline master curve of log10 E', variable projection);
2. the shifts refined together with a smooth relaxation spectrum
   (:func:`vcor.fitting.spectrum.fit_with_shifts`): the master curve is then the Prony model itself, so
   E' *and* E'' at the shifts are those of one linear viscoelastic material;
3. the smooth spectrum at the final shifts (relaxation times on a fixed log grid, 4 per decade,
   log-spectrum roughness penalty, lambda by GCV with the one-standard-error rule), merged to
   ``modes_per_decade`` modes per decade (:func:`vcor.fitting.spectrum.reduce_modes`) with the change
   in E* reported;
4. WLF and Arrhenius fitted to the per-set shifts (weighted by their standard errors), as options
   beside the tabulated shifts.

The residuals weigh

.. math:: \sum_i m_i \Big[\Big(\frac{E'_{\rm fit}}{E'_i} - 1\Big)^2
          + a''\Big(\frac{E''_{\rm fit}}{E''_i} - 1\Big)^2\Big], \qquad a'' = 0.01,

i.e. inverse variances for relative errors of about 1 % in E' and 10 % in E'': in pyvisco's example
E'' rises at the top of every set by an amount that grows with the *measured* frequency at every
temperature (an instrument phase error of about 0.02 rad at 100 Hz), and the sets do not superpose in
E'' (about 17 %); equal weights let those errors set the shifts.

With shift factors given (a shift file), steps 1-2 are skipped and the spectrum is fitted at them.

The fit runs with one BLAS thread (``threadpoolctl``): its linear algebra is many small solves, which
BLAS threads only slow down, by an order of magnitude or more on a machine whose cores are busy
(OpenBLAS's threads then wait for each other).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
from threadpoolctl import threadpool_limits

from ..materials.models import Prony
from ..materials.shift import ShiftFunction
from . import spectrum as _spectrum
from . import superpose as _superpose

__all__ = ["LOSS_WEIGHT", "MODES_PER_DECADE", "DMAFit", "fit_curve", "fit_dma", "shift_function", "tan_delta_extrema"]

#: weight a'' of the relative E'' residuals against E' (module docstring)
LOSS_WEIGHT = 0.01
#: modes per decade of the merged Prony series (fewer bring back tan delta ripple)
MODES_PER_DECADE = 2.0


@dataclass
class DMAFit:
    """Everything :func:`fit_dma` found.

    Attributes
    ----------
    T : ndarray
        Set temperatures, deg C, ascending.
    log_aT, log_aT_std : ndarray
        Per-set log10 a_T (0 at T_ref; hot sets < 0) and linearised standard errors, decades.
    T_ref : float
        Reference temperature, deg C.
    spline_shifts : ShiftResult or None
        Stage 1 (None with given shifts).
    joint : JointFit or None
        Stage 2 (None with given shifts or ``kk_refine=False``, unless an instrument lag is fitted: then
        the joint solve with the shifts held).
    spectrum : SpectrumFit
        The smooth spectrum at the final shifts.
    reduced : ReducedModes
        The spectrum merged to fewer modes (the material's Prony terms).
    wlf, arrhenius : dict
        :func:`vcor.fitting.superpose.wlf_fit`, :func:`vcor.fitting.superpose.arrhenius_fit` of the shifts.
    times : dict
        Wall time per stage, s.
    notes : list of str
    lag, lag_std : float
        The instrument's time lag between force and displacement (s; 0 when not fitted) and its
        linearised standard error (s).
    """

    T: np.ndarray
    log_aT: np.ndarray
    log_aT_std: np.ndarray
    T_ref: float
    spline_shifts: object
    joint: object
    spectrum: object
    reduced: object
    wlf: dict
    arrhenius: dict
    times: dict
    notes: list = field(default_factory=list)
    lag: float = 0.0
    lag_std: float = 0.0

    @property
    def smoothing(self) -> dict:
        """The smoothing parameters used (spline mu per quantity, joint and final lambda), to hold
        fixed when refitting resampled data."""
        return {"mu": dict(self.spline_shifts.mu) if self.spline_shifts else None,
                "lam_joint": self.joint.lam_joint if self.joint else None, "lam": float(self.spectrum.lam)}

    def prony_terms(self, reduced: bool = True):
        """(E_inf [Pa], E [Pa], beta [1/s]) at T_ref, ordered by rate; ``reduced``: the merged modes."""
        e_inf, e, beta = (self.reduced if reduced else self.spectrum).prony_terms()
        order = np.argsort(beta)
        return e_inf, np.asarray(e)[order], np.asarray(beta)[order]

    def material(self, reduced: bool = True) -> Prony:
        """The Prony material at T_ref (:meth:`prony_terms`)."""
        e_inf, e, beta = self.prony_terms(reduced)
        return Prony(float(e_inf), tuple(float(x) for x in e), tuple(float(x) for x in beta))


def shift_function(fit: DMAFit, model: str = "table") -> ShiftFunction:
    """The shift function of a fit: ``"table"`` (the per-set log10 a_T, PCHIP in T), ``"wlf"`` or
    ``"arrhenius"`` (fitted to them)."""
    if model == "table":
        return ShiftFunction.table(fit.T_ref, fit.T, fit.log_aT)
    if model == "wlf":
        return ShiftFunction("wlf", fit.T_ref, C1=fit.wlf["C1"], C2=fit.wlf["C2"])
    if model == "arrhenius":
        return ShiftFunction("arrhenius", fit.T_ref, E_a=fit.arrhenius["E_a"])
    raise ValueError(f"shift model must be table, wlf or arrhenius, got {model!r}")


def _check_size(n_points: int, n_modes: int, where: str) -> None:
    if n_points < n_modes:
        raise ValueError(f"{where}: {n_points} frequency points are fewer than the {n_modes} modes of the merged "
                         f"Prony series: too few data to fit (or resample) a spectrum")


@threadpool_limits.wrap(limits=1, user_api="blas")
def fit_dma(raw, T_ref, *, log_aT=None, kk_refine=True, components=(1.0, LOSS_WEIGHT), per_decade=_spectrum.PER_DECADE,
            margin=_spectrum.MARGIN, modes_per_decade=MODES_PER_DECADE, smoothing=None, start=None, lag=False) -> DMAFit:
    """Shifts, smooth spectrum, merged Prony series and shift functions of raw DMA sets (module docstring).

    Parameters
    ----------
    raw : mapping, object with ``.columns`` or list of DMASet
        Columns f [Hz], E_stor, E_loss [Pa], T [deg C], Set, optional weight (point multiplicities).
    T_ref : float
        Reference temperature, deg C.
    log_aT : array_like, optional
        Given shift factors per set (ascending T), decades: no shift fit.
    kk_refine : bool
        Refine the shifts together with the spectrum (stage 2).
    components : (a', a'') or "uncertainty"
        Weights of the relative E' and E'' residuals (:func:`vcor.fitting.spectrum.fit_with_shifts`).
    per_decade, margin : float
        Relaxation times per decade of the fine grid; decades beyond the data on each side.
    modes_per_decade : float
        Modes per decade after merging.
    smoothing : dict, optional
        ``{"mu": {q: mu}, "lam_joint": float, "lam": float}`` (a :attr:`DMAFit.smoothing`) held fixed
        instead of chosen by GCV.
    start : DMAFit, optional
        Warm start of the spectrum (with ``smoothing``: no lambda scans).
    lag : bool
        Fit the instrument's time lag between force and displacement together with the shifts and the
        spectrum (:func:`vcor.fitting.spectrum.fit_with_shifts`; with given shifts or
        ``kk_refine=False`` the shifts are held).

    Returns
    -------
    DMAFit

    Raises
    ------
    ValueError
        Fewer than two sets, sets sharing no range of E', tan delta or E'' (naming their
        temperatures), or fewer frequency points than merged modes.
    """
    times = {}
    t0 = time.perf_counter()
    sets = _superpose.split_sets(raw)
    sm = smoothing or {}
    notes, sh, joint = [], None, None
    start_spec = start.spectrum if start is not None else None
    if log_aT is None:
        sh = _superpose.global_shifts(sets, T_ref, mu=sm.get("mu"))
        times["spline_shifts"] = time.perf_counter() - t0
        notes += sh.notes
    if lag or (log_aT is None and kk_refine):
        t1 = time.perf_counter()
        free = log_aT is None and kk_refine
        joint = _spectrum.fit_with_shifts(sets, T_ref, sh.log_aT if log_aT is None else np.asarray(log_aT, float),
                                          components=components, per_decade=per_decade, margin=margin,
                                          lam=sm.get("lam_joint"), final_lam=sm.get("lam", "gcv1se"),
                                          start_spectrum=start_spec, lag=lag, free_shifts=free)
        times["joint"] = time.perf_counter() - t1
        std = joint.log_aT_std if free else (sh.log_aT_std if sh is not None else np.zeros(len(sets)))
        log_aT, spec = joint.log_aT, joint.spectrum
        notes += joint.notes
    else:
        t1 = time.perf_counter()
        given = log_aT is not None
        log_aT = np.asarray(log_aT, float) if given else sh.log_aT
        std = np.zeros(len(sets)) if given else sh.log_aT_std
        mc = _superpose.master_curve(sets, log_aT)
        comp = (1.0, _spectrum.loss_weights(mc.E_stor, mc.E_loss)) if isinstance(components, str) else components
        spec = _spectrum.fit_spectrum(mc.f_red, mc.E_stor, mc.E_loss, weight=mc.weight, per_decade=per_decade,
                                      margin=margin, components=comp, lam=sm.get("lam", "gcv1se"), start=start_spec)
        times["spectrum"] = time.perf_counter() - t1
    notes += spec.notes
    reduced = _spectrum.reduce_modes(spec, modes_per_decade)
    _check_size(sum(s.f.size for s in sets), reduced.n_modes, "measured data")
    T = np.array([s.T for s in sets])
    wlf = _superpose.wlf_fit(T, log_aT, T_ref, sigma=np.where(std > 0, std, 0.01))
    arr = _superpose.arrhenius_fit(T, log_aT, T_ref, sigma=np.where(std > 0, std, 0.01))
    times["total"] = time.perf_counter() - t0
    lag_s, lag_std = (joint.lag, joint.lag_std) if joint is not None else (0.0, 0.0)
    return DMAFit(T, np.asarray(log_aT, float), np.asarray(std, float), float(T_ref), sh, joint, spec, reduced, wlf,
                  arr, times, notes, lag_s, lag_std)


def fit_curve(f, E_stor, E_loss, *, per_decade=_spectrum.PER_DECADE, margin=_spectrum.MARGIN, modes_per_decade=MODES_PER_DECADE):
    """(SpectrumFit, ReducedModes) of a master curve as given (no temperature sets): f [Hz], E', E'' [Pa],
    E'' weighted :data:`LOSS_WEIGHT`."""
    spec = _spectrum.fit_spectrum(f, E_stor, E_loss, per_decade=per_decade, margin=margin,
                                  components=(1.0, LOSS_WEIGHT))
    reduced = _spectrum.reduce_modes(spec, modes_per_decade)
    _check_size(int(np.size(f)), reduced.n_modes, "master curve")
    return spec, reduced


def tan_delta_extrema(material, f_lo: float, f_hi: float, n: int = 2000) -> int:
    """Local extrema of a material's tan delta on ``n`` log-spaced frequencies over [f_lo, f_hi] (Hz)."""
    e = material.complex_modulus(2 * math.pi * np.geomspace(f_lo, f_hi, n))
    return _spectrum.count_extrema(e.imag / e.real)
