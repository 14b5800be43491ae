"""Factors and their coding: the space a design lives in.

A :class:`FactorSpace` holds named factors with a low and a high level and a letter
(A, B, C, ...). It codes actual values to the [-1, +1] scale of response-surface work,

    coded = (x - (low + high) / 2) / ((high - low) / 2),

and back. It follows the shape of scikit-learn's ``MinMaxScaler`` and of R ``rsm``'s
``coded.data``: the coding travels with the data, so every later result (coefficients,
stationary point, optimum) can be given in coded and in actual units.

The low and high levels map to exactly -1 and +1 and back; coded values are rounded to
12 decimals so that a centre level given in a CSV (0.0003 between 0.0001 and 0.0005, say)
codes to exactly 0 and replicate detection does not trip over the last bit.

The package is split by concern (each module imports only those listed before it):

* :mod:`~rsm_lrg.factors.values`: a user's values in messages (quoted, finite, listed);
* :mod:`~rsm_lrg.factors.factor`: one factor, :class:`Factor` (numeric) and
  :class:`CategoricFactor`, and :class:`FactorLike`, what both offer;
* :mod:`~rsm_lrg.factors.spec`: factor specifications (``NAME=LOW:HIGH``, ``NAME=cat:L1,L2``)
  and factors as given in Python;
* :mod:`~rsm_lrg.factors.columns`: column inference (a design's coded columns, the numeric
  columns, categoric levels from the data, bookkeeping columns);
* :mod:`~rsm_lrg.factors.space`: the factor space, :class:`FactorSpace`;
* :mod:`~rsm_lrg.factors.choice`: :func:`choose_factors`, the factors of a data frame with
  notes for the user.

Every name is importable from ``rsm_lrg.factors`` as before. The cell checks the factors
share with file input (``float_column``, ``is_empty_cell``, ``cell_error``) live in
:mod:`rsm_lrg.io`.
"""

from __future__ import annotations

from ..io import COMMA_NUMBER, cell_error, float_column, is_empty_cell
from .choice import FactorChoice, choose_factors
from .columns import (
    BOOKKEEPING,
    CODED_COLUMN_PREFIX,
    COLUMNS_LEFT_OUT,
    DESIGN_CODED,
    PAIR_RTOL,
    Note,
    design_factors,
    infer_items,
    is_bookkeeping,
)
from .component import MixtureComponent
from .factor import (
    CODED_DECIMALS,
    RESERVED_FACTOR_NAMES,
    CategoricFactor,
    Factor,
    FactorLike,
    check_factor_name,
    letters_for,
    level_text,
)
from .space import FactorSpace, design_space, encode_column, inferred_space
from .spec import given_items, parse_factor, parse_factor_spec, spec_with_levels
from .values import LIST_LIMIT, QUOTE_LIMIT, finite_float, name_list, quote_value

__all__ = ["Factor", "CategoricFactor", "FactorSpace", "FactorChoice", "choose_factors", "letters_for",
           "parse_factor_spec", "parse_factor", "level_text", "check_factor_name", "quote_value", "CODED_DECIMALS",
           "FactorLike", "MixtureComponent"]

# The names this module had before it became a package, kept for old imports: the public
# ones above and below, and the old private spellings of the helpers now public in their
# modules (new code imports the public names from their modules).
_numeric = float_column
_is_empty = is_empty_cell
_bad_cell = cell_error
_COMMA_NUMBER = COMMA_NUMBER
_names = name_list
_LIST_LIMIT = LIST_LIMIT
_DESIGN_CODED = DESIGN_CODED
_encode_column = encode_column
_spec_with_levels = spec_with_levels
_given_items = given_items
_design_factors = design_factors
_design_space = design_space

__all__ += ["QUOTE_LIMIT", "LIST_LIMIT", "RESERVED_FACTOR_NAMES", "BOOKKEEPING", "CODED_COLUMN_PREFIX",
            "PAIR_RTOL", "DESIGN_CODED", "COLUMNS_LEFT_OUT", "Note", "is_bookkeeping", "finite_float", "name_list",
            "spec_with_levels", "given_items", "design_factors", "infer_items", "design_space", "inferred_space",
            "encode_column", "float_column", "is_empty_cell", "cell_error", "COMMA_NUMBER"]
