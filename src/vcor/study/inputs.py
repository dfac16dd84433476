"""What the public study functions (:mod:`vcor.study.api`) and the ``vcor`` study commands take: a
config (a file, a mapping or a :class:`~vcor.materials.Catalogue`), a scene (its name in the config or
its mapping) and materials (names or objects), checked as the workflow checks its config.

Every config file is read by :func:`read_config`, and every config goes through the workflow's own
checks: the JSON schema (:func:`vcor.study.schema.check_schema`, which also fills in its defaults, so
that a scene's recorded config is the one the workflow records) and :func:`vcor.study.config.load_project`.
A refusal is the workflow's one line, naming the key, before any work; for a scene given as a mapping
the key is written from the argument (``scene.grid.bta: unknown key ...`` rather than
``scenes.<name>.grid.bta``), and for a config file the file is named first.

A material object (:class:`vcor.materials.Material`) is taken where a name is: in a scene's
``materials`` list it becomes a config material named ``<kind>-<8 hex digits of its parameters>``
(the same object, the same name), in a config's ``materials`` block it keeps its key.
"""

from __future__ import annotations

import copy
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..io.yamlplace import located
from ..materials.catalogue import Catalogue, content_hash
from ..materials.models import Material
from ..materials.specs import from_spec
from .config import SCENE_NAME_PATTERN, load_project
from .project import Project
from .schema import check_keys, check_schema

__all__ = ["SCENE_BLOCKS", "SCENE_NAME", "Resolved", "as_config", "plain", "project_folder", "read_config",
           "resolve_entry", "resolve_scene", "schema_path", "spec_of"]

#: the name of a scene given as a mapping that is not one of its config's scenes
SCENE_NAME = "sweep"
#: the config's sections a study function keeps besides what it builds
_SHARED = ("materials", "fits", "calibrations", "material_dir", "job_seconds", "shard_size")


def schema_path() -> Path:
    """The workflow's config schema, shipped with the package (``vcor/study/config.schema.yaml``, the
    same file as ``workflow/schemas/config.schema.yaml``)."""
    return Path(__file__).with_name("config.schema.yaml")


def read_config(path) -> dict:
    """The mapping of a YAML config file; ValueError naming the file when it is missing or not a
    mapping. The one place the study functions and commands read a config file."""
    from ..io.yamlfile import load_yaml

    path = Path(path)
    if not path.is_file():
        raise ValueError(f"config {str(path)!r}: no such file")
    cfg = load_yaml(path, what="config")  # a key given twice is refused, naming both lines
    if cfg is None:
        return {}
    if not isinstance(cfg, dict):
        raise ValueError(f"config {str(path)!r}: a mapping of sections (scenes, fits, calibrations, dem, "
                         f"materials, ...), got {type(cfg).__name__}")
    return cfg


def plain(value):
    """``value`` with NumPy arrays and scalars, tuples and material objects made plain config values
    (lists, numbers, material specs), recursively; a new object (the caller's is not changed)."""
    if isinstance(value, Material):
        return spec_of(value)
    if isinstance(value, dict):
        return {k: plain(v) for k, v in value.items()}
    if isinstance(value, np.ndarray) and value.ndim == 0:
        return value.item()
    if isinstance(value, (list, tuple, np.ndarray)):
        return [plain(v) for v in value]
    if isinstance(value, np.generic):
        return value.item()
    return copy.deepcopy(value)


def spec_of(material: Material) -> dict:
    """The config spec of a material object (its model and parameters)."""
    d = material.to_dict()
    return {"model": d.pop("kind"), **d}


def _object_name(spec: dict) -> str:
    """The name of an inline material (its canonical spec, with its ``shift`` when it has one)."""
    return f"{spec['model']}-{content_hash(spec, 8)}"


