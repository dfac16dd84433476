"""What a DEM run reads: the dataset ``results/dem/<name>.nc`` and the COR table.

The dataset (CF attributes as every vcor dataset) has the dimensions ``model`` (the DEM laws,
:data:`vcor.dem.laws.MODELS`), ``v0`` (m/s) and, for a temperature sweep, ``T`` (deg C):

* ``cor(v0[, T])``: vcor's COR, with ``status``, ``message``, ``validity`` and ``validity_message`` (why a
  flag is set) per point;
* ``cor_model(model, v0[, T])`` and ``error = cor_model - cor``;
* ``max_abs_error(model[, T])`` over the speeds, and ``v0_within_lo``, ``v0_within_hi``: the widest
  run of consecutive speeds on which ``abs(error) <= WITHIN`` (NaN when there is none);
* ``opposite_trend(model[, T])``: 1 where the law's COR changes with speed in the opposite sense to
  vcor's over the range and misses it by more than ``WITHIN`` (:mod:`vcor.dem.trend`), and the
  attribute ``trend_warning`` saying so in words (empty when no law does), pointing to the COR table;
* each law's parameters (``eta_n0``, ``E_lammps``, ``e``, ``A``, ``E_eff``, ``en``, ``vn``,
  ``young``; for ``lammps-hereditary`` the contact's series ``hereditary_E_inf``, ``hereditary_E`` and
  ``hereditary_beta`` along ``prony_term``, NaN past a temperature's last term, and
  ``hereditary_soe_error``), with units and the model they belong to, per temperature;
* the contact (``m_eff``, ``r_eff``, ``nu``, kind), the collision's config and each law's formula
  source, separation and required code version (``models``; ``yade_version_required``) in the
  attributes.

The table is CSV with a header and a units row: ``v0,cor`` (and ``T`` first for a temperature sweep).
The parameters file (:func:`parameters_csv`) lists every law's parameters with units, the contact
they hold for and the code version each law needs.
"""

from __future__ import annotations

import csv
import io
import json

import numpy as np

from ..io.receipts import atomic_text
from ..solvers.common import LONG_NAMES
from ..solvers.validity import cf_attrs as validity_attrs
from ..status import cf_attrs, code
from . import trend
from .laws import HEREDITARY, PARAMETERS, REQUIRES, SOURCES

__all__ = ["TERM_DIM", "WITHIN", "YADE_VERSION", "dem_dataset", "parameters_csv", "quality_lines", "table_csv",
           "within_range"]

#: the oldest Yade whose Ip2_FrictMat_FrictMat_MindlinPhys has vn (the velocity-dependent COR)
YADE_VERSION = "2024.02a"

#: the dimension of a series parameter (the terms of lammps-hereditary's Prony series)
TERM_DIM = "prony_term"
#: the error bound of the sub-range a dataset reports for each law (COR, absolute)
WITHIN = 0.01
#: the separation each law's deck or code implies
SEPARATION = {
    "lammps-viscoelastic": "force (limit_damping: the force is clipped at zero)",
    "lammps-coeff-restitution": "overlap (no limit_damping: the contact ends at zero overlap; the COR is e)",
    "lammps-hereditary": "force (the hereditary force is clipped at zero; its internal variables are dropped when "
                         "the overlap ends)",
    "mercurydpm-bshp": "force (the normal force is clipped at zero)",
    "yade-mindlin": "force (the normal force is clipped at zero)",
    "table": "as vcor: where the contact force vanishes",
}


