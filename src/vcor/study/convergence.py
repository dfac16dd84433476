"""Work-precision study: COR error against solver wall time for every method.

For one material and impact speed, each method runs on a ladder (steps per contact time for the
fixed-step methods, rtol for solve_ivp). The reference is Richardson-extrapolated ``direct`` (form a)
from the two finest steps, cross-checked against ``ive`` (Radau, rtol 1e-12) for Prony kernels.
The Volterra-on ladder has its own reference (the same extrapolation with the term on).
Wall times are medians of ``repeat`` runs of the solver alone (``Result.wall_time``).
"""

from __future__ import annotations

import json
import math
import statistics

import numpy as np

from .. import status as _status
from ..materials.catalogue import Catalogue
from ..solvers.common import richardson
from ..solvers.options import solver_options

__all__ = ["LADDER", "RICHARDSON_STEP_TOLS", "RTOLS", "STEP_TOLS", "V0_ATTRS", "ladder_runs", "methods_for",
           "observed_order", "reference_gap", "study"]

LADDER = (250, 500, 1000, 2000, 4000, 8000)
#: CF attributes of the impact-speed coordinate of the work-precision datasets
V0_ATTRS = {"units": "m s-1", "long_name": "impact speed"}
RTOLS = (1e-4, 1e-6, 1e-8, 1e-10)
#: step_tol ladders of the adaptive method: without Richardson extrapolation, and with it (the default)
STEP_TOLS = (1e-5, 1e-6, 1e-7, 1e-8, 1e-9)
RICHARDSON_STEP_TOLS = (1e-3, 3e-4, 1e-4, 3e-5)
REF_STEPS = (8000, 16000)


def methods_for(material) -> list[tuple[str, dict, tuple]]:
    """(name, simulate keywords, ladder) of the methods that apply to ``material``."""
    out = [("direct-a", {"method": "direct"}, LADDER)]
    if math.isfinite(material.glassy):
        out.append(("direct-b", {"method": "direct", "form": "b"}, LADDER))
    out.append(("direct-a+volterra", {"method": "direct", "volterra": True}, LADDER[:-1]))
    if material.is_prony:
        out += [("ive-Radau", {"method": "ive", "ive_method": "Radau"}, RTOLS),
                ("ive-BDF", {"method": "ive", "ive_method": "BDF"}, RTOLS),
                ("ive-numba", {"method": "ive-numba"}, LADDER)]
    out.append(("soe", {"method": "soe"}, LADDER))
    out.append(("adaptive", {"method": "adaptive"}, RICHARDSON_STEP_TOLS))
    out.append(("adaptive-plain", {"method": "adaptive", "richardson": False}, STEP_TOLS))
    if material.viscosity == 0:  # the paper's explicit scheme has no Dirac (Kelvin-Voigt) term
        out.append(("paper-explicit", {"method": "paper"}, LADDER))
    return out


def _run(material, v0, kw, level, repeat):
    from ..solvers.simulate import simulate  # here, not at the top: combining the cases loads no solver
    if "method" in kw and kw["method"] == "ive":
        args = {**kw, "rtol": level}
        repeat = 1  # slow and not noisy at this scale
    elif kw.get("method") == "adaptive":
        args = {**kw, "step_tol": level}
    else:
        args = {**kw, "steps_per_contact": int(level)}
    runs = [simulate(material, v0, **args) for _ in range(repeat)]
    r = runs[-1]
    return r, statistics.median(x.wall_time for x in runs)


def _reference(material, v0, **kw):
    from ..solvers.simulate import simulate
    a = simulate(material, v0, method="direct", steps_per_contact=REF_STEPS[0], **kw)
    b = simulate(material, v0, method="direct", steps_per_contact=REF_STEPS[1], **kw)
    if not (a.ok and b.ok):
        return math.nan, math.nan
    return richardson(a.cor, b.cor)[0], richardson(a.t0, b.t0)[0]