def project_folder(config_file) -> Path:
    """The project folder of a config file, that its relative paths are taken from: the nearest folder at
    or above the file's own that holds a ``Snakefile`` (the workflow's project, whose working directory
    the workflow takes them from, so that a config kept in a subfolder of a project reads the same files
    in a study function as in ``snakemake --configfile``), else the file's own folder."""
    own = Path(config_file).absolute().parent  # a link's own folder, not its target's
    return next((folder for folder in (own, *own.parents) if (folder / "Snakefile").is_file()), own)


def as_config(config) -> tuple[dict, Path]:
    """(config mapping, its project folder) of ``config``: None (presets only), a path to a YAML file
    (:func:`project_folder`), a mapping (the working directory) or a :class:`~vcor.materials.Catalogue`
    (its ``base_dir``). The mapping is a copy, plain (:func:`plain`)."""
    if config is None:
        return {}, Path(".")
    if isinstance(config, Catalogue):
        cfg = {"materials": config.specs, "fits": config.fits, "calibrations": config.calibrations,
               "material_dir": config.material_dir}
        out = plain(cfg), Path(config.base_dir)
    elif isinstance(config, (str, Path)):
        out = read_config(config), project_folder(config)
    elif isinstance(config, dict):
        out = plain(config), Path(".")
    else:
        raise ValueError(f"config must be None, a path to a YAML file, a mapping or a vcor.materials.Catalogue, "
                         f"got {type(config).__name__}")
    try:
        check_keys(out[0])  # before an entry is looked up by its name
    except ValueError as exc:
        raise type(exc)(f"{_where(config)}{exc}") from None
    return out


def _where(config) -> str:
    return f"config {str(config)!r}: " if isinstance(config, (str, Path)) else ""


@dataclass(frozen=True, kw_only=True)
class Resolved:
    """A checked entry of a config: its ``name``, the :class:`~vcor.study.project.Project` holding it with
    the config's materials, fits and calibrations, and the project's folder ``base_dir``."""

    name: str
    project: Project
    base_dir: Path

    @property
    def scene(self):
        """The entry as a scene (:class:`vcor.study.project.Scene`)."""
        return self.project.scenes[self.name]


def _checked(study: dict, base: Path, config, rename: tuple[str, str] | None, inline=()) -> Project:
    """The project of ``study`` (the workflow's checks); a refusal names ``config``'s file and, for an entry
    given as a mapping, writes its key from the argument (``rename``: (key prefix, argument); ``inline``:
    more such pairs, for the materials a scene's list gave inline)."""
    try:
        check_schema(study, schema_path())
        return load_project(study, base_dir=base, require_targets=False)
    except ValueError as exc:
        text = str(exc)
        if rename is not None:
            # every key path under the entry, also one the message advises ("add scenes.<name>.grid.beta")
            for prefix, argument in (rename, *inline):
                text = re.sub(rf"(?<![\w.-]){re.escape(prefix)}(?=[.:\[ ]|$)", argument, text)
            for prefix, argument in inline:  # the generated name, quoted ("material '<model>-<hash>': ...")
                text = text.replace(f"'{prefix.removeprefix('materials.')}'", argument)
            if any(re.match(rf"{re.escape(a)}(?=[.:\[ ]|$)", text) for _, a in (rename, *inline)):
                raise type(exc)(text) from None  # a key of the argument itself: no file holds it
        elif isinstance(config, (str, Path)):  # an entry of the file: where it is in the file
            placed = located(text, [config])
            if placed != text:
                raise type(exc)(placed) from None
        raise type(exc)(f"{_where(config)}{text}") from None


def _entries(project: Project, section: str) -> dict:
    return {"fits": project.catalogue.fits, "calibrations": project.catalogue.calibrations,
            "dem": project.dem}[section]


