"""Isothermal sets of raw DMA data, and the master curve they make at given shift factors.

The convention is pyvisco's: the master curve is E'(f a_T) at T_ref, so that a material at T relaxes
a_T times slower than at T_ref: E(t; T) = E_ref(t / a_T) (:mod:`vcor.materials.shift`).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

from ...materials.shift import TABLE_TOLERANCE, table_log_aT

__all__ = ["QUANTITIES", "DMASet", "MasterCurve", "given_shifts", "master_curve", "split_sets", "superpose"]

#: quantities a shift objective may use: log10 E', log10 E'', log10 tan delta
QUANTITIES = ("E_stor", "E_loss", "tan_delta")
#: points per overlap of adjacent sets at which the master curve's E' mismatch is read
OVERLAP_POINTS = 10


@dataclass(frozen=True, kw_only=True)
class DMASet:
    """One isothermal frequency sweep.

    Attributes
    ----------
    T : float
        Temperature, deg C (mean of the set's T column).
    f, E_stor, E_loss : ndarray
        Frequencies (Hz, ascending) and storage / loss moduli (Pa).
    label : float
        The set's identifier in the raw table (``Set`` column).
    weight : ndarray or None
        Multiplicity of each point (bootstrap); None means 1 for every point.
    """

    T: float
    f: np.ndarray
    E_stor: np.ndarray
    E_loss: np.ndarray
    label: float = 0.0
    weight: np.ndarray | None = None

    def y(self, q: str) -> np.ndarray:
        """log10 of quantity ``q`` (one of :data:`QUANTITIES`)."""
        if q == "E_stor":
            return np.log10(self.E_stor)
        if q == "E_loss":
            return np.log10(self.E_loss)
        if q == "tan_delta":
            return np.log10(self.E_loss / self.E_stor)
        raise ValueError(f"quantity must be one of {QUANTITIES}, got {q!r}")

    @property
    def x(self) -> np.ndarray:
        """log10 f (f in Hz)."""
        return np.log10(self.f)

    @property
    def w(self) -> np.ndarray:
        """Point multiplicities (1 unless resampled)."""
        return np.ones(self.f.size) if self.weight is None else np.asarray(self.weight, float)


def _columns(raw, where):
    """The columns f, E', E'' (float), Set, T and the optional weights of a raw table; ValueError naming ``where``."""
    c = raw.columns if hasattr(raw, "columns") else raw
    if getattr(raw, "kind", "frequency") != "frequency":
        raise ValueError(f"{where}: superposition needs raw frequency data (f,E_stor,E_loss) with T and Set columns")
    for k in ("f", "E_stor", "E_loss", "T", "Set"):
        if k not in c:
            raise ValueError(f"{where}: raw data need columns f, E_stor, E_loss, T, Set; missing {k!r}")
    f, es, el = (np.asarray(c[k], float) for k in ("f", "E_stor", "E_loss"))
    if not (np.all(f > 0) and np.all(es > 0) and np.all(el > 0)):
        raise ValueError(f"{where}: f, E_stor and E_loss must all be > 0")
    wt = np.asarray(c["weight"], float) if "weight" in c else None
    return f, es, el, np.asarray(c["Set"]), np.asarray(c["T"], float), wt


def _too_few(where, lines, rows, label: float, T: float, distinct: int) -> str:
    """The refusal of set ``label`` at ``T`` (deg C) with ``distinct`` < 3 frequencies: the file's line of its
    first row and its lines (``lines``: each row's line in the file, or None), its temperature and label."""
    at = ""
    if lines is not None:
        own = [int(n) for n in np.asarray(lines)[rows]]
        span = (f"line {own[0]}" if len(own) == 1 else f"lines {own[0]}-{own[-1]}"
                if own[-1] - own[0] == len(own) - 1 else "lines " + ", ".join(map(str, own)))
        where, at = f"{where}, line {own[0]}", f", {span}"
    return (f"{where}: the set at T = {T:.4g} deg C (Set {label:g}{at}) has {distinct} distinct "
            f"frequenc{'y' if distinct == 1 else 'ies'}; superposition needs three or more per set")


def split_sets(raw) -> list[DMASet]:
    """Group a raw multi-temperature table into sets sorted by temperature.

    Parameters
    ----------
    raw : DMATable, mapping, or list of DMASet
        Columns ``f`` (Hz), ``E_stor``, ``E_loss`` (Pa), ``T`` (deg C), ``Set`` (identifier), e.g.
        :func:`vcor.fitting.dma.data.read_table`; optional column ``weight`` (point multiplicity).

    Returns
    -------
    list of DMASet
        One per distinct ``Set`` value, sorted by mean temperature.

    Raises
    ------
    ValueError
        Missing columns, non-positive values, fewer than two sets, a set with fewer than three
        distinct frequencies, or two sets closer than the 0.5 K scatter of a set's temperature readings
        (``vcor.materials.shift.TABLE_TOLERANCE``; naming the file when there is one).
    """
    if isinstance(raw, list):
        return raw
    where = getattr(raw, "path", "raw data")
    f, es, el, sid, tt, wt = _columns(raw, where)
    out = []
    for s in np.unique(sid):
        m = sid == s
        o = np.argsort(f[m], kind="stable")
        if np.unique(f[m]).size < 3:
            raise ValueError(_too_few(where, getattr(raw, "lines", None), m, float(s), float(np.mean(tt[m])),
                                      np.unique(f[m]).size))
        out.append(DMASet(T=float(np.mean(tt[m])), f=f[m][o], E_stor=es[m][o], E_loss=el[m][o], label=float(s),
                          weight=None if wt is None else wt[m][o]))
    out.sort(key=lambda d: d.T)
    if len(out) < 2:
        raise ValueError(f"{where}: superposition needs sets at two or more temperatures, got {len(out)}")
    for a, b in zip(out, out[1:]):  # the scatter of a set's readings: closer sets are one temperature
        if b.T - a.T < TABLE_TOLERANCE:
            raise ValueError(f"{where}: sets {a.label:g} and {b.label:g} lie at {a.T:.6g} and {b.T:.6g} deg C, closer "
                             f"than {TABLE_TOLERANCE:g} K, the scatter of a set's temperature readings: their shift "
                             f"factors cannot be told apart; give them one set label, or check their T")
    return out


@dataclass(frozen=True, kw_only=True)
class MasterCurve:
    """Superposed data at T_ref, sorted by reduced frequency.

    Attributes
    ----------
    T, log_aT : ndarray
        The sets' temperatures (deg C, ascending) and log10 a_T (decades, 0 at T_ref).
    T_ref : float
        Reference temperature, deg C.
    f_red : ndarray
        Reduced frequency f a_T, Hz.
    E_stor, E_loss : ndarray
        Storage and loss moduli, Pa (with an instrument lag removed).
    T_point : ndarray or None
        Temperature of each point's set, deg C (None: a master curve as given).
    set_index : ndarray
        Index (in :func:`split_sets` order) of each point's set.
    weight : ndarray
        Point multiplicities.
    source : str
        Where the shift factors come from.
    overlap_rms : float
        How well the sets superpose: rms of the log10 E' mismatch in the overlaps of adjacent sets.
    lag : float
        The instrument lag removed from the data, s.
    """

    T: np.ndarray
    log_aT: np.ndarray
    T_ref: float
    f_red: np.ndarray
    E_stor: np.ndarray
    E_loss: np.ndarray
    T_point: np.ndarray | None
    set_index: np.ndarray
    weight: np.ndarray
    source: str = ""
    overlap_rms: float = math.nan
    lag: float = 0.0

    @classmethod
    def as_given(cls, f, E_stor, E_loss, T_ref):
        """A master curve as given (no temperature sets): f (Hz), E', E'' (Pa) at T_ref (deg C)."""
        order = np.argsort(f)
        return cls(T=np.array([T_ref]), log_aT=np.zeros(1), T_ref=float(T_ref), f_red=f[order],
                   E_stor=E_stor[order], E_loss=E_loss[order], T_point=None,
                   set_index=np.zeros(f.size, int), weight=np.ones(f.size),
                   source="a master curve as given (no temperature sets)")


def _without_lag(where, s, lag):
    """(E', E'') of set ``s`` with the lag's phase removed, E* exp(-i 2 pi f lag)."""
    if not lag:
        return s.E_stor, s.E_loss
    e = (s.E_stor + 1j * s.E_loss) * np.exp(-2j * math.pi * s.f * lag)
    if np.any(e.imag <= 0):
        raise ValueError(f"{where}: the set at {s.T:.4g} deg C has a loss angle below the instrument lag's "
                         f"phase (2 pi f x {lag:.3g} s) at {s.f[e.imag <= 0].min():.4g} Hz: the lag does not "
                         f"describe these data")
    return e.real, e.imag


def _overlap_rms(fr, es):
    """rms of the log10 E' mismatch of adjacent shifted sets where their reduced ranges overlap."""
    mism = []
    for (fa, ea), (fb, eb) in itertools.pairwise(zip(fr, es)):
        lo, hi = max(fa.min(), fb.min()), min(fa.max(), fb.max())
        if lo < hi:
            g = np.log10(np.geomspace(lo, hi, OVERLAP_POINTS))
            mism.append(np.interp(g, np.log10(fa), np.log10(ea)) - np.interp(g, np.log10(fb), np.log10(eb)))
    return float(np.sqrt(np.mean(np.concatenate(mism) ** 2))) if mism else math.nan


def master_curve(raw, log_aT, *, T_ref=math.nan, source="given per set", lag=0.0) -> MasterCurve:
    """Apply shift factors: f_red = f 10^log_aT per set (``log_aT`` in :func:`split_sets` order, i.e.
    ascending temperature, decades); ``lag`` (s): an instrument's time lag between force and
    displacement, removed from every point, E* exp(-i 2 pi f lag) with f the measured frequency
    (:func:`vcor.fitting.dma.joint.fit_with_shifts` fits it)."""
    where = getattr(raw, "path", "raw data")
    sets = split_sets(raw)
    log_aT = np.asarray(log_aT, float)
    if log_aT.size != len(sets):
        raise ValueError(f"{where}: {len(sets)} sets need {len(sets)} shift factors, got {log_aT.size}")
    fr = [s.f * 10.0**a for s, a in zip(sets, log_aT)]
    es, el = zip(*(_without_lag(where, s, lag) for s in sets))
    rms = _overlap_rms(fr, es)
    tp = np.concatenate([np.full(s.f.size, s.T) for s in sets])
    ix = np.concatenate([np.full(s.f.size, k) for k, s in enumerate(sets)])
    w = np.concatenate([s.w for s in sets])
    fr, es, el = map(np.concatenate, (fr, es, el))
    o = np.argsort(fr, kind="stable")
    return MasterCurve(T=np.array([s.T for s in sets]), log_aT=log_aT, T_ref=float(T_ref), f_red=fr[o], E_stor=es[o],
                       E_loss=el[o], T_point=tp[o], set_index=ix[o], weight=w[o], source=source, overlap_rms=rms,
                       lag=float(lag))


def given_shifts(shifts, T, T_ref) -> np.ndarray:
    """log10 a_T at the sets' temperatures ``T`` (deg C) from a shift-factor table (PCHIP in T, up to
    :data:`vcor.materials.shift.TABLE_TOLERANCE` beyond its range), made zero at ``T_ref``."""
    if shifts.kind != "shift":
        raise ValueError(f"{shifts.path}: not a shift-factor file (T,log_aT)")
    order = np.argsort(shifts.columns["T"])
    ts, ls = shifts.columns["T"][order], shifts.columns["log_aT"][order]
    tol = TABLE_TOLERANCE
    if T.min() < ts[0] - tol or T.max() > ts[-1] + tol:
        raise ValueError(f"{shifts.path}: shift factors cover {ts[0]:g}..{ts[-1]:g} deg C, the sets "
                         f"{T.min():g}..{T.max():g} deg C")
    if not ts[0] - tol <= T_ref <= ts[-1] + tol:
        raise ValueError(f"{shifts.path}: shift factors cover {ts[0]:g}..{ts[-1]:g} deg C, T_ref = {T_ref:g} "
                         f"deg C lies outside (the factors are made zero at T_ref)")
    return table_log_aT(ts, ls, T) - table_log_aT(ts, ls, T_ref)


def superpose(raw, T_ref: float, shifts=None, *, log_aT=None, source: str | None = None,
              lag: float = 0.0) -> MasterCurve:
    """Master curve at ``T_ref`` (deg C) of raw sets at given shift factors: a shift-factor table
    ``shifts`` (:func:`given_shifts`) or ``log_aT`` per set (ascending temperature, decades; ``source``
    says where they come from); ``lag`` as in :func:`master_curve`. Shift factors found from the data:
    :func:`vcor.fitting.dma.pipeline.fit_dma`."""
    if log_aT is None and shifts is None:
        raise ValueError(f"{getattr(raw, 'path', 'raw data')}: superpose needs shift factors (a shift file or "
                         f"log_aT per set); start-free shifts are found by vcor.fitting.dma.fit_dma")
    if log_aT is None:
        T = np.array([s.T for s in split_sets(raw)])
        log_aT = given_shifts(shifts, T, T_ref)
        source = f"given ({shifts.path}), PCHIP in T, zero at T_ref"
    return master_curve(raw, log_aT, T_ref=T_ref, source=source or "given per set", lag=lag)
