"""The optimize layer: optima of fitted response surfaces (scipy on the coded box).

Every function here takes fitted results (:class:`rsm_lrg.model.FitResult` or a
transformed fit), never data: fit first (``rsm_lrg.fit``), then optimise.

``single`` holds the single-response optimiser and :func:`optimize`; ``result``
:class:`OptimumResult`; ``region`` the factor box, categoric levels and constraints searched;
``mixture`` the optimum over the constrained simplex (crossed with the process factors);
``desirability`` the several-response optimiser; ``confirm`` the confirmation-run check;
``study`` the several-response fit loop the commands share. Each asks the fitted models the
questions of the prediction contract (:mod:`rsm_lrg.model.contract.prediction`).

``rsm_lrg.optimize`` is always this package (see ``rsm_lrg/__init__.py``), and the package is
callable: ``rsm_lrg.optimize(result, goal="minimize")`` is
``rsm_lrg.optimize.optimize(result, goal="minimize")``.
"""

import sys as _sys
import types as _types

from .single import OptimumResult, optimize, parse_bounds, parse_goal

__all__ = ["optimize", "OptimumResult", "parse_goal", "parse_bounds"]


class _CallablePackage(_types.ModuleType):
    def __call__(self, *args, **kwargs):
        return optimize(*args, **kwargs)


_sys.modules[__name__].__class__ = _CallablePackage
