# Config validation (the config files read again strictly, the schema, then vcor.study.config: one line
# naming the key), the run's set-up (project lock, healing of the archive: vcor.study.archive) and every
# input function. The project model (vcor.study.project) is built once, here; paths come from
# vcor.study.paths. No logic in rules.
import dataclasses
import re
import sys
from pathlib import Path

from snakemake.cli import get_argument_parser
from snakemake.exceptions import WorkflowError

import vcor.io.receipts as vreceipts
import vcor.io.yamlfile as vyamlfile
import vcor.io.yamlplace as vyamlplace
import vcor.plots as vplots
import vcor.provenance as vprovenance
import vcor.study.archive as varchive
import vcor.study.config as vconfig
import vcor.study.dem as vdem
import vcor.study.kernels as vkernels
import vcor.study.paths as vpaths
import vcor.study.schema as vschema
import vcor.study.shards as vshards
import vcor.study.uncertainty as vuncertainty
from vcor.solvers.options import COMPILED_METHODS

SCHEMA = Path(workflow.basedir) / "workflow" / "schemas" / "config.schema.yaml"
# Snakemake's own reading of the config files keeps the last of two equal keys: each file it read
# (configfile: and --configfile) is read again strictly, so that a repeated key stops the run
for _path in workflow.configfiles:
    try:
        vyamlfile.load_yaml(vyamlplace.shown(_path), what="config file")
    except ValueError as exc:
        raise WorkflowError(str(exc)) from None
try:
    vschema.check_schema(config, SCHEMA)  # fills in the schema's defaults
    PROJECT = vconfig.load_project(config, base_dir=".")
except ValueError as exc:
    # the message names a key path of the merged config: its file, line and column in front (not for a
    # key set on the command line with --config, which no file holds)
    keys = vyamlplace.key_path(str(exc)) or [None]
    said = (
        str(exc)
        if keys[0] in (workflow.config_settings.config or {})
        else vyamlplace.located(str(exc), workflow.configfiles)
    )
    raise WorkflowError(said if said != str(exc) else f"config: {exc}") from None


def _executes():
    """True for a run that executes jobs in this, the main, process (not a dry run, lint, report,
    unlock, summary or graph; not a job that parses the Snakefile again)."""
    if not workflow.is_main_process:
        return False
    args = get_argument_parser().parse_known_args(sys.argv[1:])[0]
    modes = (
        "dryrun",
        "lint",
        "report",
        "unlock",
        "summary",
        "detailed_summary",
        "dag",
        "rulegraph",
        "filegraph",
        "d3dag",
        "list_rules",
        "list_target_rules",
        "touch",
        "cleanup_metadata",
        "list_changes",
        "list_input_changes",
        "list_params_changes",
        "list_untracked",
        "delete_all_output",
        "delete_temp_output",
        "archive",
        "containerize",
        "export_cwl",
    )
    return not any(getattr(args, m, None) for m in modes)


EXECUTES = _executes()
if EXECUTES:
    # one run at a time per project; the locks a killed run left are then stale and removed
    try:
        PROJECT_LOCK = varchive.ProjectLock(".").acquire()
    except ValueError as exc:
        raise WorkflowError(str(exc))
    for _line in varchive.remove_stale_snakemake_locks("."):
        print(_line, file=sys.stderr)
# outputs that are not what their writer wrote are moved aside and computed again (a dry run says so)
for _line in varchive.heal(PROJECT, ".", apply=EXECUTES):
    print(_line, file=sys.stderr)
# the marks of compiled kernels are inputs of the jobs that solve: a project with results missing them
# gets them back (otherwise every finished job that solves would run again; vcor.study.kernels)
_KERNELS_SCRIPT = Path(workflow.basedir) / "workflow" / "scripts" / "kernels.py"
for _line in vkernels.restore_marks(COMPILED_METHODS, ".", script=_KERNELS_SCRIPT):
    print(_line, file=sys.stderr)


def _invalid_shard(path, reason):
    if EXECUTES:
        moved = vreceipts.quarantine(path)
        print(
            f"vcor: {path}: {reason}; moved to {moved.name}, it is computed again",
            file=sys.stderr,
        )
    else:
        print(
            f"vcor: {path}: {reason}; a run (not a dry run) computes it again",
            file=sys.stderr,
        )


SCENES = PROJECT.scenes
CATALOGUE = PROJECT.catalogue
MATERIAL_DIR = CATALOGUE.material_dir


def catalogue_spec(names, catalogue=CATALOGUE):
    """The catalogue of the materials ``names`` as a plain mapping, a param of the jobs that use them
    (they rebuild it with Catalogue(**spec)): only their entries, so that editing other materials of the
    config re-runs none of these jobs (vcor.materials.Catalogue.subset). ``catalogue``: a scene's
    (vcor.study.project.Project.scene_catalogue) for its jobs."""
    return dataclasses.asdict(catalogue.subset(names))


