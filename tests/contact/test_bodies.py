"""Bodies instead of a case number: vcor.contact.bodies, Green 2026 Eq. 1."""

import numpy as np
import pytest

import vcor
from vcor import materials as M
from vcor.contact import bodies
from vcor.contact.impact import make_impact
from vcor.io.netcdf import read_dataset
from vcor.materials import expfit, expsums
from vcor.study.scene import build_point, settings_of, validate_scene


def _solve(sphere, plate, v0=10.0, method="adaptive", swept="sls"):
    mat = M.get(swept)
    s = bodies.body_from_spec("sphere", sphere, swept=mat)
    p = bodies.body_from_spec("plate", plate, swept=mat)
    material, geometry = bodies.impact_inputs(s, p)
    return vcor.simulate(material, v0, method=method, **geometry)


@pytest.mark.parametrize("method", ["adaptive", "direct"])
def test_cases_are_shortcuts_of_bodies(method):
    """Case 3 = a rigid steel sphere on the swept plate; case 2 = both bodies of the swept material;
    a rigid plate = the rigid target. Equal to the last bit (the same inputs reach the solver)."""
    for swept in ("sls", "butyl-fc"):
        case3 = vcor.simulate(swept, 10.0, method=method)
        assert _solve({"material": "rigid"}, {}, method=method, swept=swept).cor == case3.cor
        case2 = vcor.simulate(swept, 10.0, method=method, case=2)
        assert _solve({}, {}, method=method, swept=swept).cor == case2.cor
        rigid = vcor.simulate(swept, 10.0, method=method, rigid=True, rho_a=1100.0)
        assert _solve({}, {"material": "rigid"}, method=method, swept=swept).cor == rigid.cor


def test_case4_is_the_stiff_plate_limit_of_bodies():
    """Case 4 drops the steel plate's contact compliance (E' = E'_a); with the plate as a body, Eq. 1
    keeps it: the COR moves by about E'_a / E'_p (~1e-4 for 15 MPa on 200 GPa)."""
    case4 = vcor.simulate("sls", 10.0, method="direct", case=4)
    body = _solve({}, {"material": {"model": "elastic", "E": 200e9}, "nu": 0.3}, method="direct")
    print(f"\ncase 4 COR {case4.cor:.8f}, bodies (steel plate in Eq. 1) {body.cor:.8f}")
    assert body.status == "ok" and 0 < abs(body.cor / case4.cor - 1) < 1e-3


def test_a_very_stiff_elastic_sphere_approaches_the_rigid_one():
    """The general path (Eq. 1's pointwise E'(t), the plate's own modulus, method direct): an elastic
    sphere of 1e15 Pa on the SLS plate gives the rigid-sphere (case 3) COR."""
    rigid = vcor.simulate("sls", 10.0, method="direct", rho_a=7800.0)
    stiff = _solve({"material": {"model": "elastic", "E": 1e15}, "rho": 7800.0}, {}, method="direct")
    assert stiff.status == "ok"
    assert abs(stiff.cor - rigid.cor) < 1e-6 and abs(stiff.t0 / rigid.t0 - 1) < 1e-6


