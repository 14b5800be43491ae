"""A fit seen at one combination of categoric levels (the numeric surface there).

The optimisers (:mod:`rsm_lrg.optimize`) and the ridge analysis search over the numeric
factors at each combination of the categoric factors' levels; :class:`LevelView` gives them
a fit-like object of the numeric factors only, whose coefficients are those of the numeric
surface at that level (:func:`rsm_lrg.model.readings.canonical.numeric_surface`) and whose
predictions (with intervals) come from the whole fit.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from .canonical import canonical_analysis, numeric_surface

__all__ = ["LevelView"]


class LevelView:
    """A fit seen at one combination of categoric levels: the numeric factors only, with
    the coefficients of the numeric surface there (:func:`rsm_lrg.model.readings.canonical.numeric_surface`)
    and predictions (with intervals) from the whole fit at that level."""

    def __init__(self, fitted, level: Mapping[str, str]):
        import pandas as pd

        coefs, terms, sub, chosen = numeric_surface(dict(zip(fitted.coefficients.index,
                                                             fitted.coefficients["coded"])),
                                                    fitted.terms, fitted.space, level)
        self.fitted, self.level = fitted, chosen
        self.sigma2, self.df_resid, self.y = fitted.sigma2, fitted.df_resid, fitted.y
        self.coded = fitted.coded[sub.letters] if fitted.coded is not None else None
        self.space, self.terms, self.response = sub, tuple(terms), fitted.response
        self.coefficients = pd.DataFrame({"coded": [coefs[t.name] for t in terms]},
                                         index=pd.Index([t.name for t in terms], name="term"))
        quad = all(t.order <= 2 for t in terms)
        self.stationary_point = canonical_analysis(coefs, terms, sub) if quad else _NO_POINT
        full = fitted.space
        self._num = full.numeric_index
        self._cat = {i: f.index(chosen[f.name]) for i, f in enumerate(full.factors) if f.kind == "categoric"}

    def full_coded(self, x) -> np.ndarray:
        """Coded settings of the whole fit (level indices inserted) for numeric coded ``x``."""
        x = np.atleast_2d(np.asarray(x, dtype=float))
        out = np.zeros((x.shape[0], len(self.fitted.space)))
        out[:, self._num] = x
        for i, j in self._cat.items():
            out[:, i] = j
        return out

    @property
    def transform(self):
        """The whole fit's response transform."""
        return self.fitted.transform

    def goal_on_model_scale(self, goal):
        """The whole fit's goal mapping (:meth:`rsm_lrg.model.results.result.FitResult.goal_on_model_scale`)."""
        return self.fitted.goal_on_model_scale(goal)

    def predict(self, points, interval=None, alpha: float = 0.05, *, coded: bool = False):
        """Predictions in response units (back-transformed under a transform) at this level."""
        if not coded:
            points = self.space.encode(np.atleast_2d(np.asarray(points, dtype=float)))
        return self.fitted.predict(self.full_coded(points), interval=interval, alpha=alpha, coded=True)

    def predict_model(self, points, interval=None, alpha: float = 0.05, *, coded: bool = False):
        """Predictions on the model's scale at this level."""
        if not coded:
            points = self.space.encode(np.atleast_2d(np.asarray(points, dtype=float)))
        return self.fitted.predict_model(self.full_coded(points), interval=interval, alpha=alpha, coded=True)


class _NoPoint:
    coded = None


_NO_POINT = _NoPoint()
