# Config validation, shard planning, and every input function. No logic inside rules.
import re

from snakemake.exceptions import WorkflowError
from snakemake.utils import validate

import vcor.bodies as vbodies
import vcor.calibrate as vcalibrate
import vcor.fit as vfit
import vcor.material_specs as vspecs
import vcor.materials as vmaterials
import vcor.plots as vplots
import vcor.provenance as vprovenance
import vcor.scene as vscene
import vcor.shards as vshards
from vcor.options import METHODS

validate(config, schema="../schemas/config.schema.yaml")

# fingerprints of the code that computes (every computing rule takes it as a param, so changed code
# re-runs those jobs; shard names contain it) and of the figure code (the figures_<scene> rules)
CODE = vprovenance.code_fingerprint()
PLOTS_CODE = vprovenance.plots_fingerprint()

SCENES = config["scenes"]
MATERIAL_DIR = config["material_dir"]
try:
    FITS = vfit.expand_fits(config.get("fits", {}))
except ValueError as exc:
    raise WorkflowError(f"config.yaml: {exc}")
FITTED = set(FITS)
# materials defined in the config (name -> spec; vcor.material_specs); written to MATERIAL_DIR by a
# local rule and then used like fitted ones. Relative CSV paths are taken from the project folder.
CONFIG_MATERIALS = config.get("materials") or {}


def _check_config_materials():
    for name, spec in CONFIG_MATERIALS.items():
        if not re.fullmatch(r"[A-Za-z0-9_.-]+", name):
            raise ValueError(
                f"config.yaml: materials.{name}: names may use letters, digits, ., - and _"
            )
        if name in vmaterials.PRESETS or name in FITTED:
            raise ValueError(
                f"config.yaml: materials.{name}: the name is taken by a "
                f"{'preset' if name in vmaterials.PRESETS else 'fit'}; choose another"
            )
        vspecs.from_spec(spec, name=name, base_dir=".")


try:
    _check_config_materials()
except ValueError as exc:
    raise WorkflowError(str(exc))
# materials that live in MATERIAL_DIR: fitted ones and the config's own
FILE_MATERIALS = FITTED | set(CONFIG_MATERIALS)
# calibrations from measured COR (vcor.calibrate): results/calibrations/<name>.nc, and the calibrated
# material in MATERIAL_DIR, usable by name like a fit
CALIBRATIONS = config.get("calibrations") or {}


def _check_calibrations():
    for name, spec in CALIBRATIONS.items():
        where = f"config.yaml: calibrations.{name}"
        if not re.fullmatch(r"[A-Za-z0-9_.-]+", name):
            raise ValueError(f"{where}: names may use letters, digits, ., - and _")
        if name in vmaterials.PRESETS or name in FILE_MATERIALS:
            raise ValueError(
                f"{where}: the name is taken by a preset, a fit or a config material; choose another"
            )
        start = spec.get("material") if isinstance(spec, dict) else None
        if isinstance(start, str) and start in CONFIG_MATERIALS:
            vspecs.from_spec(CONFIG_MATERIALS[start], name=start, base_dir=".")
        vcalibrate.check_spec(
            spec,
            where=where,
            material_dir=MATERIAL_DIR,
            pending=FITTED | set(CONFIG_MATERIALS) | set(CALIBRATIONS),
        )


try:
    _check_calibrations()
except ValueError as exc:
    raise WorkflowError(str(exc))
FILE_MATERIALS = FILE_MATERIALS | set(CALIBRATIONS)
# a body (sphere/plate) naming a config material carries its parameters inline (shard identity)
try:
    SCENES = {
        n: vbodies.inline_config_materials(sc, CONFIG_MATERIALS)
        for n, sc in SCENES.items()
    }
except ValueError as exc:
    raise WorkflowError(f"config.yaml: {exc}")


