"""Linear viscoelastic relaxation models (uniaxial moduli, SI units: Pa, s, rad/s): every built-in
model, registered, under one name.

The contract every model fulfils and the registry are in :mod:`vcor.materials.base`; one module per
model family:

=====================  ==============  =====================================================
class                  kind            module
=====================  ==============  =====================================================
:class:`Prony`         ``prony``       :mod:`vcor.materials.prony`
:class:`SLS`           ``sls``         :mod:`vcor.materials.sls` (a one-term Prony)
:class:`Elastic`       ``elastic``     :mod:`vcor.materials.elastic` (a Prony without terms)
:class:`FractionalPower` ``fractional`` :mod:`vcor.materials.fractional`
:class:`Cerf`          ``cerf``        :mod:`vcor.materials.cerf`
:class:`KelvinVoigt`   ``kelvin-voigt`` :mod:`vcor.materials.kelvin_voigt`
:class:`EqOne`         ``eq1``         :mod:`vcor.materials.eq_one` (two bodies, Green 2026 Eq. 1)
=====================  ==============  =====================================================

Importing this module registers them all; :data:`REGISTRY` then maps each kind to its
:class:`~vcor.materials.base.Family` (class, title, formula, parameters with units).
Presets (Green 2026, Eqs. 14, 23b, 24, 26) are in :mod:`vcor.materials.presets`.
"""

from __future__ import annotations

from .base import REGISTRY, Family, Material, Parameter, from_dict
from .cerf import Cerf
from .elastic import Elastic
from .eq_one import EqOne
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
    "Family",
    "FractionalPower",
    "KelvinVoigt",
    "Material",
    "Parameter",
    "Prony",
    "from_dict",
]
