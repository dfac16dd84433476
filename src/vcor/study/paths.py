"""Where the workflow writes: every result path, once, for Python and for the rules.

Each path is a pattern with Snakemake's wildcards in braces (``results/{scene}/sweep.nc``); the rules
use the patterns as their inputs and outputs, Python formats them (:func:`fmt`). Material files live
under the config's ``material_dir`` (default ``results/materials``), which the patterns of the
material rules take as their first argument. Paths are relative to the project folder.
"""

from __future__ import annotations

__all__ = [
    "CALIBRATION",
    "CALIBRATIONS_DIR",
    "CALIBRATION_FIGURE",
    "CONVERGENCE_CASE",
    "DATASET",
    "DEM",
    "DEM_DECK",
    "DEM_DIR",
    "DEM_FIGURE",
    "DEM_MANIFEST",
    "DEM_PARAMETERS",
    "DEM_TABLE",
    "DEM_YADE",
    "FAMILY_LOGS",
    "FIGURE",
    "FIT_METRICS",
    "KERNELS",
    "MANIFEST",
    "ORDERS",
    "RESULTS",
    "SCENE_DIR",
    "SHARD",
    "SHARD_DIR",
    "SHARD_INDEX",
    "SWEEP",
    "benchmark",
    "family_slug",
    "fmt",
    "log",
    "material",
    "material_table",
    "samples",
    "samples_part",
    "samples_parts",
]

#: the folder every result is written to, and its parts: a scene's, the calibrations', the DEM entries'
RESULTS = "results"
SCENE_DIR = "results/{scene}"
CALIBRATIONS_DIR = "results/calibrations"
DEM_DIR = "results/dem"

#: a scene's datasets (sweep, moduli, histories, spheres, convergence)
DATASET = "results/{scene}/{dataset}.nc"
SWEEP = "results/{scene}/sweep.nc"
#: a sweep job's shard and its index (the points it holds, JSON), in the scene's shard folder
SHARD_DIR = "results/{scene}/shards"
SHARD = SHARD_DIR + "/{shard}.nc"
SHARD_INDEX = SHARD_DIR + "/{shard}.json"
#: one material's ladder of the work-precision study
CONVERGENCE_CASE = "results/{scene}/convergence/{material_case}.nc"
ORDERS = "results/{scene}/orders.txt"
FIT_METRICS = "results/{scene}/fit_metrics.txt"
MANIFEST = "results/{scene}/MANIFEST.txt"
#: a scene's figure, ext png (the report's) or pdf (print)
FIGURE = "results/{scene}/figures/{fig}.{ext}"
#: calibrations from measured COR
CALIBRATION = "results/calibrations/{cal}.nc"
CALIBRATION_FIGURE = "results/calibrations/{cal}.{ext}"
#: DEM entries
DEM = "results/dem/{dem}.nc"
DEM_TABLE = "results/dem/{dem}/table.csv"
DEM_PARAMETERS = "results/dem/{dem}/parameters.csv"
DEM_DECK = "results/dem/{dem}/lammps/in.{kind}"
DEM_YADE = "results/dem/{dem}/yade/collision.py"
DEM_FIGURE = "results/dem/{dem}.{ext}"
#: the one target that builds every output of a DEM entry
DEM_MANIFEST = "results/dem/{dem}/MANIFEST.txt"
#: a run's mark that the numba kernels of a solver method are compiled (a temporary file: the rule
#: ``kernels`` writes it, the jobs that solve with that method wait for it, the run then removes it)
KERNELS = "results/.kernels/{method}.ready"


def fmt(pattern: str, **wildcards) -> str:
    """``pattern`` with its wildcards filled in."""
    return pattern.format(**wildcards)


def material(material_dir: str, name: str = "{name}") -> str:
    """A material file (a fit, calibration or config material), ``<material_dir>/<name>.nc``."""
    return f"{material_dir}/{name}.nc"


def material_table(material_dir: str, name: str = "{name}") -> str:
    """A fit's parameter table, ``<material_dir>/<name>.txt``."""
    return f"{material_dir}/{name}.txt"


def samples(material_dir: str, name: str = "{material}", n="{n}", seed="{seed}") -> str:
    """A fit's bootstrap samples, ``<material_dir>/samples/<name>-b<n>-s<seed>.nc`` (every sample: the parts
    merged)."""
    return f"{material_dir}/samples/{name}-b{n}-s{seed}.nc"


def samples_part(material_dir: str, name: str = "{material}", n="{n}", seed="{seed}", part="{part}",
                 parts="{parts}") -> str:
    """Part ``part`` (0-based) of ``parts`` of a fit's bootstrap samples, one job's share,
    ``<material_dir>/samples/<name>-b<n>-s<seed>-p<part>of<parts>.nc``."""
    return f"{material_dir}/samples/{name}-b{n}-s{seed}-p{part}of{parts}.nc"


def samples_parts(material_dir: str, parts: int, name: str = "{material}", n="{n}", seed="{seed}") -> list[str]:
    """Every part of a fit's bootstrap samples split over ``parts`` jobs (:func:`samples_part`)."""
    return [samples_part(material_dir, name, n, seed, k, parts) for k in range(parts)]


def family_slug(family: str) -> str:
    """A fit family's name (``butyl-prony-n{n}``) as a file name: ``{n}`` written ``N`` (``butyl-prony-nN``);
    its job's log is ``log(material_dir, FAMILY_LOGS + slug)`` (a folder of its own: no fit's name
    contains a slash, so a family's log never meets a fit's)."""
    return family.replace("{n}", "N")


#: the folder (inside a material dir's logs and benchmarks) of the fit families' jobs
FAMILY_LOGS = "families/"


def log(folder: str, name: str) -> str:
    """A job's log, ``<folder>/logs/<name>.log`` (folder: ``results/{scene}``, a material dir, ...)."""
    return f"{folder}/logs/{name}.log"


def benchmark(folder: str, name: str) -> str:
    """A job's benchmark file (Snakemake's ``benchmark:``), ``<folder>/benchmarks/<name>.tsv``."""
    return f"{folder}/benchmarks/{name}.tsv"