def study(name, v0, *, catalogue: Catalogue | None = None, repeat=3):
    """Dataset with dims (solver, level): cor, t0, wall_time, param, err_cor, err_t0, status."""
    import xarray as xr

    from ..solvers.simulate import simulate

    material = (catalogue or Catalogue()).material(name)
    simulate(material, v0)  # JIT / cache load outside the timings
    ref_cor, ref_t0 = _reference(material, v0)
    ref_v_cor, ref_v_t0 = _reference(material, v0, volterra=True)
    cross = simulate(material, v0, method="ive", rtol=1e-12).cor if material.is_prony else math.nan
    methods = methods_for(material)
    n_level = max(len(m[2]) for m in methods)
    shape = (len(methods), n_level)
    cor, t0, wall, param, steps = (np.full(shape, np.nan) for _ in range(5))
    status = np.full(shape, _status.code("invalid-input"), dtype=np.int8)
    message = np.full(shape, "not on this solver's ladder", dtype=object)
    for i, (_, kw, ladder) in enumerate(methods):
        for j, level in enumerate(ladder):
            r, w = _run(material, v0, kw, level, repeat)
            cor[i, j], t0[i, j], wall[i, j], steps[i, j] = r.cor, r.t0, w, r.steps
            param[i, j] = level
            status[i, j], message[i, j] = _status.code(r.status), r.message
    volt = np.array(["volterra" in m[0] for m in methods])[:, None]
    rc = np.where(volt, ref_v_cor, ref_cor)
    rt = np.where(volt, ref_v_t0, ref_t0)
    ds = xr.Dataset(
        {
            "cor": (("solver", "level"), cor, {"units": "1", "long_name": "coefficient of restitution"}),
            "t0": (("solver", "level"), t0, {"units": "s", "long_name": "separation time"}),
            "wall_time": (("solver", "level"), wall, {"units": "s", "long_name": "solver wall time (median)"}),
            "param": (("solver", "level"), param,
                      {"units": "1",
                       "long_name": "steps per contact time (fixed step), rtol (ive) or step_tol (adaptive)"}),
            "steps": (("solver", "level"), steps, {"units": "1", "long_name": "time steps to separation"}),
            "err_cor": (("solver", "level"), np.abs(cor - rc), {"units": "1", "long_name": "|COR - reference|"}),
            "err_t0": (("solver", "level"), np.abs(t0 - rt), {"units": "s", "long_name": "|t0 - reference|"}),
            "status": (("solver", "level"), status, _status.cf_attrs()),
            "message": (("solver", "level"), message.astype(str), {"long_name": "solver message"}),
            "solver_options": ("solver", np.array([json.dumps(solver_options(**m[1]).to_dict(), sort_keys=True)
                                                    for m in methods], dtype=str),
                               {"long_name": "resolved solver options (JSON; the ladder sets steps_per_contact, "
                                             "rtol or step_tol)"}),
            "cor_ref": ((), ref_cor, {"units": "1", "long_name": "reference COR (Richardson, direct-a)"}),
            "cor_ref_volterra": ((), ref_v_cor, {"units": "1", "long_name": "reference COR with Volterra"}),
            "cor_ive_1e12": ((), cross, {"units": "1", "long_name": "ive Radau rtol 1e-12 (Prony only)"}),
        },
        coords={
            "solver": ("solver", np.array([m[0] for m in methods], dtype=str), {"long_name": "solver and options"}),
            "level": ("level", np.arange(n_level), {"units": "1", "long_name": "ladder index"}),
        },
    )
    return ds


def ladder_runs(ds):
    """The ``status`` of the cells of a work-precision dataset that are runs, as a dataset (what a job's
    log counts): the cells past the end of a shorter ladder (no ladder value, status invalid-input) are
    not runs."""
    dims = ds["status"].dims
    on_ladder = np.isfinite(ds["param"].transpose(*dims).values).ravel()
    return ds["status"].stack(cell=dims).isel(cell=on_ladder).to_dataset()


