"""Experimental designs on a factor space: Box–Behnken, central composite, full factorial.

Every generator returns a :class:`Design` (standard order kept, run order randomised from a
seed) whose :meth:`Design.to_frame` / :meth:`Design.to_csv` give the design CSV layout that
``rsm-lrg design`` writes and that ``simulate`` and ``evaluate`` read back with
:func:`read_design`.
"""

from .box_behnken import BBD_BLOCKS, BBD_SETS, box_behnken
from .composite import ccd_alpha, central_composite
from .core import Design, as_factor_space, read_design
from .factorial import full_factorial
from .paper import paper_design

__all__ = [
    "Design",
    "box_behnken",
    "central_composite",
    "full_factorial",
    "read_design",
    "ccd_alpha",
    "as_factor_space",
    "paper_design",
    "BBD_SETS",
    "BBD_BLOCKS",
]
