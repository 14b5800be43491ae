"""Backward elimination of a REML fit by its Kenward–Roger p-values, hierarchy kept.

As :mod:`rsm_lrg.model.choice.reduce` does for least squares (the removable terms are those no
remaining term contains; the one with the largest p-value leaves while it exceeds
``alpha_out``), but each step refits the mixed model by REML (the variance ratio changes with
the terms) and reads the Kenward–Roger F tests of :mod:`rsm_lrg.model.engines.mixed`. The AICc route
is not offered: REML likelihoods of models with different fixed effects are not comparable.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from typing import Any

from ..build.spec import ModelSpec
from .reduce import Reduction, removable

__all__ = ["reduce_mixed"]


def reduce_mixed(refit: Callable[[ModelSpec], Any], spec: ModelSpec, space: Any) -> Reduction:
    """Hierarchical backward elimination by Kenward–Roger p-values.

    Parameters
    ----------
    refit : callable
        ``refit(spec)`` -> the REML :class:`~rsm_lrg.model.results.result.FitResult` of a
        specification without reduction.
    spec : ModelSpec
        The starting model, with its :class:`~rsm_lrg.model.build.spec.ReduceSpec`.
    space : FactorSpace
        The factors (for the term names).

    Returns
    -------
    Reduction
        ``steps`` has the columns of the least-squares reduction (``aicc_before`` and
        ``aicc_after`` NaN: not computed for REML).
    """
    import pandas as pd

    assert spec.reduce is not None
    if spec.reduce.method != "backward" or not spec.reduce.hierarchy:
        from ..build.spec import SpecError

        raise SpecError("reduce", "a REML fit is reduced by hierarchical backward elimination on the Kenward-Roger "
                                  f"p-values, not by {spec.reduce.method} selection")
    alpha_out = spec.reduce.alpha_out
    current = replace(spec, reduce=None)
    steps: list[dict[str, Any]] = []
    removed: list[str] = []
    while True:
        res = refit(current)
        terms = list(res.terms)
        pv = {t.term: t.p for t in res.tests}
        cand = removable(terms)
        if not res.intercept and len(cand) == len(res.model_terms) == 1:
            cand = []  # the last term of a model without an intercept stays
        scored = [(pv[t.name] if math.isfinite(pv[t.name]) else -1.0, t) for t in cand]
        if not scored:
            break
        worst_p, worst = max(scored, key=lambda z: z[0])
        if not worst_p > alpha_out:
            break
        steps.append({"step": len(steps) + 1, "term": worst.name, "p": worst_p, "aicc_before": math.nan,
                      "aicc_after": math.nan})
        removed.append(worst.name)
        terms = [t for t in terms if t is not worst]
        rest = tuple(t.name for t in terms if t.order > 0)
        if not rest:  # every term removed: the caller says so
            break
        current = replace(current, terms=rest)
    kept_names = tuple(t.name for t in terms)
    return Reduction(kept=kept_names, removed=tuple(removed), steps=pd.DataFrame(
        steps, columns=["step", "term", "p", "aicc_before", "aicc_after"]), criterion="p", alpha_out=float(alpha_out),
        start_model=spec.order if spec.terms is None else "custom")
