"""The model layer: response-surface models fitted to runs, and what is read from them.

Every fit is one :class:`FitResult` whatever its kind — OLS (any term list, blocks,
categoric factors, a transformed response, a Dask frame), a Scheffé mixture (with process
factors), REML with a random whole-plot or block intercept and Kenward–Roger tests — and
answers the prediction contract of :mod:`~rsm_lrg.model.prediction` (``FittedModel``,
``IntervalForm``), which the optimisers, the faces and the report use. The modules, by role:

* specify and build: ``spec`` (:class:`ModelSpec`), ``data`` and ``inputs`` (the checked
  inputs), ``terms`` (the model matrix, in :mod:`rsm_lrg.terms`), ``transform``, ``goals``;
* estimate: ``fit`` (:func:`fit`, the dispatch), ``least_squares`` (the QR core),
  ``dask_fit`` (partition by partition), ``mixed`` (REML, Kenward–Roger), ``mixture``
  (Scheffé models on L-pseudo components), ``actual_units`` (least squares in actual units);
* the result and its readings: ``result`` (:class:`FitResult`), ``prediction`` (the contract),
  ``anova``, ``statistics``, ``actual``, ``canonical``, ``levels``, ``diagnostics``,
  ``effects``, ``ridge``, ``mixture_region``, ``mixture_trace``;
* model choice: ``summary`` (fit summary), ``reduce`` and ``mixed_reduce`` (backward
  elimination by p or AICc, by Kenward–Roger p);
* faces: ``summary_data`` (one summary as data), ``text`` (the Design-Expert text);
* before any data: ``evaluate`` (design evaluation: VIF, leverage, FDS, power, GLS).
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
