"""Fit summary: which polynomial order do the data support? (Design-Expert "Fit Summary").

For the nested models mean ⊂ linear ⊂ 2FI ⊂ quadratic ⊂ cubic this gives

* the **sequential model sums of squares** (Type I): the extra sum of squares of each
  order given the lower ones, ``SS(order | lower) = SS_res(lower) - SS_res(order)``, on
  ``df = rank(X_order) - rank(X_lower)`` degrees of freedom, with
  ``F = MS(order | lower) / MS_res(order)`` (Design-Expert's convention: the residual of the
  model that includes the order). An order is **aliased** when some of its terms cannot be
  estimated from the design (its rank increase is smaller than its number of terms), e.g.
  the cubic terms of a Box–Behnken or central composite design;
* the **lack-of-fit test** of each order, ``F = MS_lof / MS_pe`` with pure error the
  residual of (blocks +) one mean per distinct setting (the same split as the ANOVA of
  :func:`rsm_lrg.fit`, and R ``rsm``'s ``PE()`` test);
* **model summary statistics** per order: std dev, R², adjusted R², predicted R², PRESS
  (as :class:`~rsm_lrg.model.contract.statistics.FitStatistics` defines them);
* the **suggested model**: the highest order that is significant (sequential p < alpha),
  not aliased, and whose lack of fit is not significant (p >= alpha).

Blocks (optional) enter right after the mean, as in :func:`rsm_lrg.fit`; every order is
then adjusted for blocks. The nested models are not refitted: the largest model (columns
in order: mean, blocks, linear, 2FI, quadratic, cubic terms) is factorised once by the
regression core (:mod:`rsm_lrg.model.engines.least_squares`); its aliased columns are dropped from
the factor, the sequential SS of an order is ``sum z_j^2`` over its estimable columns
(``z = Q'y``), and one more pass over the rows gives every order's residuals and PRESS —
the comparison of fitted nested models that statsmodels' ``anova_lm`` makes. The factor
coding and validation are those of :func:`rsm_lrg.fit` (:func:`~rsm_lrg.model.fit.model_inputs`),
pure error and lack of fit those of :mod:`rsm_lrg.model.readings.anova`, the statistics those of
:func:`~rsm_lrg.model.contract.statistics.fit_statistics`.

With mixture components (``components=``) the nested models are the Scheffé ones, mean ⊂
mixture-linear ⊂ mixture-quadratic ⊂ special-cubic ⊂ mixture-cubic, without an intercept
column on L-pseudo-components (as :func:`rsm_lrg.fit` fits them, process factors crossed
with every mixture term), each model's new terms after the previous model's in one
factorisation; "Linear vs Mean" is the linear model's sum of squares about the mean,
``SS_total(corrected) - SS_res(linear)`` on q - 1 df (Design-Expert's mixture fit summary),
and only the models with no more terms than distinct blends are fitted.

Reference: Myers, Montgomery & Anderson-Cook, *Response Surface Methodology* (3rd ed.),
Sec. 3.3 (extra sum of squares) and 6.2; Design-Expert help, "Fit Summary".

>>> import rsm_lrg
>>> s = fit_summary(rsm_lrg.load_table4(), "tcr_c_per_min")
>>> s.suggested
'quadratic'
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...errors import ParameterError

__all__ = ["fit_summary", "FitSummary", "ORDERS"]

#: The nested model orders of the fit summary.
ORDERS = ("linear", "2fi", "quadratic", "cubic")

_LABEL = {"mean": "Mean", "block": "Block", "linear": "Linear", "2fi": "2FI", "quadratic": "Quadratic",
          "cubic": "Cubic", "mixture-linear": "Linear", "mixture-quadratic": "Quadratic",
          "special-cubic": "Special Cubic", "mixture-cubic": "Cubic"}


@dataclass(frozen=True)
class FitSummary:
    """The fit summary (frozen).

    Attributes
    ----------
    response : str
    n : int
        Runs.
    block : str or None
    sequential : pandas.DataFrame
        Sequential model sums of squares: columns ``source, sum_sq, df, mean_sq, f, p,
        aliased``; rows Mean, (Block), Linear, 2FI, Quadratic, Cubic (each "vs" the one
        before), Residual (of the largest estimable model), Total (uncorrected).
    lack_of_fit : pandas.DataFrame
        Columns ``source, sum_sq, df, mean_sq, f, p``; one row per order plus Pure Error
        (empty when no setting is replicated).
    statistics : pandas.DataFrame
        Columns ``source, std_dev, r2, adj_r2, pred_r2, press, aliased``; one row per order.
    suggested : str or None
        ``"linear"``, ``"2fi"``, ``"quadratic"``, ``"cubic"`` or ``"mean"`` (no order is
        significant); for a mixture the Scheffé model (``"mixture-linear"``,
        ``"mixture-quadratic"``, ``"special-cubic"``, ``"mixture-cubic"``, as ``fit``'s
        ``model``) or ``"mean"``.
    alpha : float
        Significance level used for the suggestion.
    notes : tuple of str
    """

    response: str
    n: int
    block: str | None
    sequential: Any = field(repr=False)
    lack_of_fit: Any = field(repr=False)
    statistics: Any = field(repr=False)
    suggested: str | None = None
    alpha: float = 0.05
    notes: tuple = ()

    def to_dict(self) -> dict:
        """Plain JSON-safe dict: ``{"response", "n", "block", "sequential", "lack_of_fit",
        "statistics", "suggested", "alpha", "notes"}`` (NaN becomes ``None``)."""
        def rows(df):
            return [{k: _clean(v) for k, v in r.items()} for r in df.to_dict(orient="records")]

        return {"response": self.response, "n": self.n, "block": self.block,
                "sequential": rows(self.sequential), "lack_of_fit": rows(self.lack_of_fit),
                "statistics": rows(self.statistics), "suggested": self.suggested,
                "alpha": self.alpha, "notes": list(self.notes)}

    def to_frame(self):
        """The three tables side by side, one row per order (sequential, lack of fit, statistics)."""
        import pandas as pd

        seq = self.sequential.set_index("source")
        lof = self.lack_of_fit.set_index("source") if len(self.lack_of_fit) else None
        st = self.statistics.set_index("source")
        out = []
        for name in st.index:
            key = next((s for s in seq.index if s.startswith(name)), None)
            row = {"model": name}
            if key is not None:
                row.update(seq_p=seq.loc[key, "p"], seq_df=seq.loc[key, "df"])
            if lof is not None and name in lof.index:
                row.update(lof_p=lof.loc[name, "p"])
            row.update(st.loc[name].to_dict())
            row["suggested"] = name == _LABEL.get(self.suggested or "", "")
            out.append(row)
        return pd.DataFrame(out)

    def summary(self) -> str:
        """Design-Expert style text: the three tables and the suggestion."""
        from ...present import format_g, format_p, text_table

        out = [f"Fit summary for {self.response} ({self.n} runs)", "", "Sequential model sum of squares [Type I]"]
        rows = [[r.source, format_g(r.sum_sq), r.df, format_g(r.mean_sq), format_g(r.f), format_p(r.p, style="ascii"),
                 "Aliased" if r.aliased else ""] for r in self.sequential.itertuples(index=False)]
        out.append(text_table(["Source", "Sum of Squares", "df", "Mean Square", "F-value", "p-value", ""], rows,
                          ["<", ">", ">", ">", ">", ">", "<"]))
        if len(self.lack_of_fit):
            out += ["", "Lack of fit tests"]
            rows = [[r.source, format_g(r.sum_sq), r.df, format_g(r.mean_sq), format_g(r.f), format_p(r.p, style="ascii")]
                    for r in self.lack_of_fit.itertuples(index=False)]
            out.append(text_table(["Source", "Sum of Squares", "df", "Mean Square", "F-value", "p-value"], rows))
        out += ["", "Model summary statistics"]
        rows = [[r.source, format_g(r.std_dev), format_g(r.r2), format_g(r.adj_r2), format_g(r.pred_r2),
                 format_g(r.press), "Aliased" if r.aliased else ("Suggested" if r.source == _LABEL.get(self.suggested or "") else "")]
                for r in self.statistics.itertuples(index=False)]
        out.append(text_table(["Source", "Std. Dev.", "R²", "Adjusted R²", "Predicted R²", "PRESS", ""], rows))
        label = None if self.suggested is None else _LABEL.get(self.suggested, self.suggested)
        out += ["", f"Suggested model: {label}"]
        out += [f"Note: {n}" for n in self.notes]
        return "\n".join(out) + "\n"

    def __str__(self) -> str:
        return self.summary()


def _clean(v):
    if isinstance(v, (bool, np.bool_)):
        return bool(v)
    if isinstance(v, (int, np.integer)):
        return int(v)
    if isinstance(v, (float, np.floating)):
        return float(v) if math.isfinite(v) else None
    return v


def fit_summary(data, response: str, factors=None, block: str | None = None, *, alpha: float = 0.05,
                orders=None, transform=None, transform_constant: float = 0.0, components=None) -> FitSummary:
    """Sequential sums of squares, lack of fit and statistics per model order.

    Parameters
    ----------
    data : pandas.DataFrame
    response : str
        Response column [response units].
    factors, block
        As for :func:`rsm_lrg.fit`.
    alpha : float
        Level for "significant" (sequential F) and "not significant" (lack of fit).
    orders : sequence of str, optional
        Model orders to compare, a prefix-closed subset of ``ORDERS`` (default all four); with
        ``components``, of the Scheffé models ``MIXTURE_ORDERS`` (default all four).
    transform, transform_constant
        As for :func:`rsm_lrg.fit`.
    components : sequence of str, optional
        Mixture components (names or ``"NAME=LOW:HIGH"``, as for :func:`rsm_lrg.fit`;
        ``factors`` are then process factors). The models compared are the Scheffé
        mixture-linear, mixture-quadratic, special-cubic and mixture-cubic (no intercept,
        L-pseudo-components, each crossed with the process factors' main effects), those
        with no more terms than distinct blends; "Linear vs Mean" is the linear model's sum
        of squares about the mean on q - 1 df (Design-Expert's mixture fit summary; Cornell,
        *Experiments with Mixtures*, 3rd ed., Sec. 2.8). No blocks.

    Returns
    -------
    FitSummary
    """
    import pandas as pd

    from ..build.inputs import model_inputs
    from ..build.terms import MAX_TERMS, MIXTURE_ORDERS, check_model_size, model_terms, n_columns, n_model_terms
    from ..build.transform import parse_transform
    from ..contract.statistics import fit_statistics
    from ..engines.least_squares import factorise
    from ..readings.anova import f_test, lack_of_fit, pure_error

    if not 0.0 < alpha < 1.0:
        raise ParameterError("alpha", f"alpha must lie between 0 and 1, not {alpha!r}")
    mixture = components is not None
    known = tuple(MIXTURE_ORDERS) if mixture else ORDERS
    orders = known if orders is None else tuple(orders)
    bad = [o for o in orders if o not in known]
    if bad or not orders:
        raise ValueError(f"orders must be among {', '.join(known)} (got {', '.join(map(str, orders)) or 'none'})")
    orders = tuple(o for o in known if o in orders)
    tr = parse_transform(transform, transform_constant)
    notes: list[str] = []
    fitted: list[str] = []
    if mixture:
        inp, terms, fitted, ends_all = _mixture_models(data, response, components, factors, block, orders, tr, notes)
        nb = 1
        chunks = inp.chunks(terms)
        big = factorise(chunks, len(terms), inp.column_names(terms), shift=0.0)
        n_lin = ends_all[fitted[0]]
        big.submodel(range(n_lin)).require_full_rank("mixture-linear model")
        first_end = 1  # the mean, implicit in the linear blending terms
    else:
        inp = model_inputs(data, response, factors, block, transform=tr)
        nb, letters, cats = inp.nb, inp.space.letters, inp.space.categoric
        check_model_size(inp.n, len(letters), "linear", nb - 1, categoric=cats)
        for order in orders:
            count = n_model_terms(len(letters), order, cats)
            if count > MAX_TERMS:  # counted, not built
                notes.append(f"The {_LABEL[order]} model in {len(letters)} factors has {count} terms and was not "
                             f"fitted (more than the {MAX_TERMS} this toolkit builds).")
                break
            fitted.append(order)
        # one factorisation of the largest model; its estimable columns, in order
        terms = model_terms(letters, fitted[-1], cats)
        chunks = inp.chunks(terms)
        big = factorise(chunks, n_columns(terms) + nb - 1, inp.column_names(terms))
        big.submodel(range(nb - 1 + n_model_terms(len(letters), "linear", cats))).require_full_rank("linear model")
        ends_all = {o: nb - 1 + n_model_terms(len(letters), o, cats) for o in fitted}  # columns up to each order
        first_end = nb
    y, n = inp.y, inp.n
    kept = np.asarray(big.kept)
    ls = big if big.full_rank else big.submodel(kept)
    ends = {o: int(np.sum(kept < ends_all[o])) for o in fitted}  # estimable ones
    sub_chunks = chunks if big.full_rank else (lambda: ((X[:, kept], yy) for X, yy in chunks()))
    nested = dict(zip(fitted, ls.nested_press(sub_chunks, [ends[o] for o in fitted])))

    # pure error: residual of (blocks +) one mean per distinct setting, as in fit()
    pe = pure_error(inp.settings, y - ls.shift, inp.bcodes if nb > 1 else None)
    ybar = ls.ybar
    ss_mean = float(n * ybar ** 2)
    ss_tot_corr = float(np.sum((y - ybar) ** 2))
    ss_block = ls.sequential_ss(np.arange(1, nb)) if nb > 1 else 0.0
    seq_rows = [{"source": "Mean vs Total", "sum_sq": ss_mean, "df": 1, "mean_sq": ss_mean, "f": math.nan,
                 "p": math.nan, "aliased": False}]
    if nb > 1:
        seq_rows.append({"source": "Block vs Mean", "sum_sq": ss_block, "df": nb - 1,
                         "mean_sq": ss_block / (nb - 1), "f": math.nan, "p": math.nan, "aliased": False})
    lof_rows, stat_rows = [], []
    prev_label, prev_end = ("Block" if nb > 1 else "Mean"), first_end
    results = {}
    for order in fitted:
        end = ends[order]
        ss_res, press = nested[order]
        df_add = end - prev_end
        aliased = end < ends_all[order]
        df_res = n - end
        ms_res = ss_res / df_res if df_res > 0 else math.nan
        if mixture and prev_end == first_end:  # Linear vs Mean: the linear model's SS about the mean
            ss_add = max(ss_tot_corr - ss_res, 0.0)
        else:
            ss_add = ls.sequential_ss(np.arange(prev_end, end)) if df_add > 0 else 0.0
        ms_add = ss_add / df_add if df_add > 0 else math.nan
        f, p = f_test(ms_add, df_add, ms_res, df_res)
        seq_rows.append({"source": f"{_LABEL[order]} vs {prev_label}", "sum_sq": ss_add, "df": int(df_add),
                         "mean_sq": ms_add, "f": f, "p": p, "aliased": bool(aliased)})
        lof = lack_of_fit(ss_res, df_res, pe)
        lof_p = math.nan
        if lof is not None:
            lof_p = lof["p"]
            lof_rows.append({"source": _LABEL[order], "sum_sq": lof["ss"], "df": lof["df"], "mean_sq": lof["ms"],
                             "f": lof["f"], "p": lof_p})
        st = fit_statistics(n=n, mean=ybar, fitted_range=math.nan, ss_res=ss_res, df_res=df_res,
                            ss_total=ss_tot_corr, ss_block=ss_block, df_model=end - nb, n_params=end, press=press)
        stat_rows.append({"source": _LABEL[order], "std_dev": st.std_dev, "r2": st.r2, "adj_r2": st.adj_r2,
                          "pred_r2": st.pred_r2, "press": st.press, "aliased": bool(aliased)})
        results[order] = (p, aliased, lof_p, df_add)
        prev_label, prev_end = _LABEL[order], end
        last_ok = (ss_res, df_res)
    ss_res, df_res = last_ok
    seq_rows.append({"source": "Residual", "sum_sq": ss_res, "df": int(df_res),
                     "mean_sq": ss_res / df_res if df_res > 0 else math.nan, "f": math.nan, "p": math.nan,
                     "aliased": False})
    seq_rows.append({"source": "Total", "sum_sq": float(y @ y), "df": int(n), "mean_sq": float(y @ y) / n,
                     "f": math.nan, "p": math.nan, "aliased": False})
    if pe.df > 0:
        lof_rows.append({"source": "Pure Error", "sum_sq": pe.ss, "df": int(pe.df), "mean_sq": pe.ss / pe.df,
                         "f": math.nan, "p": math.nan})
    else:
        notes.append("No lack-of-fit tests: no factor setting is replicated, so there is no pure error.")

    suggested = "mean"
    for order in results:  # the orders fitted (one beyond MAX_TERMS terms is counted, not fitted)
        p, aliased, lof_p, df_add = results[order]
        if aliased or df_add == 0:
            continue
        if p == p and p < alpha and not (lof_p == lof_p and lof_p < alpha):
            suggested = order
    if suggested == "mean":
        notes.append("No model order is significant with a non-significant lack of fit; "
                     "consider the highest significant order or a transformation.")
    cols_seq = ["source", "sum_sq", "df", "mean_sq", "f", "p", "aliased"]
    cols_lof = ["source", "sum_sq", "df", "mean_sq", "f", "p"]
    return FitSummary(
        response=response, n=int(n), block=block,
        sequential=pd.DataFrame(seq_rows, columns=cols_seq),
        lack_of_fit=pd.DataFrame(lof_rows, columns=cols_lof),
        statistics=pd.DataFrame(stat_rows, columns=["source", "std_dev", "r2", "adj_r2", "pred_r2", "press", "aliased"]),
        suggested=suggested, alpha=float(alpha), notes=tuple(notes),
    )


def _mixture_models(data: Any, response: str, components: Any, factors: Any, block: str | None,
                    orders: tuple, transform: Any, notes: list[str]) -> tuple[Any, list, list[str], dict[str, int]]:
    """The inputs of a mixture fit summary (as :func:`rsm_lrg.fit` reads them), the Scheffé
    terms of the largest estimable model in nesting order (each model's new terms after the
    previous model's), the models fitted, and the number of columns up to each.

    A model that adds no term (special cubic of two components) is left out; the models
    with more terms than distinct blends (settings, with process factors) are not fitted
    (a note says so)."""
    from ...factors import MixtureComponent
    from ..build.inputs import chosen_terms, mixture_inputs
    from ..build.mixture import scheffe_names

    if block is not None:
        from ...errors import ParameterError

        raise ParameterError("block", "the fit summary of a blocked mixture is not available yet (fit the blocked "
                                      "model itself: fit --component ... --block COL)")
    inp = mixture_inputs(data, response, components, factors, block, transform=transform)
    space = inp.space
    q = sum(isinstance(f, MixtureComponent) for f in space.factors)
    letters = space.letters
    blends = int(np.unique(np.asarray(inp.settings, dtype=float), axis=0).shape[0])
    kind = "blends" if q == len(space) else "settings"
    names: list[str] = []
    fitted: list[str] = []
    ends_all: dict[str, int] = {}
    for order in orders:
        new = [t for t in scheffe_names(letters[:q], order, letters[q:]) if t not in names]
        if not new:
            continue
        if len(names) + len(new) > blends:
            if fitted:
                notes.append(f"The {_LABEL[order]} model has {len(names) + len(new)} terms and was not fitted "
                             f"({blends} distinct {kind}).")
                break
            raise ValueError(f"{blends} distinct {kind} cannot fit {len(names) + len(new)} terms (the {order} model "
                             f"in {q} components)")
        names += new
        fitted.append(order)
        ends_all[order] = len(names)
    if fitted[0] != "mixture-linear":
        raise ValueError("a mixture fit summary starts from the mixture-linear model (orders must include it)")
    by_name = {t.name: t for t in chosen_terms(names, letters, None, intercept=False)}  # sorted by degree there
    return inp, [by_name[nm] for nm in names], fitted, ends_all  # nesting order: each model's terms first
