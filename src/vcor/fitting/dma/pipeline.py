r"""Raw DMA sets to a Prony material and its shift factors: the measured-data fit (``method: spectrum``).

:func:`fit_dma` runs the chain on raw isothermal frequency sweeps (f in Hz, E', E'' in Pa, T in deg C):

1. start-free shift factors of all sets at once (:func:`vcor.fitting.dma.shifts.global_shifts`: one
   P-spline master curve of log10 E', variable projection);
2. the shifts refined together with a smooth relaxation spectrum
   (:func:`vcor.fitting.dma.joint.fit_with_shifts`): the master curve is then the Prony model itself, so
   E' *and* E'' at the shifts are those of one linear viscoelastic material;
3. the smooth spectrum at the final shifts (relaxation times on a fixed log grid, 4 per decade,
   log-spectrum roughness penalty, lambda by GCV with the one-standard-error rule), merged to
   ``modes_per_decade`` modes per decade (:func:`vcor.fitting.spectrum.modes.reduce_modes`) with the change
   in E* reported;
4. WLF and Arrhenius fitted to the per-set shifts (weighted by their standard errors,
   :mod:`vcor.fitting.dma.laws`), as options beside the tabulated shifts.

The residuals weigh

.. math:: \sum_i m_i \Big[\Big(\frac{E'_{\rm fit}}{E'_i} - 1\Big)^2
          + a''\Big(\frac{E''_{\rm fit}}{E''_i} - 1\Big)^2\Big], \qquad a'' = 0.01,

i.e. inverse variances for relative errors of about 1 % in E' and 10 % in E'': in pyvisco's example
E'' rises at the top of every set by an amount that grows with the *measured* frequency at every
temperature (an instrument phase error of about 0.02 rad at 100 Hz), and the sets do not superpose in
E'' (about 17 %); equal weights let those errors set the shifts.

With shift factors given (a shift file), steps 1-2 are skipped and the spectrum is fitted at them.

The fit runs with one BLAS thread (:func:`vcor.threads.one_blas_thread`): its linear algebra is many small solves, which
BLAS threads only slow down, by an order of magnitude or more on a machine whose cores are busy
(OpenBLAS's threads then wait for each other).
"""


from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ...materials.models import Prony
from ...threads import one_blas_thread
from ..spectrum.model import MARGIN, N_DENSE, PER_DECADE, count_extrema
from ..spectrum.modes import reduce_modes
from ..spectrum.smooth import fit_spectrum, loss_weights
from .joint import LOSS_WEIGHT, fit_with_shifts
from .laws import arrhenius_fit, wlf_fit
from .sets import master_curve, split_sets
from .shifts import global_shifts

__all__ = ["LOSS_WEIGHT", "MODES_PER_DECADE", "DMAFit", "fit_curve", "fit_dma", "tan_delta_extrema"]

#: modes per decade of the merged Prony series (fewer bring back tan delta ripple)
MODES_PER_DECADE = 2.0


