"""Experimental designs on a factor space: Box–Behnken, central composite, full factorial
(each crossed with categoric factors), optimal designs (D/I/A, constraints), augmentation,
screening designs (definitive screening, fractional factorial, Plackett–Burman) and
space-filling designs (Latin hypercube, Sobol') and mixture designs (simplex lattice,
simplex centroid, extreme vertices) and optimal split-plot designs (hard-to-change factors in
whole plots, GLS criteria).

Every generator returns a :class:`Design` (standard order kept, run order randomised from a
seed) whose :meth:`Design.to_frame` / :meth:`Design.to_csv` give the design CSV layout that
``rsm-lrg design`` writes and that ``simulate`` and ``evaluate`` read back with
:func:`read_design`.
"""

from .augment import augment
from .box_behnken import BBD_BLOCKS, BBD_SETS, box_behnken
from .composite import ccd_alpha, central_composite
from .constraints import Constraints
from .core import Design, as_factor_space, read_design
from .factorial import full_factorial
from .mixture import MixtureDesign, cross_process, extreme_vertices, simplex_centroid, simplex_lattice
from .mixture_optimal import mixture_optimal
from .multi_stratum import split_split_plot, stratum_criteria, strip_plot
from .optimal import criterion_value, optimal
from .paper import paper_design
from .screening import (
    alias_matrix,
    conference_matrix,
    definitive_screening,
    fractional_factorial,
    plackett_burman,
)
from .spacefill import latin_hypercube, sobol
from .split_plot import gls_criteria, gls_information, split_plot, split_plot_ccd

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
    "optimal",
    "criterion_value",
    "augment",
    "Constraints",
    "definitive_screening",
    "conference_matrix",
    "fractional_factorial",
    "plackett_burman",
    "alias_matrix",
    "latin_hypercube",
    "sobol",
    "MixtureDesign",
    "simplex_lattice",
    "simplex_centroid",
    "extreme_vertices",
    "split_plot",
    "split_plot_ccd",
    "split_split_plot",
    "strip_plot",
    "stratum_criteria",
    "gls_information",
    "gls_criteria",
    "mixture_optimal",
    "cross_process",
]
