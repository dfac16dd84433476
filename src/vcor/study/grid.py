"""A scene's grid as typed axes, and its points with an integer index.

A grid is the product of the scene's materials and its axes. Every axis has a name, sorted unique
values, a unit, a long name and a *role*, decided here and nowhere else (:func:`axis_role`):

* ``speed``: ``v0``, the impact speed (m/s);
* ``temperature``: ``T`` (deg C), through the material's shift function;
* ``sample``: the bootstrap sample of an uncertainty scene (:mod:`vcor.study.uncertainty`);
* ``geometry``: a geometry keyword of :func:`vcor.simulate` (:data:`vcor.contact.impact.GEOMETRY_AXES`);
* ``material``: any other name, a scalar parameter of the scene's materials.

Point ``i`` of a grid is ``numpy.unravel_index(i, grid.shape)`` over ``(material, *axes)``: the
material varies slowest, the last axis fastest. A point is a mapping ``{index, material, <axis>:
value, ...}``; :func:`point_key` names it without its index (the index moves when a grid is
extended; the key does not), which is what shards are addressed by.

Axis values are given as a list or a range ``{start, stop, step}`` (stop inclusive) /
``{start, stop, num[, log]}``. A list that names a value twice is refused (a grid point is computed
once); values are stored with 12 significant digits (:func:`canon`), so that ``0.1 * 3`` and ``0.3``
are one value.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass

import numpy as np

from ..contact.impact import GEOMETRY_AXES

__all__ = [
    "AXIS_UNITS",
    "MAX_AXIS_VALUES",
    "ROLES",
    "Axis",
    "Grid",
    "axis_error",
    "axis_length",
    "axis_role",
    "axis_values",
    "canon",
    "first_below",
    "point_key",
]

#: the most values one grid axis may have
MAX_AXIS_VALUES = 100_000

#: what an axis is to a point (module docstring)
ROLES = ("speed", "temperature", "sample", "geometry", "material")

#: unit (UDUNITS) and long name of every axis name vcor knows; a material parameter not listed is "1"
AXIS_UNITS = {
    "v0": ("m s-1", "impact speed"),
    "r": ("m", "sphere radius"),
    "rho_a": ("kg m-3", "sphere density"),
    "rho_b": ("kg m-3", "plate density"),
    "h": ("m", "plate half-thickness"),
    "nu": ("1", "Poisson ratio of the viscoelastic body"),
    "E_plate": ("Pa", "elastic plate modulus (case 4)"),
    "nu_plate": ("1", "plate Poisson ratio (case 4)"),
    "beta": ("s-1", "relaxation (decay) rate"),
    "alpha": ("s-1", "SLS rate alpha (rubbery/glassy = alpha/beta)"),
    "E_glassy": ("Pa", "glassy modulus"),
    "E0": ("Pa", "rubbery modulus"),
    "E1": ("Pa", "relaxing modulus"),
    "E": ("Pa", "modulus"),
    "E_inf": ("Pa", "rubbery modulus"),
    "b1": ("s-1/2", "CERF rate parameter"),
    "tau": ("s", "retardation time"),
    "T": ("degC", "temperature (materials with a shift function: E(t; T) = E(t / a_T))"),
    "sample": ("1", "bootstrap sample of the fitted materials (scenes with uncertainty)"),
}


def axis_role(name: str) -> str:
    """The role of an axis name (module docstring): the one place that decides it.

    Examples
    --------
    >>> from vcor.study.grid import axis_role
    >>> [axis_role(name) for name in ("v0", "T", "r", "beta")]
    ['speed', 'temperature', 'geometry', 'material']
    """
    if name == "v0":
        return "speed"
    if name == "T":
        return "temperature"
    if name == "sample":
        return "sample"
    if name in GEOMETRY_AXES:
        return "geometry"
    return "material"


def canon(v) -> float:
    """Canonical float (12 significant digits) so that 0.1 * 3 and 0.3 name the same point.

    Examples
    --------
    >>> from vcor.study.grid import canon
    >>> 0.1 * 3 == 0.3, canon(0.1 * 3) == canon(0.3)
    (False, True)
    """
    return float(f"{float(v):.12g}")


def _finite(what, v) -> float:
    said = f"{what}: must" if what.startswith("[") else f"{what} must"  # an element: "[2]: must" (axis_error)
    if isinstance(v, (bool, str, bytes)) or v is None:
        raise ValueError(f"{said} be a finite number, got {v!r}")
    try:
        x = float(v)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"{said} be a finite number, got {v!r}") from None
    if not math.isfinite(x):
        raise ValueError(f"{said} be a finite number, got {x!r}")
    return x


def _range_length(spec: dict) -> int:
    unknown = set(spec) - {"start", "stop", "step", "num", "log"}
    if unknown or not {"start", "stop"} <= set(spec) or ("step" in spec) == ("num" in spec):
        raise ValueError(f"an axis range is {{start, stop, step}} or {{start, stop, num[, log]}}, got {spec!r}")
    start, stop = _finite("start", spec["start"]), _finite("stop", spec["stop"])
    if "step" in spec:
        step = _finite("step", spec["step"])
        if not step > 0:
            raise ValueError(f"step must be > 0, got {step}")
        if stop < start:
            raise ValueError(f"the range is empty: stop {stop} < start {start}")
        return math.floor((stop - start) / step + 1e-9) + 1
    num = spec["num"]
    if isinstance(num, bool) or not isinstance(num, (int, np.integer)) or num < 1:
        raise ValueError(f"num must be an integer >= 1, got {num!r}")
    if "log" in spec and not isinstance(spec["log"], bool):
        raise ValueError(f"log must be true or false, got {spec['log']!r}")
    if spec.get("log") and not (start > 0 and stop > 0):
        raise ValueError(f"a log range needs start and stop > 0, got {start}, {stop}")
    if num == 1 and stop != start:
        raise ValueError(f"num 1 gives start ({start:g}) alone and leaves stop ({stop:g}) out: give num >= 2, or "
                         f"the one value as a list [{start:g}]")
    return int(num)


def axis_length(spec) -> int:
    """The number of values of an axis spec before they are built; ValueError for a spec that is not
    a list of numbers or a range (module docstring)."""
    if isinstance(spec, dict):
        return _range_length(spec)
    if isinstance(spec, (str, bytes)) or not isinstance(spec, (list, tuple, np.ndarray, int, float)):
        raise ValueError(f"an axis is a list of numbers or a range {{start, stop, step}} / "
                         f"{{start, stop, num[, log]}}, got {spec!r}")
    # a list as it is: numpy would turn [1, "3 m/s"] into text throughout
    values = list(spec) if isinstance(spec, (list, tuple)) else list(np.atleast_1d(spec))
    if not values:
        raise ValueError("the axis is empty (give at least one value)")
    for i, v in enumerate(values):
        _finite(f"[{i}]", v)
    return len(values)


def axis_error(name: str, exc: Exception) -> str:
    """The message of an axis spec's ValueError ``exc`` under the axis' ``name`` (or path): ``v0[2]: must be
    ...`` for an element's, ``v0: ...`` for the axis'."""
    said = str(exc)
    return f"{name}{said}" if said.startswith("[") else f"{name}: {said}"


def first_below(spec, bound: float) -> str:
    """``[i]``, the index of the first element of a listed axis ``spec`` at or below ``bound``; "" for a range
    or where none is (the axis' own checks have passed: every element is a finite number)."""
    if isinstance(spec, dict):
        return ""
    return next((f"[{i}]" for i, v in enumerate(np.atleast_1d(spec)) if float(v) <= bound), "")


def axis_values(spec) -> list[float]:
    """Grid axis values from a list or a range (module docstring): sorted unique floats. ValueError on
    NaN, infinities, booleans, an empty axis, a value listed twice or an axis longer than
    MAX_AXIS_VALUES.

    Examples
    --------
    >>> from vcor.study.grid import axis_values
    >>> axis_values([10, 1, 5])
    [1.0, 5.0, 10.0]
    >>> axis_values({"start": 0.1, "stop": 0.3, "step": 0.1})
    [0.1, 0.2, 0.3]
    >>> axis_values({"start": 1, "stop": 100, "num": 3, "log": True})
    [1.0, 10.0, 100.0]
    >>> axis_values([1, 1.0])
    Traceback (most recent call last):
    ...
    ValueError: 1 listed more than once; give each value once
    """
    n = axis_length(spec)
    if n > MAX_AXIS_VALUES:
        raise ValueError(f"{n} values, more than the {MAX_AXIS_VALUES} one axis may have")
    if isinstance(spec, dict):
        start, stop = float(spec["start"]), float(spec["stop"])
        if "step" in spec:
            vals = [start + i * float(spec["step"]) for i in range(n)]
        else:
            vals = list(np.geomspace(start, stop, n) if spec.get("log") else np.linspace(start, stop, n))
    else:
        vals = [float(v) for v in np.atleast_1d(spec)]
    canonical = [canon(v) for v in vals]
    if len(set(canonical)) < len(canonical):
        twice = sorted({v for v in canonical if canonical.count(v) > 1})
        raise ValueError(f"{_fmt(twice)} listed more than once; give each value once")
    return sorted(canonical)


def _fmt(values) -> str:
    return ", ".join(f"{v:g}" for v in values)


@dataclass(frozen=True, kw_only=True)
class Axis:
    """One grid axis: ``name``, sorted unique ``values``, ``role`` (:data:`ROLES`), ``unit`` and
    ``long_name``.

    Examples
    --------
    >>> from vcor.study.grid import Axis
    >>> a = Axis.of("T", [20.0, 40.0])
    >>> a.role, a.unit, a.values
    ('temperature', 'degC', (20.0, 40.0))
    """

    name: str
    values: tuple
    role: str
    unit: str
    long_name: str

    @classmethod
    def of(cls, name: str, values) -> Axis:
        """The axis ``name`` with ``values`` (already canonical), its role and unit looked up."""
        unit, long_name = AXIS_UNITS.get(name, ("1", name))
        return cls(name=name, values=tuple(float(v) for v in values), role=axis_role(name), unit=unit,
                   long_name=long_name)

    def to_dict(self) -> dict:
        return {"name": self.name, "values": list(self.values), "role": self.role, "unit": self.unit,
                "long_name": self.long_name}


@dataclass(frozen=True, kw_only=True)
class Grid:
    """The materials and axes of a scene's sweep (module docstring).

    Examples
    --------
    >>> from vcor.study.grid import Grid
    >>> grid = Grid.from_scene({"materials": ["sls", "butyl-fc"],
    ...                         "grid": {"v0": [1, 10], "r": {"start": 0.005, "stop": 0.01, "num": 2}}})
    >>> grid.shape, grid.size, [(a.name, a.role, a.unit) for a in grid.axes]
    ((2, 2, 2), 8, [('v0', 'speed', 'm s-1'), ('r', 'geometry', 'm')])
    >>> grid.point(5)
    {'index': 5, 'material': 'butyl-fc', 'v0': 1.0, 'r': 0.01}
    >>> grid.index_of({"material": "butyl-fc", "v0": 1.0, "r": 0.01})
    5
    """

    materials: tuple
    axes: tuple

    @classmethod
    def from_scene(cls, scene: dict, samples: int | None = None) -> Grid:
        """The grid of a scene's config (``materials``, ``grid``; ``samples`` bootstrap samples add the
        ``sample`` axis); ValueError naming the axis (``<axis>: ...``) otherwise."""
        spec = scene.get("grid") or {}
        if "v0" not in spec:
            raise ValueError("the grid must contain 'v0' (m/s)")
        axes = []
        for name, values in spec.items():
            try:
                axes.append(Axis.of(name, axis_values(values)))
            except ValueError as exc:
                raise ValueError(axis_error(name, exc)) from None
        if samples is not None:
            axes.append(Axis.of("sample", [float(k) for k in range(samples)]))
        return cls(materials=tuple(scene.get("materials") or ()), axes=tuple(axes))

    @classmethod
    def from_dict(cls, d: dict) -> Grid:
        """The grid :meth:`to_dict` wrote (what a job receives; nothing is parsed again)."""
        return cls(materials=tuple(d["materials"]), axes=tuple(Axis(**{**a, "values": tuple(a["values"])})
                                                               for a in d["axes"]))

    def to_dict(self) -> dict:
        return {"materials": list(self.materials), "axes": [a.to_dict() for a in self.axes]}

    # -- shape and lookup ------------------------------------------------------------------------
    @property
    def names(self) -> list[str]:
        return [a.name for a in self.axes]

    @property
    def shape(self) -> tuple:
        return (len(self.materials),) + tuple(len(a.values) for a in self.axes)

    @property
    def size(self) -> int:
        return int(np.prod(self.shape))

    def axis(self, name: str) -> Axis:
        for a in self.axes:
            if a.name == name:
                return a
        raise KeyError(name)

    def values(self) -> dict[str, list[float]]:
        """{axis name: values}, in config order."""
        return {a.name: list(a.values) for a in self.axes}

    def of_role(self, role: str) -> list[Axis]:
        return [a for a in self.axes if a.role == role]

    # -- points ----------------------------------------------------------------------------------
    def point(self, index: int) -> dict:
        """Point ``index`` (module docstring)."""
        pos = np.unravel_index(int(index), self.shape)
        out = {"index": int(index), "material": self.materials[pos[0]]}
        for a, i in zip(self.axes, pos[1:]):
            out[a.name] = a.values[i]
        return out

    def points(self) -> list[dict]:
        """Every point, in index order (as :meth:`point` gives them, built for all at once)."""
        pos = np.unravel_index(np.arange(self.size), self.shape)
        names = ["material", *(a.name for a in self.axes)]
        columns = [[self.materials[i] for i in pos[0].tolist()],
                   *([a.values[i] for i in p.tolist()] for a, p in zip(self.axes, pos[1:]))]
        return [{"index": i, **dict(zip(names, values))} for i, values in enumerate(zip(*columns))]

    def index_of(self, point: dict) -> int:
        """The index of a point given by its material and axis values (exact values, as the grid holds
        them); KeyError when the grid has no such point."""
        try:
            pos = [self.materials.index(point["material"])]
            pos += [a.values.index(float(point[a.name])) for a in self.axes]
        except ValueError:
            raise KeyError(point_key(point)) from None
        return int(np.ravel_multi_index(pos, self.shape))


def point_key(point: dict) -> str:
    """The name of a point without its index (module docstring): canonical JSON of the rest.

    Examples
    --------
    >>> from vcor.study.grid import point_key
    >>> point_key({"index": 7, "v0": 1.0, "material": "sls"})
    '{"material": "sls", "v0": 1.0}'
    """
    return _SORTED_JSON({k: v for k, v in point.items() if k != "index"})


#: ``json.dumps(obj, sort_keys=True)`` without building an encoder per call (the same text)
_SORTED_JSON = json.JSONEncoder(sort_keys=True).encode
