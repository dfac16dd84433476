"""What a DEM run reads: the dataset ``results/dem/<name>.nc`` and the COR table.

The dataset (CF attributes as every vcor dataset) has the dimensions ``model`` (the DEM laws,
:data:`vcor.dem.laws.MODELS`), ``v0`` (m/s) and, for a temperature sweep, ``T`` (deg C):

* ``cor(v0[, T])``: vcor's COR, with ``status``, ``message`` and ``validity`` per point;
* ``cor_model(model, v0[, T])`` and ``error = cor_model - cor``;
* ``max_abs_error(model[, T])`` over the speeds, and ``v0_within_lo``, ``v0_within_hi``: the widest
  run of consecutive speeds on which ``abs(error) <= WITHIN`` (NaN when there is none);
* each law's parameters (``eta_n0``, ``E_lammps``, ``e``, ``A``, ``E_eff``, ``en``, ``vn``), with
  units and the model they belong to, per temperature;
* the contact (``m_eff``, ``r_eff``, ``nu``, kind), the collision's config and each law's formula
  source and separation in the attributes.

The table is CSV with a header and a units row: ``v0,cor`` (and ``T`` first for a temperature sweep).
"""

from __future__ import annotations

import json

import numpy as np

from ..io.receipts import atomic_text
from ..status import cf_attrs, code
from .laws import PARAMETERS, SOURCES

__all__ = ["WITHIN", "dem_dataset", "table_csv", "within_range"]

#: the error bound of the sub-range a dataset reports for each law (COR, absolute)
WITHIN = 0.01
#: the separation each law's deck or code implies
SEPARATION = {
    "lammps-viscoelastic": "force (limit_damping: the force is clipped at zero)",
    "lammps-coeff-restitution": "overlap (no limit_damping: the contact ends at zero overlap; the COR is e)",
    "mercurydpm-bshp": "force (the normal force is clipped at zero)",
    "yade-mindlin": "force (the normal force is clipped at zero)",
    "table": "as vcor: where the contact force vanishes",
}


def within_range(v0, error, bound: float = WITHIN) -> tuple[float, float]:
    """(lowest, highest) speed of the widest run of consecutive speeds with ``abs(error) <= bound``;
    (nan, nan) when there is none."""
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


def dem_dataset(name: str, collisions: list, fits: list, temperatures=None, config: dict | None = None):
    """The dataset of one ``dem:`` entry (module docstring): ``collisions`` and ``fits`` per temperature
    (one of each without a temperature sweep)."""
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

    def squeeze(dims, arr):
        return (dims, arr) if with_t else (dims[1:], arr[0])

    data = {
        "cor": squeeze(("T", "v0"), cor),
        "status": squeeze(("T", "v0"), status),
        "message": squeeze(("T", "v0"), message),
        "validity": squeeze(("T", "v0"), validity),
        "cor_model": squeeze(("T", "model", "v0"), cor_model),
        "error": squeeze(("T", "model", "v0"), error),
        "max_abs_error": squeeze(("T", "model"), max_err),
        "v0_within_lo": squeeze(("T", "model"), within[..., 0]),
        "v0_within_hi": squeeze(("T", "model"), within[..., 1]),
    }
    params = {}
    for model in models:
        for p, (unit, meaning) in PARAMETERS[model].items():
            key = p if p not in params else f"{p}_{model}"
            params[key] = (model, unit, meaning, np.array([f[model][p] for f in fits]))
    for key, (model, unit, meaning, values) in params.items():
        data[key] = (("T",), values) if with_t else ((), values[0])
    contact = collisions[0].contact
    coords = {"model": ("model", np.array(models, dtype=str)), "v0": ("v0", v0)}
    if with_t:
        coords["T"] = ("T", np.asarray(temperatures, dtype=float))
    ds = xr.Dataset(data, coords=coords)
    units = {"cor": "1", "cor_model": "1", "error": "1", "max_abs_error": "1", "v0_within_lo": "m s-1",
             "v0_within_hi": "m s-1", "validity": "1"}
    names = {"cor": "vcor's COR (hereditary contact, the contact ends where the force vanishes)",
             "cor_model": "the DEM law's COR with its fitted parameters", "error": "cor_model - cor",
             "max_abs_error": "largest abs(error) over the speeds",
             "v0_within_lo": f"lowest speed of the widest run of speeds with abs(error) <= {WITHIN}",
             "v0_within_hi": f"highest speed of the widest run of speeds with abs(error) <= {WITHIN}",
             "message": "solver message", "validity": "validity flags of an ok result (vcor.solvers.validity)"}
    for v, text in names.items():
        ds[v].attrs["long_name"] = text
        if v in units:
            ds[v].attrs["units"] = units[v]
    ds["status"].attrs.update(cf_attrs())
    ds["status"].attrs["long_name"] = "status of vcor's solve at the point"
    for key, (model, unit, meaning, _) in params.items():
        ds[key].attrs.update(units=unit, long_name=meaning, model=model)
    ds["v0"].attrs.update(units="m s-1", long_name="impact speed (relative normal approach speed of a pair)")
    ds["model"].attrs["long_name"] = "DEM contact law (vcor.dem.laws)"
    if with_t:
        ds["T"].attrs.update(units="degC", long_name="temperature")
    ds.attrs.update({
        "dem": name,
        "dem_config": json.dumps(config or {}),
        "contact": json.dumps({"kind": contact.kind, "m_eff_kg": contact.m_eff, "r_eff_m": contact.r_eff,
                               "nu": contact.nu, "radii_m": list(contact.radii),
                               "densities_kg_m-3": list(contact.densities)}),
        "E_eff_note": "E_eff: vcor's contact stiffness at a quarter of its contact time at the reference speed "
                      "(vcor.dem.fit); it sets a DEM contact's duration, not its COR",
        "models": json.dumps({m: {"source": SOURCES[m], "separation": SEPARATION[m],
                                  "parameters": {p: u for p, (u, _) in PARAMETERS[m].items()}} for m in models}),
        "v_ref_m_s": collisions[0].v_ref,
    })
    return ds


def table_csv(path, collisions: list, temperatures=None) -> None:
    """The COR table (module docstring), written atomically."""
    lines = ["T,v0,cor" if temperatures is not None else "v0,cor",
             "degC,m/s,1" if temperatures is not None else "m/s,1"]
    for i, col in enumerate(collisions):
        for v, c, s in zip(col.v0, col.cor, col.status):
            if s != "ok":
                continue
            row = f"{v:.10g},{c:.10g}"
            lines.append(f"{float(temperatures[i]):.10g},{row}" if temperatures is not None else row)
    atomic_text(path, "\n".join(lines) + "\n")