def test_eq1_against_series_combination():
    """README: with both bodies viscoelastic, Eq. 1 combines E'_a(t) and E'_b(t) pointwise in time; the
    viscoelastic (correspondence-principle) combination adds the compliances in the Laplace domain.
    Same glassy and rubbery limits, different relaxation in between, different COR. Equal for two
    bodies of the same material (E'/2)."""
    a, b = M.get("sls"), M.get("butyl-prony3")
    ca = cb = 1.0 / (1.0 - 0.5**2)
    eq1, series = M.EqOne(a, ca, b, cb), bodies.series_modulus(a, ca, b, cb)
    # the series result is exact: its complex modulus is 1 / (1/E*_a + 1/E*_b)
    w = np.geomspace(1.0, 1e7, 50)
    want = 1.0 / (1.0 / (ca * a.complex_modulus(w)) + 1.0 / (cb * b.complex_modulus(w)))
    assert np.max(np.abs(series.complex_modulus(w) / want - 1)) < 1e-10
    t = np.geomspace(1e-7, 1.0, 200)
    rel = eq1.relaxation_modulus(t) / series.relaxation_modulus(t) - 1
    for lim in (0.0, np.inf):
        at = np.array([lim])
        assert eq1.relaxation_modulus(at)[0] == pytest.approx(series.relaxation_modulus(at)[0], rel=1e-12)
    geo = bodies.impact_inputs(bodies.body_from_spec("sphere", {"material": "sls"}),
                               bodies.body_from_spec("plate", {"material": "butyl-prony3"}))[1]
    r_eq1 = vcor.simulate(eq1, 10.0, method="direct", **geo)
    r_ser = vcor.simulate(series, 10.0, method="direct", **geo)
    i = int(np.argmax(np.abs(rel)))
    print(f"\nSLS sphere on butyl-prony3 plate (nu 0.5 both): E'_eq1/E'_series - 1 largest {rel[i]:+.4f} at "
          f"t = {t[i]:.3g} s; COR Eq. 1 {r_eq1.cor:.5f}, series {r_ser.cor:.5f} "
          f"({r_eq1.cor / r_ser.cor - 1:+.4f}); t0 {1e6 * r_eq1.t0:.1f} / {1e6 * r_ser.t0:.1f} us")
    assert np.max(np.abs(rel)) > 0.01  # a real difference, not rounding
    assert abs(r_eq1.cor / r_ser.cor - 1) > 1e-3
    same_eq1, same_series = M.EqOne(a, ca, a, ca), bodies.series_modulus(a, ca, a, ca)
    assert np.max(np.abs(same_eq1.relaxation_modulus(t) / same_series.relaxation_modulus(t) - 1)) < 1e-12


def test_eq1_antiderivatives_are_the_integrals():
    from scipy.integrate import quad

    for a, b in (("sls", "butyl-prony3"), ("butyl-fc", "sls")):
        m = M.EqOne(M.get(a), 4 / 3, M.get(b), 4 / 3)
        for T in (1e-6, 1e-3, 0.1):
            pts = [T * 1e-6, T * 1e-3]
            k1 = quad(lambda x, m=m: float(m.relaxation_modulus(x)), 0, T, epsabs=0, epsrel=1e-13, limit=500,
                      points=pts)[0]
            k2 = quad(lambda x, T=T, m=m: (T - x) * float(m.relaxation_modulus(x)), 0, T, epsabs=0, epsrel=1e-13,
                      limit=500, points=pts)[0]
            assert m.antiderivative(np.array([T]), 1)[0] == pytest.approx(k1, rel=1e-12)
            assert m.antiderivative(np.array([T]), 2)[0] == pytest.approx(k2, rel=1e-12)
    d = M.EqOne(M.get("sls"), 4 / 3, M.get("butyl-fc"), 4 / 3).to_dict()
    assert M.from_dict(d) == M.EqOne(M.get("sls"), 4 / 3, M.get("butyl-fc"), 4 / 3)


#: the acceptance pairs: an elastic config-material sphere (E = 70 GPa, an aluminium-like stiffness) on an
#: SLS and a Prony plate
STIFF_BALL = {"material": {"model": "elastic", "E": 7e10}}


@pytest.mark.parametrize("plate", ["sls", "butyl-prony3"])
@pytest.mark.parametrize("v0", [1.0, 10.0])
def test_an_elastic_sphere_on_a_viscoelastic_plate_runs_by_default(plate, v0):
    """No method given: adaptive solves it (the Eq. 1 contact modulus as its exponential sum, the plate's
    mobility from the plate's own modulus), within 1e-6 of direct at 8 times its default steps (whose
    own error is ~2e-9), and reports the sum's error, below soe_tol."""
    s = bodies.body_from_spec("sphere", STIFF_BALL)
    material, geometry = bodies.impact_inputs(s, bodies.body_from_spec("plate", {"material": plate}))
    res = vcor.simulate(material, v0, **geometry)
    ref = vcor.simulate(material, v0, method="direct", steps_per_contact=16000, **geometry)
    print(f"\nelastic sphere on {plate}, {v0} m/s: COR {res.cor:.9f} (direct {ref.cor:.9f}, "
          f"{res.cor / ref.cor - 1:+.1e}), t0 {res.t0 / ref.t0 - 1:+.1e}, sum error {res.soe_error:.1e}")
    assert res.method == "adaptive" and res.ok and ref.ok
    assert abs(res.cor / ref.cor - 1) <= 1e-6 and abs(res.t0 / ref.t0 - 1) <= 1e-6
    assert 0.0 < res.soe_error <= vcor.SolverOptions().soe_tol