def resolve_entry(section: str, entry, name, config, argument: str) -> Resolved:
    """The checked entry of a config ``section`` (``fits``, ``calibrations`` or ``dem``) given as its name
    in ``config`` (a fit family's member too, ``butyl-prony-n3``) or as a mapping (named ``name``, default
    ``argument``), with the config's materials, fits and calibrations; ValueError in one line naming the
    key otherwise, before any work."""
    cfg, base = as_config(config)
    study = {k: cfg[k] for k in _SHARED if k in cfg}
    rename = None
    if isinstance(entry, str):
        name = entry
        if section == "dem" and entry in (cfg.get("dem") or {}):
            study["dem"] = {entry: cfg["dem"][entry]}
    elif isinstance(entry, dict):
        name = argument if name is None else name
        if not isinstance(name, str) or not re.fullmatch(r"[A-Za-z0-9_.-]+", name):
            raise ValueError(f"name must be a text of letters, digits, ., - and _, got {name!r}")
        study[section] = {**(study.get(section) or {}), name: plain(entry)}
        rename = (f"{section}.{name}", argument)
    else:
        raise ValueError(f"{argument} must be a mapping (an entry of a config's {section} block) or the name of "
                         f"one in config, got {type(entry).__name__}")
    project = _checked(study, base, config, rename)
    if name not in _entries(project, section):
        # a dem study holds the named entry only: the config's own block lists them all
        known = sorted(_entries(project, section) if section != "dem" else (cfg.get("dem") or {}))
        if config is None and isinstance(entry, str):
            raise ValueError(f"{argument}: {name!r} names an entry of a config's {section} block, but no config was "
                             f"given: pass config= (the config file, or its mapping, that defines it), or give the "
                             f"entry itself as a mapping")
        raise ValueError(f"{_where(config)}{argument}: {name!r} is not an entry of the config's {section} block "
                         f"({known or 'it has none'})")
    return Resolved(name=name, project=project, base_dir=base)


def _objects_named(scene: dict, cfg: dict) -> tuple[dict, list]:
    """(the scene with each material object or inline spec (a mapping with ``model``, as ``simulate`` takes
    it) of its material lists (``materials``, ``convergence.materials``) replaced by a config material's
    name (added to ``cfg``'s materials block), and the pairs (``materials.<that name>``,
    ``scene.<list>[<index>]``) that say the keys as the call wrote them)."""
    keys: list[tuple[str, str]] = []
    if isinstance(scene.get("materials"), (list, tuple)):
        names, said = _list_named(scene["materials"], cfg, "scene.materials")
        scene, keys = {**scene, "materials": names}, keys + said
    block = scene.get("convergence")
    if isinstance(block, dict) and isinstance(block.get("materials"), (list, tuple)):
        names, said = _list_named(block["materials"], cfg, "scene.convergence.materials")
        scene, keys = {**scene, "convergence": {**block, "materials": names}}, keys + said
    return scene, keys


def _list_named(materials, cfg: dict, where: str) -> tuple[list, list]:
    """(names, key pairs) of :func:`_objects_named` for one list of materials, at ``where`` in the scene."""
    inline = (Material, dict)
    if not any(isinstance(m, inline) for m in materials):
        return list(materials), []
    block = dict(cfg.get("materials") or {})
    names = []
    for i, m in enumerate(materials):
        if isinstance(m, dict):  # first the checks of a config's materials block (its schema: shift models)
            try:
                check_schema({"materials": {"inline": plain(m)}}, schema_path())
            except ValueError as exc:
                said = re.sub(r"^materials\.inline(?=[.:\[ ]|$)", f"{where}[{i}]", str(exc))
                raise ValueError(said) from None
        if isinstance(m, (dict, Material)):
            # checked, then written as its canonical spec; a spec's shift function goes with it (a T axis
            # needs it), as in a config's materials block
            shift = {"shift": plain(m["shift"])} if isinstance(m, dict) and "shift" in m else {}
            spec = {**spec_of(from_spec(m, where=f"{where}[{i}]") if isinstance(m, dict) else m), **shift}
            names.append(_object_name(spec))
            block[names[-1]] = spec
        else:
            names.append(m)
    cfg["materials"] = block
    keys = [(f"materials.{n}", f"{where}[{i}]") for i, (n, m) in enumerate(zip(names, materials))
            if isinstance(m, inline)]
    for i, n in enumerate(names):
        if n in names[:i]:
            raise ValueError(f"{where}[{i}]: the same material as {where}[{names.index(n)}] (a scene "
                             f"takes each material once)")
    return names, keys


