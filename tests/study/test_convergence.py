"""Work-precision study (docs/validation.md, "Convergence"): statuses, options and orders."""

import json

import numpy as np

from vcor import status
from vcor.solvers.options import SolverOptions
from vcor.study import convergence, summary


def test_study_records_options_statuses_and_order_two():
    ds = convergence.study("sls", 10.0, repeat=1)
    solvers = list(ds["solver"].values)
    assert {"direct-a", "direct-b", "direct-a+volterra", "ive-Radau", "ive-numba", "soe", "paper-explicit",
            "adaptive"} <= set(solvers)
    # every solver row says which resolved options it used (the ladder sets steps_per_contact or rtol)
    for name, text in zip(solvers, ds["solver_options"].values):
        opts = json.loads(str(text))
        assert set(opts) == set(SolverOptions.names())
        assert opts["method"] == {"ive-R": "ive", "ive-B": "ive", "ive-n": "ive-numba", "paper": "paper", "soe": "soe",
                                 "adapt": "adaptive"}.get(
            name[:5], "direct"), name
    assert ds["status"].dtype == np.int8
    assert ds["status"].attrs["flag_meanings"] == status.cf_attrs()["flag_meanings"]
    # cells beyond a solver's ladder are flagged, with a message, never left as unlabelled NaN
    off = ~np.isfinite(ds["param"].values)
    assert off.any()
    assert np.all(ds["status"].values[off] == status.code("invalid-input"))
    assert all("ladder" in str(m) for m in ds["message"].values[off])
    on = ~off
    assert np.all(ds["status"].values[on] == status.code("ok"))
    # a job's log counts the runs, not the cells past a shorter ladder
    runs = summary.outcome_of(convergence.ladder_runs(ds))
    assert (runs.points, runs.failed) == (int(on.sum()), 0) and int(off.sum()) > 0
    for name in ("direct-a", "direct-b", "ive-numba", "soe", "adaptive-plain"):
        order = convergence.observed_order(ds, name)
        print(f"\nsls v0 = 10, {name}: observed order {order:.3f}")
        assert 1.9 < order < 2.2  # README table: 2.00-2.02 (adaptive-plain, in the steps taken: 1.96)
    # the sweep default (adaptive, Richardson from three grids for this SLS), in the steps of all, over the rungs
    # whose error the reference resolves (above 3x its gap to ive at rtol 1e-12: the finer rungs of this
    # ladder reach that floor)
    rungs = ds.sel(solver="adaptive")
    err, steps = rungs["err_cor"].values, rungs["steps"].values
    above = np.isfinite(err) & (err > 3 * convergence.reference_gap(ds))
    assert above.sum() >= 2
    order = float(np.polyfit(np.log(1.0 / steps[above]), np.log(err[above]), 1)[0])
    print(f"\nsls v0 = 10, adaptive (Richardson): observed order {order:.3f} over {above.sum()} rungs")
    assert order > 2.4
    assert convergence.observed_order(ds, "paper-explicit") < 1.0  # README: 0.89-0.93
    # the reference (Richardson on direct) against an independent solver: Radau on the internal variables
    gap = convergence.reference_gap(ds)
    print(f"sls v0 = 10: |reference - ive rtol 1e-12| = {gap:.2e}")
    assert gap < 1e-9  # docs/validation.md: 7e-12
    table = convergence.orders_table(convergence.combine({("sls", 0): ds}, ["sls"], [10.0]))
    header, row = table.splitlines()[2:4]
    assert header.split()[-1] == "1e-12|" and float(row.split()[-1]) == float(f"{gap:.1e}")


