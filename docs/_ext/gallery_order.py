"""The order of the example gallery (sphinx-gallery's ``within_subsection_order``): a reader's path
from one impact to a study, then measured data and their uses."""

from __future__ import annotations

#: example files in reading order; a file not listed follows them, by name
ORDER = ["plot_first_impact.py", "plot_cor_against_speed.py", "plot_parameter_study.py", "plot_dma_fit.py",
         "plot_calibration.py", "plot_dem_export.py"]


class ExampleOrder:
    """Sort key of sphinx-gallery: constructed with the gallery's folder, called with a file name."""

    def __init__(self, src_dir):
        self.src_dir = src_dir

    def __call__(self, filename: str):
        return (ORDER.index(filename), "") if filename in ORDER else (len(ORDER), filename)

    def __repr__(self):
        return f"<{type(self).__name__}>"  # sphinx-gallery compares configurations by repr
