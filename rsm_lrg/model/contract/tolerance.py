"""Regression tolerance intervals: where a proportion P of individual runs at a setting lies,
with confidence C.

At a setting ``x`` the fitted mean is ``ŷ`` with variance ``v_mean`` (``se_fit²``), and a new
run scatters around the true mean with variance ``v_new`` estimated on ``ν`` degrees of
freedom. With ``n* = v_new / v_mean`` (the "effective number of runs" behind the mean; for OLS
``n* = MSE / se_fit² = 1 / x'(X'X)⁻¹x``) the tolerance interval is ``ŷ ± K √v_new`` with

* two-sided (Wallis' factor, as R ``tolerance::regtol.int(side = 2)``)::

      K₂ = √( ν · χ²_{1; P}(λ = 1/n*) / χ²_{ν; 1-C} ),

  ``χ²_{1; P}(λ)`` the P quantile of the non-central chi-square with 1 df and non-centrality
  ``λ``, ``χ²_{ν; 1-C}`` the (1 - C) quantile of the central chi-square on ν df: the interval
  holds *at least* P of the runs with confidence about C (Wallis' approximation, exact as
  ``ν → ∞``);

* one-sided (exact, as ``regtol.int(side = 1)``)::

      K₁ = t'_{ν; C}(δ = z_P √n*) / √n*,

  ``t'`` the C quantile of the non-central t with ν df and non-centrality ``δ``, ``z_P`` the
  standard normal P quantile: ``ŷ - K₁ √v_new`` is a lower bound below which at most 1 - P of
  the runs fall, with confidence C (and ``ŷ + K₁ √v_new`` the upper bound).

**Generalised through the fit's covariance and degrees of freedom.** OLS (every kind of
fixed-effects fit: polynomial, categoric at a level, Scheffé mixture, blocks for the average
block): ``v_mean = σ̂² x'(X'X)⁻¹x``, ``v_new = σ̂²`` (the residual mean square), ν = residual df
— exactly ``regtol.int``'s ``MSE``, ``se.fit`` and ``df``. REML (split-plot whole plots or
random blocks, :mod:`rsm_lrg.model.engines.mixed`): ``v_mean = x'Φ_A x`` (Kenward–Roger's adjusted
covariance), ``v_new = σ̂²_group + σ̂²`` (a new run in a new whole plot or block: both variance
components), and ν the Kenward–Roger denominator df of the mean at ``x`` (the df of the
prediction interval as well). The REML interval is therefore wider than the OLS one of the same
data twice over: a larger ``v_new`` (the whole-plot variance) and fewer df (ν_KR is at most
of the order of the number of whole plots, not of runs). That ν is an approximation: the
variance of a new run is not a single mean square, and the KR df of the mean stands in for its
df (the same approximation as the REML prediction interval).

**Transformed response**: computed on the model's scale and the ends back-transformed (swapped
for a decreasing transform), as the CI and PI are (:meth:`FitResult.predict`); a proportion of
runs is invariant under a monotone transform, so the back-transformed interval keeps its
meaning.

Design-Expert prints a tolerance interval beside the CI and PI ("TI"; Stat-Ease's help page
"Interval Estimates" — statease.com/docs/latest/contents/analysis/interval-estimate-calculation —
defines it as containing at least a proportion P of individual outcomes, with defaults P = 99 %
and 1 - α = 95 %). We could not establish from a public source which tolerance factor it uses
for a regression, so agreement with Design-Expert is not claimed; the reference here is R's
``regtol.int``.

References: Wallis, W. A. (1951), "Tolerance intervals for linear regression", *Proc. Second
Berkeley Symp.*, 43–51; Young, D. S. (2010), "tolerance: An R package for estimating tolerance
intervals", *J. Stat. Softw.* 36(5) (``regtol.int``).

For a plain sample of n runs (an intercept-only model: ``n* = n``, ν = n - 1) the factors
are the normal tolerance factors: n = 10, P = 0.90, C = 0.95 gives the one-sided 2.355 and the
two-sided 2.839 of the NIST/SEMATECH e-Handbook (Sec. 7.2.6.3) and Howe's table.

>>> k1 = tolerance_factor([10.0], 9.0, 0.90, 0.95, side=1)
>>> k2 = tolerance_factor([10.0], 9.0, 0.90, 0.95, side=2)
>>> round(float(k1[0]), 3), round(float(k2[0]), 3)
(2.355, 2.839)
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, NamedTuple, Protocol

import numpy as np

from ...errors import ParameterError

__all__ = [
    "TOLERANCE_PAIRS", "TOLERANCE_COLUMNS", "tolerance_factor", "tolerance_bounds", "PredictionVariance",
    "prediction_variance", "add_tolerance_interval", "check_proportion", "new_run_variance", "coefficient_covariance",
]

#: The column pairs :func:`add_tolerance_interval` adds: the two-sided interval and the two
#: one-sided bounds (``ti_one_sided_low``: at least P of the runs lie above it; ``..._high``:
#: at least P below it), each with confidence C.
TOLERANCE_PAIRS: tuple[tuple[str, str], ...] = (("ti_low", "ti_high"), ("ti_one_sided_low", "ti_one_sided_high"))
#: Every column :func:`add_tolerance_interval` adds.
TOLERANCE_COLUMNS: tuple[str, ...] = tuple(c for pair in TOLERANCE_PAIRS for c in pair)


class FittedForTolerance(Protocol):
    """What the tolerance interval needs of a fit (a :class:`~rsm_lrg.model.results.result.FitResult`):
    its prediction contract (:class:`~rsm_lrg.model.contract.prediction.IntervalForm`) and the
    Kenward–Roger mean at points when the form's df depend on the point."""

    @property
    def interval_form(self) -> Any: ...

    def kr_mean(self, points: Any, *, coded: bool = False) -> tuple[np.ndarray, np.ndarray]: ...


