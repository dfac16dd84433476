"""``python -m vcor``: the command line, the same as ``vcor`` (:mod:`vcor.cli`)."""

import sys

from .cli import main

if __name__ == "__main__":
    sys.exit(main())
