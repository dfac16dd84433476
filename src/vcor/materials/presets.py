"""The paper's materials by name (Green 2026, Eqs. 14, 23b, 24, 26), plus two limits.

=================  =======================================================================
name               model
=================  =======================================================================
``sls``            SLS, E_g = 15 MPa, alpha = 300 1/s, beta = 1200 1/s (Eq. 14)
``butyl-fc``       Bagley-Torvik Butyl B252, E0 + E1/sqrt(pi t), order 1/2 (Eq. 23b)
``butyl-cerf``     the paper's CERF fit of it (Eq. 24)
``butyl-prony3``   Szumski's 3-term Prony fit (Eq. 26)
``elastic``        the SLS glassy modulus without relaxation, 15 MPa (the elastic-limit check)
``kelvin-voigt``   E = 15 MPa, tau = 0.1 ms: illustrative, not from a paper
=================  =======================================================================
"""

from __future__ import annotations

import functools

from .models import SLS, Cerf, Elastic, FractionalPower, KelvinVoigt, Material, Prony

__all__ = ["PRESETS", "get"]

PRESETS = {
    "sls": lambda: SLS(15e6, 300.0, 1200.0),
    "butyl-fc": lambda: FractionalPower(3 * 7.6e5, 3 * 2.95e5),
    "butyl-cerf": lambda: Cerf(0.442e6, 0.6765e9, 700.0),
    "butyl-prony3": lambda: Prony(10.421e6, (20.181e6, 38.204e6, 87.344e6), (972.0, 6426.0, 34221.0)),
    "elastic": lambda: Elastic(15e6),
    "kelvin-voigt": lambda: KelvinVoigt(15e6, 1e-4),
}


def get(name: str) -> Material:
    """Preset material by name (see ``PRESETS``); a Material is returned as it is."""
    if isinstance(name, Material):
        return name
    if not isinstance(name, str) or name not in PRESETS:
        raise ValueError(
            f"unknown material {name!r}; allowed presets: {sorted(PRESETS)} "
            "(fitted materials: vcor.materials.from_file)"
        )
    return _preset(name)


@functools.cache
def _preset(name: str) -> Material:
    # materials are frozen: one object per preset serves every call (and keys the solvers' caches)
    return PRESETS[name]()
