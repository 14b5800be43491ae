"""``python -m rsm_lrg`` is the ``rsm-lrg`` command."""

import sys

from .cli import main

if __name__ == "__main__":
    sys.exit(main())
