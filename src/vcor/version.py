"""The package version (one place: the package, provenance records and ``vcor --version`` read it)."""

__version__ = "0.2.0"