def test_an_elastic_sphere_on_a_maxwell_fluid_plate_runs_by_every_method():
    """A Maxwell-fluid plate (SLS, alpha = 0): the two-body modulus falls as e^-beta t to 1e-160 within the
    sum's window, where no fit holds a relative error (the weights' rounding); it is fitted where it is
    above expsums.RELAXED of its start and held absolutely beyond. adaptive, soe and ive agree with direct
    at 16000 steps per contact time to 1e-6, the sum's reported error within soe_tol."""
    maxwell = {"model": "sls", "E_glassy": 40e6, "alpha": 0.0, "beta": 6000.0}
    kw = {"r": 0.003, "rho_a": 2700.0, "target": {"plate": {"material": maxwell, "h": 0.01}}}
    aluminium = {"model": "elastic", "E": 70e9}
    ref = vcor.simulate(aluminium, 1.0, method="direct", steps_per_contact=16000, **kw)
    for method in ("adaptive", "soe", "ive"):
        res = vcor.simulate(aluminium, 1.0, method=method, **kw)
        print(f"\n{method}: COR {res.cor:.10g} (direct {ref.cor:.10g}), soe_error {res.soe_error:.2g}")
        assert res.ok and abs(res.cor / ref.cor - 1) <= 1e-6 and abs(res.t0 / ref.t0 - 1) <= 1e-6, method
        assert 0.0 < res.soe_error <= vcor.SolverOptions().soe_tol


@pytest.mark.parametrize("sphere, plate", [("sls", "butyl-prony3"), ("butyl-fc", "sls"), ("butyl-cerf", "butyl-fc")])
def test_every_pair_of_viscoelastic_bodies_runs_by_default(sphere, plate):
    """Two viscoelastic bodies of different laws (a not completely monotone Eq. 1 modulus, fitted with
    terms of both signs): adaptive within 1e-6 of direct at 8 times its default steps; soe (the fixed-step
    exponential-sum history) within 1e-9 of direct at the same step."""
    material, geometry = bodies.impact_inputs(bodies.body_from_spec("sphere", {"material": sphere}),
                                              bodies.body_from_spec("plate", {"material": plate}))
    res = vcor.simulate(material, 10.0, **geometry)
    ref = vcor.simulate(material, 10.0, method="direct", steps_per_contact=16000, **geometry)
    assert res.ok and abs(res.cor / ref.cor - 1) <= 1e-6 and abs(res.t0 / ref.t0 - 1) <= 1e-6
    same_dt = vcor.simulate(material, 10.0, method="direct", **geometry)
    soe = vcor.simulate(material, 10.0, method="soe", dt=same_dt.dt, **geometry)
    assert abs(soe.cor - same_dt.cor) <= 1e-9 and 0.0 < soe.soe_error <= 1e-10


#: fractional and CERF spheres whose Eq. 1 modulus with an SLS plate needs the fit's finest rate grid to reach
#: soe_tol 1e-10 (E0, E1 in Pa and Pa s^0.5; E0, E1 in Pa and b1 in s^-0.5)
HARD_TO_FIT = [(M.FractionalPower(1e5, 1e5), 1.0), (M.Cerf(4.42e5, 6.765e7, 7e4), 0.001),
               (M.Cerf(4.42e5, 6.765e7, 7e4), 100.0)]


@pytest.mark.parametrize("sphere, v0", HARD_TO_FIT, ids=lambda x: getattr(x, "kind", x))
def test_pairs_whose_modulus_needs_the_finest_fit_run_by_default(sphere, v0):
    """A soft fractional and a fast CERF sphere on the paper's SLS plate (Eq. 1 moduli that the coarser rate
    grids of vcor.materials.expfit fit only to ~2e-10): adaptive at its defaults runs, reports the sum's
    error below soe_tol, and agrees with direct at 16000 steps per contact time within 1e-6."""
    material, geometry = bodies.impact_inputs(bodies.body_from_spec("sphere", {"material": sphere}),
                                              bodies.body_from_spec("plate", {"material": "sls"}))
    res = vcor.simulate(material, v0, **geometry)
    ref = vcor.simulate(material, v0, method="direct", steps_per_contact=16000, **geometry)
    assert res.method == "adaptive" and res.ok and ref.ok, res.message
    assert abs(res.cor / ref.cor - 1) <= 1e-6 and abs(res.t0 / ref.t0 - 1) <= 1e-6
    assert 0.0 < res.soe_error <= vcor.SolverOptions().soe_tol


