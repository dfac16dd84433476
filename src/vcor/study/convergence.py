"""Work-precision study: COR error against solver wall time for every method.

For one material and impact speed, each method runs on a ladder (steps per contact time for the
fixed-step methods, rtol for solve_ivp). The reference is Richardson-extrapolated ``direct`` (form a)
from the two finest steps, cross-checked against ``ive`` (Radau, rtol 1e-12) for Prony kernels.
Its own error is estimated for every kernel as the distance to the same extrapolation one step
coarser (``cor_ref_error``: that coarser value's error, larger than the reference's); an error within
ERROR_FLOOR times it measures the reference as much as the solver and is left out of the observed
orders. The Volterra-on ladder has its own reference (the same extrapolation with the term on).
A reference that does not finish leaves the errors NaN and says why (``reference_status``,
``reference_message``). Wall times are medians of ``repeat`` runs of the solver alone
(``Result.wall_time``).
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

__all__ = ["ERROR_FLOOR", "LADDER", "REF_CHECK_STEPS", "RICHARDSON_STEP_TOLS", "RTOLS", "STEP_TOLS", "V0_ATTRS",
           "error_floor", "ladder_runs", "methods_for", "observed_order", "reference_gap", "study"]

LADDER = (250, 500, 1000, 2000, 4000, 8000)
#: CF attributes of the impact-speed coordinate of the work-precision datasets
V0_ATTRS = {"units": "m s-1", "long_name": "impact speed"}
RTOLS = (1e-4, 1e-6, 1e-8, 1e-10)
#: step_tol ladders of the adaptive method: without Richardson extrapolation, and with it (the default)
STEP_TOLS = (1e-5, 1e-6, 1e-7, 1e-8, 1e-9)
RICHARDSON_STEP_TOLS = (1e-3, 3e-4, 1e-4, 3e-5)
REF_STEPS = (8000, 16000)
#: the reference's error estimate: its distance to the extrapolation from this step and REF_STEPS[0]
REF_CHECK_STEPS = 4000
#: errors at most this many times the reference's error estimate (or its distance to ive) are left out
#: of the observed orders
ERROR_FLOOR = 3.0


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
    """(COR, t0 (s), the COR's error estimate, status code, message) of the Richardson-extrapolated
    ``direct`` reference (module docstring); NaN values, the failed run's status and a message saying
    which run failed and why when one did not finish."""
    from ..solvers.simulate import simulate
    runs = []
    for n in (REF_CHECK_STEPS, *REF_STEPS):
        r = simulate(material, v0, method="direct", steps_per_contact=n, **kw)
        if not r.ok:
            return (math.nan, math.nan, math.nan, _status.code(r.status),
                    f"the reference's direct run at {n} steps per contact time ended {r.status}: {r.message}")
        runs.append(r)
    check, a, b = runs
    cor = richardson(a.cor, b.cor)[0]
    return cor, richardson(a.t0, b.t0)[0], abs(cor - richardson(check.cor, a.cor)[0]), _status.code("ok"), ""


def _references(material, v0):
    """(the dataset's reference variables, reference COR and t0 (s), the same with Volterra) of one case:
    both references (:func:`_reference`), their error estimates, floors and statuses, and the ive cross-check."""
    from ..solvers.simulate import simulate

    ref_cor, ref_t0, ref_error, ref_status, ref_message = _reference(material, v0)
    ref_v_cor, ref_v_t0, ref_v_error, ref_v_status, ref_v_message = _reference(material, v0, volterra=True)
    cross = simulate(material, v0, method="ive", rtol=1e-12).cor if material.is_prony else math.nan
    estimate = f"distance to the extrapolation from {REF_CHECK_STEPS} and {REF_STEPS[0]} steps"
    floor = (f"COR errors at most this measure the reference as much as the solver: {ERROR_FLOOR:g} x the larger "
             f"of the reference's error estimate and its distance to ive at rtol 1e-12")
    variables = {
        "cor_ref": ((), ref_cor, {"units": "1", "long_name": "reference COR (Richardson, direct-a)"}),
        "cor_ref_error": ((), ref_error, {"units": "1",
                                          "long_name": f"error estimate of the reference COR: {estimate}"}),
        "err_cor_floor": ((), _floor(ref_error, abs(ref_cor - cross)), {"units": "1", "long_name": floor}),
        "reference_status": ((), np.int8(ref_status), _status.cf_attrs()),
        "reference_message": ((), ref_message, {"long_name": "why the reference did not finish (empty: it did)"}),
        "cor_ref_volterra": ((), ref_v_cor, {"units": "1", "long_name": "reference COR with Volterra"}),
        "cor_ref_volterra_error": ((), ref_v_error, {"units": "1", "long_name": "error estimate of the reference "
                                                                              f"COR with Volterra: {estimate}"}),
        "err_cor_floor_volterra": ((), _floor(ref_v_error, math.nan),
                                   {"units": "1", "long_name": f"the same floor for the Volterra ladder "
                                                               f"({ERROR_FLOOR:g} x its reference's error estimate)"}),
        "reference_volterra_status": ((), np.int8(ref_v_status), _status.cf_attrs()),
        "reference_volterra_message": ((), ref_v_message, {"long_name": "why the reference with Volterra did not "
                                                                        "finish (empty: it did)"}),
        "cor_ive_1e12": ((), cross, {"units": "1", "long_name": "ive Radau rtol 1e-12 (Prony only)"}),
    }
    return variables, ref_cor, ref_t0, ref_v_cor, ref_v_t0


def study(name, v0, *, catalogue: Catalogue | None = None, repeat=3):
    """Dataset with dims (solver, level): cor, t0, wall_time, param, err_cor, err_t0, status."""
    import xarray as xr

    from ..solvers.simulate import simulate

    material = (catalogue or Catalogue()).material(name)
    simulate(material, v0)  # JIT / cache load outside the timings
    references, ref_cor, ref_t0, ref_v_cor, ref_v_t0 = _references(material, v0)
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
            **references,
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
    """Slope of log err_cor against log(1/steps) over the finite points above the reference's floor
    (:func:`error_floor`): steps per contact (the ladder) for fixed-step methods, the steps taken for
    ``adaptive`` (with Richardson: the steps of all its grids) and ``adaptive-plain``; NaN with fewer than
    three such points."""
    d = ds.sel(solver=solver)
    p, e = d["steps" if solver.startswith("adaptive") else "param"].values, d["err_cor"].values
    ok = np.isfinite(p) & np.isfinite(e) & (e > error_floor(ds, "volterra" in solver))
    if ok.sum() < 3:
        return math.nan
    return float(np.polyfit(np.log(1.0 / p[ok]), np.log(e[ok]), 1)[0])


def error_floor(ds, volterra: bool = False) -> float:
    """One case's ``err_cor_floor`` (``err_cor_floor_volterra`` for the Volterra ladder): the COR error at or
    below which its errors measure the reference as much as the solver (:func:`_floor`); 0 for a dataset
    without it."""
    name = "err_cor_floor_volterra" if volterra else "err_cor_floor"
    return float(ds[name]) if name in ds else 0.0


def _floor(error, gap):
    """ERROR_FLOOR times the larger of a reference's error estimate and its distance to ive at rtol 1e-12
    (where there is one)."""
    return ERROR_FLOOR * (max(error, gap) if math.isfinite(gap) else error)


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
    """Observed orders (:func:`observed_order`: slope of log COR error against log dt for the fixed-step
    solvers, against log of the steps taken for ``adaptive``; ive's tolerance ladders have none), then the
    reference's error estimate ``cor_ref_error`` and its cross-check ``|cor_ref - cor_ive_1e12|`` ('-' where
    there is none: a kernel that is not a Prony sum, or a reference or ive run that did not finish)."""
    lines = [f"# observed order of the COR error: in dt (fixed-step solvers), in the steps taken (adaptive), over the "
             f"errors above {ERROR_FLOOR:g} x the reference's error scale; '-' where not applicable or fewer than "
             f"three such errors",
             "# last columns: the reference's error estimate (distance to the extrapolation one step coarser) and "
             "|reference COR - ive Radau at rtol 1e-12|; '-' without one",
             f"{'material':14s} {'v0 [m/s]':>8s} " + " ".join(f"{s:>18s}" for s in ds["solver"].values)
             + f" {'ref error est.':>18s} {'|ref - ive 1e-12|':>18s}"]
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
            for value in (float(d["cor_ref_error"]) if "cor_ref_error" in d else math.nan, reference_gap(d)):
                vals.append("-" if not math.isfinite(value) else f"{value:.1e}")
            lines.append(f"{m!s:14s} {v:8g} " + " ".join(f"{x:>18s}" for x in vals))
    return "\n".join(lines) + "\n"
