"""vcor.sweep on the local machine (vcor.study.api, .pool, .progress): processes give the numbers of one
process, the work is handed out largest first, bad input is refused before any work in one line naming
the argument, Ctrl-C stops every process within a second, and the progress bar shows on a terminal only."""

import fcntl
import json
import os
import pty
import signal
import struct
import subprocess
import sys
import termios
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import vcor
from vcor.study import api, pool, scene

ROOT = Path(__file__).resolve().parents[2]
REPO_CONFIG = ROOT / "config.yaml"
ENV = {**os.environ, "PYTHONPATH": str(ROOT / "src")}

# two materials, a geometry axis, the error estimate (whose finer runs end at the step budget), flagged points
SCENE = {"materials": ["sls", "butyl-fc"], "grid": {"v0": [0.5, 3.0, 10.0, 30.0], "nu": [0.45, 0.5]},
         "error_estimate": True, "solver": {"method": "direct", "steps_per_contact": 200, "max_steps": 250}}


def test_processes_give_the_numbers_of_one_process():
    one = vcor.sweep(SCENE, workers=1, progress=False)
    two = vcor.sweep(SCENE, workers=2, progress=False)
    assert set(np.unique(one["error_status"].values)) != {0}  # failed runs stored, not raised
    assert (one["validity"] != 0).any()
    a, b = one.drop_vars("wall_time"), two.drop_vars("wall_time")
    a.attrs.pop("history"), b.attrs.pop("history")
    xr.testing.assert_identical(a, b)


def test_chunks_hand_out_every_point_once_largest_work_first():
    sc = {"materials": ["sls", "fitted"], "grid": {"v0": list(np.linspace(1, 30, 40)), "beta": [600, 1200]}}
    points = [{**p, "material_id": "x"} for p in scene.grid_of(sc).points()]
    settings = scene.settings_of({})
    chunks = pool.chunks_of(points, settings, 2, from_data={"fitted"})
    flat = [i for c in chunks for i in c]
    assert sorted(flat) == list(range(len(points)))
    assert len(chunks) >= 2 * pool.CHUNKS_PER_WORKER
    mats = [points[i]["material"] for i in flat]
    assert mats == sorted(mats, key=lambda m: m != "fitted")  # the fitted material's (larger) work first


@pytest.mark.parametrize(("kwargs", "words"), [
    ({"scene": {"materials": ["slss"], "grid": {"v0": [1]}}}, "scene.materials: unknown material 'slss'"),
    ({"scene": {"materials": ["SLS"], "grid": {"v0": [1]}}}, "did you mean 'sls'?"),
    ({"scene": "my-first"}, "scene: 'my-first' names a scene, but no config was given: pass config="),
    ({"scene": {"materials": ["sls"], "grid": {"v0": [1], "bta": [1]}}}, "scene.grid.bta: "),
    ({"scene": {"materials": ["sls"], "grid": {"v0": [1, 2, 1]}}}, "scene.grid.v0: 1 listed more than once"),
    ({"scene": {"materials": ["sls"], "grid": {"v0": [1]}}, "workers": 0}, "workers must be an integer >= 1"),
    ({"scene": {"materials": ["sls"], "grid": {"v0": [1]}}, "progress": "yes"}, "progress must be None"),
    ({"scene": "s", "config": {"scenes": {}}}, "scene: 's' is not a scene of the config"),
    ({"scene": {"materials": ["sls"]}}, "scene.grid: the scene has no grid"),
])
def test_bad_input_is_refused_before_any_work_naming_the_argument(monkeypatch, kwargs, words):
    def no_work(*args, **kw):
        raise AssertionError("solving started")

    monkeypatch.setattr(api, "solve_points", no_work)
    with pytest.raises(ValueError) as info:
        vcor.sweep(**kwargs)
    assert words in str(info.value) and "\n" not in str(info.value)


def test_a_config_file_is_named_in_its_refusals(tmp_path):
    (tmp_path / "my.yaml").write_text("scenes:\n  s: {materials: [sls], grid: {v0: [1], bta: [2]}}\n")
    with pytest.raises(ValueError, match=r"^config file .*my.yaml, line 2, column 41: scenes\.s\.grid\.bta: "):
        vcor.sweep("s", config=tmp_path / "my.yaml")


