"""One BLAS thread for scipy's linear algebra where vcor's numbers go through it.

With a multi-threaded BLAS (OpenBLAS, as scipy's wheels ship it) the last digits of a small LU or QR
factorisation can depend on the number of threads, and so on the machine and on how the process was
started: a Snakemake job runs with one thread (``OPENBLAS_NUM_THREADS=1``), a notebook with every core.
scipy's ``Radau`` and ``BDF`` integrators (method ``ive``) and the exponential-sum fit of two bodies
(:mod:`vcor.materials.expfit`) run inside :func:`one_blas_thread`, so their numbers are the same
everywhere (``tests/test_threads.py``), and their small factorisations are not slowed by threads.
``threadpoolctl``'s controller is built once, after scipy's BLAS is loaded (a limit reaches only the
libraries loaded when it is set); entering the limit then needs no new scan of the process's libraries,
which a fresh ``threadpool_limits`` makes every time.
"""

from __future__ import annotations

import contextlib
import functools

__all__ = ["one_blas_thread"]


@functools.cache
def _controller():
    import scipy.linalg  # noqa: F401 (loads scipy's BLAS before the controller lists the libraries)
    from threadpoolctl import ThreadpoolController

    return ThreadpoolController()


@contextlib.contextmanager
def one_blas_thread():
    """A block in which the BLAS libraries loaded by scipy run one thread."""
    with _controller().limit(limits=1, user_api="blas"):
        yield