def check_proportion(proportion: Any, name: str = "tolerance") -> float:
    """``proportion`` as a float strictly between 0 and 1, else a :class:`ParameterError`
    naming ``name``."""
    try:
        p = float(proportion)
    except (TypeError, ValueError):
        raise ParameterError(name, f"{name} (the proportion of runs) must be a number between 0 and 1, "
                                   f"not {proportion!r}") from None
    if not 0.0 < p < 1.0:
        raise ParameterError(name, f"{name} (the proportion of runs) must lie strictly between 0 and 1, not {p:g}")
    return p


def tolerance_factor(n_star: Any, df: Any, proportion: float, confidence: float, side: int = 2) -> np.ndarray:
    """The tolerance factor K (multiplier of ``√v_new``) per setting [-].

    Parameters
    ----------
    n_star : array_like
        ``v_new / v_mean`` per setting (``MSE / se_fit²`` for OLS) [-], > 0.
    df : float or array_like
        Degrees of freedom of the variance estimate [-], > 0 (NaN or <= 0 gives NaN).
    proportion : float
        P, the proportion of runs to cover, in (0, 1).
    confidence : float
        C, in (0, 1).
    side : {1, 2}
        1: the one-sided factor (non-central t); 2: Wallis' two-sided factor.

    Returns
    -------
    ndarray
        K per setting (NaN where ``df`` or ``n_star`` is not positive and finite).
    """
    from scipy import stats

    if side not in (1, 2):
        raise ParameterError("side", f"side must be 1 or 2, not {side!r}")
    proportion = check_proportion(proportion)
    confidence = check_proportion(confidence, "confidence")
    ns = np.atleast_1d(np.asarray(n_star, dtype=float))
    nu = np.broadcast_to(np.asarray(df, dtype=float), ns.shape)
    ok = np.isfinite(ns) & (ns > 0) & np.isfinite(nu) & (nu > 0)
    k = np.full(ns.shape, np.nan)
    if not ok.any():
        return k
    n_ok, nu_ok = ns[ok], nu[ok]
    with np.errstate(all="ignore"):
        if side == 2:
            k[ok] = np.sqrt(nu_ok * stats.ncx2.ppf(proportion, 1.0, 1.0 / n_ok) / stats.chi2.ppf(1.0 - confidence, nu_ok))
        else:
            root = np.sqrt(n_ok)
            k[ok] = stats.nct.ppf(confidence, nu_ok, stats.norm.ppf(proportion) * root) / root
    return k


def tolerance_bounds(predicted: Any, var_mean: Any, var_new: Any, df: Any, proportion: float, confidence: float,
                     side: int = 2) -> tuple[np.ndarray, np.ndarray]:
    """``(ŷ - K √v_new, ŷ + K √v_new)`` per setting, with K of :func:`tolerance_factor` and
    ``n* = v_new / v_mean`` [response units on the model's scale].

    For ``side=1`` the two arrays are the one-sided lower and upper bounds (each at
    proportion P and confidence C on its own side).
    """
    pred = np.atleast_1d(np.asarray(predicted, dtype=float))
    vm = np.broadcast_to(np.asarray(var_mean, dtype=float), pred.shape)
    vn = np.broadcast_to(np.asarray(var_new, dtype=float), pred.shape)
    with np.errstate(divide="ignore", invalid="ignore"):
        n_star = vn / vm
    k = tolerance_factor(n_star, df, proportion, confidence, side=side)
    half = k * np.sqrt(vn)
    return pred - half, pred + half


