"""Fit statistics as Design-Expert reports them under the ANOVA.

R² and adjusted R² leave block variation out (Design-Expert's convention): with
``SS_adj = SS_total - SS_block``,

    R² = 1 - SS_res / SS_adj,      adj R² = 1 - (SS_res / df_res) / (SS_adj / (df_model + df_res)),
    PRESS = sum (e_i / (1 - h_ii))²,  pred R² = 1 - PRESS / SS_adj,

adequate precision = (max ŷ - min ŷ) / sqrt(mean V(ŷ)) over the design points with
mean V(ŷ) = p σ² / n (p model parameters, σ² the residual mean square), and
C.V. % = 100 · std dev / mean.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

__all__ = ["FitStatistics", "fit_statistics"]


@dataclass(frozen=True)
class FitStatistics:
    """Summary statistics of a fit (all floats; NaN where undefined, ``null`` in JSON).

    Attributes
    ----------
    r2, adj_r2, pred_r2 : float
        R², adjusted R², predicted R² (from PRESS) [-].
    press : float
        Prediction error sum of squares [response units²].
    adeq_precision : float
        Signal-to-noise ratio; above 4 is desirable (Design-Expert) [-].
    std_dev : float
        √(residual mean square) [response units].
    mean : float
        Mean response [response units].
    cv_percent : float
        Coefficient of variation, 100 · std_dev / mean [%].
    """

    r2: float
    adj_r2: float
    pred_r2: float
    press: float
    adeq_precision: float
    std_dev: float
    mean: float
    cv_percent: float

    def to_dict(self) -> dict:
        """``{"r2", "adj_r2", "pred_r2", "press", "adeq_precision", "std_dev", "mean", "cv_percent"}``."""
        return asdict(self)

    def __getitem__(self, key: str) -> float:  # dict-style access, stats["r2"]
        return getattr(self, key)

    def keys(self):
        return self.to_dict().keys()

    # -- faces: read like the CLI's block under the ANOVA ----------------------------------
    _LABELS = (("std_dev", "Std. Dev."), ("mean", "Mean"), ("cv_percent", "C.V. %"), ("press", "PRESS"),
               ("r2", "R²"), ("adj_r2", "Adjusted R²"), ("pred_r2", "Predicted R²"),
               ("adeq_precision", "Adeq Precision"))

    def _cells(self) -> list[tuple[str, str]]:
        from ..present import format_number

        return [(label, format_number(getattr(self, key), 4, missing="n/a")) for key, label in self._LABELS]

    def __str__(self) -> str:
        """Two columns, as the CLI prints the fit statistics (4 significant figures).

        >>> print(FitStatistics(0.96812, 0.93093, 0.81842, 2.079e-4, 18.4626, 1.744e-3, 0.035037, 4.9777))
        Std. Dev.  0.001744   R²              0.9681
        Mean       0.03504    Adjusted R²     0.9309
        C.V. %     4.978      Predicted R²    0.8184
        PRESS      0.0002079  Adeq Precision  18.46
        """
        cells = self._cells()
        left, right = cells[:4], cells[4:]
        wl = max(len(a) for a, _ in left)
        wv = max(len(b) for _, b in left)
        wr = max(len(a) for a, _ in right)
        return "\n".join(f"{a:<{wl}}  {b:<{wv}}  {c:<{wr}}  {d}" for (a, b), (c, d) in zip(left, right))

    def __repr__(self) -> str:
        return "FitStatistics(\n  " + "\n  ".join(str(self).splitlines()) + "\n)"

    def _repr_html_(self) -> str:
        from html import escape

        cells = self._cells()
        rows = "".join(f"<tr><th style='text-align:left'>{escape(a)}</th><td style='text-align:right'>{escape(b)}</td>"
                       f"<th style='text-align:left'>{escape(c)}</th><td style='text-align:right'>{escape(d)}</td></tr>"
                       for (a, b), (c, d) in zip(cells[:4], cells[4:]))
        return f"<table class='rsm-lrg-statistics'><caption>Fit statistics</caption>{rows}</table>"


def _nan_div(a, b):
    return a / b if b not in (0, 0.0) and math.isfinite(b) else math.nan


def fit_statistics(*, n, mean, fitted_range, ss_res, df_res, ss_total, ss_block, df_model, n_params,
                   press) -> FitStatistics:
    """Compute :class:`FitStatistics` from the numbers of one fit (see the module docstring).

    ``press`` and the sums of squares come from the regression core
    (:class:`~rsm_lrg.model.least_squares.Regression`); ``fitted_range`` is
    ``max ŷ - min ŷ`` (NaN when not known: no adequate precision).
    """
    ss_adj = ss_total - ss_block
    ms_res = _nan_div(ss_res, df_res)
    r2 = 1.0 - _nan_div(ss_res, ss_adj) if ss_adj > 0 else math.nan
    adj = 1.0 - _nan_div(ms_res, _nan_div(ss_adj, df_model + df_res)) if ss_adj > 0 and df_res > 0 else math.nan
    pred = 1.0 - press / ss_adj if (math.isfinite(press) and ss_adj > 0) else math.nan
    std = math.sqrt(ms_res) if math.isfinite(ms_res) else math.nan
    mean_var = n_params * ms_res / n if math.isfinite(ms_res) else math.nan
    adeq = fitted_range / math.sqrt(mean_var) if (math.isfinite(mean_var) and mean_var > 0) else math.nan
    mean = float(mean)
    cv = 100.0 * std / abs(mean) if mean != 0 and math.isfinite(std) else math.nan
    return FitStatistics(r2=float(r2), adj_r2=float(adj), pred_r2=float(pred), press=float(press),
                         adeq_precision=float(adeq), std_dev=float(std), mean=mean, cv_percent=float(cv))
