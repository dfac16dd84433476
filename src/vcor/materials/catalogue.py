"""One catalogue that turns a material's name into the material, its shift function and its identity.

A name is, in this order of precedence (a config may not reuse a taken name):

* a preset (:mod:`vcor.materials.presets`),
* a config material (the ``materials:`` block; built from its spec, :mod:`vcor.materials.specs`),
* a fitted material (the ``fits:`` block; read from ``<material_dir>/<name>.nc``, written by the fit
  rule),
* a calibrated material (the ``calibrations:`` block; read likewise, written by the calibrate rule).

The *identity* of a material is a hash of what determines its parameters, not of its name or path:
a preset's or config material's resolved parameters (and shift function); for a fit, its spec, the
content of its data files and the code fingerprint (:func:`vcor.provenance.code_fingerprint`; fits
are deterministic, so this fixes the parameters before the file exists); for a calibration, its spec,
its data file's content, its start material's identity and the code. Shards name their points'
materials by identity, so a changed spec, table, data file or code recomputes exactly what it changes.
"""

from __future__ import annotations

import dataclasses
import difflib
import functools
import hashlib
import json
from dataclasses import dataclass, field
from pathlib import Path

from ..io.fileversion import version
from ..provenance import code_fingerprint
from .files import from_file
from .models import REGISTRY, Material, from_dict
from .presets import PRESETS, get
from .shift import ShiftFunction, at_temperature, shift_from_file
from .specs import from_spec, shift_function

__all__ = ["FIT_SCALARS", "SOURCES", "Catalogue", "content_hash", "file_digest", "with_parameters"]

#: where a name comes from, in order of precedence
SOURCES = ("preset", "config", "fit", "calibration")


def content_hash(obj, n: int = 12) -> str:
    """First ``n`` hex digits of the SHA-1 of ``obj`` as canonical JSON (sorted keys)."""
    return hashlib.sha1(json.dumps(obj, sort_keys=True, default=float).encode()).hexdigest()[:n]


def file_digest(path) -> str:
    """SHA-256 of a file's bytes, or "missing"."""
    path = Path(path)
    return hashlib.sha256(path.read_bytes()).hexdigest() if path.is_file() else "missing"


@functools.lru_cache(maxsize=64)
def _file_material(path: str, mtime_ns: int) -> Material:
    # read once per file version (a sweep resolves its material at every point; materials are immutable)
    return from_file(path)


