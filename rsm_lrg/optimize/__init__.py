"""The optimize layer: optima of fitted response surfaces (scipy on the coded box).

``single`` holds the single-response optimiser: :func:`optimize` and :class:`OptimumResult`.

The package is callable, so ``rsm_lrg.optimize(result, goal="minimize")`` works whether
``rsm_lrg.optimize`` resolves to this package or to the function.
"""

import sys as _sys
import types as _types

from .single import OptimumResult, optimize, parse_bounds, parse_goal

__all__ = ["optimize", "OptimumResult", "parse_goal", "parse_bounds"]


class _CallablePackage(_types.ModuleType):
    def __call__(self, *args, **kwargs):
        return optimize(*args, **kwargs)


_sys.modules[__name__].__class__ = _CallablePackage