@dataclass(frozen=True, kw_only=True)
class DMAFit:
    """Everything :func:`fit_dma` found: the shifts and their laws, the stages' records, the smooth
    spectrum and its merged modes.

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
        :func:`vcor.fitting.dma.laws.wlf_fit`, :func:`vcor.fitting.dma.laws.arrhenius_fit` of the shifts.
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
    spline_shifts: object = None
    joint: object = None
    spectrum: object
    reduced: object
    wlf: dict = field(default_factory=dict)
    arrhenius: dict = field(default_factory=dict)
    times: dict = field(default_factory=dict)
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


def _check_size(n_points: int, n_modes: int, where: str) -> None:
    if n_points < n_modes:
        raise ValueError(f"{where}: {n_points} frequency points are fewer than the {n_modes} modes of the merged "
                         f"Prony series: too few data to fit (or resample) a spectrum")


@dataclass(kw_only=True)
class _Stages:
    """What the stages of :func:`fit_dma` pass on: the shifts, their errors, the spectrum, the records."""

    log_aT: np.ndarray | None
    std: np.ndarray | None = None
    spline: object = None
    joint: object = None
    spectrum: object = None
    times: dict = field(default_factory=dict)
    notes: list = field(default_factory=list)


def _joint_stage(sets, T_ref, st: _Stages, *, free, components, grid, smoothing, start_spec, lag):
    """Stage 2: the shifts (and lag) refined with the spectrum, or the lag fitted at held shifts."""
    t1 = time.perf_counter()
    per_decade, margin = grid
    joint = fit_with_shifts(sets, T_ref, st.log_aT, components=components, per_decade=per_decade, margin=margin,
                            lam=smoothing.get("lam_joint"), final_lam=smoothing.get("lam", "gcv1se"),
                            start_spectrum=start_spec, lag=lag, free_shifts=free)
    st.times["joint"] = time.perf_counter() - t1
    if free:
        st.std = joint.log_aT_std
    st.log_aT, st.spectrum, st.joint = joint.log_aT, joint.spectrum, joint
    st.notes += joint.notes


def _smooth_stage(sets, st: _Stages, *, components, grid, smoothing, start_spec):
    """Stage 3 alone: the smooth spectrum of the master curve at the shifts."""
    t1 = time.perf_counter()
    mc = master_curve(sets, st.log_aT)
    comp = (1.0, loss_weights(mc.E_stor, mc.E_loss)) if isinstance(components, str) else components
    st.spectrum = fit_spectrum(mc.f_red, mc.E_stor, mc.E_loss, weight=mc.weight, per_decade=grid[0], margin=grid[1],
                               components=comp, lam=smoothing.get("lam", "gcv1se"), start=start_spec)
    st.times["spectrum"] = time.perf_counter() - t1


@one_blas_thread()
def fit_dma(raw, T_ref, *, log_aT=None, kk_refine=True, components=(1.0, LOSS_WEIGHT), per_decade=PER_DECADE,
            margin=MARGIN, modes_per_decade=MODES_PER_DECADE, smoothing=None, start=None, lag=False) -> DMAFit:
    """Shifts, smooth spectrum, merged Prony series and shift functions of raw DMA sets (module docstring).

    Parameters
    ----------
    raw : DMATable, mapping, or list of DMASet
        Columns f [Hz], E_stor, E_loss [Pa], T [deg C], Set, optional weight (point multiplicities).
    T_ref : float
        Reference temperature, deg C.
    log_aT : array_like, optional
        Given shift factors per set (ascending T), decades: no shift fit.
    kk_refine : bool
        Refine the shifts together with the spectrum (stage 2).
    components : (a', a'') or "uncertainty"
        Weights of the relative E' and E'' residuals (:func:`vcor.fitting.dma.joint.fit_with_shifts`).
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
        spectrum (:func:`vcor.fitting.dma.joint.fit_with_shifts`; with given shifts or
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
    t0 = time.perf_counter()
    sets = split_sets(raw)
    sm = smoothing or {}
    start_spec = start.spectrum if start is not None else None
    given = log_aT is not None
    st = _Stages(log_aT=np.asarray(log_aT, float) if given else None, std=np.zeros(len(sets)) if given else None)
    if not given:
        st.spline = global_shifts(sets, T_ref, mu=sm.get("mu"))
        st.times["spline_shifts"] = time.perf_counter() - t0
        st.notes += st.spline.notes
        st.log_aT, st.std = st.spline.log_aT, st.spline.log_aT_std
    options = {"components": components, "grid": (per_decade, margin), "smoothing": sm, "start_spec": start_spec}
    if lag or (not given and kk_refine):
        _joint_stage(sets, T_ref, st, free=not given and kk_refine, lag=lag, **options)
    else:
        _smooth_stage(sets, st, **options)
    st.notes += st.spectrum.notes
    reduced = reduce_modes(st.spectrum, modes_per_decade)
    _check_size(sum(s.f.size for s in sets), reduced.n_modes, "measured data")
    T = np.array([s.T for s in sets])
    std = np.asarray(st.std, float)
    wlf, arr = wlf_fit(T, st.log_aT, T_ref, sigma=std), arrhenius_fit(T, st.log_aT, T_ref, sigma=std)
    st.times["total"] = time.perf_counter() - t0
    joint = st.joint
    return DMAFit(T=T, log_aT=np.asarray(st.log_aT, float), log_aT_std=std, T_ref=float(T_ref),
                  spline_shifts=st.spline, joint=joint, spectrum=st.spectrum, reduced=reduced, wlf=wlf, arrhenius=arr,
                  times=st.times, notes=st.notes, lag=joint.lag if joint is not None else 0.0,
                  lag_std=joint.lag_std if joint is not None else 0.0)


def fit_curve(f, E_stor, E_loss, *, per_decade=PER_DECADE, margin=MARGIN, modes_per_decade=MODES_PER_DECADE):
    """(SpectrumFit, ReducedModes) of a master curve as given (no temperature sets): f [Hz], E', E'' [Pa],
    E'' weighted :data:`LOSS_WEIGHT`."""
    spec = fit_spectrum(f, E_stor, E_loss, per_decade=per_decade, margin=margin, components=(1.0, LOSS_WEIGHT))
    reduced = reduce_modes(spec, modes_per_decade)
    _check_size(int(np.size(f)), reduced.n_modes, "master curve")
    return spec, reduced


def tan_delta_extrema(material, f_lo: float, f_hi: float, n: int = N_DENSE) -> int:
    """Local extrema of a material's tan delta on ``n`` log-spaced frequencies over [f_lo, f_hi] (Hz)."""
    e = material.complex_modulus(2 * math.pi * np.geomspace(f_lo, f_hi, n))
    return count_extrema(e.imag / e.real)
