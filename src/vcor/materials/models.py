"""Linear viscoelastic relaxation models (uniaxial moduli, SI units: Pa, s, rad/s): every built-in
model, registered, under one name.

The contract every model fulfils and the registry are in :mod:`vcor.materials.base`; one module per
model family:

* :class:`~vcor.materials.prony.Prony` (``prony``): :mod:`vcor.materials.prony`;
* :class:`~vcor.materials.sls.SLS` (``sls``, a one-term Prony): :mod:`vcor.materials.sls`;
* :class:`~vcor.materials.elastic.Elastic` (``elastic``, a Prony without terms): :mod:`vcor.materials.elastic`;
* :class:`~vcor.materials.fractional.FractionalPower` (``fractional``): :mod:`vcor.materials.fractional`;
* :class:`~vcor.materials.cerf.Cerf` (``cerf``): :mod:`vcor.materials.cerf`;
* :class:`~vcor.materials.kelvin_voigt.KelvinVoigt` (``kelvin-voigt``): :mod:`vcor.materials.kelvin_voigt`;
* :class:`~vcor.materials.eq_one.EqOne` (``eq1``, two bodies, Green 2026 Eq. 1): :mod:`vcor.materials.eq_one`;
* :class:`~vcor.materials.expfit.ExponentialSum` (``exponential-sum``, the solvers' fit of a modulus with
  terms of either sign, not a material): :mod:`vcor.materials.expfit`.

Importing this module registers them all; :data:`~vcor.materials.base.REGISTRY` then maps each kind to its
:class:`~vcor.materials.base.Family` (class, title, formula, parameters with units).
Presets (Green 2026, Eqs. 14, 23b, 24, 26) are in :mod:`vcor.materials.presets`.

Examples
--------
>>> from vcor.materials.models import REGISTRY
>>> REGISTRY["cerf"].names
('E0', 'E1', 'b1')
>>> REGISTRY["fractional"].unit("E1")
'Pa s0.5'
>>> REGISTRY["sls"].cls(15e6, 300.0, 1200.0).rubbery  # E_glassy alpha / beta, Pa
3750000.0
"""

from __future__ import annotations

from .base import REGISTRY, Family, Material, Parameter, from_dict
from .cerf import Cerf
from .elastic import Elastic
from .eq_one import EqOne
from .expfit import ExponentialSum
from .fractional import FractionalPower
from .kelvin_voigt import KelvinVoigt
from .prony import Prony
from .sls import SLS

__all__ = [
    "REGISTRY",
    "SLS",
    "Cerf",
    "Elastic",
    "EqOne",
    "ExponentialSum",
    "Family",
    "FractionalPower",
    "KelvinVoigt",
    "Material",
    "Parameter",
    "Prony",
    "from_dict",
]