def test_inline_material_specs_are_taken_as_simulate_takes_them():
    """A scene's materials list takes a spec {model: ..., parameters} as simulate does (named like a material
    object); a bad one is refused naming its place in the list."""
    spec = {"model": "sls", "E_glassy": 2e7, "alpha": 300.0, "beta": 1200.0}
    ds = vcor.sweep({"materials": [spec, "sls"], "grid": {"v0": [1.0]}}, workers=1, progress=False)
    name = str(ds["material"].values[0])
    assert name.startswith("sls-") and float(ds["cor"].sel(material=name, v0=1.0)) == vcor.simulate(spec, 1.0).cor
    with pytest.raises(ValueError, match=r"scene\.materials\[0\]\.E_glassy must be in \(0, 1e\+20\] Pa"):
        vcor.sweep({"materials": [{**spec, "E_glassy": -1.0}], "grid": {"v0": [1.0]}}, progress=False)


def test_the_dataset_names_the_geometry_its_points_ran_with():
    """The attribute ``geometry`` is the scene's geometry over the defaults (``geometry_defaults`` holds
    r = 0.01 m, the scene r = 0.004 m), without the grid's axes, which the coordinates give."""
    ds = vcor.sweep({"materials": ["sls"], "grid": {"v0": [1.0], "h": [0.01, 0.02]}, "geometry": {"r": 0.004}},
                    workers=1, progress=False)
    geometry = json.loads(ds.attrs["geometry"])
    assert geometry["r"] == 0.004 and geometry["nu"] == 0.5 and json.loads(ds.attrs["geometry_defaults"])["r"] == 0.01
    assert "h" not in geometry and "v0" not in geometry  # a grid axis: the coordinates give it
    assert float(ds["cor"].sel(material="sls", v0=1.0, h=0.02)) == vcor.simulate("sls", 1.0, r=0.004, h=0.02).cor


def test_an_inline_spec_keeps_its_shift_function_for_a_temperature_axis():
    """An inline spec with ``shift`` sweeps a T axis as the same material of a config's materials block
    does (the same numbers); the shift is part of its name, so the spec without it is another material."""
    shift = {"model": "wlf", "C1": 8.86, "C2": 101.6, "T_ref": 20.0}
    spec = {"model": "fractional", "E0": 2.28e6, "E1": 0.885e6}
    ds = vcor.sweep({"materials": [{**spec, "shift": shift}], "grid": {"v0": [1.0], "T": [10.0, 30.0]}},
                    workers=1, progress=False)
    cfg = {"materials": {"mine": {**spec, "shift": shift}}}
    ref = vcor.sweep({"materials": ["mine"], "grid": {"v0": [1.0], "T": [10.0, 30.0]}}, config=cfg, workers=1,
                     progress=False)
    np.testing.assert_array_equal(ds["cor"].values, ref["cor"].values)
    assert ds["cor"].sel(T=10.0).item() != ds["cor"].sel(T=30.0).item()
    both = vcor.sweep({"materials": [spec, {**spec, "shift": shift}], "grid": {"v0": [1.0]}}, workers=1,
                      progress=False)
    assert both.sizes["material"] == 2


def test_material_objects_and_numpy_grids_are_taken():
    mat = vcor.materials.SLS(15e6, 300.0, 1200.0)
    ds = vcor.sweep({"materials": [mat], "grid": {"v0": np.array([1.0, 10.0])}}, workers=1, progress=False)
    name = ds["material"].item()
    assert name.startswith("sls-")
    np.testing.assert_array_equal(ds["cor"].sel(material=name).values,
                                  [vcor.simulate("sls", v).cor for v in (1.0, 10.0)])


