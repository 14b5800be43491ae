"""The prediction contract: what every fitted model answers, whatever its kind.

A consumer (the optimiser, desirability, confirmation, ridge, the profiler page, the text and
HTML summaries, the report) asks a fitted model the questions of :class:`FittedModel` and
never which kind of model it holds. The uncertainty of a prediction is one
:class:`IntervalForm` per fit: how the standard error, the variance of the mean, the
variance of a new run and their degrees of freedom follow from the model row ``x`` (on the
model's scale). :meth:`IntervalForm.at` is the one routine that computes them; the profiler
page's script computes the same from :meth:`IntervalForm.to_dict`.

Ordinary least squares (with blocks, categoric factors, mixtures, a transform, or from a
Dask frame)::

    se²(x) = x' C x σ²      var_mean(x) = se²(x)      var_new(x) = var_mean(x) + σ²
    df     = n - p (constant)

REML with one random intercept (whole plots or random blocks; Kenward & Roger 1997, as
pbkrtest computes them, :mod:`rsm_lrg.model.engines.mixed`)::

    se²(x) = x' Φ x         var_mean(x) = x' Φ_A x     var_new(x) = var_mean(x) + σ²_g + σ²
    df(x)  = 2 / A₂(x),     A₂(x) = Σ_rs W_rs a_r a_s / c²,  a_r = x' Φ P_r Φ x,  c = x' Φ x

(the one-df Kenward–Roger den df of the contrast ``x b``; a variance component estimated at
zero keeps its ``P_r`` and its row of ``W``). With several random intercepts
(``random_effects=[...]``) ``σ²_g`` is the sum of their variances (a new run in new levels of
every random effect) and ``r`` runs over every component and the residual.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Protocol, runtime_checkable

import numpy as np

if TYPE_CHECKING:
    import pandas as pd

    from ...factors import FactorSpace
    from ..build.transform import Transform

__all__ = ["IntervalForm", "FittedModel", "INTERVALS"]

#: The intervals :meth:`FittedModel.predict` adds.
INTERVALS = (None, "confidence", "prediction", "both")


@dataclass(frozen=True)
class IntervalForm:
    """How a fit's prediction uncertainty follows from the model row ``x`` (model scale).

    Attributes
    ----------
    cov_se : (p, p) ndarray
        Covariance of the coefficients whose quadratic form is ``se_fit²``
        [model-scale units²]: ``C σ²`` (OLS) or ``Φ`` (REML, GLS).
    cov_mean : (p, p) ndarray
        Covariance used for the confidence interval of the mean: ``C σ²`` or Kenward–Roger's
        ``Φ_A`` [model-scale units²].
    s2_residual : float
        Variance of a run about its group's mean, ``σ²`` [model-scale units²].
    s2_group : float
        Variance of a new whole plot's or block's effect, ``σ²_g`` (0 for OLS; REML: may be
        estimated at 0) [model-scale units²]. A new run varies by ``s2_new = σ²_g + σ²``
        beyond the mean.
    df : float
        Degrees of freedom of the t quantile when they do not depend on ``x`` (OLS:
        ``n - p``; NaN without residual df); ignored when ``kr_w`` is given.
    kr_phi_p_phi : tuple of (p, p) ndarray
        ``Φ P_r Φ`` per variance parameter (REML only; empty for OLS).
    kr_w : (r, r) ndarray or None
        Kenward–Roger's ``W`` (the inverse expected information of the variance parameters)
        in units of ``kr_unit²``: ``W`` itself is ``kr_unit² kr_w`` [model-scale units⁴].
    kr_unit : float
        The variance unit ``kr_w`` is given in (a REML fit's response scale squared, so that
        ``W`` stays within the floats for a response in any unit) [model-scale units²].
    """

    cov_se: np.ndarray = field(repr=False)
    cov_mean: np.ndarray = field(repr=False)
    s2_residual: float
    df: float
    s2_group: float = 0.0
    kr_phi_p_phi: tuple = field(default=(), repr=False)
    kr_w: np.ndarray | None = field(default=None, repr=False)
    kr_unit: float = 1.0

    @property
    def s2_new(self) -> float:
        """Variance of one new run beyond the mean's, ``σ²_g + σ²`` [model-scale units²]."""
        return self.s2_group + self.s2_residual

    @property
    def kenward_roger(self) -> bool:
        """Whether the degrees of freedom are Kenward–Roger's, one per point."""
        return self.kr_w is not None

    def at(self, X: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """``(se_fit, var_mean, var_new, df)`` at each row of the model matrix ``X`` (n x p).

        Returns
        -------
        tuple of (n,) ndarray
            Standard error of the mean [model-scale units], the variances of the mean and of
            a new run [units²], and the degrees of freedom of their t quantile [-] (NaN where
            they are undefined: no residual df, or ``x = 0``).
        """
        X = np.atleast_2d(np.asarray(X, dtype=float))
        se2 = np.einsum("ij,jk,ik->i", X, self.cov_se, X)
        var_mean = np.einsum("ij,jk,ik->i", X, self.cov_mean, X)
        if self.kr_w is None:
            df = np.full(X.shape[0], self.df, dtype=float)
        else:
            a = np.stack([np.einsum("ij,jk,ik->i", X, M, X) for M in self.kr_phi_p_phi])  # (r, n)
            A2 = np.einsum("rn,rs,sn->n", a, self.kr_w, a)
            with np.errstate(divide="ignore", invalid="ignore"):
                A2 = A2 / (se2 / self.kr_unit) ** 2
                df = np.where(A2 > 0, 2.0 / A2, math.inf)
            df = np.where(se2 > 0, df, math.nan)
        return np.sqrt(np.maximum(se2, 0.0)), var_mean, var_mean + self.s2_new, df

    def mean_of_new_runs(self, X: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
        """``(variance, df)`` of the mean of ``n`` new runs at each row of ``X``, made in one new
        whole plot or block, about the prediction: ``var_mean + σ²_g + σ²/n`` (the
        confirmation interval of :func:`rsm_lrg.optimize.confirm.confirm`) [units², -]."""
        _, var_mean, _, df = self.at(X)
        return var_mean + self.s2_group + self.s2_residual / int(n), df

    def to_dict(self) -> dict:
        """Plain JSON-safe data for a page's script (``cov_se``, ``cov_mean``, ``s2_new``,
        ``df`` and, for Kenward–Roger, ``kr``: ``{"phi_p_phi": [...], "w": [...], "unit": u}``)."""
        def mat(M: np.ndarray) -> list:
            return [[float(v) for v in row] for row in np.asarray(M, dtype=float)]

        def num(v: float) -> float | None:
            return float(v) if math.isfinite(v) else None

        out: dict[str, Any] = {"cov_se": mat(self.cov_se), "cov_mean": mat(self.cov_mean), "s2_new": num(self.s2_new),
                               "df": num(self.df)}
        if self.kr_w is not None:
            out["kr"] = {"phi_p_phi": [mat(M) for M in self.kr_phi_p_phi], "w": mat(self.kr_w),
                         "unit": float(self.kr_unit)}
        return out


@runtime_checkable
class FittedModel(Protocol):
    """What every fitted model answers, whatever its kind (OLS, transformed, blocked,
    categoric, mixture, REML whole plot or random block, and the kinds to come). Consumers take
    this protocol and never ask which kind they hold.

    Attributes
    ----------
    response : str
        The response column.
    space : FactorSpace
        The factors (numeric, categoric, mixture components) with their coding.
    transform : Transform
        The response transform (identity when none): goals are read on the response's scale.
    terms, model_terms : tuple of Term
        The model's columns (with the intercept) and its terms (without).
    interval_form : IntervalForm
        How the uncertainty of a prediction follows from the model row.
    notes : tuple of str
        What the fit says about itself.
    """

    response: str
    space: FactorSpace
    terms: tuple

    @property
    def transform(self) -> Transform: ...

    @property
    def model_terms(self) -> tuple: ...

    @property
    def interval_form(self) -> IntervalForm: ...

    @property
    def notes(self) -> tuple: ...

    @property
    def label(self) -> str: ...

    def predict(self, points: Any, interval: str | None = None, alpha: float = 0.05, *,
                coded: bool = False) -> pd.DataFrame:
        """Prediction on the response's scale with ``se_fit`` and the asked intervals."""
        ...

    def predict_coded(self, coded: np.ndarray) -> np.ndarray:
        """The prediction on the model's scale at coded settings (n x k)."""
        ...

    def predictive(self, coded: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(mean, variance, df)`` of a new run at coded settings, on the model's scale: the
        posterior predictive Student t (df infinite: normal)."""
        ...

    def goal_on_model_scale(self, goal: Any) -> tuple[str, float | None, str, float | None]:
        """A goal on the response's scale, mapped onto the model's."""
        ...

    def to_dict(self) -> dict:
        """The fit's JSON."""
        ...

    def summary(self) -> str:
        """The fit's text."""
        ...

