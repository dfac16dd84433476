"""Datasets other than sweeps: material moduli curves and impact time histories (for figures)."""

from __future__ import annotations

import json

import numpy as np

from .. import spheres as S
from .. import status as _status
from ..contact.impact import GEOMETRY_DEFAULTS
from ..fitting.g_star import bridges_ice, fit_g_star
from ..materials.catalogue import Catalogue
from ..solvers import validity as _validity
from ..solvers.common import LONG_NAMES, UNITS
from ..solvers.options import solver_options

__all__ = ["histories_dataset", "moduli_dataset"]


def moduli_dataset(names, *, t_min=1e-6, t_max=1e-1, omega_min=1e1, omega_max=1e7, n=400,
                   catalogue: Catalogue | None = None):
    """E(t) on a log time grid and E*(omega) (storage, loss, tan delta) on a log frequency grid."""
    import xarray as xr

    t = np.geomspace(t_min, t_max, n)
    w = np.geomspace(omega_min, omega_max, n)
    et, st, lo = [], [], []
    glassy, rubbery = [], []
    for name in names:
        mat = (catalogue or Catalogue()).material(name)
        et.append(mat.relaxation_modulus(t))
        e = mat.complex_modulus(w)
        st.append(e.real)
        lo.append(e.imag)
        glassy.append(mat.glassy)
        rubbery.append(mat.rubbery)
    st, lo = np.array(st), np.array(lo)
    ds = xr.Dataset(
        {
            "relaxation_modulus": (("material", "t"), np.array(et),
                                   {"units": "Pa", "long_name": "relaxation modulus E(t)"}),
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


def _history_run(material, method, v0, base, geometry, catalogue):
    from ..solvers.simulate import simulate  # here, not at the top: the moduli job loads no solver

    mat = catalogue.material(material)
    return simulate(mat, float(v0), options=base.replace(method=method), history=True, **geometry)


def histories_dataset(runs, v0, *, options=None, geometry=None, ghost=None, n_samples=600,
                      catalogue: Catalogue | None = None):
    """Time histories of ``runs`` = [(material, method), ...] at impact speed v0 (m/s).

    ``options`` are the scene's solver options (``SolverOptions`` or a dict); each run uses its own
    method with those of the options that apply to it (the separation ``rule`` always), and
    ``ghost`` (default: the options' ghost). Each run is resampled (linear interpolation of its own
    solution) onto ``n_samples`` uniform times from 0 to (1 + ghost) t0; ``t`` is therefore a
    (run, sample) variable. ``ghost`` marks the samples after separation. Scalars of each run are
    stored per run, with its validity flags and their sentence (``validity``, ``validity_message``:
    :mod:`vcor.solvers.validity`, as in a sweep dataset; 0 and "" for a run inside the model's stated
    range or not ok). A run that is not ok is stored as NaN with its status and message.
    """
    import xarray as xr

    catalogue = catalogue or Catalogue()
    base = solver_options(options or {})
    if ghost is not None:
        base = base.replace(ghost=ghost)
    geometry = dict(geometry or {})
    labels, cols = [], {k: [] for k in ("t", "s", "sdot", "F", "U", "zdot", "ghost")}
    scal = {k: [] for k in ("cor", "t0", "s_max", "f_max", "s_residual", "w_h", "wall_time")}
    status, message, flags, reasons = [], [], [], []
    for material, method in runs:
        res, name, text = _status.guarded(_history_run, material, method, v0, base, geometry, catalogue)
        labels.append(f"{material}/{method}")
        status.append(res.status if res is not None else name)
        message.append(res.message if res is not None else text)
        flags.append(res.validity if res is not None else 0)
        reasons.append(res.validity_message if res is not None else "")
        for k, values in scal.items():
            values.append(getattr(res, k) if res is not None else np.nan)
        h = res.history if res is not None else None
        if res is None or not res.ok or h is None:
            for k, values in cols.items():
                values.append(np.zeros(n_samples, bool) if k == "ghost" else np.full(n_samples, np.nan))
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
        attrs = {"units": u, "long_name": ln}
        if k == "ghost":
            arr = arr.astype(np.int8)
            attrs.update(flag_values=np.array([0, 1], dtype=np.int8), flag_meanings="in_contact after_separation")
        data[k] = (("run", "sample"), arr, attrs)
    for k, v in scal.items():
        data[k] = ("run", np.array(v, dtype=float), {"units": UNITS[k], "long_name": LONG_NAMES[k]})
    data["status"] = ("run", _status.codes_of(status), _status.cf_attrs())
    data["message"] = ("run", np.array(message, dtype=str), {"long_name": "solver message"})
    data["validity"] = ("run", np.array(flags, dtype=np.int8), _validity.cf_attrs())
    data["validity_message"] = ("run", np.array(reasons, dtype=str),
                                {"long_name": "why an ok result is outside the model's stated range"})
    coords = {
        "run": ("run", np.array(labels, dtype=str), {"long_name": "material/method"}),
        "sample": ("sample", np.arange(n_samples), {"units": "1", "long_name": "sample index"}),
    }
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(_history_attrs(base, labels, geometry, v0))
    return ds


def _history_attrs(base, labels, geometry, v0) -> dict:
    """The histories' global attributes: each run's own options (its method, with the scene's options that
    apply to it) by run label, the geometry and its defaults, the speed."""
    options = {label: base.replace(method=label.rsplit("/", 1)[1]).to_dict() for label in labels}
    return {"solver_options": json.dumps(options, sort_keys=True), "geometry": json.dumps(geometry, sort_keys=True),
            "geometry_defaults": json.dumps(dict(GEOMETRY_DEFAULTS), sort_keys=True), "v0": float(v0),
            "v0_units": "m s-1"}


def spheres_dataset(b_values, *, rules=("overlap", "force"), tau_ratios=(), steps_per_contact=2000, ice=None):
    """Viscoelastic spheres: eps(b) numerically (Kelvin-Voigt, both rules; SLS variants with
    relaxation time tau = tau_ratio * t_c), the series at orders 1..4, both Pades and the root of
    Ramirez Eq. 27. A failed point is stored as NaN with its message in ``message`` (never raised).
    ``ice`` ({g_min_cm_s, g_max_cm_s, n}): g* fitted to the Bridges ice law on that range
    (``vcor.fitting.g_star.fit_g_star``; the numerical eps for each rule, and the Pade) and the fitted curves."""
    import xarray as xr

    b = np.array(sorted(float(x) for x in b_values))
    rules = list(rules)
    num = np.full((len(rules), b.size), np.nan)
    msg = np.full((len(rules), b.size), "", dtype=object)
    st = np.zeros((len(rules), b.size), dtype=np.int8)
    her = np.full((len(tau_ratios), len(rules), b.size), np.nan)
    her_msg = np.full((len(tau_ratios), len(rules), b.size), "", dtype=object)
    her_st = np.zeros((len(tau_ratios), len(rules), b.size), dtype=np.int8)

    def solve(fn, *args):
        value, name, message = _status.guarded(fn, *args, steps_per_contact=steps_per_contact)
        return (np.nan if value is None else value), name, message

    for i, rule in enumerate(rules):
        for j, x in enumerate(b):
            num[i, j], name, msg[i, j] = solve(S.cor_numeric, x, rule)
            st[i, j] = _status.code(name)
            for k, tr in enumerate(tau_ratios):
                her[k, i, j], name, her_msg[k, i, j] = solve(S.cor_numeric_sls, x, tr, rule)
                her_st[k, i, j] = _status.code(name)
    eps = ("1", "coefficient of restitution")
    ds = xr.Dataset(
        {
            "eps_numeric": (("rule", "b"), num, {"units": eps[0], "long_name": "eps, direct solver, Kelvin-Voigt"}),
            "status": (("rule", "b"), st, _status.cf_attrs()),
            "message": (("rule", "b"), msg.astype(str), {"long_name": "solver message (empty when ok)"}),
            "eps_series": (("order", "b"), np.array([S.cor_series(b, k) for k in (1, 2, 3, 4)]),
                           {"units": "1", "long_name": "truncated series 1 + sum C_k b^k (Ramirez Eq. 65)"}),
            "eps_pade": ("b", S.cor_pade(b), {"units": "1", "long_name": "Ramirez [1/4] Pade (Eq. 35)"}),
            "eps_pade_force": ("b", S.cor_pade_force(b),
                               {"units": "1", "long_name": "Mueller & Poeschel 2011 Pade (force rule)"}),
            "eps_root": ("b", S.cor_root(b), {"units": "1", "long_name": "root of Ramirez Eq. 27"}),
            "eps_sls": (("tau_ratio", "rule", "b"), her,
                        {"units": "1", "long_name": "eps, SLS with the Kelvin-Voigt viscosity, tau = tau_ratio t_c"}),
            "status_sls": (("tau_ratio", "rule", "b"), her_st, _status.cf_attrs()),
            "message_sls": (("tau_ratio", "rule", "b"), her_msg.astype(str), {"long_name": "solver message"}),
        },
        coords={
            "b": ("b", b, {"units": "1", "long_name": "b = 3/2 A (rho/m_eff)^(2/5) g^(1/5)"}),
            "rule": ("rule", np.array(rules, dtype=str), {"long_name": "separation rule"}),
            "order": ("order", np.arange(1, 5), {"units": "1", "long_name": "series order"}),
            "tau_ratio": ("tau_ratio", np.array(tau_ratios, dtype=float),
                          {"units": "1", "long_name": "relaxation time / elastic contact time"}),
        },
    )
    ds.attrs.update(C=list(S.C), pade_d=list(S.pade_coefficients()), C1_closed_form=S.C1_CLOSED_FORM)
    if ice is not None:
        ds = ds.merge(_ice_fits(ice, rules))
    return ds


def _ice_fits(ice, rules):
    """g* of the Ramirez model fitted to the Bridges ice law (see :func:`spheres_dataset`)."""
    import xarray as xr

    g = np.geomspace(float(ice.get("g_min_cm_s", 0.05)), float(ice.get("g_max_cm_s", 5.0)), int(ice.get("n", 21)))
    eps = bridges_ice(g)
    c1 = abs(S.C[0])

    def one(model, rule):
        f = fit_g_star(g, eps, model=model, rule=rule)
        b = (g / f.g_star) ** 0.2 / c1
        curve = S.cor_pade(b) if model == "pade" else S.cor_numeric(b, rule)
        return f, curve

    names, gs, se, rms, curves, st, msg = [], [], [], [], [], [], []
    for model, rule in [("numeric", r) for r in rules] + [("pade", "overlap")]:
        out, name, message = _status.guarded(one, model, rule)  # a failed fit is stored, never raised
        names.append(f"numeric-{rule}" if model == "numeric" else "pade")
        f, curve = out if out is not None else (None, np.full(g.size, np.nan))
        gs.append(f.g_star if f else np.nan)
        se.append(f.stderr if f else np.nan)
        rms.append(f.rms if f else np.nan)
        curves.append(curve)
        st.append(_status.code(name))
        msg.append(message)
    return xr.Dataset(
        {
            "ice_g_star": ("ice_model", np.array(gs),
                           {"units": "cm s-1", "long_name": "g* fitted to the Bridges ice law"}),
            "ice_g_star_stderr": ("ice_model", np.array(se),
                                  {"units": "cm s-1", "long_name": "standard error of g* (residual scatter)"}),
            "ice_rms": ("ice_model", np.array(rms), {"units": "1", "long_name": "rms misfit in eps"}),
            "ice_status": ("ice_model", np.array(st, dtype=np.int8), _status.cf_attrs()),
            "ice_message": ("ice_model", np.array(msg, dtype=str), {"long_name": "fit message (empty when ok)"}),
            "ice_eps_law": ("ice_g", eps, {"units": "1", "long_name": "Bridges et al. law 0.32 g^-0.234"}),
            "ice_eps_fit": (("ice_model", "ice_g"), np.array(curves), {"units": "1", "long_name": "fitted model"}),
        },
        coords={"ice_model": ("ice_model", np.array(names, dtype=str), {"long_name": "fitted model of eps"}),
                "ice_g": ("ice_g", g, {"units": "cm s-1", "long_name": "impact speed g"})},
    )