def within_range(v0, error, bound: float = WITHIN) -> tuple[float, float]:
    """(lowest, highest) speed of the widest run of consecutive speeds with ``abs(error) <= bound``;
    (nan, nan) when there is none.

    Examples
    --------
    >>> import numpy as np
    >>> from vcor.dem.export import within_range
    >>> within_range(np.array([0.1, 1.0, 10.0, 100.0]), np.array([0.02, 0.005, -0.008, 0.03]))
    (1.0, 10.0)
    """
    good = np.isfinite(error) & (np.abs(error) <= bound)
    best, start = (0, -1, -1), None
    for i, g in enumerate(list(good) + [False]):
        if g and start is None:
            start = i
        elif not g and start is not None:
            if i - start > best[0]:
                best = (i - start, start, i - 1)
            start = None
    return (float(v0[best[1]]), float(v0[best[2]])) if best[0] else (np.nan, np.nan)


#: units and long names of the dataset's variables other than the laws' parameters
_UNITS = {"cor": "1", "cor_model": "1", "error": "1", "max_abs_error": "1", "v0_within_lo": "m s-1",
          "v0_within_hi": "m s-1", "validity": "1", "opposite_trend": "1", "soe_error": "1"}
_NAMES = {"cor": "vcor's COR (hereditary contact, the contact ends where the force vanishes)",
          "cor_model": "the DEM law's COR with its fitted parameters", "error": "cor_model - cor",
          "max_abs_error": "largest abs(error) over the speeds",
          "v0_within_lo": f"lowest speed of the widest run of speeds with abs(error) <= {WITHIN}",
          "v0_within_hi": f"highest speed of the widest run of speeds with abs(error) <= {WITHIN}",
          "message": "solver message", "validity": "validity flags of an ok result (vcor.solvers.validity)",
          "validity_message": "why the validity flags are set: the quantity, its value and the limit",
          "soe_error": LONG_NAMES["soe_error"],
          "opposite_trend": "1 where the law's COR changes with speed in the opposite sense to vcor's over the "
                            f"range and misses it by more than {WITHIN} (vcor.dem.trend): no value of its "
                            "parameters follows the curve"}


def _describe(ds, params: dict, with_t: bool) -> None:
    """Units and long names of every variable and coordinate, in place."""
    for v, text in _NAMES.items():
        ds[v].attrs["long_name"] = text
        if v in _UNITS:
            ds[v].attrs["units"] = _UNITS[v]
    ds["status"].attrs.update(cf_attrs())
    ds["status"].attrs["long_name"] = "status of vcor's solve at the point"
    ds["validity"].attrs.update({k: v for k, v in validity_attrs().items() if k != "long_name"})
    ds["opposite_trend"].attrs.update(flag_values=np.array([0, 1], dtype=ds["opposite_trend"].dtype),
                                      flag_meanings="same_trend_or_within opposite_trend")
    for key, (model, unit, meaning, _) in params.items():
        ds[key].attrs.update(units=unit, long_name=meaning, model=model)
    ds["v0"].attrs.update(units="m s-1", long_name="impact speed (relative normal approach speed of a pair)")
    ds["model"].attrs["long_name"] = "DEM contact law (vcor.dem.laws)"
    if with_t:
        ds["T"].attrs.update(units="degC", long_name="temperature")


def _global_attrs(ds, name: str, collisions: list, models: list, config) -> None:
    """The entry, its config, the contact and each law's source, separation and required version."""
    contact = collisions[0].contact
    ds.attrs.update({
        "dem": name,
        "dem_config": json.dumps(config or {}),
        "contact": json.dumps({"kind": contact.kind, "m_eff_kg": contact.m_eff, "r_eff_m": contact.r_eff,
                               "nu": contact.nu, "radii_m": list(contact.radii),
                               "densities_kg_m-3": list(contact.densities)}),
        "E_eff_note": "E_eff: vcor's contact stiffness at a quarter of its contact time at the reference speed "
                      "(vcor.dem.fit); it sets a DEM contact's duration, not its COR",
        "models": json.dumps({m: {"source": SOURCES[m], "separation": SEPARATION[m], "requires": REQUIRES[m],
                                  "parameters": {p: u for p, (u, _) in PARAMETERS[m].items()}} for m in models}),
        "v_ref_m_s": collisions[0].v_ref,
    })


