"""Materials: linear viscoelastic relaxation models, presets, config specs, temperature shifts,
exponential sums and the catalogue that resolves a material's name.

Every model gives E(t), dE/dt, E*(omega) (uniaxial, Pa) and the exact step integrals the solvers use;
see :mod:`vcor.materials.models`; :data:`REGISTRY` maps each model's name (``kind``) to its class and its
parameters with units.
"""

from .catalogue import Catalogue
from .files import from_file
from .models import (
           REGISTRY,
           SLS,
           Cerf,
           Elastic,
           EqOne,
           FractionalPower,
           KelvinVoigt,
           Material,
           Prony,
           from_dict,
)
from .presets import PRESETS, get

__all__ = ["PRESETS", "REGISTRY", "SLS", "Catalogue", "Cerf", "Elastic", "EqOne", "FractionalPower", "KelvinVoigt",
           "Material", "Prony", "from_dict", "from_file", "get"]