def test_a_pair_no_fit_reaches_soe_tol_for_runs_with_the_best_fit_and_says_so():
    """A soft elastic sphere (1 MPa) on a plate of an SLS that falls 50-fold within microseconds: the Eq. 1
    modulus is a sigmoid in t that no exponential sum fits to 1e-10 in double precision (the fit's weights
    lose more than 1e-10 to cancellation). With its defaults adaptive takes the best fit within FIT_ACCEPT,
    reports its error (the larger of its check and its rounding loss) in soe_error and the message, and
    agrees with direct at 16000 steps per contact time within 1e-6; asked for the strict tolerance alone,
    the fit still refuses, naming the best error it reached."""
    sphere, plate = M.Elastic(1e6), M.SLS(1.5e7, 2e4, 1e6)
    for v0 in (0.001, 1.0, 100.0):
        res = vcor.simulate(sphere, v0, target={"plate": {"material": plate}})
        ref = vcor.simulate(sphere, v0, target={"plate": {"material": plate}}, method="direct",
                            steps_per_contact=16000)
        assert res.ok and vcor.SolverOptions().soe_tol < res.soe_error <= expsums.FIT_ACCEPT
        assert "not the tolerance 1e-10" in res.message and f"{res.soe_error:.2g}" in res.message
        assert abs(res.cor / ref.cor - 1) <= 1e-6 and abs(res.t0 / ref.t0 - 1) <= 1e-6
    material, geometry = bodies.impact_inputs(bodies.body_from_spec("sphere", {"material": sphere}),
                                              bodies.body_from_spec("plate", {"material": plate}))
    eq_one = make_impact(material, 1.0, geometry).material
    with pytest.raises(ValueError, match=r"no exponential sum reaches a relative error of 1e-10 .* \(best [0-9.e-]+\)"):
        expfit.fit_exponential_sum(eq_one.relaxation_modulus, eq_one.summed_rates, 2.0**-27, 2.0, 1e-10)
    # the best fit's error is the larger of its check and its weights' rounding loss (which is the larger here)
    fit, error = expfit.fit_exponential_sum(eq_one.relaxation_modulus, eq_one.summed_rates, 2.0**-27, 2.0, 1e-10,
                                            accept=expsums.FIT_ACCEPT)
    t = np.geomspace(2.0**-27, 2.0, 20001)
    modulus = eq_one.relaxation_modulus(t)
    rounding = (abs(fit.E_inf) + np.sum(np.abs(fit.E))) / np.min(modulus) * np.finfo(float).eps
    assert 1e-10 < rounding <= error * (1.0 + 1e-12) and error <= expsums.FIT_ACCEPT
    assert np.max(np.abs(fit.relaxation_modulus(t) / modulus - 1.0)) <= 1.01 * error


def test_the_internal_variable_methods_take_a_pair_from_t_zero():
    """ive and ive-numba take the Eq. 1 modulus as its exponential sum from t = 0 (fitted and checked there
    too): ive (Radau, rtol 1e-10) within 1e-7 of direct at 16000 steps per contact; two fractional bodies
    (E'(0) infinite) are refused naming the methods that solve them."""
    material, geometry = bodies.impact_inputs(bodies.body_from_spec("sphere", STIFF_BALL),
                                              bodies.body_from_spec("plate", {"material": "sls"}))
    ref = vcor.simulate(material, 1.0, method="direct", steps_per_contact=16000, **geometry)
    res = vcor.simulate(material, 1.0, method="ive", **geometry)
    assert res.ok and abs(res.cor / ref.cor - 1) <= 1e-7 and 0.0 < res.soe_error <= 1e-10
    assert vcor.simulate(material, 1.0, method="ive-numba", **geometry).ok
    fc = {"material": "butyl-fc"}
    singular, geometry = bodies.impact_inputs(bodies.body_from_spec("sphere", {"material": {
        "model": "fractional", "E0": 1e6, "E1": 1e6}}), bodies.body_from_spec("plate", fc))
    with pytest.raises(ValueError, match="use method 'adaptive'"):
        vcor.simulate(singular, 1.0, method="ive", **geometry)