def get_scene_catalogue(wildcards):
    """The catalogue of the materials a scene's jobs use (its sweep, tables, histories, bodies), as the
    scene takes them (without shift functions when it has no temperature axis)."""
    sc = SCENES[wildcards.scene]
    runs = (sc.config.get("histories") or {}).get("runs", [])
    return catalogue_spec(
        sc.used_materials() + [run[0] for run in runs],
        PROJECT.scene_catalogue(wildcards.scene),
    )


# fingerprints of the code that computes (every computing rule takes it as a param, so changed code
# re-runs those jobs; shard names contain it) and of the figure code (the figures_<scene> rules)
CODE = vprovenance.code_fingerprint()
PLOTS_CODE = vprovenance.plots_fingerprint()


def _names(names, empty):
    """A wildcard constraint matching exactly ``names`` (``empty``, a name no file has, when none)."""
    return "|".join(re.escape(n) for n in sorted(names)) or empty


wildcard_constraints:
    scene=_names(SCENES, "no-scene"),
    material=_names(CATALOGUE.fits, "no-fitted-material"),
    material_case="[A-Za-z0-9_.-]+?",
    shard=vshards.SHARD_PATTERN,
    fig="|".join(vplots.FIGURES),


_PLANS = {}


def material_identities(scene):
    """{material name: content identity} of a scene's swept materials (vcor.materials.Catalogue)."""
    catalogue = PROJECT.scene_catalogue(scene)
    return {m: catalogue.identity(m) for m in SCENES[scene].materials}


def shard_plan(scene):
    """{shard id: vcor.study.shards.Shard} of a scene's sweep, planned once per run."""
    if scene not in _PLANS:
        sc = SCENES[scene]
        _PLANS[scene] = vshards.plan_shards(
            sc.config,
            vpaths.fmt(vpaths.SHARD_DIR, scene=scene),
            sc.shard_size,
            material_identities(scene),
            on_invalid=_invalid_shard,
            grid=sc.grid,
            settings=sc.settings,
            job_seconds=sc.job_seconds,
            from_data=PROJECT.fitted_to_data,
        )
    return _PLANS[scene]


def kernels_of(methods):
    """The marks of the numba kernels of ``methods`` compiled by the kernels jobs, one per compiled
    method (vcor.study.kernels says why they are plain inputs)."""
    return [
        vpaths.fmt(vpaths.KERNELS, method=m)
        for m in sorted(set(methods))
        if m in COMPILED_METHODS
    ]


def get_scene_kernels(wildcards):
    """The kernels of a scene's solver method (its sweep's shards)."""
    return kernels_of([SCENES[wildcards.scene].settings["solver"]["method"]])


def get_histories_kernels(wildcards):
    """The kernels of the methods of a scene's time histories."""
    return kernels_of(method for _, method in get_histories_spec(wildcards)["runs"])


def get_all_kernels(wildcards):
    """The kernels of every method (the work-precision study runs them all)."""
    return kernels_of(COMPILED_METHODS)


def dem_rule_name(name):
    name = re.sub(r"\W", "_", name)
    return f"dem_entry_{name}"


def fit_family_rule_names(families):
    """{family: ``fit_family_<name>``}, the name of the job fitting each family: {n} written N, other
    characters that are not letters, digits or _ written _, and _2, _3, ... after a name already taken.
    """
    names = {}
    for family in families:
        slug = re.sub(r"\W", "_", vpaths.family_slug(family))
        base = f"fit_family_{slug}"
        name, k = base, 1
        while name in names.values():
            k += 1
            name = f"{base}_{k}"
        names[family] = name
    return names


# the fit families fitted whole, one job each (vcor.study.project.Project.fit_groups)
FIT_GROUPS = PROJECT.fit_groups()
FIT_FAMILY_RULES = fit_family_rule_names(FIT_GROUPS)
GROUPED_FITS = {m for members in FIT_GROUPS.values() for m in members}


def get_scene(wildcards):
    return SCENES[wildcards.scene].config


def get_grid(wildcards):
    return SCENES[wildcards.scene].grid.to_dict()


def get_histories_spec(wildcards):
    return SCENES[wildcards.scene].config["histories"]


def get_spheres_spec(wildcards):
    return SCENES[wildcards.scene].config["spheres"]


def get_convergence_spec(wildcards):
    return SCENES[wildcards.scene].config["convergence"]


def get_convergence_v0s(wildcards):
    return SCENES[wildcards.scene].config["convergence"]["v0"]


def get_convergence_cases(wildcards):
    spec = SCENES[wildcards.scene].config["convergence"]
    return [
        vpaths.fmt(vpaths.CONVERGENCE_CASE, scene=wildcards.scene, material_case=m)
        for m in spec["materials"]
    ]


def get_settings(wildcards):
    return SCENES[wildcards.scene].settings


def get_shard_points(wildcards):
    return shard_plan(wildcards.scene)[wildcards.shard].points


def get_shard_files(wildcards):
    return [
        vpaths.fmt(vpaths.SHARD, scene=wildcards.scene, shard=s)
        for s in shard_plan(wildcards.scene)
    ]


