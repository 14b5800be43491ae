"""The optimize layer: optima of fitted response surfaces (scipy on the coded box).

Every function here takes fitted results (:class:`rsm_lrg.model.FitResult` or a
transformed fit), never data: fit first (``rsm_lrg.fit``), then optimise.

``single`` holds the single-response optimiser, :func:`optimize` and
:class:`OptimumResult`; ``desirability`` the several-response optimiser; ``confirm`` the
confirmation-run check.

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