@dataclass(frozen=True, kw_only=True)
class Catalogue:
    """Every material a project can name (module docstring). ``specs``: config materials (name ->
    spec); ``fits``: fit specs (name -> spec, names expanded); ``calibrations``: calibration specs;
    ``material_dir``: where fitted and calibrated files live; ``base_dir``: the folder relative paths
    in specs are taken from (the project folder)."""

    specs: dict = field(default_factory=dict)
    fits: dict = field(default_factory=dict)
    calibrations: dict = field(default_factory=dict)
    material_dir: str = "results/materials"
    base_dir: str = "."

    # -- names ---------------------------------------------------------------------------------
    def source(self, name: str) -> str:
        """"preset", "config", "fit" or "calibration"; ValueError naming the known names otherwise."""
        if isinstance(name, str):
            if name in PRESETS:
                return "preset"
            for source, block in (("config", self.specs), ("fit", self.fits), ("calibration", self.calibrations)):
                if name in block:
                    return source
        known = [*PRESETS, *self.specs, *self.fits, *self.calibrations]
        close = difflib.get_close_matches(str(name).lower(), known, n=1, cutoff=0.6)
        raise ValueError(f"unknown material {name!r}; presets {sorted(PRESETS)}"
                         + "".join(f", {label} {sorted(block)}" for label, block in
                                   (("config materials", self.specs), ("fits", self.fits),
                                    ("calibrations", self.calibrations)) if block)
                         + (f"; did you mean {close[0]!r}?" if close else ""))

    def subset(self, names) -> Catalogue:
        """The catalogue of ``names`` alone, with what they are built from (a calibration's start
        material), each block in name order: what a job that uses only these materials is given, so
        that adding, removing or reordering other materials of the config changes nothing it sees.
        Names that are not in a block (presets) need no entry."""
        keep, todo = set(), [n for n in names if isinstance(n, str)]
        while todo:
            name = todo.pop()
            if name not in keep:
                keep.add(name)
                start = (self.calibrations.get(name) or {}).get("material")
                if isinstance(start, str):
                    todo.append(start)

        def pick(block):
            return {k: block[k] for k in sorted(block) if k in keep}

        return Catalogue(specs=pick(self.specs), fits=pick(self.fits), calibrations=pick(self.calibrations),
                         material_dir=self.material_dir, base_dir=self.base_dir)

    def without_shifts(self) -> Catalogue:
        """The catalogue with the shift functions of its config materials left out: what the jobs of a scene
        without a temperature axis are given. Its materials are taken at their reference temperature, where
        no shift function enters a number, so that editing one (a WLF C1) re-runs none of its jobs; their
        identities are those of the same materials without a shift function. Fits and calibrations keep
        theirs (read from their files, part of what their identity covers)."""
        specs = {k: {key: v for key, v in spec.items() if key != "shift"} if isinstance(spec, dict) else spec
                 for k, spec in self.specs.items()}
        return dataclasses.replace(self, specs=specs)

    def check(self, name: str, where: str) -> None:
        """ValueError naming ``where`` unless ``name`` is known."""
        try:
            self.source(name)
        except ValueError as exc:
            raise ValueError(f"{where}: {exc}") from None

    def computed(self) -> set[str]:
        """Names whose material is computed by a workflow rule (fits and calibrations)."""
        return set(self.fits) | set(self.calibrations)

    def file_of(self, name: str) -> Path | None:
        """The material file of a fit or calibration (None for presets and config materials)."""
        return Path(self.material_dir) / f"{name}.nc" if self.source(name) in ("fit", "calibration") else None

    # -- materials -----------------------------------------------------------------------------
    def material(self, name: str, overrides: dict | None = None) -> Material:
        """The material of ``name`` with scalar parameters replaced by ``overrides`` (a grid's material
        axes); ValueError naming the parameter when the material has no such scalar parameter."""
        source = self.source(name)
        if source == "preset":
            mat = get(name)
        elif source == "config":
            mat = _config_material(json.dumps(self.specs[name], sort_keys=True), name, str(self.base_dir))
        else:
            path = self.file_of(name)
            key = version(path)
            if key is None:
                raise ValueError(f"material {name!r} ({source}) has no file {path} yet: it is computed by the "
                                 f"workflow's {'fit' if source == 'fit' else 'calibrate'} rule")
            mat = _file_material(*key)
        return with_parameters(mat, overrides, name) if overrides else mat

    def scalar_parameters(self, name: str) -> list[str]:
        """The scalar parameters a grid may sweep for ``name`` (``Material.params()`` names), known
        before a fit's or calibration's file exists: a fit has the scalars of its model (a Prony fit
        E_inf; a CERF fit E0, E1, b1), a calibration those of its start material."""
        source = self.source(name)
        if source == "fit":
            return list(FIT_SCALARS.get(self.fits[name].get("model", "prony"), ()))
        if source == "calibration":
            start = self.calibrations[name].get("material")
            if isinstance(start, str):
                return self.scalar_parameters(start)
            return _scalars(from_spec(start, name=name, base_dir=self.base_dir).to_dict())
        return _scalars(self.material(name).to_dict())

    def shift(self, name: str) -> ShiftFunction | None:
        """The material's shift function (config spec or material file), or None."""
        source = self.source(name)
        if source == "config":
            return shift_function(self.specs[name], name)
        if source in ("fit", "calibration") and self.file_of(name).is_file():
            return shift_from_file(self.file_of(name))
        return None

    def at(self, name: str, overrides: dict | None = None, T: float | None = None) -> Material:
        """The material with ``overrides``, at temperature ``T`` (deg C) when given."""
        mat = self.material(name, overrides)
        return mat if T is None else at_temperature(mat, self.shift(name), T, name)

    # -- identity and provenance -----------------------------------------------------------------
    def identity(self, name: str) -> str:
        """Content identity of the material (module docstring), 12 hex digits."""
        source = self.source(name)
        if source == "preset":
            return content_hash({"material": get(name).to_dict()})
        if source == "config":
            shift = self.shift(name)
            return content_hash({"material": self.material(name).to_dict(),
                                 "shift": shift.to_dict() if shift else None})
        if source == "fit":
            spec = self.fits[name]
            data = spec.get("data") or {}
            files = {k: file_digest(Path(self.base_dir) / data[k]) for k in ("file", "shift_file") if k in data}
            return content_hash({"fit": {"spec": spec, "files": files, "code": code_fingerprint()}})
        spec = self.calibrations[name]
        start = spec.get("material")
        return content_hash({"calibration": {
            "spec": spec, "data": file_digest(Path(self.base_dir) / str(spec.get("data", ""))),
            "start": self.identity(start) if isinstance(start, str) else None, "code": code_fingerprint()}})

    def describe(self, name: str) -> dict:
        """What a dataset records of a material: its source, parameters, shift function, spec and
        identity (enough to rebuild it without the config)."""
        source = self.source(name)
        shift = self.shift(name)
        spec = {"config": self.specs, "fit": self.fits, "calibration": self.calibrations}.get(source, {}).get(name)
        return {"source": source, "material": self.material(name).to_dict(),
                "shift": shift.to_dict() if shift else None, "spec": spec, "identity": self.identity(name)}


#: the scalar parameters of a fitted material (those of its model in the registry), by fit model
#: (vcor.fitting.fits fits Prony series and CERF laws)
FIT_SCALARS = {model: REGISTRY[model].scalars for model in ("prony", "cerf")}


def _scalars(d: dict) -> list[str]:
    return [k for k, v in d.items() if k != "kind" and not isinstance(v, (list, dict))]


@functools.lru_cache(maxsize=256)
def _config_material(spec_json: str, name: str, base_dir: str) -> Material:
    return from_spec(json.loads(spec_json), name=name, base_dir=base_dir)


def with_parameters(material: Material, overrides: dict, name: str = "material") -> Material:
    """``material`` with scalar parameters replaced (``Material.params()`` names, SI); ValueError naming
    the parameter and the allowed ones otherwise."""
    d = material.to_dict()
    for key, value in overrides.items():
        if key not in d or key == "kind" or isinstance(d[key], (list, dict)):
            raise ValueError(f"material {name!r} has no scalar parameter {key!r}; allowed: {_scalars(d)}")
        d[key] = float(value)
    return from_dict(d)