def get_shard_rows(wildcards):
    """For each shard (in get_shard_files' order), the grid index of each of its points."""
    return [shard.rows for shard in shard_plan(wildcards.scene).values()]


def shard_materials(wildcards):
    """The materials a shard's job is given (vcor.study.shards.shard_materials)."""
    sc = SCENES[wildcards.scene]
    return vshards.shard_materials(get_shard_points(wildcards), sc.body_materials())


def get_shard_catalogue(wildcards):
    return catalogue_spec(
        shard_materials(wildcards), PROJECT.scene_catalogue(wildcards.scene)
    )


def get_shard_material_files(wildcards):
    return PROJECT.material_files_of(wildcards.scene, shard_materials(wildcards))


def get_material_files(wildcards):
    """Computed material files a scene's jobs read (fits, calibrations; none for presets and config
    materials: no fit unless needed)."""
    return PROJECT.material_files_of(wildcards.scene)


def get_material_identity(wildcards):
    """The content identity of the material a rule writes (vcor.materials.Catalogue.identity)."""
    name = (
        getattr(wildcards, "material", None)
        or getattr(wildcards, "name", None)
        or wildcards.cal
    )
    return CATALOGUE.identity(name)


def get_fit_spec(wildcards):
    return CATALOGUE.fits[wildcards.material]


def get_samples_identity(wildcards):
    """The content identity of a samples file, or of one job's part of it (vcor.study.uncertainty.samples_identity)."""
    spec = {"bootstrap": int(wildcards.n), "seed": int(wildcards.seed)}
    part = getattr(wildcards, "part", None)
    share = None if part is None else (int(part), int(wildcards.parts))
    return vuncertainty.samples_identity(CATALOGUE, wildcards.material, spec, share)


def fit_data_files(names):
    """Measured data the fits of ``names`` read (inputs: editing them refits)."""
    data = [CATALOGUE.fits[name].get("data") or {} for name in names]
    return list(
        dict.fromkeys(d[k] for d in data for k in ("file", "shift_file") if k in d)
    )


def get_fit_data_files(wildcards):
    return fit_data_files([wildcards.material])


def get_material_spec(wildcards):
    return CATALOGUE.specs[wildcards.name]


def get_material_table(wildcards):
    """A config Prony material's CSV table (an input: editing it re-runs what uses the material)."""
    spec = CATALOGUE.specs[wildcards.name]
    return [spec["file"]] if "file" in spec else []


def get_scene_fitted_names(wildcards):
    return [m for m in SCENES[wildcards.scene].materials if m in CATALOGUE.fits]


def get_scene_fit_files(wildcards):
    return [vpaths.material(MATERIAL_DIR, m) for m in get_scene_fitted_names(wildcards)]


def get_moduli_materials(wildcards):
    return SCENES[wildcards.scene].moduli_materials()


def figure_inputs(scene):
    """Every dataset the scene's figures need (the union over its figures; fits: one file each; the
    bootstrap samples of those fits when the scene has an uncertainty band)."""
    out = {}
    for fig, opts in SCENES[scene].figures.items():
        for n in vplots.FIGURES[fig][1]:
            if n == "material_fit":
                out[f"{fig}_fits"] = [
                    vpaths.material(MATERIAL_DIR, m) for m in opts.get("materials", [])
                ]
            elif n == "material_samples":
                out[f"{fig}_samples"] = [
                    path
                    for path, m in PROJECT.samples_of(scene)
                    if m in opts.get("materials", [])
                ]
            else:
                out[n] = vpaths.fmt(vpaths.DATASET, scene=scene, dataset=n)
    return out


def figure_options(scene):
    """Each figure's options from the scene, plus the band's probability (``level``) of the scene's
    uncertainty for the figures that draw bootstrap samples themselves."""
    spec = SCENES[scene].uncertainty
    out = {}
    for fig, opts in SCENES[scene].figures.items():
        out[fig] = dict(opts or {})
        if spec is not None and "material_samples" in vplots.FIGURES[fig][1]:
            out[fig]["level"] = spec["level"]
    return out


def figure_rule_name(scene):
    name = re.sub(r"\W", "_", scene)
    return f"figures_{name}"


def get_scene_targets(wildcards):
    return PROJECT.scene_targets(wildcards.scene)


def get_calibration_spec(wildcards):
    return CATALOGUE.calibrations[wildcards.cal]


def get_calibration_inputs(wildcards):
    """The data file and a named start material's file (config, fitted or calibrated)."""
    spec = CATALOGUE.calibrations[wildcards.cal]
    start = spec.get("material")
    files = [spec["data"]]
    if isinstance(start, str) and CATALOGUE.source(start) != "preset":
        files.append(vpaths.material(MATERIAL_DIR, start))
    return files


def get_dem_targets(wildcards):
    """Every output of a dem: entry (its manifest's inputs)."""
    return PROJECT.dem_targets(wildcards.dem)


def get_all_targets():
    return PROJECT.all_targets()
