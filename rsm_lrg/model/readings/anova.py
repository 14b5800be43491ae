"""The analysis of variance as Design-Expert prints it (the paper's Table 5).

Every sum of squares comes from the regression core
(:mod:`rsm_lrg.model.engines.least_squares`): the partial (Type III) sum of squares of a term with
columns ``S`` is the extra sum of squares for dropping it,

    SS_S = b_S' (C_SS)^-1 b_S          (a 1-df term: b_j^2 / C_jj),

so no term needs a refit. Blocks enter first (sequential SS) and are kept out of the model
row. Pure error is the residual of the largest model the design can fit — one mean per
distinct factor setting, plus the block effects when blocked — and lack of fit is the rest
of the residual (:func:`pure_error`; R ``rsm``'s ``PE()`` lack-of-fit test, Myers,
Montgomery & Anderson-Cook, *Response Surface Methodology*, 3rd ed., Sec. 2.7 and 7.4).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ...present import clean_anova_records
from ..build.terms import block_contrasts
from ..engines.least_squares import least_squares, partial_ss

__all__ = ["partial_ss", "pure_error", "PureError", "anova_table", "anova_rows", "lack_of_fit", "f_test", "ANOVA_COLUMNS",
           "TOTAL_UNCORRECTED", "TOTAL_ROWS"]

#: Columns of :attr:`FitResult.anova`.
ANOVA_COLUMNS = ["source", "sum_sq", "df", "mean_sq", "f", "p"]


@dataclass(frozen=True)
class PureError:
    """Replicate groups and the pure-error sum of squares.

    Attributes
    ----------
    groups : ndarray of int
        Group number of each run (runs with the same factor settings share one, whatever
        their block).
    n_groups : int
        Number of distinct factor settings.
    ss : float
        Pure-error sum of squares [response units^2].
    df : int
        ``n - n_groups - block_df``.
    block_df : int
        Degrees of freedom of the block effects that remain estimable once every setting
        has its own mean (0 without blocks, or when no setting spans two blocks).
    """

    groups: np.ndarray
    n_groups: int
    ss: float
    df: int
    block_df: int = 0


def _group_means(groups: np.ndarray, values: np.ndarray, n_groups: int) -> np.ndarray:
    """Per-run mean of ``values`` (n,) or (n, m) over its group."""
    counts = np.bincount(groups, minlength=n_groups)
    if values.ndim == 1:
        return (np.bincount(groups, weights=values, minlength=n_groups) / counts)[groups]
    cols = [np.bincount(groups, weights=values[:, j], minlength=n_groups) / counts for j in range(values.shape[1])]
    return np.column_stack(cols)[groups] if cols else values.copy()


def _factorize(values: np.ndarray) -> tuple[np.ndarray, int]:
    """Codes 0..u-1 of the distinct values in order of first appearance, and u (as
    ``pandas.factorize`` numbers them; 0.0 and -0.0 are one value). The values are finite."""
    uniq, first, inverse = np.unique(values, return_index=True, return_inverse=True)
    rank = np.empty(uniq.size, dtype=np.int64)
    rank[np.argsort(first, kind="stable")] = np.arange(uniq.size)
    return rank[inverse.ravel()], int(uniq.size)


def pure_error(keys: np.ndarray, y: np.ndarray, blocks: np.ndarray | None = None) -> PureError:
    """Pure error: the residual of the model with one mean per distinct factor setting
    (plus the block effects, when blocked).

    Without blocks this is the within-group sum of squares ``Σ (y - ȳ_group)²`` on
    ``n - g`` degrees of freedom (g distinct settings). With blocks it is the residual of
    ``y ~ block + setting`` (R ``rsm``: ``y ~ Block + PE(x1, ...)``): a setting run once in
    each of two blocks then contributes pure error once the block effects are removed. It
    is computed without the n x (g + b) indicator matrix: the setting means are absorbed by
    centring ``y`` and the block contrasts within each setting (Frisch–Waugh–Lovell), and the
    pure error is the residual of the centred ``y`` on the centred contrasts, with
    ``df = n - g - rank(centred contrasts)``.

    Parameters
    ----------
    keys : (n, m) array
        The coded factor settings, one row per run. Coded values are rounded by
        :class:`FactorSpace`, so equal settings compare equal.
    y : (n,) array
        Response (centre it first when it sits on a large offset: the result is the same
        and more accurate).
    blocks : (n,) array of int, optional
        Block code of each run (0..b-1).

    Returns
    -------
    PureError
        The pure-error SS [response units²] and its df.
    """
    keys = np.asarray(keys, dtype=float)
    y = np.asarray(y, dtype=float)
    if keys.ndim == 1:
        keys = keys[:, None]
    # group number of each distinct row, in order of first appearance: factorise column by
    # column, folding the codes so far with the next column's (the key stays below n)
    groups = np.zeros(keys.shape[0], dtype=np.int64)
    for j in range(keys.shape[1]):
        codes, n_unique = _factorize(keys[:, j])
        groups = _factorize(groups * n_unique + codes)[0]
    n_groups = int(groups.max()) + 1 if groups.size else 0
    yt = y - _group_means(groups, y, n_groups)
    block_df = 0
    if blocks is not None:
        codes = np.unique(np.asarray(blocks), return_inverse=True)[1].ravel()
        nb = int(codes.max()) + 1 if codes.size else 0
        if nb > 1:
            B = block_contrasts(codes, nb)
            Bt = B - _group_means(groups, B, n_groups)
            if np.any(Bt != 0.0):  # the regression core on the centred contrasts (some may be aliased)
                ls = least_squares(Bt, yt)
                block_df = ls.rank
                return PureError(groups=groups, n_groups=n_groups, ss=ls.submodel(ls.kept).ss_res,
                                 df=int(y.size - n_groups - block_df), block_df=block_df)
    ss = float(np.sum(yt ** 2))
    return PureError(groups=groups, n_groups=n_groups, ss=ss, df=int(y.size - n_groups - block_df), block_df=block_df)


def f_test(ms: float, df: int, ms_den: float, df_den: int) -> tuple[float, float]:
    """``F = ms / ms_den`` and its upper tail ``P(F(df, df_den) > F)`` (``scipy.special.fdtrc``);
    NaN where a mean square or the degrees of freedom are missing."""
    from ..contract.statistics import fdtrc  # the t and F tails without importing SciPy

    if df > 0 and df_den > 0 and ms_den > 0 and ms == ms:
        f = ms / ms_den
        return float(f), float(fdtrc(df, df_den, f))
    return np.nan, np.nan


def lack_of_fit(ss_res: float, df_res: int, pe: PureError | None) -> dict | None:
    """The lack-of-fit split of a residual: ``{"ss", "df", "ms", "f", "p"}`` with
    ``SS_lof = SS_res - SS_pe`` on ``df_res - df_pe`` degrees of freedom and
    ``F = MS_lof / MS_pe`` (``None`` without pure error; ms, F and p NaN without lack-of-fit df)."""
    if pe is None or pe.df <= 0:
        return None
    df = int(df_res - pe.df)
    ss = max(ss_res - pe.ss, 0.0)
    ms = ss / df if df > 0 else np.nan
    f, p = f_test(ms, df, pe.ss / pe.df, pe.df) if df > 0 else (np.nan, np.nan)
    return {"ss": ss, "df": df, "ms": ms, "f": f, "p": p}


def _row(source, ss, df, ms=np.nan, f=np.nan, p=np.nan):
    return {"source": source, "sum_sq": float(ss), "df": int(df), "mean_sq": float(ms), "f": float(f), "p": float(p)}


#: The total row of a model without an intercept (sum of y², n df; R's ``lm`` convention).
TOTAL_UNCORRECTED = "Uncor Total"
#: The names the total row has: corrected about the mean, or uncorrected (no intercept).
TOTAL_ROWS = ("Cor Total", TOTAL_UNCORRECTED)


def anova_table(rows: list[dict]) -> Any:
    """The Design-Expert ANOVA as a DataFrame with :data:`ANOVA_COLUMNS`.

    Parameters
    ----------
    rows : list of dict
        The rows of :func:`anova_rows`.

    Returns
    -------
    pandas.DataFrame
        One row per source.
    """
    import pandas as pd

    return pd.DataFrame(rows, columns=ANOVA_COLUMNS)


def anova_rows(*, term_names, term_ss, ss_model, df_model, ss_block, df_block, ss_res, df_res,
               ss_total, df_total, pe: PureError | None, term_df=None, total_label: str = "Cor Total",
               clean: bool = False) -> list[dict]:
    """Assemble the Design-Expert ANOVA rows: ``{source, sum_sq, df, mean_sq, f, p}`` each
    (:data:`ANOVA_COLUMNS`, Python numbers; :func:`anova_table` makes them a DataFrame).

    F of a term or of the model is its mean square over the residual mean square; F of
    lack of fit is MS(lack of fit) / MS(pure error). Numbers that do not apply are NaN
    (``null`` in JSON).

    Returns
    -------
    list of dict
        Model, the terms, Block, Residual, Lack of Fit, Pure Error, the total, as apply.
    """
    ms_res = ss_res / df_res if df_res > 0 else np.nan

    def test(ss, df):
        ms = ss / df if df > 0 else np.nan
        return (ms, *f_test(ms, df, ms_res, df_res))

    rows = [_row("Model", ss_model, df_model, *test(ss_model, df_model))]
    for name, ss, df in zip(term_names, term_ss, term_df if term_df is not None else [1] * len(term_names)):
        rows.append(_row(name, ss, df, *test(ss, df)))
    if df_block:
        rows.append(_row("Block", ss_block, df_block, ss_block / df_block))
    rows.append(_row("Residual", ss_res, df_res, ms_res))
    lof = lack_of_fit(ss_res, df_res, pe)
    if lof is not None and pe is not None:  # lack_of_fit gives None without pure error
        if lof["df"] > 0:
            rows.append(_row("Lack of Fit", lof["ss"], lof["df"], lof["ms"], lof["f"], lof["p"]))
        rows.append(_row("Pure Error", pe.ss, pe.df, pe.ss / pe.df))
    rows.append(_row(total_label, ss_total, df_total))
    if clean:  # round-off rows as shown (rsm_lrg.present.clean_anova), before any frame is built
        clean_anova_records(rows)
    return rows
