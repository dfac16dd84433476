"""Synthetic DMA data shared by the tests (importable from every test folder: pytest puts the folder of
tests/conftest.py on sys.path): a known Prony material shifted by WLF (C1 = 8.86,
C2 = 101.6 K, T_ref = 20 deg C), five sets at -10..50 deg C, ten frequencies 0.1..100 Hz, multiplicative
normal noise on E' and E''. Two materials: ``SPARSE`` (5 terms, rates over six decades; its tan delta
ripples between the terms, which a smooth-spectrum fit does not follow) and ``SMOOTH`` (17 terms, two per
decade over 1..1e8 1/s, a log-normal spectrum centred at 1e4 1/s, 1.5 decades wide). ``lag`` (s) adds an
instrument's time lag between force and displacement: every point's E* times exp(i 2 pi f lag)."""

import numpy as np

from vcor.fitting import spectrum
from vcor.materials.shift import wlf_log_aT

E_INF = 2e6
E5 = np.array([5e6, 20e6, 60e6, 150e6, 400e6])
BETA5 = 10.0 ** np.linspace(1, 7, 5)
SPARSE = (E_INF, E5, BETA5)
RATES17 = 10.0 ** np.arange(0.0, 8.01, 0.5)
_W17 = np.exp(-(np.log10(RATES17) - 4.0) ** 2 / (2 * 1.5**2))
SMOOTH = (E_INF, 600e6 * _W17 / _W17.sum(), RATES17)
T_REF, C1, C2 = 20.0, 8.86, 101.6
TEMPS = np.linspace(-10, 50, 5)
TRUE = wlf_log_aT(TEMPS, T_REF, C1, C2)
FREQ = np.geomspace(0.1, 100, 10)  # Hz


def synthetic(seed=0, noise=0.01, temps=TEMPS, f=FREQ, *, material=SPARSE, lag=0.0):
    """Columns f [Hz], E_stor, E_loss [Pa], T [deg C], Set of the known ``material`` (E_inf [Pa], E [Pa],
    beta [1/s])."""
    rng = np.random.default_rng(seed)
    e_inf, e_j, beta = material
    cols = {k: [] for k in ("f", "E_stor", "E_loss", "T", "Set")}
    for k, T in enumerate(temps):
        e = spectrum.complex_modulus(2 * np.pi * f * 10 ** wlf_log_aT(T, T_REF, C1, C2), e_inf, e_j, 1 / beta)
        e = e * np.exp(2j * np.pi * f * lag)
        n = 1 + noise * rng.standard_normal((2, f.size))
        cols["f"] += list(f)
        cols["E_stor"] += list(e.real * n[0])
        cols["E_loss"] += list(e.imag * n[1])
        cols["T"] += [T] * f.size
        cols["Set"] += [k] * f.size
    return {k: np.array(v) for k, v in cols.items()}


def write_csv(path, cols):
    """The columns as a pyvisco-style raw CSV (MPa)."""
    rows = ["f,E_stor,E_loss,T,Set", "Hz, MPa, MPa, C, -"]
    rows += [f"{f:.17g},{a / 1e6:.17g},{b / 1e6:.17g},{t:.17g},{int(s)}"
             for f, a, b, t, s in zip(cols["f"], cols["E_stor"], cols["E_loss"], cols["T"], cols["Set"])]
    path.write_text("\n".join(rows) + "\n")
    return path