def _check_scenes():
    """Semantic checks the schema cannot express; the message names the key."""
    for name, scene in SCENES.items():
        if not re.fullmatch(r"[A-Za-z0-9_-]+", name):
            raise ValueError(
                f"config.yaml: scenes.{name}: scene names may use letters, digits, - and _"
            )
        figures = scene.get("figures", {})
        need = vplots.needs(figures)
        if "grid" in scene:
            vscene.validate_scene(name, scene, MATERIAL_DIR, FILE_MATERIALS)
            vscene.check_temperature_axis(name, scene, CONFIG_MATERIALS, FITS)
        if "sweep" in need and "grid" not in scene:
            raise ValueError(
                f"config.yaml: scenes.{name}.figures: {sorted(figures)} need a sweep: add scenes.{name}.grid"
            )
        if "convergence" in need and "convergence" not in scene:
            raise ValueError(
                f"config.yaml: scenes.{name}.figures: {sorted(figures)} need scenes.{name}.convergence"
            )
        for mat in scene.get("convergence", {}).get("materials", []):
            vscene.check_material_name(
                mat, FILE_MATERIALS, f"config.yaml: scenes.{name}.convergence.materials"
            )
        if "spheres" in need and "spheres" not in scene:
            raise ValueError(
                f"config.yaml: scenes.{name}.figures: {sorted(figures)} need scenes.{name}.spheres"
            )
        if "histories" in need and "histories" not in scene:
            raise ValueError(
                f"config.yaml: scenes.{name}.figures: {sorted(figures)} need scenes.{name}.histories"
            )
        for fig, opts in figures.items():
            axis = vplots.NEEDS_AXIS.get(fig)
            if axis and axis not in scene.get("grid", {}):
                raise ValueError(
                    f"config.yaml: scenes.{name}.figures.{fig} needs a sweep with a "
                    f"grid axis {axis}: add scenes.{name}.grid.{axis}"
                )
            fits = opts.get("materials")
            if "material_fit" in vplots.FIGURES[fig][1] and (
                not isinstance(fits, list) or not fits or not set(fits) <= FITTED
            ):
                raise ValueError(
                    f"config.yaml: scenes.{name}.figures.{fig}.materials must be a list of fits "
                    f"(of {sorted(FITTED)}), got {fits!r}"
                )
        for mat, method in scene.get("histories", {}).get("runs", []):
            if method not in METHODS or method == "paper":
                raise ValueError(
                    f"config.yaml: scenes.{name}.histories.runs: unknown method {method!r}"
                )
            if mat not in scene["materials"]:
                raise ValueError(
                    f"config.yaml: scenes.{name}.histories.runs: {mat!r} is not in scenes.{name}.materials"
                )


try:
    _check_scenes()
except ValueError as exc:
    raise WorkflowError(str(exc))


wildcard_constraints:
    scene="|".join(re.escape(s) for s in SCENES),
    material="|".join(re.escape(m) for m in sorted(FITTED)) or "no-fitted-material",
    material_case="[A-Za-z0-9_.-]+?",
    shard=vshards.SHARD_PATTERN,
    fig="|".join(vplots.FIGURES),


_PLANS = {}
_IDENTITIES = {}


def material_identities(scene):
    """{material name: content identity} of a scene's materials (see vcor.shards)."""
    if scene not in _IDENTITIES:
        _IDENTITIES[scene] = {
            m: vshards.material_identity(
                m,
                fits=FITS,
                material_dir=MATERIAL_DIR,
                materials=CONFIG_MATERIALS,
                calibrations=CALIBRATIONS,
            )
            for m in SCENES[scene]["materials"]
        }
    return _IDENTITIES[scene]


def shard_plan(scene):
    if scene not in _PLANS:
        _PLANS[scene] = vshards.plan_shards(
            SCENES[scene],
            f"results/{scene}/shards",
            SCENES[scene].get("shard_size", config["shard_size"]),
            material_identities(scene),
        )
    return _PLANS[scene]


def get_identities(wildcards):
    return material_identities(wildcards.scene)


def get_scene(wildcards):
    return SCENES[wildcards.scene]


def get_histories_spec(wildcards):
    return SCENES[wildcards.scene]["histories"]


def get_spheres_spec(wildcards):
    return SCENES[wildcards.scene]["spheres"]


def get_convergence_spec(wildcards):
    return SCENES[wildcards.scene]["convergence"]


def get_convergence_v0s(wildcards):
    return SCENES[wildcards.scene]["convergence"]["v0"]


