"""Deprecated alias: the paper reproduction moved to :mod:`rsm_lrg.paper.reproduction` (it
computes) and :mod:`rsm_lrg.report.reproduction_page` (it presents).

Kept so that ``from rsm_lrg.report.reproduce import reproduce, write_reproduction, Row, ...``
still works. Nothing in the package imports this module (``rsm_lrg.report`` does not), so
the report layer never loads the paper layer; the one import below is the single exception
listed in the import-linter contract (``ignore_imports`` in pyproject.toml).
"""

import warnings as _warnings

from ..paper.reproduction import *  # noqa: F403
from ..paper.reproduction import (  # noqa: F401
    __all__ as _paper_all,
)
from ..paper.reproduction import (  # noqa: F401
    _claim,
    _close,
    _fmt,
    _info,
)
from .reproduction_page import _cell_css, banner, display_number  # noqa: F401

__all__ = [*_paper_all, "banner", "display_number"]

_warnings.warn("rsm_lrg.report.reproduce is deprecated: use rsm_lrg.paper (reproduce, write_reproduction) and "
               "rsm_lrg.report.reproduction_page (banner, display_number)", DeprecationWarning, stacklevel=2)
