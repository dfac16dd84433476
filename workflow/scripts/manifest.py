"""List a scene's outputs with sizes and SHA-256 (what to archive); thin: vcor.io.manifest does it."""

import sys

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821

from vcor.io.manifest import write_manifest

write_manifest(snakemake.wildcards.scene, snakemake.input, snakemake.output[0])  # noqa: F821
