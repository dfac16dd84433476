"""Datasets other than sweeps: material moduli curves and impact time histories (for figures)."""

from __future__ import annotations

import numpy as np

from .solvers import simulate
from .sweep import SOLVER_DEFAULTS, resolve_material

__all__ = ["moduli_dataset", "histories_dataset"]


def moduli_dataset(names, *, t_min=1e-6, t_max=1e-1, omega_min=1e1, omega_max=1e7, n=400,
                   material_dir="results/materials"):
    """E(t) on a log time grid and E*(omega) (storage, loss, tan delta) on a log frequency grid."""
    import xarray as xr

    t = np.geomspace(t_min, t_max, n)
    w = np.geomspace(omega_min, omega_max, n)
    et, st, lo = [], [], []
    glassy, rubbery = [], []
    for name in names:
        mat = resolve_material(name, material_dir=material_dir)
        et.append(mat.relaxation_modulus(t))
        e = mat.complex_modulus(w)
        st.append(e.real)
        lo.append(e.imag)
        glassy.append(mat.glassy)
        rubbery.append(mat.rubbery)
    st, lo = np.array(st), np.array(lo)
    ds = xr.Dataset(
        {
            "relaxation_modulus": (("material", "t"), np.array(et), {"units": "Pa", "long_name": "relaxation modulus E(t)"}),
            "storage_modulus": (("material", "omega"), st, {"units": "Pa", "long_name": "storage modulus Re E*"}),
            "loss_modulus": (("material", "omega"), lo, {"units": "Pa", "long_name": "loss modulus Im E*"}),
            "tan_delta": (("material", "omega"), lo / st, {"units": "1", "long_name": "loss tangent"}),
            "glassy_modulus": ("material", np.array(glassy), {"units": "Pa", "long_name": "E(0+) (inf: unbounded)"}),
            "rubbery_modulus": ("material", np.array(rubbery), {"units": "Pa", "long_name": "E(t -> inf)"}),
        },
        coords={
            "material": ("material", np.array(list(names), dtype=str), {"long_name": "material"}),
            "t": ("t", t, {"units": "s", "long_name": "time"}),
            "omega": ("omega", w, {"units": "rad s-1", "long_name": "angular frequency"}),
        },
    )
    return ds


def histories_dataset(runs, v0, *, solver=None, geometry=None, ghost=0.5, n_samples=600,
                      material_dir="results/materials"):
    """Time histories of ``runs`` = [(material, method), ...] at impact speed v0 (m/s).

    Each run is resampled (linear interpolation of its own solution) onto ``n_samples`` uniform
    times from 0 to (1 + ghost) t0; ``t`` is therefore a (run, sample) variable. ``ghost`` marks
    the samples after separation. Scalars of each run are stored per run.
    """
    import xarray as xr

    solver = {**SOLVER_DEFAULTS, **(solver or {})}
    geometry = dict(geometry or {})
    labels, cols = [], {k: [] for k in ("t", "s", "sdot", "F", "U", "zdot", "ghost")}
    scal = {k: [] for k in ("cor", "t0", "s_max", "f_max", "s_residual", "w_h", "wall_time")}
    status, message = [], []
    for material, method in runs:
        mat = resolve_material(material, material_dir=material_dir)
        res = simulate(mat, float(v0), method=method, dt=solver["dt"], volterra=solver["volterra"],
                       form=solver["form"], rtol=solver["rtol"], ive_method=solver["ive_method"],
                       steps_per_contact=int(solver["steps_per_contact"]), history=True, ghost=ghost, **geometry)
        labels.append(f"{material}/{method}")
        status.append(res.status)
        message.append(res.message)
        for k in scal:
            scal[k].append(getattr(res, k))
        h = res.history
        if h is None:
            tt = np.zeros(n_samples)
            for k in cols:
                cols[k].append(np.zeros(n_samples, dtype=bool if k == "ghost" else float))
            cols["t"][-1] = tt
            continue
        t_end = h.t[-1]
        tt = np.linspace(0.0, t_end, n_samples)
        cols["t"].append(tt)
        for k, src in (("s", h.s), ("sdot", h.sdot), ("F", h.F), ("U", h.U), ("zdot", h.zdot)):
            cols[k].append(np.interp(tt, h.t, src))
        cols["ghost"].append(tt > res.t0 if res.ok else np.zeros(n_samples, bool))
    meta = {
        "t": ("s", "time"),
        "s": ("m", "interference s(t)"),
        "sdot": ("m s-1", "interference rate s'(t)"),
        "F": ("N", "contact force"),
        "U": ("m", "plate displacement under the contact"),
        "zdot": ("m s-1", "sphere velocity"),
        "ghost": ("1", "sample after separation (ghost solution, F may be negative)"),
    }
    data = {}
    for k, (u, ln) in meta.items():
        arr = np.array(cols[k])
        if k == "ghost":
            arr = arr.astype(np.int8)
        data[k] = (("run", "sample"), arr, {"units": u, "long_name": ln})
    units = {"cor": "1", "t0": "s", "s_max": "m", "f_max": "N", "s_residual": "m", "w_h": "J", "wall_time": "s"}
    for k, v in scal.items():
        data[k] = ("run", np.array(v, dtype=float), {"units": units[k], "long_name": k})
    data["status"] = ("run", np.array(status, dtype=str), {"long_name": "solver status"})
    data["message"] = ("run", np.array(message, dtype=str), {"long_name": "solver message"})
    coords = {
        "run": ("run", np.array(labels, dtype=str), {"long_name": "material/method"}),
        "sample": ("sample", np.arange(n_samples), {"units": "1", "long_name": "sample index"}),
    }
    ds = xr.Dataset(data, coords=coords)
    ds.attrs["v0"] = float(v0)
    ds.attrs["v0_units"] = "m s-1"
    return ds
