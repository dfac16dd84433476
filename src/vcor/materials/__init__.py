"""Materials: linear viscoelastic relaxation models, presets, config specs, temperature shifts,
exponential sums and the catalogue that resolves a material's name.

Every model gives E(t), dE/dt, E*(omega) (uniaxial, Pa) and the exact step integrals the solvers use;
see :mod:`vcor.materials.models`.
"""

from .catalogue import Catalogue
from .files import from_file
from .models import (
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

__all__ = ["PRESETS", "SLS", "Catalogue", "Cerf", "Elastic", "EqOne", "FractionalPower", "KelvinVoigt", "Material",
           "Prony", "from_dict", "from_file", "get"]