class PredictionVariance(NamedTuple):
    """The variances of a prediction per setting [model-scale units², -]."""

    #: Variance of the fitted mean.
    var_mean: np.ndarray
    #: Variance of a new run about the true mean.
    var_new: np.ndarray
    #: Degrees of freedom of the estimate.
    df: np.ndarray


def new_run_variance(fit: FittedForTolerance) -> float:
    """The variance of one new run about the true mean [model-scale units²]: the contract's
    ``s2_new`` — the residual mean square σ̂² (OLS), σ̂²_group + σ̂² (REML: a run in a new whole
    plot or block)."""
    return float(fit.interval_form.s2_new)


def coefficient_covariance(fit: FittedForTolerance) -> np.ndarray:
    """The covariance of the model's coefficients (intercept and terms, in ``coefficients``
    order) that the mean's interval uses [model-scale units²]: the contract's ``cov_mean``,
    ``σ̂² (X'X)⁻¹`` (OLS) or Kenward–Roger's ``Φ_A`` (REML)."""
    return np.asarray(fit.interval_form.cov_mean, dtype=float)


def prediction_variance(fit: FittedForTolerance, points: Any, se_fit: Sequence[float] | np.ndarray, *,
                        coded: bool = False) -> PredictionVariance:
    """The variances of the prediction at ``points`` on the model's scale, from the fit's
    prediction contract (see the module docstring): ``(se_fit², s2_new, df)`` when the
    form's df are one number (OLS: ``se_fit² = x'Cx σ̂²``, ``s2_new = σ̂²``, ν = n - p), else
    ``(x'Φ_A x, σ̂²_group + σ̂², ν_KR(x))`` per point (REML).

    Parameters
    ----------
    fit : FitResult
        The fitted model.
    points : DataFrame, mapping or array
        The settings, as for :meth:`FitResult.predict`.
    se_fit : array_like
        The standard error of the mean at each point (``predict``'s ``se_fit``) [model-scale units].
    coded : bool
        Whether ``points`` are coded.
    """
    form = fit.interval_form
    se = np.asarray(se_fit, dtype=float)
    var_new = np.full(se.shape, float(form.s2_new))
    if form.kenward_roger:  # the df (and the mean's covariance, Φ_A) depend on the point
        var_mean, df = fit.kr_mean(points, coded=coded)
        return PredictionVariance(np.asarray(var_mean, dtype=float), var_new, np.asarray(df, dtype=float))
    return PredictionVariance(se**2, var_new, np.full(se.shape, float(form.df)))


def add_tolerance_interval(fit: FittedForTolerance, out: Any, points: Any, proportion: Any, alpha: float, *,
                           coded: bool = False) -> Any:
    """Add the tolerance columns (:data:`TOLERANCE_COLUMNS`) to ``out``, the model-scale
    prediction frame of :meth:`FitResult.predict_model` (columns ``predicted``, ``se_fit``).

    Parameters
    ----------
    fit : FitResult
        The fitted model.
    out : pandas.DataFrame
        The prediction on the model's scale; changed in place and returned.
    points : DataFrame, mapping or array
        The settings ``out`` was predicted at.
    proportion : float
        P, the proportion of runs the interval covers, in (0, 1).
    alpha : float
        1 - C, C the confidence level.
    coded : bool
        Whether ``points`` are coded.

    Returns
    -------
    pandas.DataFrame
        ``out`` with ``ti_low``, ``ti_high`` (two-sided) and ``ti_one_sided_low``,
        ``ti_one_sided_high`` (one-sided bounds) [model-scale units].
    """
    p = check_proportion(proportion)
    confidence = 1.0 - float(alpha)
    pv = prediction_variance(fit, points, out["se_fit"].to_numpy(), coded=coded)
    pred = out["predicted"].to_numpy(dtype=float)
    for side, (lo, hi) in zip((2, 1), TOLERANCE_PAIRS):
        a, b = tolerance_bounds(pred, pv.var_mean, pv.var_new, pv.df, p, confidence, side=side)
        out[lo], out[hi] = a, b
    return out