LONG_SWEEP = textwrap.dedent("""
    import os, sys
    import vcor
    from vcor.study import progress
    progress.DELAY = 0  # the bar at once (the test is about where it shows, not when)
    vcor.simulate("sls", 1.0)
    print("ready", os.getpid(), flush=True)
    try:
        vcor.sweep({"materials": ["sls"], "grid": {"v0": {"start": 1, "stop": 30, "num": %d},
                    "beta": {"start": 600, "stop": 4800, "num": 40, "log": True}},
                    "tie": {"alpha": {"to": "beta", "ratio": 0.25}}}, workers=%d, progress=%s)
    except KeyboardInterrupt:
        print("interrupted", flush=True)  # vcor.sweep has returned (raised): the time the test measures
        raise
    print("done", flush=True)
""")


def _children(pid):
    out = set()
    for task in Path(f"/proc/{pid}/task").iterdir():
        text = (task / "children").read_text().split()
        out |= {int(t) for t in text}
    return out


def _alive(pid):
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except FileNotFoundError:
        return False
    return stat.rsplit(")", 1)[1].split()[0] != "Z"


def test_a_worker_that_dies_stops_the_sweep_with_an_error_not_a_wait(monkeypatch):
    parent = os.getpid()
    solve_rows = pool.solve_rows
    first = [True]

    def dying(*args, **kwargs):  # a worker killed mid-sweep (out of memory, say): its chunk never comes back
        if os.getpid() != parent:
            time.sleep(1.0)  # dies while the calling process waits for this chunk
            os._exit(9)
        if first[0]:  # the caller solves chunks too: on a loaded machine it could take them all before the
            first[0] = False  # worker starts, and no worker would die; this second lets the worker take one
            time.sleep(1.0)
        return solve_rows(*args, **kwargs)

    monkeypatch.setattr(pool, "solve_rows", dying)
    points = scene.grid_of({"materials": ["sls"], "grid": {"v0": list(np.linspace(0.5, 10.0, 40))}}).points()
    start = time.perf_counter()
    with pytest.raises(RuntimeError, match="ended with exit code"):
        pool.solve(points, scene.settings_of({}), workers=2)
    assert time.perf_counter() - start < 30.0


def test_ctrl_c_stops_the_sweep_and_its_processes_within_a_second():
    # SIGINT as a terminal's Python has it: in the full suite this test's process can have SIGINT ignored
    # (left so by code run earlier in the same pytest worker), a child inherits that, Python then installs
    # no KeyboardInterrupt handler and the sweep runs to its end
    with subprocess.Popen([sys.executable, "-c", LONG_SWEEP % (2000, 2, "False")], env=ENV, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True,
                          preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL)) as proc:
        try:
            assert proc.stdout.readline().startswith("ready")
            deadline = time.monotonic() + 60
            while not (children := _children(proc.pid)) and time.monotonic() < deadline:
                time.sleep(0.05)
            assert children, "the worker process did not start"  # workers=2: this process and one worker
            time.sleep(0.5)
            assert proc.poll() is None
            start = time.monotonic()
            proc.send_signal(signal.SIGINT)
            line = proc.stdout.readline()
            took = time.monotonic() - start
            # vcor.sweep has raised: its workers are gone already (not only once the interpreter exits)
            left = [c for c in children if _alive(c)]
            proc.wait(timeout=10)
            err = proc.stderr.read()
        finally:
            proc.kill()
    print(f"SIGINT to vcor.sweep raising: {took:.3f} s")
    # 80000 points: several seconds of work on two cores, so the sweep is still solving when SIGINT comes
    assert line.startswith("interrupted"), f"the sweep printed {line!r} after SIGINT, not 'interrupted'"
    assert took <= 1.0
    assert not left, "worker processes left behind"
    assert proc.returncode != 0 and "KeyboardInterrupt" in err.splitlines()[-1]


def _run_in_pty(code):
    """(output, exit code) of ``python -c code`` with a terminal as its standard streams."""
    pid, fd = pty.fork()
    if pid == 0:  # pragma: no cover - the child
        os.execve(sys.executable, [sys.executable, "-c", code], ENV)
    fcntl.ioctl(fd, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 120, 0, 0))  # a terminal of 120 columns
    chunks = []
    while True:
        try:
            data = os.read(fd, 4096)
        except OSError:
            break
        if not data:
            break
        chunks.append(data)
    _, status = os.waitpid(pid, 0)
    return b"".join(chunks).decode(errors="replace"), os.waitstatus_to_exitcode(status)


