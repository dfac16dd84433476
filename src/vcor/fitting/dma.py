"""Measured DMA data: pyvisco's CSV conventions, time-temperature superposition,
WLF / Arrhenius shift functions.

Files (the column and units conventions of NREL's pyvisco input files):

* frequency domain ``f,E_stor,E_loss`` (Hz; Pa, kPa, MPa or GPa),
* time domain ``t,E_relax`` (s; a modulus unit),
* raw multi-temperature sets: either of the above plus ``T,Set`` (deg C or K; set number),
* shift factors ``T,log_aT`` (deg C or K; log10 of a_T, a_T = 10^log_aT).

A second row of unit names is allowed (and read); without it the values are SI (Hz, s, Pa, deg C).
A UTF-8 byte-order mark is accepted. Every error names the file, the line (1-based) and the column.

Superposition (:func:`superpose`): each set's temperature is the mean of its T column; with shift
factors given they are interpolated in T like a tabulated shift function (PCHIP, up to 0.5 K beyond
their range and no further; :mod:`vcor.materials.shift`), or taken per set
(``log_aT``); otherwise adjacent sets are shifted horizontally onto each other by matching log f at
equal log E' over the E' range they share (E' superposes; in pyvisco's example E'' does not), and the
shifts are summed from the reference temperature (the pairwise shifts of ``method: free``; the
default measured-data fit finds all shifts at once, :mod:`vcor.fitting.superpose`). Where E' is flat
(glassy, rubbery plateaus) that is ill-conditioned. ``wlf_fit`` / ``arrhenius_fit`` fit the shift function to the per-set log a_T and report
the residuals. The convention is pyvisco's: the master curve is E'(f a_T) at T_ref, so that a
material at T relaxes a_T times slower than at T_ref: E(t; T) = E_ref(t / a_T) (:mod:`vcor.materials.shift`).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from threadpoolctl import threadpool_limits

from ..io.csvfile import cell_number, data_rows, read_rows, units_row
from ..materials.shift import GAS_CONSTANT, TABLE_TOLERANCE, table_log_aT, wlf_log_aT
from .prony import FitData, fit_prony

__all__ = ["DMATable", "Superposition", "arrhenius_fit", "check_data", "fit_master", "read_table", "set_arrays",
           "superpose", "wlf_fit"]

MODULUS_UNITS = {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9}
UNITS = {"f": {"Hz": 1.0}, "t": {"s": 1.0}, "E_stor": MODULUS_UNITS, "E_loss": MODULUS_UNITS,
         "E_relax": MODULUS_UNITS, "T": {"C": 0.0, "K": -273.15}, "Set": {"-": 1.0, "": 1.0},
         "log_aT": {"-": 1.0, "": 1.0}}
KINDS = {"frequency": ("f", "E_stor", "E_loss"), "time": ("t", "E_relax"), "shift": ("T", "log_aT")}
POSITIVE = ("f", "t", "E_stor", "E_loss", "E_relax")


@dataclass
class DMATable:
    """A read file: ``kind`` (frequency, time or shift), columns in SI (Hz, s, Pa, deg C), the path."""

    kind: str
    columns: dict
    path: str

    @property
    def is_raw(self) -> bool:
        return "T" in self.columns and "Set" in self.columns and self.kind != "shift"


def _where(path, line, col=None):
    return f"{path}, line {line}" + (f", column {col!r}" if col is not None else "")


def read_table(path) -> DMATable:
    """Read and check a DMA/shift-factor CSV (module docstring); errors name file, line and column."""
    path = Path(path)
    rows = read_rows(path, "DMA file")
    header = [h.strip() for h in rows[0]]
    kind = next((k for k, cols in KINDS.items() if set(cols) <= set(header)), None)
    allowed = set().union(*KINDS.values(), {"Set"})
    unknown = [h for h in header if h not in allowed]
    if kind is None or unknown:
        raise ValueError(f"{_where(path, 1)}: columns {header}: expected f,E_stor,E_loss (frequency), t,E_relax "
                         f"(time) or T,log_aT (shift factors), optionally with T,Set"
                         + (f"; unknown (misspelt?) columns {unknown}" if unknown else ""))
    if kind != "shift" and ("T" in header) != ("Set" in header):
        raise ValueError(f"{_where(path, 1)}: a raw multi-temperature set needs both T and Set columns")
    # T: the unit's value is an offset to deg C; every other column's a factor to SI
    scale, start = units_row(path, rows, header, UNITS, {h: 0.0 if h == "T" else 1.0 for h in header})
    values = {h: [] for h in header}
    for lineno, row in data_rows(path, rows, header, start):
        for h, cell in zip(header, row):
            v = cell_number(path, lineno, h, cell)
            if h in POSITIVE and not v > 0:
                raise ValueError(f"{_where(path, lineno, h)}: {cell.strip()} must be > 0")
            values[h].append(v * scale[h] if h != "T" else v + scale[h])
    if not values[header[0]]:
        raise ValueError(f"{path}: no data rows")
    cols = {h: np.array(v) for h, v in values.items()}
    if kind == "shift":
        order = np.argsort(cols["T"])
        d = np.diff(cols["log_aT"][order])
        if np.any(np.diff(cols["T"][order]) == 0) or not (np.all(d < 0) or np.all(d > 0)):
            i = int(np.argmax(d >= 0)) if np.any(d >= 0) else 0
            line = int(order[i + 1]) + start + 1
            raise ValueError(f"{_where(path, line, 'log_aT')}: shift factors must be strictly monotone in T "
                             f"(log_aT falls as T rises), and temperatures distinct")
    return DMATable(kind, cols, str(path))


@dataclass
class Superposition:
    """Per-set temperatures (deg C) and log10 a_T, the reference temperature, the master curve
    (f_reduced = f a_T in Hz, E', E'' in Pa), and how well the sets superpose (rms of log10 E'
    mismatch in the overlaps of adjacent sets)."""

    T: np.ndarray
    log_aT: np.ndarray
    T_ref: float
    f_reduced: np.ndarray
    E_stor: np.ndarray
    E_loss: np.ndarray
    source: str
    overlap_rms: float = math.nan
    notes: list = field(default_factory=list)
    #: temperature (deg C) of the set of each master-curve point (None: a master curve as given)
    T_point: np.ndarray | None = None


def set_arrays(raw: DMATable) -> list:
    """The raw sets of a table as (T [deg C, mean of the set's T column], f [Hz], E' [Pa], E'' [Pa]),
    frequencies ascending, sets by temperature; ValueError naming the file unless the table holds raw
    frequency data at two or more temperatures."""
    if raw.kind != "frequency" or not raw.is_raw:
        raise ValueError(f"{raw.path}: superposition needs raw frequency data with T and Set columns")
    c = raw.columns
    out = []
    for s in np.unique(c["Set"]):
        m = c["Set"] == s
        order = np.argsort(c["f"][m])
        out.append((float(np.mean(c["T"][m])), c["f"][m][order], c["E_stor"][m][order], c["E_loss"][m][order]))
    out.sort(key=lambda x: x[0])
    if len(out) < 2:
        raise ValueError(f"{raw.path}: superposition needs sets at two or more temperatures, got {len(out)}")
    return out


def _pair_shift(fa, ea, fb, eb):
    """log10 shift d such that set b at f 10^d overlays set a in E': the mean gap in log f at equal
    log E' over the E' range both sets cover (None when they share none), each gap weighted by the
    local slope squared (its inverse variance: where E' is flat a gap is mostly noise). In flat
    regions (glassy, rubbery plateaus) the shift is still ill-conditioned; the overlap residual of
    :func:`superpose` shows how well the sets lie on one curve."""
    la, lb = np.log10(ea), np.log10(eb)
    lo, hi = max(la.min(), lb.min()), min(la.max(), lb.max())
    if not lo < hi:
        return None
    grid = np.linspace(lo, hi, 25)
    xa = np.interp(grid, np.maximum.accumulate(la), np.log10(fa))
    xb = np.interp(grid, np.maximum.accumulate(lb), np.log10(fb))
    # a gap read where E' is flat carries noise / slope: weight each by slope^2 (inverse variance)
    ga, gb = np.gradient(xa, grid), np.gradient(xb, grid)
    w = 1.0 / (ga**2 + gb**2 + 1e-12)
    return float(np.sum(w * (xa - xb)) / np.sum(w))


def check_data(raw: DMATable, shifts: DMATable | None = None) -> None:
    """What a fit needs of its files, checked before fitting: frequency-domain data; raw sets at two or
    more temperatures; a shift-factor file (T, log_aT) covering the sets' temperatures."""
    if raw.kind != "frequency":
        raise ValueError(f"{raw.path}: measured-data fits take frequency-domain data (f,E_stor,E_loss)")
    if shifts is not None and shifts.kind != "shift":
        raise ValueError(f"{shifts.path}: not a shift-factor file (T,log_aT)")
    if not raw.is_raw:
        return
    T = np.array([s[0] for s in set_arrays(raw)])
    if shifts is not None:
        ts = shifts.columns["T"]
        if T.min() < ts.min() - 0.5 or T.max() > ts.max() + 0.5:
            raise ValueError(f"{shifts.path}: shift factors cover {ts.min():g}..{ts.max():g} deg C, the sets "
                             f"{T.min():g}..{T.max():g} deg C")


@threadpool_limits.wrap(limits=1, user_api="blas")  # many small solves (vcor.fitting.dmafit)
def superpose(raw: DMATable, T_ref: float, shifts: DMATable | None = None, *, log_aT=None,
              source: str | None = None, lag: float = 0.0) -> Superposition:
    """Master curve at ``T_ref`` (deg C) from raw sets, with ``shifts`` (a shift-factor table), with
    ``log_aT`` (per set, ascending temperature, decades; ``source`` says where they come from) or with
    shift factors found from the data pairwise (module docstring). ``lag`` (s): an instrument's time lag
    between force and displacement, removed from every point, E* exp(-i 2 pi f lag) with f the measured
    frequency (:func:`vcor.fitting.spectrum.fit_with_shifts` fits it)."""
    sets = set_arrays(raw)
    T = np.array([s[0] for s in sets])
    notes = []
    if log_aT is not None:
        log_aT = np.asarray(log_aT, dtype=float)
        if log_aT.shape != T.shape:
            raise ValueError(f"{raw.path}: {T.size} sets need {T.size} shift factors, got {log_aT.size}")
        source = source or "given per set"
    elif shifts is not None:
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
        log_aT = table_log_aT(ts, ls, T) - table_log_aT(ts, ls, T_ref)
        source = f"given ({shifts.path}), PCHIP in T, zero at T_ref"
    else:
        steps = []
        for (ta, fa, ea, _), (tb, fb, eb, _) in itertools.pairwise(sets):
            d = _pair_shift(fa, ea, fb, eb)
            if d is None:
                raise ValueError(f"{raw.path}: the sets at {ta:.4g} and {tb:.4g} deg C share no E' range: "
                                 f"their shift cannot be found from the data; give shift factors")
            steps.append(d)
        cum = np.concatenate(([0.0], np.cumsum(steps)))  # log10 f shift of each set onto the coldest
        # a_T of set k: f_reduced = f a_T; shifting set k by 10^cum onto the coldest set means
        # log a_T(k) = cum_k + const; zero at T_ref (interpolated)
        log_aT = cum - np.interp(T_ref, T, cum)
        source = "found from the data (E' overlaps of adjacent sets)"
    fr, es, el, tp, mism = [], [], [], [], []
    for (t, f, e1, e2), la in zip(sets, log_aT):
        if lag:
            e = (e1 + 1j * e2) * np.exp(-2j * math.pi * f * lag)
            if np.any(e.imag <= 0):
                raise ValueError(f"{raw.path}: the set at {t:.4g} deg C has a loss angle below the instrument lag's "
                                 f"phase (2 pi f x {lag:.3g} s) at {f[e.imag <= 0].min():.4g} Hz: the lag does not "
                                 f"describe these data")
            e1, e2 = e.real, e.imag
        fr.append(f * 10.0**la)
        es.append(e1)
        el.append(e2)
        tp.append(np.full(f.size, t))
    for (fa, ea), (fb, eb) in itertools.pairwise(zip(fr, es)):
        lo, hi = max(fa.min(), fb.min()), min(fa.max(), fb.max())
        if lo < hi:
            g = np.geomspace(lo, hi, 10)
            mism.append(np.interp(np.log10(g), np.log10(fa), np.log10(ea))
                        - np.interp(np.log10(g), np.log10(fb), np.log10(eb)))
    rms = float(np.sqrt(np.mean(np.concatenate(mism) ** 2))) if mism else math.nan
    fr, es, el, tp = map(np.concatenate, (fr, es, el, tp))
    order = np.argsort(fr, kind="stable")
    return Superposition(T, log_aT, float(T_ref), fr[order], es[order], el[order], source, rms, notes, tp[order])


def wlf_fit(T, log_aT, T_ref):
    """(C1, C2 in K, residuals) of the WLF law through per-set log a_T (least squares)."""
    from scipy.optimize import least_squares

    T, y = np.asarray(T, dtype=float), np.asarray(log_aT, dtype=float)
    dT = T - T_ref
    lo = max(1e-3, -dT.min() + 1e-3)  # C2 + T - T_ref > 0 for every set

    def res(p):
        return wlf_log_aT(T, T_ref, p[0], p[1]) - y

    fit = least_squares(res, x0=[17.44, max(51.6, 2 * lo)], bounds=([0.0, lo], [np.inf, np.inf]))
    return float(fit.x[0]), float(fit.x[1]), res(fit.x)


def arrhenius_fit(T, log_aT, T_ref):
    """(activation energy E_a in J/mol, residuals): log10 a_T = E_a / (R ln 10) (1/T - 1/T_ref), T in K."""
    x = 1.0 / (np.asarray(T, dtype=float) + 273.15) - 1.0 / (T_ref + 273.15)
    y = np.asarray(log_aT, dtype=float)
    slope = float(x @ y / (x @ x))
    return slope * GAS_CONSTANT * math.log(10.0), slope * x - y


@threadpool_limits.wrap(limits=1, user_api="blas")
def fit_master(sp: Superposition, n_terms: int | None = None):
    """Prony fit (``vcor.fitting.prony.fit_prony``) of the master curve E*(omega = 2 pi f_reduced) at T_ref.
    ``n_terms`` defaults to one term per decade of reduced frequency (a tolerance on the worst error
    would chase the noise of measured data). Returns the FitResult (metrics: worst and RMS relative
    errors of ``|E*|`` and tan delta)."""
    data = FitData(omega=2 * math.pi * sp.f_reduced, E_star=sp.E_stor + 1j * sp.E_loss, name="master curve",
                        measured=True)
    n = n_terms or max(1, math.ceil(math.log10(sp.f_reduced.max() / sp.f_reduced.min())))
    return fit_prony(data, n_terms=n)
