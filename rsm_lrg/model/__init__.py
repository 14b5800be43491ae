"""The model layer: response-surface models fitted to runs, and what is read from them.

Every fit is one :class:`FitResult` whatever its kind — OLS (any term list, blocks,
categoric factors, a transformed response, a Dask frame), a Scheffé mixture (with process
factors), REML with a random whole-plot or block intercept and Kenward–Roger tests — and
answers the prediction contract of :mod:`~rsm_lrg.model.contract.prediction` (``FittedModel``,
``IntervalForm``), which the optimisers, the faces and the report use. The subpackages, by role,
from the floor up (an import-linter contract keeps every import pointing down):

* ``build``: specify and build (``spec``: :class:`ModelSpec`; ``data``, ``inputs``: the checked
  inputs; ``terms``; ``transform``; ``mixture``, ``mixture_region``; ``goals``);
* ``contract``: the prediction contract (``prediction``), the statistics (``statistics``) and the
  tolerance intervals (``tolerance``) every kind shares;
* ``engines``: estimation (``least_squares``: the QR core; ``mixed``: REML, Kenward–Roger;
  ``glm_family``; ``gp_core``, ``gp_kernels``, ``gp_trend``);
* ``readings``: what is read from a fit (``anova``, ``actual``, ``actual_units``, ``canonical``,
  ``ridge``, ``effects``, ``diagnostics``, ``levels``, ``mixture_trace``);
* ``choice``: the terms and order the data support (``summary``, ``reduce``, ``mixed_reduce``,
  ``select``, ``loo_compare``); ``faces``: the fit in words (``summary_data``, ``text``);
* ``results``: one result per kind (``result``: :class:`FitResult`; ``glm_result``; ``gp_result``);
* ``pipelines``: each kind's fit (``dask_fit``, ``glm``, ``gp``);
* at the top, ``fit`` (:func:`fit`: specify, build, estimate, assemble, and the dispatch) and,
  before any data, ``evaluate`` (design evaluation: VIF, leverage, FDS, power, GLS).
"""

from .build.spec import ModelSpec, ReduceSpec, SpecError
from .build.terms import MODELS, Term, design_matrix, model_terms, parse_term
from .build.transform import Transform, parse_transform
from .contract.statistics import FitStatistics
from .engines.least_squares import Regression
from .fit import COEF_COLUMNS, FitResult, actual_coefficients, fit, fit_transformed
from .readings.anova import ANOVA_COLUMNS, PureError, partial_ss, pure_error
from .readings.canonical import StationaryPoint, canonical_analysis

__all__ = [
    "fit", "FitResult", "FitStatistics", "StationaryPoint", "PureError", "Term", "MODELS",
    "model_terms", "design_matrix", "parse_term", "partial_ss", "pure_error",
    "canonical_analysis", "actual_coefficients", "ANOVA_COLUMNS", "COEF_COLUMNS", "Regression",
    "ModelSpec", "ReduceSpec", "SpecError", "Transform", "parse_transform", "fit_transformed",
]