def test_the_progress_bar_shows_on_a_terminal_and_not_in_a_pipe():
    code = LONG_SWEEP % (10, 2, "None")
    out, rc = _run_in_pty(code)
    assert rc == 0 and "done" in out
    assert "vcor.sweep:" in out and "400/400" in out and " ok, " in out and " flagged, " in out and " failed" in out
    piped = subprocess.run([sys.executable, "-c", code], env=ENV, capture_output=True, text=True, check=True)
    assert "done" in piped.stdout
    assert piped.stderr == "" and "\r" not in piped.stdout


def test_dir_lists_the_public_names_loaded_on_first_use():
    """Tab completion (IPython, Jupyter) asks dir(vcor): the lazily loaded functions are in it."""
    out = subprocess.run([sys.executable, "-c", "import vcor; print(' '.join(dir(vcor)))"], capture_output=True,
                         text=True, check=True).stdout.split()
    assert {"simulate", "sweep", "fit", "calibrate", "dem_export", "Result", "SolverOptions"} <= set(out)
    assert "import_module" not in out and "TYPE_CHECKING" not in out


@pytest.mark.parametrize("call, message", [
    (lambda: vcor.sweep({"materials": ["sls"], "grid": {"v0": [1]}, "figures": {"fig4": {"material": "sls"}}}),
     r"^scene\.figures\.fig4 needs a sweep with a grid axis beta: add scene\.grid\.beta$"),
    (lambda: vcor.fit("butyl-prony-n3"), r"^fit: 'butyl-prony-n3' names an entry of a config's fits block, but no "
                                         r"config was given: pass config="),
    (lambda: vcor.sweep({"materials": [{"model": "sls", "E_glassy": 2e7, "alpha": 300.0, "beta": 1200.0,
                                        "shift": {"model": "wlf", "C1": 8}}], "grid": {"v0": [1]}}),
     r"^scene\.materials\[0\]\.shift \(wlf\): missing \['C2', 'T_ref'\]; takes"),
    (lambda: vcor.sweep({"materials": ["sls"], "grid": {"v0": {"start": 1, "stop": 2, "num": 10**9}}}),
     r"^scene\.grid: 1000000000 points in one sweep job \(no shard_size\)"),
    (lambda: vcor.sweep({"materials": ["sls", {"model": "sls", "E_glassy": 2e7, "alpha": 300.0, "beta": 1200.0,
                                               "shift": {"model": "table", "T": [0, 20], "log_aT": [1, 0],
                                                         "T_ref": 20}}], "grid": {"v0": [1], "T": [10]}}),
     r"^scene\.materials\[1\]\.shift\.model: 'table' is not allowed"),
    (lambda: vcor.sweep({"materials": [{"model": "elastic", "E": 1e9}, {"model": "elastic", "E": 1e9}],
                         "grid": {"v0": [1]}}), r"^scene\.materials\[1\]: the same material as scene\.materials\[0\]"),
    (lambda: vcor.sweep({"materials": [{"model": "sls", "E_glassy": 2e7, "alpha": 300.0, "beta": 1200.0,
                                        "shift": {"model": "wlf", "C1": 8.86, "C2": 101.6, "T_ref": 20}}],
                         "grid": {"v0": [1], "T": [-300]}}),
     r"^scene\.grid\.T: material scene\.materials\[0\]: temperature T must be in"),
    (lambda: vcor.moduli({"moduli": ["sls"]}), r"^scene: got \{'moduli': \['sls'\]\}; allowed: a mapping with"),
    (lambda: vcor.sweep({"materials": [{"model": "sls", "E_glassy": 2e7, "alpha": 300.0, "beta": 1200.0,
                                        "shift": {"model": "wlff", "C1": 1}}], "grid": {"v0": [1]}}),
     r"^scene\.materials\[0\]\.shift\.model: 'wlff' is not allowed; allowed: \['wlf', 'arrhenius'\]"),
    (lambda: vcor.convergence({"convergence": {"materials": ["sls", {"model": "sls", "E_glassy": -2e7, "alpha": 300.0,
                                                                      "beta": 1200.0}], "v0": [1]}}),
     r"^scene\.convergence\.materials\[1\]\.E_glassy must be in \(0, 1e\+20\] Pa"),
    (lambda: vcor.convergence({"convergence": {"materials": [{"model": "elastic", "E": 1e9}, {"model": "elastic",
                                                                                              "E": 1e9}], "v0": [1]}}),
     r"^scene\.convergence\.materials\[1\]: the same material as scene\.convergence\.materials\[0\]"),
])
def test_refusals_of_study_calls_name_the_argument(call, message):
    """Each refusal names the key as the call wrote it (scene., fit:), before any work."""
    with pytest.raises(ValueError, match=message):
        call()