def test_a_kelvin_voigt_material_gets_the_methods_that_take_it():
    """The paper's explicit scheme has no Dirac term: a Kelvin-Voigt material's study leaves it out (the
    combined table marks it as not applying) instead of failing the job."""
    ds = convergence.study("kelvin-voigt", 3.0, repeat=1)
    assert "paper-explicit" not in set(ds["solver"].values)
    assert np.all(ds["status"].values[np.isfinite(ds["param"].values)] == status.code("ok"))
    fc = convergence.study("butyl-fc", 3.0, repeat=1)
    fc.attrs["material"], ds.attrs["material"] = "butyl-fc", "kelvin-voigt"  # as the case files carry them
    both = convergence.combine({("butyl-fc", 0): fc, ("kelvin-voigt", 0): ds}, ["butyl-fc", "kelvin-voigt"], [3.0])
    assert "material" not in both.attrs  # one case's material does not describe the study
    row = both.sel(material="kelvin-voigt", v0=3.0, solver="paper-explicit")
    assert np.all(row["status"].values == status.code("invalid-input"))
    assert all("does not apply" in str(m) for m in row["message"].values)
    # the cross-check exists (ive applies) and says how far the reference is from it
    print(f"\nkelvin-voigt 3 m/s: |reference - ive rtol 1e-12| = {convergence.reference_gap(ds):.1e}")
    assert np.isfinite(convergence.reference_gap(ds))


def test_the_reference_records_its_error_estimate_and_orders_leave_out_its_floor():
    """The reference's error estimate (its distance to the extrapolation one step coarser) is at least its
    true error (against ive at rtol 1e-12, SLS at 10 m/s); the floor below which errors measure the reference is
    stored, and the observed orders are fitted above it only: errors that flatten at the reference's own
    error give no order (a ladder of errors C h^2 that meets a floor of 2e-6)."""
    ds = convergence.study("sls", 10.0, repeat=1)
    estimate, gap = float(ds["cor_ref_error"]), convergence.reference_gap(ds)
    print(f"\nsls v0 = 10: reference error estimate {estimate:.1e}, |reference - ive rtol 1e-12| {gap:.1e}")
    assert gap <= estimate < 1e-8
    assert float(ds["err_cor_floor"]) == convergence.ERROR_FLOOR * max(estimate, gap)
    assert int(ds["reference_status"]) == status.code("ok") and str(ds["reference_message"].values) == ""
    assert np.isfinite(float(ds["cor_ref_volterra_error"]))
    # synthetic: one solver whose errors fall as steps^-2 down to a floor of 2e-6, where they flatten
    steps = np.array([250.0, 500.0, 1000.0, 2000.0, 4000.0, 8000.0])
    err = np.maximum(1e-3 * (250.0 / steps) ** 2, 2e-6)
    case = ds.isel(solver=[0], level=range(steps.size)).copy(deep=True)
    case["param"][:] = steps
    case["err_cor"][:] = err
    case["err_cor_floor"] = 6e-6
    assert 1.99 < convergence.observed_order(case, str(case["solver"].values[0])) < 2.01
    case["err_cor_floor"] = 0.0
    assert convergence.observed_order(case, str(case["solver"].values[0])) < 1.9  # the floor bends the fit


def test_a_reference_that_does_not_finish_says_why(monkeypatch):
    """A reference run that ends with another status leaves the errors NaN and the case says why (status and
    message), instead of NaN errors beside runs that are ok."""
    from vcor.solvers import simulate as front

    real = front.simulate

    def failing(material, v0, **kw):
        r = real(material, v0, **kw)
        if kw.get("method") == "direct" and kw.get("steps_per_contact") == convergence.REF_STEPS[1]:
            r.status, r.message, r.cor, r.t0 = "step-budget", "stopped by the step budget (test)", np.nan, np.nan
        return r

    monkeypatch.setattr(front, "simulate", failing)
    ds = convergence.study("sls", 3.0, repeat=1)
    assert int(ds["reference_status"]) == status.code("step-budget")
    assert "16000 steps per contact time ended step-budget: stopped by the step budget (test)" in str(
        ds["reference_message"].values)
    assert np.all(np.isnan(ds["err_cor"].sel(solver="direct-a").values))
    assert np.isnan(float(ds["cor_ref"])) and np.isnan(float(ds["err_cor_floor"]))
