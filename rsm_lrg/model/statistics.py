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

import numpy as np

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


def _nan_div(a, b):
    return a / b if b not in (0, 0.0) and math.isfinite(b) else math.nan


def fit_statistics(*, y, fitted, residuals, hat, ss_res, df_res, ss_total, ss_block, df_model, n_params) -> FitStatistics:
    """Compute :class:`FitStatistics` from the pieces of one fit (see the module docstring)."""
    n = y.size
    ss_adj = ss_total - ss_block
    ms_res = _nan_div(ss_res, df_res)
    r2 = 1.0 - _nan_div(ss_res, ss_adj) if ss_adj > 0 else math.nan
    adj = 1.0 - _nan_div(ms_res, _nan_div(ss_adj, df_model + df_res)) if ss_adj > 0 and df_res > 0 else math.nan
    with np.errstate(divide="ignore", invalid="ignore"):
        one_minus_h = 1.0 - hat
        ok = one_minus_h > 1e-10
        press = float(np.sum((residuals[ok] / one_minus_h[ok]) ** 2)) if ok.all() else math.nan
    pred = 1.0 - press / ss_adj if (math.isfinite(press) and ss_adj > 0) else math.nan
    std = math.sqrt(ms_res) if math.isfinite(ms_res) else math.nan
    mean_var = n_params * ms_res / n if math.isfinite(ms_res) else math.nan
    spread = float(np.max(fitted) - np.min(fitted))
    adeq = spread / math.sqrt(mean_var) if (math.isfinite(mean_var) and mean_var > 0) else math.nan
    mean = float(np.mean(y))
    cv = 100.0 * std / abs(mean) if mean != 0 and math.isfinite(std) else math.nan
    return FitStatistics(r2=float(r2), adj_r2=float(adj), pred_r2=float(pred), press=float(press),
                         adeq_precision=float(adeq), std_dev=float(std), mean=mean, cv_percent=float(cv))
