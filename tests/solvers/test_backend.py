"""The numba back end: each method's kernels loaded under its machine-wide lock, so that parallel
jobs with an empty cache compile a method once (vcor.solvers.backend)."""

import fcntl
import threading

from vcor.solvers import backend


def test_load_kernels_waits_for_the_lock_in_the_cache_folder(tmp_path, monkeypatch):
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    assert backend.cache_folder() == tmp_path
    done = threading.Event()
    with open(tmp_path / backend.lock_name("adaptive"), "a") as held:
        fcntl.flock(held, fcntl.LOCK_EX)  # another job compiling the adaptive kernels
        worker = threading.Thread(target=lambda: (backend.load_kernels(["adaptive"]), done.set()))
        worker.start()
        assert not done.wait(0.5)  # it waits while the lock is held
        fcntl.flock(held, fcntl.LOCK_UN)
    worker.join(60)
    assert done.is_set()


def test_load_kernels_compiles_what_the_methods_use():
    backend.load_kernels(["adaptive"])
    compiled = backend.compiled_signatures()
    assert compiled["_adaptive_kernels.adaptive_grids"]  # the one-call path of the adaptive method


def test_another_methods_lock_does_not_block(tmp_path, monkeypatch):
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    done = threading.Event()
    with open(tmp_path / backend.lock_name("direct"), "a") as held:
        fcntl.flock(held, fcntl.LOCK_EX)  # another job compiling the direct method's kernels
        worker = threading.Thread(target=lambda: (backend.load_kernels(["adaptive"]), done.set()))
        worker.start()
        assert done.wait(120)  # adaptive loads while direct's lock is held
        fcntl.flock(held, fcntl.LOCK_UN)
    worker.join(1)