def observed_order(ds, solver):
    """Slope of log err_cor against log(1/steps) over the finite points: steps per contact (the
    ladder) for fixed-step methods, the steps taken for ``adaptive`` (with Richardson: the steps of
    both grids) and ``adaptive-plain``."""
    d = ds.sel(solver=solver)
    p, e = d["steps" if solver.startswith("adaptive") else "param"].values, d["err_cor"].values
    ok = np.isfinite(p) & np.isfinite(e) & (e > 0)
    if ok.sum() < 3:
        return math.nan
    return float(np.polyfit(np.log(1.0 / p[ok]), np.log(e[ok]), 1)[0])


def reference_gap(ds) -> float:
    """``|cor_ref - cor_ive_1e12|`` of one case: the Richardson reference against an independent solver
    (Radau on the internal variables, rtol 1e-12); NaN where either is missing (a kernel that is not a
    Prony sum has no ive run; a run that did not finish has no COR)."""
    return float(abs(ds["cor_ref"] - ds["cor_ive_1e12"]))


def combine(cases, materials, v0s):
    """Stack per-case datasets into dims (material, v0, solver, level); solvers that do not apply to
    a material (e.g. ive for the fractional law) are NaN with status invalid-input and a message."""
    import xarray as xr

    solvers = []
    for ds in cases.values():
        for s in ds["solver"].values:
            if str(s) not in solvers:
                solvers.append(str(s))
    rows = []
    for m in materials:
        cols = []
        for i, v in enumerate(v0s):
            ds = cases[(m, i)].reindex(solver=solvers)
            missing = ~np.isin(solvers, cases[(m, i)]["solver"].values)
            ds["status"] = ds["status"].fillna(_status.code("invalid-input")).astype(np.int8)
            ds["message"] = ds["message"].where(~missing[:, None], f"solver does not apply to material {m}")
            cols.append(ds.expand_dims(v0=[float(v)]))
        rows.append(xr.concat(cols, dim="v0"))
    out = xr.concat(rows, dim="material").assign_coords(material=("material", np.array(materials, dtype=str)))
    out.attrs = {}  # a case's global attributes (its one material) do not describe the study
    out["v0"].attrs.update(V0_ATTRS)
    out["material"].attrs["long_name"] = "material"
    for name in ("status", "message"):
        out[name].attrs.update(cases[(materials[0], 0)][name].attrs)
    return out


def orders_table(ds) -> str:
    """Observed orders (slope of log COR error vs log dt) for the fixed-step solvers and, last, the
    cross-check of the reference: ``|cor_ref - cor_ive_1e12|`` ('-' where there is none: a kernel that is
    not a Prony sum, or a reference or ive run that did not finish)."""
    lines = ["# observed order of the COR error in dt (fixed-step solvers); '-' where not applicable",
             "# last column: |reference COR - ive Radau at rtol 1e-12|, the reference's error scale; '-' without one",
             f"{'material':14s} {'v0 [m/s]':>8s} " + " ".join(f"{s:>18s}" for s in ds["solver"].values)
             + f" {'|ref - ive 1e-12|':>18s}"]
    for m in ds["material"].values:
        for v in ds["v0"].values:
            d = ds.sel(material=m, v0=v)
            vals = []
            for s in ds["solver"].values:
                if str(s).startswith("ive-") and str(s) != "ive-numba":
                    vals.append("-")
                else:
                    o = observed_order(d, str(s))
                    vals.append("-" if not math.isfinite(o) else f"{o:.2f}")
            gap = reference_gap(d)
            vals.append("-" if not math.isfinite(gap) else f"{gap:.1e}")
            lines.append(f"{m!s:14s} {v:8g} " + " ".join(f"{x:>18s}" for x in vals))
    return "\n".join(lines) + "\n"