def test_workers_takes_any_integer_type():
    ds = vcor.sweep({"materials": ["sls"], "grid": {"v0": [1.0]}}, workers=np.int64(1), progress=False)
    assert ds["cor"].item() == vcor.simulate("sls", 1.0).cor


@pytest.mark.parametrize("call, message", [
    (lambda: vcor.sweep("convergence", config=REPO_CONFIG),
     r"scenes\.convergence\.grid: the scene has no grid for vcor\.sweep \(add grid: .*\); it has convergence "
     r"\(vcor\.convergence\)$"),
    (lambda: vcor.histories({"materials": ["sls"], "grid": {"v0": [1.0]}}),
     r"^scene\.histories: the scene has no histories for vcor\.histories \(add histories: .*\); it has grid "
     r"\(vcor\.sweep\)$"),
    (lambda: vcor.viscoelastic_spheres({"materials": ["sls"]}), r"^scene\.spheres: the scene has no spheres"),
    (lambda: vcor.convergence({"materials": ["sls"]}), r"^scene\.convergence: the scene has no convergence"),
])
def test_a_scene_without_the_block_a_function_needs_is_refused_naming_it(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_histories_load_the_kernels_before_timing_the_runs(monkeypatch):
    """Each run's wall_time is its solve: the methods' kernels are loaded (numba's cache, or compiled)
    before the first run is timed, as the work-precision study does."""
    from vcor.study import scene_datasets

    calls = []
    from vcor.solvers import backend

    monkeypatch.setattr(backend, "load_kernels", lambda methods: calls.append(("load", list(methods))))
    solve = scene_datasets.datasets.histories_dataset
    monkeypatch.setattr(scene_datasets.datasets, "histories_dataset",
                        lambda *a, **k: calls.append(("solve",)) or solve(*a, **k))
    vcor.histories({"materials": ["sls"], "histories": {"v0": 1.0, "runs": [["sls", "direct"], ["sls", "adaptive"]]}})
    assert calls == [("load", ["adaptive", "direct"]), ("solve",)]


def test_a_convergence_study_takes_inline_material_specs():
    """As the other study functions: an inline spec becomes a named config material of that content."""
    from vcor.study.inputs import resolve_scene

    spec = {"model": "sls", "E_glassy": 2e7, "alpha": 300.0, "beta": 1200.0}
    study = resolve_scene({"convergence": {"materials": ["sls", spec], "v0": [1.0]}}, dataset="convergence")
    names = study.project.scenes[study.name].config["convergence"]["materials"]
    assert names[0] == "sls" and names[1].startswith("sls-")
    material = study.project.catalogue.material(names[1])
    assert material.relaxation_modulus(0.0) == pytest.approx(2e7, rel=1e-12)


@pytest.mark.parametrize("call, message", [
    (lambda: vcor.dem_export({"sphere": {"material": "sls", "r": 0.005}, "v0": [1.0], "modles": ["table"]},
                             config=REPO_CONFIG), r"^dem\.modles: unknown key"),
    (lambda: vcor.sweep({"materials": ["sls"], "grod": {"v0": [1.0]}}, config=REPO_CONFIG),
     r"^scene\.grod: unknown key"),
])
def test_a_refusal_of_a_mapping_argument_does_not_name_the_config_file(call, message):
    """The key is in the argument, which no file holds: the refusal starts with the argument's key path, not
    with the config file the call also gave (for its materials)."""
    with pytest.raises(ValueError, match=message):
        call()
