"""Provenance: which code computed a number.

``code_fingerprint()`` is a short hash of everything in the installed package that can change a
number in a dataset: the vcor version, the source of every module except the drawing and
command-line ones (the ``plots`` subpackage, ``cli.py``, ``cli_study.py``), and the versions of numpy,
scipy and numba. It enters
the identity of every sweep shard and the parameters of every computing workflow rule, so a
change of code recomputes what it may have changed (and ``snakemake -n`` lists it), and an
aggregate never combines results of different code. ``plots_fingerprint()`` does the same for the
figures. The git commit, where there is one, is recorded beside it for people, not used for
identity (an installed copy has none; a dirty tree has the same commit).
"""

from __future__ import annotations

import functools
import hashlib
import subprocess
from pathlib import Path

__all__ = ["code_fingerprint", "git_commit", "plots_fingerprint", "source"]

_PACKAGE = Path(__file__).resolve().parent
#: modules that draw or parse arguments but compute no stored number
_PLOTS = _PACKAGE / "plots"
_CLI = (_PACKAGE / "cli.py", _PACKAGE / "cli_study.py")


def _hash_files(paths) -> hashlib._Hash:
    h = hashlib.sha256()
    for p in sorted(paths):
        h.update(str(p.relative_to(_PACKAGE)).encode() + b"\0" + p.read_bytes() + b"\0")
    return h


@functools.lru_cache(maxsize=1)
def code_fingerprint() -> str:
    """16 hex digits identifying the computing code (see the module docstring). The dependency
    versions are read from their installed metadata (importing numba to ask would cost the
    workflow's aggregate jobs, which do not solve, ~0.3 s each)."""
    from importlib.metadata import version

    from .version import __version__

    files = [p for p in _PACKAGE.rglob("*.py") if p not in _CLI and _PLOTS not in p.parents]
    h = _hash_files(files)
    h.update(f"vcor {__version__}; numpy {version('numpy')}; scipy {version('scipy')}; "
             f"numba {version('numba')}".encode())
    return h.hexdigest()[:16]


@functools.lru_cache(maxsize=1)
def plots_fingerprint() -> str:
    """16 hex digits identifying the figure code (the ``plots`` subpackage)."""
    return _hash_files(_PLOTS.glob("*.py")).hexdigest()[:16]


@functools.lru_cache(maxsize=1)
def git_commit() -> str:
    """The git commit of the source tree ("+dirty" with local changes), or "unknown"."""
    try:
        out = subprocess.run(["git", "-C", str(_PACKAGE), "rev-parse", "HEAD"], capture_output=True, text=True,
                             timeout=5, check=False)
        commit = out.stdout.strip() if out.returncode == 0 else "unknown"
        dirty = subprocess.run(["git", "-C", str(_PACKAGE), "status", "--porcelain", "--", str(_PACKAGE)],
                               capture_output=True, text=True, timeout=5, check=False).stdout.strip()
        return commit + ("+dirty" if dirty and commit != "unknown" else "")
    except (OSError, subprocess.SubprocessError):
        return "unknown"


def source() -> str:
    """The CF ``source`` attribute: vcor version, code fingerprint and git commit."""
    from .version import __version__

    return f"vcor {__version__} (code {code_fingerprint()}, git {git_commit()})"
