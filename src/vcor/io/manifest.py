"""The per-scene manifest: every output with its size and SHA-256 (what to archive)."""

from __future__ import annotations

import hashlib
from pathlib import Path

__all__ = ["write_manifest"]


def write_manifest(scene: str, paths, out) -> None:
    """List a scene's outputs with their sizes (bytes) and SHA-256 digests in ``out`` (what to archive)."""
    with open(out, "w") as fh:
        fh.write(f"# scene {scene}: outputs (bytes, sha256)\n")
        for path in paths:
            data = Path(path).read_bytes()
            fh.write(f"{path}\t{len(data)}\t{hashlib.sha256(data).hexdigest()}\n")
