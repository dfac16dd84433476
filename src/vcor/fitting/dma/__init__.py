"""Measured DMA data to a material at any temperature: one time-temperature package.

* :mod:`~vcor.fitting.dma.data`: reading and checking pyvisco's CSV files;
* :mod:`~vcor.fitting.dma.sets`: isothermal sets, and the master curve at given shift factors;
* :mod:`~vcor.fitting.dma.shifts`: start-free shift factors of all sets at once (P-spline master curves);
* :mod:`~vcor.fitting.dma.joint`: the shifts (and an instrument lag) refined together with a smooth spectrum;
* :mod:`~vcor.fitting.dma.laws`: WLF and Arrhenius fitted to the shifts, the shift function a fit stores;
* :mod:`~vcor.fitting.dma.pipeline`: the measured-data fit, raw sets to a Prony material
  (shifts refined with a smooth spectrum, :mod:`vcor.fitting.spectrum`).

Names load their module on first use (PEP 562): the workflow's planning reads the data checks
without loading the fitting's optimisers.
"""

from importlib import import_module

#: each public name and the module that defines it
_HOME = {
    "data": ("DMATable", "check_data", "read_table"),
    "joint": ("MAX_LAG_PHASE", "JointFit", "fit_with_shifts"),
    "laws": ("arrhenius_fit", "shift_function", "wlf_fit"),
    "pipeline": ("LOSS_WEIGHT", "MODES_PER_DECADE", "DMAFit", "fit_curve", "fit_dma", "tan_delta_extrema"),
    "sets": ("QUANTITIES", "DMASet", "MasterCurve", "given_shifts", "master_curve", "split_sets", "superpose"),
    "shifts": ("ShiftResult", "anchor_matrix", "global_shifts", "pairwise_shifts", "superposition_rms"),
}
_MODULE_OF = {name: module for module, names in _HOME.items() for name in names}

__all__ = sorted(_MODULE_OF)


def __getattr__(name):
    if name in _MODULE_OF:
        value = getattr(import_module(f"{__name__}.{_MODULE_OF[name]}"), name)
        globals()[name] = value  # loaded once
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