def _per_temperature(values: list) -> np.ndarray:
    """One parameter at every temperature: a vector, or (temperature, term) for a series, padded with
    NaN past a temperature's last term."""
    if all(np.ndim(v) == 0 for v in values):
        return np.array(values, dtype=float)
    n = max(len(v) for v in values)
    out = np.full((len(values), n), np.nan)
    for i, v in enumerate(values):
        out[i, : len(v)] = v
    return out


def dem_dataset(name: str, collisions: list, fits: list, temperatures=None, config: dict | None = None):
    """The dataset of one ``dem:`` entry (module docstring): ``collisions`` and ``fits`` per temperature
    (one of each without a temperature sweep).

    Examples
    --------
    An SLS sphere (r = 10 mm) on a rigid wall at three speeds, every law fitted to vcor's COR:

    >>> import numpy as np
    >>> from vcor.dem import fit
    >>> from vcor.dem.export import dem_dataset
    >>> col = fit.collision("sls", [0.5, 1.0, 2.0], target="rigid")
    >>> ds = dem_dataset("demo", [col], [fit.fit_laws(col)])
    >>> ds["model"].values.tolist()
    ['lammps-viscoelastic', 'lammps-coeff-restitution', 'lammps-hereditary', 'mercurydpm-bshp', 'yade-mindlin',
     'table']
    >>> np.round(ds["max_abs_error"].values, 3)
    array([0.065, 0.03 , 0.   , 0.065, 0.065, 0.   ])
    """
    import xarray as xr

    models = list(fits[0])
    v0 = collisions[0].v0
    with_t = temperatures is not None
    nt = len(collisions)
    cor = np.array([c.cor for c in collisions])
    cor_model = np.array([[f[m]["cor"] for m in models] for f in fits])  # T, model, v0
    error = cor_model - cor[:, None, :]
    max_err = np.nanmax(np.abs(error), axis=2)
    within = np.array([[within_range(v0, error[t, k]) for k in range(len(models))] for t in range(nt)])
    status = np.array([[code(s) for s in c.status] for c in collisions], dtype=np.int8)
    message = np.array([[str(m) for m in c.message] for c in collisions])
    validity = np.array([c.validity for c in collisions], dtype=np.int8)
    validity_message = np.array([[str(m) for m in c.validity_message] for c in collisions])
    soe_error = np.array([c.soe_error for c in collisions], dtype=float)
    ok = status == code("ok")
    opposed = np.array([trend.opposite(cor[t], cor_model[t], ok[t], WITHIN) for t in range(nt)], dtype=np.int8)
    prefix = [f"At T = {float(T):g} degC: " if with_t else "" for T in (temperatures if with_t else [None])]
    warnings = [trend.warning(v0, cor[t], cor_model[t], ok[t], models, WITHIN, prefix[t]) for t in range(nt)]

    def squeeze(dims, arr):
        return (dims, arr) if with_t else (dims[1:], arr[0])

    data = {
        "cor": squeeze(("T", "v0"), cor),
        "status": squeeze(("T", "v0"), status),
        "message": squeeze(("T", "v0"), message),
        "validity": squeeze(("T", "v0"), validity),
        "validity_message": squeeze(("T", "v0"), validity_message),
        "soe_error": squeeze(("T", "v0"), soe_error),
        "cor_model": squeeze(("T", "model", "v0"), cor_model),
        "error": squeeze(("T", "model", "v0"), error),
        "max_abs_error": squeeze(("T", "model"), max_err),
        "v0_within_lo": squeeze(("T", "model"), within[..., 0]),
        "v0_within_hi": squeeze(("T", "model"), within[..., 1]),
        "opposite_trend": squeeze(("T", "model"), opposed),
    }
    params = {}
    for model in models:
        for p, (unit, meaning) in PARAMETERS[model].items():
            key = p if p not in params else f"{p}_{model}"
            params[key] = (model, unit, meaning, _per_temperature([f[model][p] for f in fits]))
    for key, (_, _, _, values) in params.items():
        dims = ("T", TERM_DIM) if values.ndim == 2 else ("T",)
        data[key] = (dims, values) if with_t else (dims[1:], values[0])
    coords = {"model": ("model", np.array(models, dtype=str)), "v0": ("v0", v0)}
    if with_t:
        coords["T"] = ("T", np.asarray(temperatures, dtype=float))
    ds = xr.Dataset(data, coords=coords)
    if TERM_DIM in ds.dims:
        ds = ds.assign_coords({TERM_DIM: np.arange(1, ds.sizes[TERM_DIM] + 1)})
        ds[TERM_DIM].attrs.update(units="1", long_name="term i of lammps-hereditary's Prony series")
    _describe(ds, params, with_t)
    _global_attrs(ds, name, collisions, models, config)
    ds.attrs["trend_warning"] = " ".join(w for w in warnings if w)
    if HEREDITARY in models:
        ds.attrs["hereditary_series"] = " | ".join(dict.fromkeys(f[HEREDITARY]["source"] for f in fits))
        ds.attrs["hereditary_nsteps"] = int(fits[0][HEREDITARY]["nsteps"])
    if "yade-mindlin" in models:
        ds.attrs["yade_version_required"] = YADE_VERSION
        ds.attrs["yade_version_note"] = REQUIRES["yade-mindlin"]
    return ds


