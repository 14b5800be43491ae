"""The Gaussian process beside the polynomial orders, by leave-one-out on the same runs
(:func:`compare_loo`): PRESS and predicted R² for each polynomial order (from the fit
summary, :mod:`rsm_lrg.model.choice.summary`) and the closed-form leave-one-out of the GP (Dubrule
1983; :class:`~rsm_lrg.model.results.gp_result.LeaveOneOut`), so that a user sees when a polynomial
is enough. Both predicted R² are ``1 - PRESS / SS_total`` about the mean. The polynomials'
PRESS refits every coefficient without each run; the GP's refits its trend, the covariance
parameters held at their estimates from all runs (so it is slightly optimistic).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["LooComparison", "compare_loo", "compare_with_polynomials"]


def _f(v: Any) -> float | None:
    v = float(v)
    return v if np.isfinite(v) else None


@dataclass(frozen=True)
class LooComparison:
    """Leave-one-out of the polynomial orders and the GP.

    Attributes
    ----------
    table : pandas.DataFrame
        Columns ``model, press, pred_r2, rmse, aliased``: one row per polynomial order, then
        ``"GP (kernel, trend)"``.
    best : str
        The model with the smallest PRESS (aliased orders left out).
    """

    table: Any
    best: str

    def to_dict(self) -> dict:
        return {"models": [{"model": r.model, "press": _f(r.press), "pred_r2": _f(r.pred_r2), "rmse": _f(r.rmse),
                            "aliased": bool(r.aliased)} for r in self.table.itertuples(index=False)],
                "best": self.best}

    def summary(self) -> str:
        from ...present import format_g, text_table

        rows = [[r.model, format_g(r.press), format_g(r.pred_r2), format_g(r.rmse),
                 "Aliased" if r.aliased else ("Smallest PRESS" if r.model == self.best else "")]
                for r in self.table.itertuples(index=False)]
        return ("Leave-one-out: polynomials (PRESS) and the Gaussian process (closed form)\n"
                + text_table(["Model", "PRESS", "Predicted R²", "LOO RMSE", ""], rows) + "\n")


def compare_loo(summary: Any, gp: Any) -> LooComparison:
    """Put the GP's leave-one-out beside the fit summary's PRESS (the same runs).

    Parameters
    ----------
    summary : FitSummary
    gp : GPResult

    Returns
    -------
    LooComparison
    """
    import pandas as pd

    if summary.n != gp.n:
        raise ValueError(f"the fit summary has {summary.n} runs and the Gaussian process {gp.n}: compare on the "
                         "same runs")
    rows = []
    for r in summary.statistics.itertuples(index=False):
        rows.append({"model": r.source, "press": r.press, "pred_r2": r.pred_r2,
                     "rmse": float(np.sqrt(r.press / summary.n)) if np.isfinite(r.press) else float("nan"),
                     "aliased": bool(r.aliased)})
    loo = gp.loo
    rows.append({"model": f"GP ({gp.kernel}, {gp.trend})", "press": float(np.sum(loo.residuals ** 2)),
                 "pred_r2": loo.q2, "rmse": loo.rmse, "aliased": False})
    table = pd.DataFrame(rows, columns=["model", "press", "pred_r2", "rmse", "aliased"])
    ok = table[~table["aliased"] & np.isfinite(table["press"])]
    best = str(ok.loc[ok["press"].idxmin(), "model"])
    return LooComparison(table=table, best=best)


def compare_with_polynomials(data: Any, gp: Any) -> LooComparison:
    """The polynomial orders fitted to the runs of a GP (its factors, their ranges and coding,
    its response), their PRESS beside the GP's closed-form leave-one-out (:func:`compare_loo`):
    what ``rsm-lrg report --model gp`` shows, as ``fit-summary --gp`` prints.

    Parameters
    ----------
    data : pandas.DataFrame
        The runs the GP was fitted to.
    gp : GPResult

    Returns
    -------
    LooComparison

    Raises
    ------
    ValueError
        When not even the linear polynomial can be fitted to the runs, or they are not the GP's.
    """
    from .summary import fit_summary

    factors = [f"{f.name}={f.low!r}:{f.high!r}" for f in gp.space.factors]
    return compare_loo(fit_summary(data, gp.response, factors=factors), gp)
