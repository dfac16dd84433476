"""Bodies instead of a case number: vcor.contact.bodies, Green 2026 Eq. 1."""

import numpy as np
import pytest

import vcor
from vcor import materials as M
from vcor.contact import bodies
from vcor.io.netcdf import read_dataset
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


def test_methods_that_cannot_solve_eq1_say_so():
    with pytest.raises(ValueError, match="use method 'direct'"):
        _solve({"material": {"model": "elastic", "E": 1e9}}, {}, method="adaptive")
    with pytest.raises(ValueError, match="direct"):
        _solve({"material": "sls"}, {"material": "butyl-prony3"}, method="adaptive", swept="sls")


SCENE = {"materials": ["sls"], "grid": {"v0": [1.0, 10.0]}, "sphere": {"material": {"model": "elastic", "E": 2e11}},
         "plate": {"h": 0.02}}


@pytest.mark.parametrize("change, words", [
    ({}, ["scenes.s.solver.method", "method: direct"]),
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
    scene = {**SCENE, "solver": {"method": "direct"}}
    validate_scene("s", scene)
    settings = settings_of(scene)
    material, _, geometry = build_point({"material": "sls", "v0": 10.0}, settings)
    assert material.kind == "eq1" and geometry["plate_material"] == M.get("sls") and geometry["rho_a"] == 7800.0
    assert geometry["rho_b"] == 1100.0 and geometry["nu_plate"] == 0.5


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