def table_csv(path, collisions: list, temperatures=None) -> None:
    """The COR table (module docstring), written atomically.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from vcor.dem import fit
    >>> from vcor.dem.export import table_csv
    >>> path = Path(tempfile.mkdtemp()) / "cor.csv"
    >>> table_csv(path, [fit.collision("sls", [1.0, 2.0], target="rigid")])
    >>> print(path.read_text(), end="")
    v0,cor
    m/s,1
    1,0.686...
    2,0.714...
    """
    lines = ["T,v0,cor" if temperatures is not None else "v0,cor",
             "degC,m/s,1" if temperatures is not None else "m/s,1"]
    for i, col in enumerate(collisions):
        for v, c, s in zip(col.v0, col.cor, col.status):
            if s != "ok":
                continue
            row = f"{v:.10g},{c:.10g}"
            lines.append(f"{float(temperatures[i]):.10g},{row}" if temperatures is not None else row)
    atomic_text(path, "\n".join(lines) + "\n")


def _parameter_rows(ds) -> list[str]:
    """model,parameter,T,value,unit,meaning rows of every law's parameters and of the contact."""
    has_t = "T" in ds.dims
    temps = [float(t) for t in ds["T"].values] if has_t else [None]
    rows = []
    for key, var in ds.data_vars.items():
        if "model" not in var.attrs:
            continue
        name = key.removesuffix(f"_{var.attrs['model']}")
        for i, T in enumerate(temps):
            values = np.atleast_1d(var.values[i] if has_t else var.values)
            labels = [name] if TERM_DIM not in var.dims else [f"{name}[{k + 1}]" for k in range(values.size)]
            rows += [[var.attrs["model"], label, "" if T is None else f"{T:.10g}", f"{float(value):.12g}",
                      var.attrs["units"], var.attrs["long_name"]]
                     for label, value in zip(labels, values) if np.isfinite(value)]
    contact = json.loads(ds.attrs["contact"])
    for name, unit, value in [("m_eff", "kg", contact["m_eff_kg"]), ("r_eff", "m", contact["r_eff_m"]),
                              ("nu", "1", contact["nu"])]:
        rows.append(["contact", name, "", f"{value:.12g}", unit, f"the contact's {name} ({contact['kind']})"])
    for i, (r, rho) in enumerate(zip(contact["radii_m"], contact["densities_kg_m-3"]), start=1):
        rows.append(["contact", f"radius_{i}", "", f"{r:.12g}", "m", f"radius of sphere {i}"])
        rows.append(["contact", f"density_{i}", "", f"{rho:.12g}", "kg m-3", f"density of sphere {i}"])
    return rows


