"""The numba back end: kernels loaded under one machine-wide lock, so that parallel jobs with an
empty cache compile once (vcor.solvers.backend)."""

import fcntl
import threading

from vcor.solvers import backend


def test_load_kernels_waits_for_the_lock_in_the_cache_folder(tmp_path, monkeypatch):
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    assert backend.cache_folder() == tmp_path
    done = threading.Event()
    with open(tmp_path / backend.LOCK_NAME, "a") as held:
        fcntl.flock(held, fcntl.LOCK_EX)  # another job compiling
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
