"""The numba back end: each method's kernels loaded under its machine-wide lock, so that parallel
jobs with an empty cache compile a method once (vcor.solvers.backend)."""

import fcntl
import os
import threading

from vcor.solvers import backend


def test_load_kernels_waits_for_the_lock_in_the_cache_folder(tmp_path, monkeypatch):
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    folder = backend.cache_folder()
    assert folder.parent == tmp_path and folder.name.startswith("vcor-kernels-")
    folder.mkdir()
    done = threading.Event()
    with open(folder / backend.lock_name("adaptive"), "a") as held:
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
    backend.cache_folder().mkdir()
    done = threading.Event()
    with open(backend.cache_folder() / backend.lock_name("direct"), "a") as held:
        fcntl.flock(held, fcntl.LOCK_EX)  # another job compiling the direct method's kernels
        worker = threading.Thread(target=lambda: (backend.load_kernels(["adaptive"]), done.set()))
        worker.start()
        assert done.wait(120)  # adaptive loads while direct's lock is held
        fcntl.flock(held, fcntl.LOCK_UN)
    worker.join(1)


def test_a_changed_kernel_source_names_another_cache_folder(tmp_path):
    """numba checks a cached kernel against its own file only: a kernel calling into another file (the
    adaptive march's separation) would load stale code after that file changed. The cache folder is named
    by a hash of every kernel source, so a change to any of them compiles every kernel again: here, in a
    copy of the package, a changed _separation.py names another folder."""
    import shutil
    import subprocess
    import sys
    from pathlib import Path

    import vcor

    pkg = tmp_path / "pkg"
    shutil.copytree(Path(vcor.__file__).parent, pkg / "vcor", ignore=shutil.ignore_patterns("__pycache__"))
    code = "from vcor.solvers import backend; print(backend.cache_folder().name)"

    def folder():
        env = {**os.environ, "PYTHONPATH": str(pkg), "NUMBA_CACHE_DIR": str(tmp_path / "cache")}
        return subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                              check=True).stdout.strip()

    before = folder()
    assert before == backend.cache_folder().name  # the same sources: the same folder as this process's
    with open(pkg / "vcor/solvers/_separation.py", "a") as fh:
        fh.write("\n# changed\n")
    assert folder() != before


def test_every_kernel_module_is_a_kernel_source():
    """The cache folder's hash covers every module that holds kernels (backend.KERNEL_MODULES) and the
    records and flags they are built from."""
    from pathlib import Path

    names = {Path(m.__file__).name for m in backend.KERNEL_MODULES} | {"_records.py", "_jit.py"}
    assert names <= set(backend.KERNEL_SOURCES), names - set(backend.KERNEL_SOURCES)