def _within(a: float, b: float) -> str:
    """The speeds within WITHIN, from ``a`` to ``b`` (m/s; NaN or a > b: none), in words."""
    return (f"at no speed within {WITHIN:g}" if not (np.isfinite(a) and np.isfinite(b) and a <= b)
            else f"within {WITHIN:g} only at {a:.3g} m/s" if a == b
            else f"within {WITHIN:g} from {a:.3g} to {b:.3g} m/s")


def quality_lines(ds, laws=None) -> list[str]:
    """How well the dataset's laws (``laws``: these only) follow vcor's COR, in words, for the files a DEM user
    reads without the dataset (the deck, the script, the parameters file): per law the largest ``abs(error)``
    over the speeds (and temperatures) and the speeds within ``WITHIN``; the ``trend_warning``; the speeds
    where vcor's own result is outside the model's stated range (``validity``) or not ok."""
    models = [str(m) for m in ds["model"].values if laws is None or str(m) in laws]
    lines = []
    for m in models:
        errs = np.atleast_1d(ds["max_abs_error"].sel(model=m).values)
        err = float(np.nanmax(errs))
        lo = np.atleast_1d(ds["v0_within_lo"].sel(model=m).values)
        hi = np.atleast_1d(ds["v0_within_hi"].sel(model=m).values)
        if "T" in ds.dims:  # a law that misses at one temperature may follow the curve at another: each its own
            each = "; ".join(f"at {T:g} degC {e:.3g}, {_within(float(a), float(b))}"
                             for T, e, a, b in zip(ds["T"].values, errs, lo, hi))
            lines.append(f"{m}: largest |COR of the law - vcor's COR| {err:.3g} over the speeds and temperatures; "
                         f"{each}")
        else:
            lines.append(f"{m}: largest |COR of the law - vcor's COR| {err:.3g} over the speeds; "
                         f"{_within(float(lo[0]), float(hi[0]))}")
    if ds.attrs.get("trend_warning"):
        lines.append(f"WARNING: {ds.attrs['trend_warning']}")
    flagged = np.atleast_1d(ds["validity"].values != 0)
    failed = np.atleast_1d(ds["status"].values != 0)
    v0 = ds["v0"].values
    for what, mask in (("outside the model's stated range (validity flags; see the dataset's validity_message)",
                        flagged), ("not solved (status not ok: no law is fitted there)", failed)):
        speeds = sorted({float(v0[j]) for j in np.argwhere(mask)[:, -1]})
        if speeds:
            lines.append(f"vcor's COR at v0 = {', '.join(f'{v:.3g}' for v in speeds)} m/s is {what}")
    return lines


def parameters_csv(path, ds) -> None:
    """Every law's parameters of the DEM dataset ``ds`` (:func:`dem_dataset`) as CSV, written atomically:
    ``#`` lines first (the entry, the code version each law needs), then the header
    ``model,parameter,T,value,unit,meaning`` (T in deg C, empty without a temperature sweep), then one
    row per law, parameter and temperature, and the contact's (``model`` = ``contact``)."""
    models = json.loads(ds.attrs["models"])
    lines = [f"# vcor DEM parameters of entry {ds.attrs['dem']} (dataset results/dem/{ds.attrs['dem']}.nc)"]
    lines += [f"# {m} requires: {info['requires']}" for m, info in models.items()]
    lines += [f"# {line}" for line in quality_lines(ds)]
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(["model", "parameter", "T", "value", "unit", "meaning"])
    writer.writerows(_parameter_rows(ds))
    atomic_text(path, "\n".join(lines) + "\n" + out.getvalue())
