"""Measured DMA data to a material at any temperature: one time-temperature package.

* :mod:`~vcor.fitting.dma.data`: reading and checking pyvisco's CSV files;
* :mod:`~vcor.fitting.dma.sets`: isothermal sets, and the master curve at given shift factors;
* :mod:`~vcor.fitting.dma.shifts`: start-free shift factors of all sets at once (P-spline master curves);
* :mod:`~vcor.fitting.dma.joint`: the shifts (and an instrument lag) refined together with a smooth spectrum;
* :mod:`~vcor.fitting.dma.laws`: WLF and Arrhenius fitted to the shifts, the shift function a fit stores;
* :mod:`~vcor.fitting.dma.pipeline`: the measured-data fit, raw sets to a Prony material
  (shifts refined with a smooth spectrum, :mod:`vcor.fitting.spectrum`).
"""

from .data import DMATable, check_data, read_table
from .joint import MAX_LAG_PHASE, JointFit, fit_with_shifts
from .laws import arrhenius_fit, shift_function, wlf_fit
from .pipeline import LOSS_WEIGHT, MODES_PER_DECADE, DMAFit, fit_curve, fit_dma, tan_delta_extrema
from .sets import QUANTITIES, DMASet, MasterCurve, given_shifts, master_curve, split_sets, superpose
from .shifts import ShiftResult, anchor_matrix, global_shifts, pairwise_shifts, superposition_rms

__all__ = ["LOSS_WEIGHT", "MAX_LAG_PHASE", "MODES_PER_DECADE", "QUANTITIES", "DMAFit", "DMASet", "DMATable",
           "JointFit", "MasterCurve", "ShiftResult", "anchor_matrix", "arrhenius_fit", "check_data", "fit_curve",
           "fit_dma", "fit_with_shifts", "given_shifts", "global_shifts", "master_curve", "pairwise_shifts",
           "read_table", "shift_function", "split_sets", "superpose", "superposition_rms", "tan_delta_extrema",
           "wlf_fit"]
