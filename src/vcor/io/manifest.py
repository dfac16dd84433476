"""The per-scene manifest: every output with its size and SHA-256 (what to archive)."""

from __future__ import annotations

import hashlib
from pathlib import Path

from .receipts import atomic_text

__all__ = ["write_manifest"]


def write_manifest(what: str, paths, out) -> None:
    """List the outputs of ``what`` (``scene <name>``, ``DEM entry <name>``) with their sizes (bytes)
    and SHA-256 digests in ``out`` (what to archive)."""
    lines = [f"# {what}: outputs (bytes, sha256)"]
    for path in paths:
        data = Path(path).read_bytes()
        lines.append(f"{path}\t{len(data)}\t{hashlib.sha256(data).hexdigest()}")
    atomic_text(out, "\n".join(lines) + "\n")
