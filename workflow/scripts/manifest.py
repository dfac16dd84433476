"""List a scene's outputs with sizes and SHA-256 (what to archive)."""

import hashlib
import os
import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

with open(snakemake.output[0], "w") as fh:  # noqa: F821
    fh.write(f"# scene {snakemake.wildcards.scene}: outputs (bytes, sha256)\n")  # noqa: F821
    for path in snakemake.input:  # noqa: F821
        digest = hashlib.sha256(open(path, "rb").read()).hexdigest()
        fh.write(f"{path}\t{os.path.getsize(path)}\t{digest}\n")
