"""Smooth relaxation spectra of complex-modulus data, in modules of one idea each.

* :mod:`~vcor.fitting.spectrum.model`: the Prony model on a log grid, E*, E(t), metrics;
* :mod:`~vcor.fitting.spectrum.residual`: the one residual and Jacobian every fit shares;
* :mod:`~vcor.fitting.spectrum.smooth`: the smooth fit (log-spectrum, roughness penalty);
* :mod:`~vcor.fitting.spectrum.lam`: the choice of its regularisation parameter;
* :mod:`~vcor.fitting.spectrum.leverage`: the leverages of the data points;
* :mod:`~vcor.fitting.spectrum.modes`: the merge into a few modes per decade;
* :mod:`~vcor.fitting.spectrum.lm`: the Levenberg-Marquardt solver of the fits.

The joint fit of a spectrum with the shift factors of temperature sets, which shares the residual, is
:mod:`vcor.fitting.dma.joint`.
"""

from .lam import GCV_GAMMA, LAM_GRID
from .leverage import leverage
from .model import (
    MARGIN,
    N_DENSE,
    PER_DECADE,
    complex_modulus,
    count_extrema,
    fit_metrics,
    relaxation_modulus,
    shift_derivative,
    tau_grid,
)
from .modes import ReducedModes, reduce_modes
from .smooth import SpectrumFit, component_weights, fit_spectrum, loss_weights

__all__ = ["GCV_GAMMA", "LAM_GRID", "MARGIN", "N_DENSE", "PER_DECADE", "ReducedModes",
           "SpectrumFit", "complex_modulus", "component_weights", "count_extrema", "fit_metrics", "fit_spectrum",
           "leverage", "loss_weights", "reduce_modes", "relaxation_modulus", "shift_derivative",
           "tau_grid"]