def get_convergence_cases(wildcards):
    spec = SCENES[wildcards.scene]["convergence"]
    return [f"results/{wildcards.scene}/convergence/{m}.nc" for m in spec["materials"]]


def get_settings(wildcards):
    return vscene.settings_of(SCENES[wildcards.scene])


def get_shard_points(wildcards):
    return shard_plan(wildcards.scene)[wildcards.shard]


def get_shard_files(wildcards):
    return [
        f"results/{wildcards.scene}/shards/{s}.nc" for s in shard_plan(wildcards.scene)
    ]


def get_fitted_inputs(wildcards):
    """Fitted and config material files a scene uses (none for presets: no fit unless needed)."""
    scene = SCENES[wildcards.scene]
    used = (
        set(scene.get("materials", []))
        | set(scene.get("moduli", []))
        | set(scene.get("convergence", {}).get("materials", []))
    )
    return [f"{MATERIAL_DIR}/{m}.nc" for m in sorted(used & FILE_MATERIALS)]


def get_fit_spec(wildcards):
    return FITS[wildcards.material]


def get_fit_data_files(wildcards):
    """Measured data a fit reads (inputs: editing them refits)."""
    d = FITS[wildcards.material].get("data") or {}
    return [d[k] for k in ("file", "shift_file") if k in d]


def get_material_spec(wildcards):
    return CONFIG_MATERIALS[wildcards.name]


def get_material_table(wildcards):
    """A config Prony material's CSV table (an input: editing it re-runs what uses the material)."""
    spec = CONFIG_MATERIALS[wildcards.name]
    return [spec["file"]] if "file" in spec else []


def get_scene_fitted_names(wildcards):
    return [m for m in SCENES[wildcards.scene].get("materials", []) if m in FITTED]


def get_scene_fit_files(wildcards):
    return [f"{MATERIAL_DIR}/{m}.nc" for m in get_scene_fitted_names(wildcards)]


def get_moduli_materials(wildcards):
    scene = SCENES[wildcards.scene]
    return scene.get("moduli", scene["materials"])


def figure_inputs(scene):
    """Every dataset the scene's figures need (the union over its figures; fits: one file each)."""
    out = {}
    for fig, opts in SCENES[scene].get("figures", {}).items():
        for n in vplots.FIGURES[fig][1]:
            if n == "material_fit":
                out[f"{fig}_fits"] = [
                    f"{MATERIAL_DIR}/{m}.nc" for m in opts.get("materials", [])
                ]
            else:
                out[n] = f"results/{scene}/{n}.nc"
    return out


def figure_rule_name(scene):
    name = re.sub(r"\W", "_", scene)
    return f"figures_{name}"


def get_scene_targets(wildcards):
    return scene_targets(wildcards.scene)


def scene_targets(scene):
    cfg = SCENES[scene]
    figures = cfg.get("figures", {})
    out = []
    if "grid" in cfg:
        out.append(f"results/{scene}/sweep.nc")
    need = vplots.needs(figures)
    for n in ("moduli", "histories", "spheres", "convergence"):
        if n in need:
            out.append(f"results/{scene}/{n}.nc")
    for fig in figures:
        out += [
            f"results/{scene}/figures/{fig}.png",
            f"results/{scene}/figures/{fig}.pdf",
        ]
    if "convergence" in cfg:
        out.append(f"results/{scene}/orders.txt")
    if set(cfg.get("materials", [])) & FITTED:
        out.append(f"results/{scene}/fit_metrics.txt")
    return out


def get_calibration_spec(wildcards):
    return CALIBRATIONS[wildcards.cal]


def get_calibration_inputs(wildcards):
    """The data file and a named start material's file (config, fitted or calibrated)."""
    spec = CALIBRATIONS[wildcards.cal]
    start = spec.get("material")
    files = [spec["data"]]
    if isinstance(start, str) and start in FILE_MATERIALS:
        files.append(f"{MATERIAL_DIR}/{start}.nc")
    return files


def calibration_targets():
    return [
        f"results/calibrations/{c}.{ext}"
        for c in CALIBRATIONS
        for ext in ("nc", "png", "pdf")
    ]


def get_all_targets():
    return [f"results/{s}/MANIFEST.txt" for s in SCENES] + calibration_targets()