def test_a_kelvin_voigt_partner_is_refused_naming_the_bodies():
    """A Dirac term has no pointwise Eq. 1 combination: the message names both bodies as the user gave
    them (sphere, plate, target.*) and says what does work."""
    kv = bodies.body_from_spec("sphere", {"material": "kelvin-voigt"})
    with pytest.raises(ValueError, match=r"sphere.material \(kelvin-voigt\) on plate.material \(sls\).*no method"):
        bodies.impact_inputs(kv, bodies.body_from_spec("plate", {"material": "sls"}))
    with pytest.raises(ValueError, match=r"sphere.material \(sls\) on target.sphere.material \(kelvin-voigt\)"):
        vcor.simulate("sls", 1.0, target={"sphere": {"material": "kelvin-voigt"}})
    with pytest.raises(ValueError, match=r"target.plate.material: a Kelvin-Voigt plate"):
        vcor.simulate("sls", 1.0, target={"plate": {"material": "kelvin-voigt"}})


SCENE = {"materials": ["sls"], "grid": {"v0": [1.0, 10.0]}, "sphere": {"material": {"model": "elastic", "E": 2e11}},
         "plate": {"h": 0.02}}


@pytest.mark.parametrize("change, words", [
    ({"sphere": {"material": "kelvin-voigt"}}, ["scenes.s", "sphere.material (kelvin-voigt) on plate.material",
                                               "no method"]),
    ({"sphere": {"material": "sls"}, "plate": {"material": "sls"}}, ["both bodies name a material"]),
    ({"geometry": {"r": 0.02}}, ["scenes.s.geometry", "bodies"]),
    ({"grid": {"v0": [1.0], "h": [0.01, 0.02]}}, ["scenes.s.grid", "geometry axes ['h']"]),
    ({"sphere": {"material": "my-config-material"}}, ["scenes.s.sphere.material", "unknown material"]),
    ({"sphere": {"material": {"model": "elastic", "E": -1.0}}}, ["scenes.s", "sphere.material", "E must be in"]),
    ({"plate": {"rho": 0}}, ["plate.rho"]),
    ({"sphere": {"r": 0.01, "radius": 2}}, ["sphere", "radius"]),
])
def test_bad_bodies_fail_before_solving(change, words):
    scene = {**SCENE, **change}
    with pytest.raises(ValueError) as exc:
        validate_scene("s", scene)
    for w in words:
        assert w in str(exc.value), (w, str(exc.value))


def test_scene_point_with_bodies():
    scene = dict(SCENE)  # no solver: the default method takes two bodies
    validate_scene("s", scene)
    settings = settings_of(scene)
    material, _, geometry = build_point({"material": "sls", "v0": 10.0}, settings)
    assert material.kind == "eq1" and geometry["plate_material"] == M.get("sls") and geometry["rho_a"] == 7800.0
    assert geometry["rho_b"] == 1100.0 and geometry["nu_plate"] == 0.5


#: a config with an elastic config material ("ball", E = 70 GPa) as the sphere of a scene (on the swept SLS
#: and Prony plates) and of a DEM entry (on an SLS plate target), no solver given anywhere
BALL_CONFIG = {"material_dir": "results/materials", "materials": {"ball": {"model": "elastic", "E": 7e10}},
               "scenes": {"ball": {"materials": ["sls", "butyl-prony3"], "grid": {"v0": [1.0, 10.0]},
                                   "sphere": {"material": "ball"}, "plate": {}}},
               "dem": {"ball": {"sphere": {"material": "ball", "r": 0.005}, "target": {"plate": {"material": "sls"}},
                                "v0": [0.5, 2.0, 8.0]}}}


def _direct_fine(material_name, v0, sphere=None, target=None):
    """direct at 16000 steps per contact time of the ball on a plate of ``material_name`` (the reference)."""
    ball = bodies.body_from_spec("sphere", {**STIFF_BALL, **(sphere or {})})
    plate = bodies.body_from_spec("plate", target or {"material": material_name})
    material, geometry = bodies.impact_inputs(ball, plate)
    return vcor.simulate(material, v0, method="direct", steps_per_contact=16000, **geometry)


