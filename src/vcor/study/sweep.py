"""A scene's sweep, from its points to its dataset: the one code path of :func:`vcor.sweep` and the
workflow's sweep jobs.

* :func:`solve_points` solves points into a shard dataset (:func:`vcor.study.pool.solve`, then
  :func:`vcor.study.runner.rows_dataset`), with the attributes a shard file carries: what the workflow's
  ``sweep_shard`` job writes for its points (one worker), and what :func:`vcor.sweep` solves every point
  of the scene into (``workers`` processes, with a progress bar);
* :func:`combine` joins shards into the scene's dataset (:func:`vcor.study.aggregation.aggregate`, with
  :func:`~vcor.study.aggregation.dataset_attrs`) as an :class:`~vcor.io.archived.Archive`: the workflow's
  ``aggregate`` job writes it to ``results/<scene>/sweep.nc``, :func:`vcor.sweep` returns it as read
  back from the same writer.

The two datasets are equal in every variable and attribute but the points' ``wall_time`` (each run
times itself) and the ``history`` attribute (when, and by which command, the file was written).
"""

from __future__ import annotations

import json
from collections.abc import Sequence

from ..io.archived import Archive
from ..materials.catalogue import Catalogue
from ..provenance import code_fingerprint
from .aggregation import aggregate, dataset_attrs
from .grid import Grid
from .progress import ProgressBar
from .scene import material_params

__all__ = ["SHARD_TITLE", "TITLE", "combine", "shard_attrs", "solve_points"]

#: the title of a scene's sweep dataset, and of a shard's
TITLE = "vcor sweep, scene {scene}"
SHARD_TITLE = "vcor sweep shard"


def shard_attrs(points: Sequence[dict], settings: dict, catalogue: Catalogue) -> dict:
    """The global attributes of a shard: its settings, the parameters of its materials and the code
    fingerprint (which the aggregate checks), as JSON texts as in its file."""
    materials = material_params(sorted({p["material"] for p in points}), catalogue)
    return {"settings": json.dumps(settings, default=float), "materials": json.dumps(materials, default=float),
            "code_fingerprint": code_fingerprint()}


def solve_points(points: Sequence[dict], settings: dict, catalogue: Catalogue, *, workers: int = 1,
                 progress: bool = False, from_data: frozenset | set = frozenset()):
    """The shard dataset of ``points`` (dimension ``point``, in their order), solved in ``workers``
    processes (:mod:`vcor.study.pool`) with a progress bar when ``progress`` (:mod:`vcor.study.progress`);
    ``from_data``: the names of materials fitted to measured data (their estimated work is larger)."""
    # the solvers (numba) load where points are solved, not in a job that only combines shards
    from .pool import solve
    from .runner import rows_dataset

    points = list(points)
    with ProgressBar(len(points), enabled=progress) as bar:
        rows = solve(points, settings, catalogue, workers=workers, on_rows=bar.advance, from_data=from_data)
    ds = rows_dataset(points, rows, settings)
    ds.attrs.update(shard_attrs(points, settings, catalogue))
    return ds


def combine(name: str, scene: dict, grid: Grid, shards: Sequence, rows: Sequence, catalogue: Catalogue) -> Archive:
    """The scene's sweep dataset from its ``shards``: row ``i`` of shard ``k`` is grid point ``rows[k][i]``
    (:func:`vcor.study.aggregation.aggregate`); ``scene`` is the scene's checked config."""
    ds = aggregate(list(shards), list(rows), grid, scene, catalogue)
    return Archive(dataset=ds, title=TITLE.format(scene=name), extra_attrs=dataset_attrs(name, scene, catalogue))
