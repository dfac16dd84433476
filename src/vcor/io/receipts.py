"""Receipts: what a file's writer wrote, so that a reader can tell a file from a truncated, altered or
replaced one.

Every file vcor writes goes through :func:`atomic` (a temporary name in the same folder, then a rename:
a killed job never leaves a file that looks complete), and the NetCDF files a job reads get a receipt,
``<folder>/.receipts/<name>.json``: the file's size and SHA-256 and the *identity* it was written for
(a shard's id, a material's content identity; :meth:`vcor.materials.Catalogue.identity`). Before a file
is used, :func:`problem` compares it with its receipt: a missing receipt, other bytes or another
identity is a reason not to use it. The workflow then moves the file aside (:func:`quarantine`,
``<name>.invalid``) and computes it again; a job that meets such a file stops with the reason
(:func:`verified`).
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import tempfile
from pathlib import Path

__all__ = ["RECEIPTS", "atomic", "atomic_text", "problem", "quarantine", "receipt_path", "verified", "writable_file",
           "write_receipt"]

#: the folder of the receipts, beside the files they describe
RECEIPTS = ".receipts"


def writable_file(path, what: str = "output file") -> Path:
    """``path`` as a file :func:`atomic` may write, checked before any work: not an existing folder, device,
    pipe or socket (the rename would replace a device node with a regular file, and fails on a folder), in
    a folder that exists or can be made, and where this process can create a file (tried). ValueError
    naming ``what``."""
    path = Path(path)
    if (path.exists() or path.is_symlink()) and not path.is_file():
        kind = "a folder" if path.is_dir() else "not a regular file (a device, pipe or socket, or a broken link)"
        raise ValueError(f"{what} {str(path)!r} is {kind}: give the path of a file to write")
    folder = path.parent
    while not folder.exists() and folder != folder.parent:
        folder = folder.parent
    if not folder.is_dir():
        raise ValueError(f"{what} {str(path)!r}: {str(folder)!r} is a file, not a folder")
    try:  # the one sure test (permissions, a read-only or virtual file system such as /proc)
        with tempfile.TemporaryFile(dir=folder):
            pass
    except OSError as exc:
        raise ValueError(f"{what} {str(path)!r}: cannot write in the folder {str(folder)!r} ({exc.strerror})") from None
    return path


@contextlib.contextmanager
def atomic(path):
    """Yield a temporary path in ``path``'s folder; on success it is renamed to ``path`` (atomic on one
    file system), on an exception it is removed and ``path`` is left as it was. ``path`` must be a file
    :func:`writable_file` accepts (else ValueError, before anything is written)."""
    path = writable_file(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".part", dir=path.parent)
    os.close(fd)
    try:
        yield Path(tmp)
        os.chmod(tmp, 0o666 & ~_umask())  # mkstemp's file is private (0600); a written file follows the umask
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.remove(tmp)
        raise


def _umask() -> int:
    """The process's umask, read without changing it where Linux shows it (``os.umask`` can only set it)."""
    with contextlib.suppress(OSError, ValueError, StopIteration):
        status = Path("/proc/self/status").read_text().splitlines()
        return int(next(line for line in status if line.startswith("Umask:")).split()[1], 8)
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def atomic_text(path, text: str) -> Path:
    """Write ``text`` to ``path`` atomically (:func:`atomic`)."""
    with atomic(path) as tmp:
        Path(tmp).write_text(text)
    return Path(path)


def receipt_path(path) -> Path:
    path = Path(path)
    return path.parent / RECEIPTS / f"{path.name}.json"


def _digest(path: Path) -> tuple[int, str]:
    h = hashlib.sha256()
    size = 0
    with path.open("rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
            size += len(block)
    return size, h.hexdigest()


def write_receipt(path, identity: str | None = None) -> Path:
    """Write the receipt of the file at ``path`` (its size, SHA-256 and ``identity``)."""
    path = Path(path)
    size, sha = _digest(path)
    text = json.dumps({"file": path.name, "bytes": size, "sha256": sha, "identity": identity}, indent=1)
    return atomic_text(receipt_path(path), text + "\n")


def problem(path, identity: str | None = None) -> str | None:
    """Why the file at ``path`` must not be used (None: it is what its writer wrote, for ``identity``
    when given)."""
    path = Path(path)
    if not path.is_file():
        return "it does not exist"
    receipt = receipt_path(path)
    if not receipt.is_file():
        return f"it has no receipt ({receipt}): not written by this workflow, or its writer was interrupted"
    try:
        want = json.loads(receipt.read_text())
        size, sha = want["bytes"], want["sha256"]
    except (OSError, ValueError, KeyError, TypeError):
        return f"its receipt {receipt} cannot be read"
    got_size, got_sha = _digest(path)
    if (got_size, got_sha) != (size, sha):
        return (f"its content ({got_size} bytes, sha256 {got_sha[:12]}) is not what was written ({size} bytes, "
                f"sha256 {sha[:12]}): truncated, altered or replaced")
    if identity is not None and want.get("identity") != identity:
        return f"it was written for identity {want.get('identity')!r}, the current config asks for {identity!r}"
    return None


def verified(path, identity: str | None = None) -> Path:
    """``path`` if :func:`problem` finds nothing, else ValueError naming the file and the reason."""
    reason = problem(path, identity)
    if reason is not None:
        raise ValueError(f"{path}: {reason}; it is not used (the workflow recomputes it: run snakemake again)")
    return Path(path)


def quarantine(path) -> Path:
    """Move the file (and its receipt) aside to ``<name>.invalid``, replacing an older one; returns the
    new path. The workflow then computes the file again."""
    path = Path(path)
    target = path.with_name(path.name + ".invalid")
    os.replace(path, target)
    receipt = receipt_path(path)
    if receipt.is_file():
        os.replace(receipt, receipt_path(target))
    return target
