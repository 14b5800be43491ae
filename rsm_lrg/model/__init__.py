"""The model layer: polynomial response-surface models fitted by OLS in coded units.

``least_squares`` (the regression core: one factorisation, every statistic derived from
it), ``terms`` (model terms and the design matrix), ``fit`` (:func:`fit`, :class:`FitResult`;
``dask_fit`` for a Dask DataFrame), ``summary`` (fit summary), ``effects`` (Lenth's PSE and half-normal scores of
screening effects), ``reduce`` (backward
elimination), ``evaluate`` (design evaluation), ``diagnostics``,
``anova`` (Design-Expert ANOVA, Table 5), ``statistics`` (R², PRESS, adequate precision),
``canonical`` (stationary point and eigen-analysis), ``text`` (the summary text).
"""

from .anova import ANOVA_COLUMNS, PureError, partial_ss, pure_error
from .canonical import StationaryPoint, canonical_analysis
from .fit import COEF_COLUMNS, FitResult, actual_coefficients, fit, fit_transformed
from .least_squares import Regression
from .spec import ModelSpec, ReduceSpec, SpecError
from .statistics import FitStatistics
from .terms import MODELS, Term, design_matrix, model_terms, parse_term
from .transform import Transform, parse_transform

__all__ = [
    "fit", "FitResult", "FitStatistics", "StationaryPoint", "PureError", "Term", "MODELS",
    "model_terms", "design_matrix", "parse_term", "partial_ss", "pure_error",
    "canonical_analysis", "actual_coefficients", "ANOVA_COLUMNS", "COEF_COLUMNS", "Regression",
    "ModelSpec", "ReduceSpec", "SpecError", "Transform", "parse_transform", "fit_transformed",
]