def test_a_scene_and_a_dem_entry_with_an_elastic_config_sphere_run_by_default():
    """The acceptance pair through the study layer, no solver given: the scene's points and the DEM entry's
    collisions are solved by adaptive, within 1e-6 of direct at 16000 steps per contact time."""
    from vcor.study import dem as study_dem
    from vcor.study import runner
    from vcor.study.config import load_project

    project = load_project(BALL_CONFIG, ".")
    sc = BALL_CONFIG["scenes"]["ball"]
    validate_scene("ball", sc, project.catalogue)
    settings = settings_of(sc)
    assert settings["solver"]["method"] == "adaptive"
    ds = runner.run_points([{"index": i, "material": m, "v0": v} for i, (m, v) in
                            enumerate((m, v) for m in sc["materials"] for v in sc["grid"]["v0"])], settings,
                           project.catalogue)
    for i in range(ds.sizes["point"]):
        m, v0 = str(ds["material"].values[i]), float(ds["v0"].values[i])
        ref = _direct_fine(m, v0)
        assert ds["status"].values[i] == 0 and abs(float(ds["cor"].values[i]) / ref.cor - 1) <= 1e-6, (m, v0)
        assert 0.0 < float(ds["soe_error"].values[i]) <= 1e-10
    spec = BALL_CONFIG["dem"]["ball"]
    (col,), _, _ = study_dem.run_dem("ball", spec, project.catalogue)
    for v0, cor in zip(spec["v0"], col.cor):
        ref = _direct_fine("sls", v0, sphere={"r": 0.005})
        assert abs(cor / ref.cor - 1) <= 1e-6, v0


@pytest.mark.slow
def test_workflow_scene_and_dem_entry_with_an_elastic_config_sphere(make_project, smk, tmp_path):
    """The same config through Snakemake: the sweep and the DEM dataset hold adaptive's numbers (the sweep
    records the method), within 1e-6 of direct at 16000 steps per contact time."""

    path = make_project(tmp_path, {**BALL_CONFIG, "shard_size": 100})
    smk(path, "-j2", "results/ball/sweep.nc")
    ds = read_dataset(path / "results/ball/sweep.nc")
    for m in ("sls", "butyl-prony3"):
        for v0 in (1.0, 10.0):
            ref = _direct_fine(m, v0)
            assert abs(ds["cor"].sel(material=m, v0=v0).item() / ref.cor - 1) <= 1e-6, (m, v0)
    assert "adaptive" in ds.attrs.get("solver", "") or "adaptive" in str(ds.attrs)


@pytest.mark.slow
def test_workflow_scene_with_bodies(make_project, smk, tmp_path):
    """A scene with sphere and plate bodies runs through the workflow; the sweep's COR is the one of
    vcor.simulate with the same bodies."""
    scene = {**SCENE, "solver": {"method": "direct"}, "figures": {"fig8": {}}}
    cfg = {"shard_size": 100, "material_dir": "results/materials", "scenes": {"bodies": scene}}
    path = make_project(tmp_path, cfg)
    smk(path, "-j2", "results/bodies/sweep.nc")
    ds = read_dataset(path / "results/bodies/sweep.nc")
    for v0 in (1.0, 10.0):
        want = _solve(SCENE["sphere"], SCENE["plate"], v0=v0, method="direct")
        assert ds["cor"].sel(material="sls", v0=v0).item() == want.cor


@pytest.mark.slow
def test_workflow_body_may_name_a_config_material(make_project, smk, tmp_path):
    """A body naming a config material: its parameters are inlined into the scene's settings, so editing
    the material changes the shard names (its content is part of their identity)."""
    scene = {"materials": ["sls"], "grid": {"v0": [10.0]}, "solver": {"method": "direct"},
             "sphere": {"material": "my-ball"}, "plate": {}}
    cfg = {"shard_size": 100, "material_dir": "results/materials",
           "materials": {"my-ball": {"model": "elastic", "E": 5e8}}, "scenes": {"b": scene}}
    path = make_project(tmp_path, cfg)
    smk(path, "-j2", "results/b/sweep.nc")
    want = _solve({"material": {"model": "elastic", "E": 5e8}}, {}, method="direct")
    assert read_dataset(path / "results/b/sweep.nc")["cor"].item() == want.cor
    import yaml

    cfg["materials"]["my-ball"]["E"] = 6e8
    (path / "config.yaml").write_text(yaml.safe_dump(cfg, sort_keys=False))
    out = smk(path, "-n", "results/b/sweep.nc")
    assert "sweep_shard" in out.stdout + out.stderr