def _scene_entry(scene, cfg: dict, config, name=None) -> tuple[str, dict, bool, list]:
    """(name, scene mapping, given by name, the keys of its inline materials: :func:`_objects_named`) of the
    ``scene`` argument; ``name`` names a scene given as a mapping (default: the config's scene that equals
    it, else SCENE_NAME)."""
    scenes = cfg.get("scenes") or {}
    if name is not None and not (isinstance(name, str) and re.fullmatch(SCENE_NAME_PATTERN, name)):
        raise ValueError(f"name must be a text of letters, digits, - and _ (a scene's name), got {name!r}")
    if isinstance(scene, str) and name is not None:
        raise ValueError(f"name names a scene given as a mapping; scene {scene!r} is the name of one of config's")
    if isinstance(scene, str):
        if config is None:
            raise ValueError(f"scene: {scene!r} names a scene, but no config was given: pass config= (the config "
                             f"file, or its mapping, that defines it), or give the scene itself as a mapping")
        if scene not in scenes:
            raise ValueError(f"{_where(config)}scene: {scene!r} is not a scene of the config "
                             f"({sorted(scenes) if scenes else 'it has none'})")
        return scene, scenes[scene], True, []
    if not isinstance(scene, dict):
        raise ValueError(f"scene must be a mapping (as under scenes.<name> of a config) or the name of a scene "
                         f"of config, got {type(scene).__name__}")
    named, keys = _objects_named(dict(scene), cfg)
    given = plain(named)
    if name is not None:
        return name, given, False, keys
    same = [n for n, s in scenes.items() if s == given]
    return (same[0] if same else SCENE_NAME), given, False, keys


#: a scene's dataset -> (the block that defines it, how to add one, the study function that computes it)
SCENE_BLOCKS = {
    "sweep": ("grid", "grid: {v0: [...]}", "vcor.sweep"),
    "histories": ("histories", "histories: {v0: ..., runs: [[material, method], ...]}", "vcor.histories"),
    "spheres": ("spheres", "spheres: {b: [...], rules: [overlap, force]}", "vcor.viscoelastic_spheres"),
    "convergence": ("convergence", "convergence: {materials: [...], v0: [...]}", "vcor.convergence"),
    "moduli": ("materials", "materials: [...], and moduli: [...] for others than those", "vcor.moduli"),
}


def resolve_scene(scene, config=None, name=None, dataset: str = "sweep") -> Resolved:
    """The checked study of ``scene`` (its name in ``config``, or a mapping, named ``name``) with ``config``'s
    materials, fits and calibrations, for its ``dataset`` (a key of SCENE_BLOCKS); ValueError (one line
    naming the key: module docstring) before any work, also when the scene lacks the block that dataset
    needs (saying which of its blocks it has, and the functions that compute them)."""
    cfg, base = as_config(config)
    name, entry, by_name, inline = _scene_entry(scene, cfg, config, name)
    study = {k: cfg[k] for k in _SHARED if k in cfg}
    study["scenes"] = {name: plain(entry)}
    key = f"scenes.{name}"
    project = _checked(study, base, config, None if by_name else (key, "scene"), inline)
    sc = project.scenes[name]
    block, add, _ = SCENE_BLOCKS[dataset]
    has = {"sweep": sc.grid is not None, "moduli": bool(sc.moduli_materials())}
    if not has.get(dataset, block in sc.config):
        others = [f"{SCENE_BLOCKS[d][0]} ({SCENE_BLOCKS[d][2]})" for d in SCENE_BLOCKS
                  if d not in (dataset, "moduli") and SCENE_BLOCKS[d][0] in sc.config]
        said = f"; it has {', '.join(others)}" if others else ""
        raise ValueError(f"{_where(config)}{key if by_name else 'scene'}.{block}: the scene has no {block} for "
                         f"{SCENE_BLOCKS[dataset][2]} (add {add}){said}")
    return Resolved(name=name, project=project, base_dir=base)
