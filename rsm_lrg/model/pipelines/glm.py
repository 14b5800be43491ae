"""Generalised linear models: pass/fail and count responses (:func:`fit_glm`).

``rsm_lrg.fit(data, y, ..., family="binomial"|"poisson", link=...)`` comes here. The
model's terms, the factor coding and the model matrix are those of every other fit
(:mod:`rsm_lrg.model.build.inputs`, :mod:`rsm_lrg.model.build.terms`: coded units, effect-coded
categoric factors); only the estimator differs. The steps, as lme4's ``lFormula ->
mkLmerDevfun -> optimizeLmer -> mkMerMod``:

1. *specify and check* (:func:`glm_inputs`): the response is 0/1, or a count of successes
   with a column of trials (binomial), or a count (poisson), checked on every row (a bad
   cell names its row); the terms are checked for aliasing by the regression core; the data
   are checked for separation (:func:`check_separation`) **before** any estimation: when a
   combination of the terms splits the successes from the failures (or the zero counts from
   the rest) the maximum-likelihood coefficients are infinite, and the fit is refused with a
   :class:`SeparationError` naming the rows, rather than reported with huge coefficients and
   meaningless standard errors as R's ``glm`` does after a warning;
2. *estimate* (:func:`irls`): iteratively reweighted least squares (Fisher scoring; Newton's
   method for the canonical links logit and log), each step a Householder QR of the
   weighted model matrix, iterated until the coefficients stop changing (relative step below
   1e-12, then one step more), i.e. to the maximum-likelihood estimate itself rather than to
   R's default deviance tolerance of 1e-8;
3. *the analysis of deviance* (:func:`deviance_tables`): each term dropped from the full model
   and refitted (likelihood-ratio chi-square, R's ``drop1(fit, test = "LRT")`` over every
   term, Design-Expert's table for these models), and the sequential table (terms added in
   order, R's ``anova(fit, test = "LRT")``);
4. *assemble* one :class:`~rsm_lrg.model.results.glm_result.GLMResult`.

The dispersion is 1 (binomial, poisson): standard errors are the Wald ones from the
expected (Fisher) information at the estimate, as R's ``summary.glm`` gives them.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ...errors import ParameterError
from ...factors import quote_value
from ..build.inputs import ModelInputs, chosen_terms, model_inputs
from ..build.spec import ModelSpec, SpecError
from ..build.terms import Term, check_model_size, model_terms, term_columns
from ..engines.glm_family import Family, family
from ..results.glm_result import DevianceRow, GLMResult

__all__ = ["fit_glm", "glm_inputs", "irls", "IRLSFit", "check_separation", "SeparationError", "deviance_tables",
           "MAX_ITERATIONS", "GLMScorer", "select_glm_terms"]

#: IRLS iterations before a fit is declared not converged.
MAX_ITERATIONS = 100
#: Relative coefficient step below which IRLS has converged (one more step is then taken).
STEP_TOLERANCE = 1e-12


class SeparationError(ValueError):
    """The data are separated: the maximum-likelihood coefficients are infinite.

    Attributes
    ----------
    rows : tuple of int
        1-based data rows that the separating combination of terms fits exactly.
    complete : bool
        Complete separation (every row fitted exactly) or quasi-complete (some rows).
    """

    def __init__(self, message: str, rows: Sequence[int], complete: bool) -> None:
        super().__init__(message)
        self.rows = tuple(rows)
        self.complete = complete


@dataclass(frozen=True)
class GLMInputs:
    """The checked inputs of a GLM: the fit's inputs (response as a proportion of ``trials``
    for the binomial family) and the trials per run (ones for a 0/1 response or a count)."""

    inputs: ModelInputs
    trials: np.ndarray
    trials_column: str | None
    rows: np.ndarray


@dataclass(frozen=True)
class IRLSFit:
    """The maximum-likelihood fit of one model matrix (:func:`irls`).

    Attributes
    ----------
    params : ndarray
        Coefficients (link scale, coded units).
    cov : ndarray
        Their covariance: the inverse expected information ``(X' W X)^-1`` (dispersion 1).
    mu, eta : ndarray
        Fitted means (response scale; per trial for the binomial) and linear predictors.
    deviance : float
        Residual deviance.
    iterations : int
        IRLS iterations taken.
    """

    params: np.ndarray
    cov: np.ndarray
    mu: np.ndarray
    eta: np.ndarray
    deviance: float
    iterations: int


def _names(factors: Any) -> list[str]:
    """Column names of a ``factors`` argument given as names or ``NAME=...`` strings."""
    if factors is None or isinstance(factors, (str, bytes)) or not hasattr(factors, "__iter__"):
        return [str(factors).split("=", 1)[0].strip()] if isinstance(factors, str) else []
    if isinstance(factors, dict):
        return [str(k) for k in factors]
    return [str(f).split("=", 1)[0].strip() for f in factors if isinstance(f, str)]


def _whole_numbers(v: np.ndarray) -> np.ndarray:
    return np.isfinite(v) & (v == np.round(v))


def glm_inputs(data: Any, response: str, factors: Any, fam: Family, trials: str | None, *,
               intercept: bool = True) -> GLMInputs:
    """Check the response (and trials) on every row and code the factors as every fit does.

    Binomial: without ``trials`` the response is 0/1; with it the response counts the
    successes of ``trials`` runs (whole numbers, ``0 <= successes <= trials``, ``trials >=
    1``) and the fit is made on the proportion. Poisson: the response is a count (a whole
    number >= 0). A row whose response cell is empty is left out (noted), as in every fit.

    Raises
    ------
    ValueError
        A cell that breaks the rules above, naming the column and the 1-based row.
    ParameterError
        ``trials`` with the poisson family, or a trials column that is missing, is the
        response or is a factor (``parameter="trials"``).
    """
    import pandas as pd

    from ..build.data import columns_text, response_values

    if not isinstance(data, pd.DataFrame):
        raise TypeError("data must be a pandas DataFrame")
    if response not in data.columns:
        raise ValueError(f"response column {quote_value(str(response))} not found (columns: {columns_text(data)})")
    y, empty = response_values(data, response)
    work = data
    m_all = np.ones(len(data))
    if trials is not None:
        if fam.name != "binomial":
            raise ParameterError("trials", f"a trials column goes with the binomial family, not {fam.name}")
        trials = str(trials)
        if trials not in data.columns:
            raise ParameterError("trials", f"trials column {quote_value(trials)} not found (columns: "
                                           f"{columns_text(data)})")
        if trials == response:
            raise ParameterError("trials", f"column {quote_value(trials)} cannot be both the response (successes) "
                                           "and the trials")
        if trials in _names(factors):
            raise ParameterError("trials", f"column {quote_value(trials)} is the trials column and cannot be a factor")
        m_all, m_empty = response_values(data, trials)
        for i in np.flatnonzero(~empty):
            m, s = m_all[i], y[i]
            where = f"row {i + 1}"
            if m_empty[i]:
                raise ValueError(f"trials column {quote_value(trials)}, {where}: is empty (the response is given)")
            if not (_whole_numbers(np.array([m]))[0] and m >= 1):
                raise ValueError(f"trials column {quote_value(trials)}, {where}: {m:g} is not a whole number of "
                                 "trials (1 or more)")
            if not (_whole_numbers(np.array([s]))[0] and 0 <= s <= m):
                raise ValueError(f"response {quote_value(response)}, {where}: {s:g} is not a count of successes "
                                 f"between 0 and the {m:g} trials")
        work = data.drop(columns=[trials])
        work[response] = np.where(empty, np.nan, y / np.where(m_empty, 1.0, m_all))
    else:
        for i in np.flatnonzero(~empty):
            s = y[i]
            if fam.name == "binomial" and s not in (0.0, 1.0):
                raise ValueError(f"response {quote_value(response)}, row {i + 1}: {s:g} is not 0 or 1 (a binomial "
                                 "response is pass/fail as 0/1, or a count of successes with a trials column)")
            if fam.name == "poisson" and not (_whole_numbers(np.array([s]))[0] and s >= 0):
                raise ValueError(f"response {quote_value(response)}, row {i + 1}: {s:g} is not a count (a whole "
                                 "number, 0 or more) as the poisson family needs")
    inp = model_inputs(work, response, factors, None, origin=not intercept)
    rows = np.flatnonzero(~empty)
    return GLMInputs(inputs=inp, trials=np.asarray(m_all[rows], dtype=float), trials_column=trials, rows=rows)


def glm_terms(inp: ModelInputs, spec: ModelSpec) -> tuple[Term, ...]:
    """The terms of ``spec`` over the factors of ``inp`` (a standard order's size checked
    against the runs before any term is built)."""
    space = inp.space
    if spec.terms is None:
        try:
            check_model_size(inp.n, len(space), spec.order, 0, categoric=space.categoric)
        except ValueError as exc:
            raise ValueError(f"{exc}{inp.hint}") from None
        return tuple(model_terms(space.letters, spec.order, space.categoric))
    try:
        return chosen_terms(spec.terms, space.letters, space.categoric, intercept=spec.intercept)
    except ValueError as exc:
        raise SpecError("terms", str(exc)) from None


def check_separation(X: np.ndarray, y: np.ndarray, m: np.ndarray, fam: Family, names: Sequence[str],
                     rows: Sequence[int] | np.ndarray | None = None) -> None:
    """Refuse data whose maximum-likelihood coefficients are infinite (Albert & Anderson
    1984; the linear programme of Konis 2007, R ``detectseparation``).

    Binomial: a direction ``b`` with ``x_i b >= 0`` on every run with a success and
    ``x_i b <= 0`` on every run with a failure, not zero on all runs, sends the likelihood
    up along ``b`` for ever. Poisson (log link): a ``b`` with ``x_i b = 0`` on every run with a
    positive count and ``x_i b <= 0`` on the zero counts, not zero on all, does the same.
    The linear programme maximises the total margin over ``|b_j| <= 1``; a positive optimum
    is separation.

    Raises
    ------
    SeparationError
        Naming the kind (complete, quasi-complete), the terms of the separating combination
        and the rows it fits exactly (``rows``: the 1-based data rows of the runs).
    """
    from scipy.optimize import linprog

    n, p = X.shape
    scale = np.maximum(np.abs(X).max(axis=0), 1e-300)
    Xs = X / scale
    if fam.name == "binomial":
        succ, fail = m * y > 0, m * (1.0 - y) > 0
        A_ub = np.vstack([-Xs[succ], Xs[fail]])
        c = -(Xs[succ].sum(axis=0) - Xs[fail].sum(axis=0))
        A_eq = None
    else:
        zero = y == 0
        if not zero.any():
            return
        A_ub, c = Xs[zero], Xs[zero].sum(axis=0)
        A_eq = Xs[~zero] if (~zero).any() else None
    res = linprog(c, A_ub=A_ub, b_ub=np.zeros(A_ub.shape[0]), A_eq=A_eq,
                  b_eq=None if A_eq is None else np.zeros(A_eq.shape[0]), bounds=[(-1.0, 1.0)] * p, method="highs")
    if res.status != 0 or -res.fun <= 1e-7 * max(1.0, n):
        return
    bx = res.x
    if fam.name == "binomial" and not (succ & fail).any():  # complete? every run strictly on its side
        sign = np.where(succ, -1.0, 1.0)
        strict = linprog(np.r_[np.zeros(p), -1.0], A_ub=np.c_[sign[:, None] * Xs, np.ones(n)], b_ub=np.zeros(n),
                         bounds=[(-1.0, 1.0)] * p + [(0.0, 1.0)], method="highs")
        if strict.status == 0 and strict.x[-1] > 1e-9:
            bx = strict.x[:p]
    margin = Xs @ bx
    exact = np.abs(margin) > 1e-9 * max(1.0, float(np.abs(margin).max()))
    data_rows = [int(r) + 1 for r in (np.asarray(rows) if rows is not None else np.arange(n))[exact]]
    shown = ", ".join(str(r) for r in data_rows[:12]) + (f" and {len(data_rows) - 12} more" if len(data_rows) > 12
                                                           else "")
    used = [nm for nm, v in zip(names, bx) if abs(v) > 1e-9]
    combo = ", ".join(used)
    complete = bool(exact.all())
    if fam.name == "binomial":
        kind = "completely" if complete else "quasi-completely"
        msg = (f"the successes and failures are {kind} separated: a combination of {combo} predicts the outcome of "
               f"row{'s' if len(data_rows) > 1 else ''} {shown} without error, so the maximum-likelihood "
               "coefficients are infinite and no finite fit exists; fit fewer terms, or add runs where those "
               "outcomes overlap")
    else:
        msg = (f"the zero counts are separated: a combination of {combo} drives the mean of "
               f"row{'s' if len(data_rows) > 1 else ''} {shown} to 0, so the maximum-likelihood coefficients are "
               "infinite and no finite fit exists; fit fewer terms, or add runs with counts there")
    raise SeparationError(msg, data_rows, complete)


def irls(X: np.ndarray, y: np.ndarray, m: np.ndarray, fam: Family, *, start: np.ndarray | None = None,
         max_iterations: int = MAX_ITERATIONS) -> IRLSFit:
    """Maximum likelihood by iteratively reweighted least squares (Fisher scoring).

    Each step solves the weighted least squares of the working response
    ``z = eta + (y - mu) / mu'(eta)`` on ``X`` with weights ``w = m mu'(eta)^2 / V(mu)`` by
    a Householder QR of ``sqrt(w) X``, starting from R's ``mustart`` (or from ``start``,
    coefficients); a step that makes the deviance non-finite or larger is halved. It stops
    one step after the relative coefficient step falls below :data:`STEP_TOLERANCE`.

    Parameters
    ----------
    X : (n, p) ndarray
        Model matrix (full column rank).
    y : (n,) ndarray
        Proportions of ``m`` trials (binomial) or counts (poisson).
    m : (n,) ndarray
        Trials per run (the prior weights; ones for a 0/1 response or a count).
    fam : Family

    Returns
    -------
    IRLSFit

    Raises
    ------
    ValueError
        No convergence within ``max_iterations`` steps.
    """
    def deviance(mu: np.ndarray) -> float:
        return float(np.sum(fam.unit_deviance(y, mu, m)))

    if start is None:
        mu = fam.start(y, m)
        eta = fam.linkfun(mu)
        beta = None
    else:
        beta = np.asarray(start, dtype=float)
        eta = X @ beta
        mu = fam.linkinv(eta)
    dev = deviance(mu)
    settled = False
    it = 0
    while True:
        it += 1
        if it > max_iterations:
            raise ValueError(f"the {fam.label} fit did not converge in {max_iterations} iterations (the data may be "
                             "nearly separated: some outcomes almost perfectly predicted)")
        d = fam.mu_eta(eta)
        z = eta + (y - mu) / d
        sw = np.sqrt(m * d * d / fam.variance(mu))
        Q, R = np.linalg.qr(X * sw[:, None])
        new = np.linalg.solve(R, Q.T @ (z * sw))
        if beta is not None:
            for _ in range(60):  # step halving (R halves only a non-finite deviance)
                mu_new = fam.linkinv(X @ new)
                dev_new = deviance(mu_new)
                if np.isfinite(dev_new) and dev_new <= dev * (1.0 + 1e-10) + 1e-12:
                    break
                new = 0.5 * (new + beta)
        step = float(np.max(np.abs(new - beta)) / (1.0 + np.max(np.abs(new)))) if beta is not None else np.inf
        beta = new
        eta = X @ beta
        mu = fam.linkinv(eta)
        dev = deviance(mu)
        if settled:
            break
        settled = step < STEP_TOLERANCE
    d = fam.mu_eta(eta)
    sw = np.sqrt(m * d * d / fam.variance(mu))
    Rf = np.asarray(np.linalg.qr(X * sw[:, None], mode="r"))
    Rinv = np.linalg.solve(Rf, np.eye(Rf.shape[0]))
    return IRLSFit(params=beta, cov=Rinv @ Rinv.T, mu=mu, eta=eta, deviance=dev, iterations=it)


def deviance_tables(X: np.ndarray, y: np.ndarray, m: np.ndarray, fam: Family, terms: Sequence[Term],
                    intercept: bool, full: IRLSFit) -> tuple[tuple[DevianceRow, ...], tuple[DevianceRow, ...]]:
    """``(drop, sequential)``: the likelihood-ratio test of each term dropped from the full
    model (R ``drop1(fit, scope = every term, test = "LRT")``) and of each term added in
    order (R ``anova(fit, test = "LRT")``); one :class:`DevianceRow` per model term."""
    from scipy.special import chdtrc

    lead = 1 if intercept else 0
    model_terms_ = [t for t in terms if t.order != 0] if intercept else list(terms)
    groups = term_columns(model_terms_, lead)
    p = X.shape[1]
    n = X.shape[0]

    def sub_deviance(cols: np.ndarray) -> float:
        if cols.size == 0:  # no column at all: eta = 0
            return float(np.sum(fam.unit_deviance(y, fam.linkinv(np.zeros(n)), m)))
        return irls(X[:, cols], y, m, fam, start=full.params[cols]).deviance

    drop = []
    for t, g in zip(model_terms_, groups):
        keep = np.setdiff1d(np.arange(p), g)
        dev = sub_deviance(keep)
        chi = max(dev - full.deviance, 0.0)
        drop.append(DevianceRow(source=t.name, df=int(g.size), chi_square=chi, p=float(chdtrc(g.size, chi)),
                                resid_df=n - keep.size, resid_deviance=dev))
    seq = []
    prev = sub_deviance(np.arange(lead))
    for k, (t, g) in enumerate(zip(model_terms_, groups)):
        cols = np.arange(int(g[-1]) + 1)
        dev = full.deviance if k == len(groups) - 1 else sub_deviance(cols)
        chi = max(prev - dev, 0.0)
        seq.append(DevianceRow(source=t.name, df=int(g.size), chi_square=chi, p=float(chdtrc(g.size, chi)),
                               resid_df=n - cols.size, resid_deviance=dev))
        prev = dev
    return tuple(drop), tuple(seq)


def fit_glm(data: Any, response: str, factors: Any = None, *, spec: ModelSpec,
            family_name: str | Family | None = "binomial", link: str | None = None, trials: str | None = None,
            block: str | None = None, components: Any = None, random_effect: Any = None) -> GLMResult:
    """Fit a generalised linear model (see the module docstring): the model terms of
    ``spec`` over the coded factors, by maximum likelihood.

    Parameters
    ----------
    data : pandas.DataFrame
        One row per run (or per group of ``trials`` runs).
    response : str
        0/1 outcome, successes (with ``trials``) or count.
    factors : None, sequence or FactorSpace
        As for :func:`rsm_lrg.fit`.
    spec : ModelSpec
        The model: an order or terms, with or without an intercept, optionally with a
        term selection (``reduce``: p-values are likelihood-ratio tests); no transform (the
        link is the GLM's transform), no mixture model.
    family_name : {"binomial", "poisson"} or Family
    link : str, optional
        ``logit`` (default), ``probit``, ``cloglog`` (binomial); ``log`` (poisson).
    trials : str, optional
        Column of the number of trials of each row (binomial): the response is then the
        number of successes.
    block, components, random_effect : optional
        Not available with a GLM (a ParameterError naming the argument).

    Returns
    -------
    GLMResult

    Raises
    ------
    ParameterError
        A bad family, link, trials column or an option a GLM does not take (``parameter``
        names it).
    SeparationError
        Separated data (infinite estimates), naming the rows.
    ValueError
        Bad cells (naming the row), fewer runs than coefficients, aliased terms.
    """
    if family_name is None:
        raise ParameterError("family", f"a {'link' if link is not None else 'trials column'} goes with a family: "
                                       "give the family too (binomial or poisson)")
    fam = family(family_name, link)
    if block is not None:
        raise ParameterError("block", "blocks in a generalised linear model are not available yet")
    if components is not None:
        raise ParameterError("component", "mixture components in a generalised linear model are not available yet")
    if random_effect is not None:
        raise ParameterError("whole_plot", "a random whole-plot or block effect in a generalised linear model (a "
                                           "GLMM) is not available yet")
    if not spec.transform.identity:
        raise SpecError("transform", f"a {fam.name} model reaches the response through its {fam.link} link; give "
                                     "no transform")
    if spec.mixture:
        raise SpecError("model", "a mixture model with a binomial or poisson response is not available yet")
    gi = glm_inputs(data, response, factors, fam, trials, intercept=spec.intercept)
    inp = gi.inputs
    terms = glm_terms(inp, spec)
    reduction = None
    if spec.reduce is not None:  # choose the terms (rsm_lrg.model.choice.select), then fit the model chosen
        from dataclasses import replace

        reduction = select_glm_terms(inp, gi, fam, spec, terms)
        spec = replace(spec, terms=tuple(t for t in reduction.kept if t != "Intercept"), reduce=None)
        terms = glm_terms(inp, spec)
    col_names = inp.column_names(terms)
    X = inp.rows(terms)
    n, p = X.shape
    what = f"the {spec.order} model" if spec.terms is None else "the model"
    if n < p:
        raise ValueError(f"{n} runs cannot fit {p} coefficients ({what} in {len(inp.space)} factors){inp.hint}")
    from ..engines.least_squares import least_squares

    least_squares(X, inp.y, col_names).require_full_rank(f"{spec.order} model" if spec.terms is None else "model")
    y, m = np.asarray(inp.y, dtype=float), gi.trials
    check_separation(X, y, m, fam, col_names, rows=gi.rows)
    full = irls(X, y, m, fam)
    drop, seq = deviance_tables(X, y, m, fam, terms, spec.intercept, full)
    if spec.intercept:
        mu0 = np.full(n, float(np.sum(m * y) / np.sum(m)))
    else:
        mu0 = fam.linkinv(np.zeros(n))
    null_dev = float(np.sum(fam.unit_deviance(y, mu0, m)))
    prep = inp.prep
    return GLMResult(response=response, spec=spec, family=fam, space=inp.space, terms=tuple(terms),
                     column_names=tuple(col_names), params=full.params, cov=full.cov, mu=full.mu, eta=full.eta,
                     y=y, trials=m, trials_column=gi.trials_column, deviance=full.deviance, null_deviance=null_dev,
                     log_likelihood=fam.log_likelihood(y, full.mu, m), iterations=full.iterations,
                     drop_table=drop, sequential_table=seq, data=prep.data, coded=inp.coded,
                     input_notes=tuple(prep.notes), omitted_rows=tuple(prep.omitted_rows),
                     omitted_data=prep.omitted_data, reduction=reduction,
                     start_model=None if reduction is None else reduction.start_model)


class GLMScorer:
    """Sub-models of a GLM for the term searches of :mod:`rsm_lrg.model.choice.select`: each one
    fitted by :func:`irls` (cached); p-values are likelihood-ratio tests (the term dropped),
    AICc and BIC from the log-likelihood with ``K = p`` (dispersion 1)."""

    def __init__(self, X: np.ndarray, y: np.ndarray, m: np.ndarray, fam: Family, col: dict, fixed: int) -> None:
        self.X, self.y, self.m, self.fam, self.col, self.fixed = X, y, m, fam, col, fixed
        self.cache: dict[tuple, IRLSFit] = {}

    def columns(self, ts: Sequence) -> list[int]:
        return sorted([*range(self.fixed), *(c for t in ts for c in self.col[id(t)])])

    def fit(self, ts: Sequence) -> IRLSFit:
        key = tuple(self.columns(ts))
        if key not in self.cache:
            self.cache[key] = irls(self.X[:, list(key)], self.y, self.m, self.fam)
        return self.cache[key]

    def criteria(self, ts: Sequence) -> tuple[float, float] | None:
        n, p = self.X.shape[0], len(self.columns(ts))
        if n - p - 1 <= 0:
            return None
        ll = self.fam.log_likelihood(self.y, self.fit(ts).mu, self.m)
        return -2.0 * ll + 2.0 * p + 2.0 * p * (p + 1) / (n - p - 1), -2.0 * ll + p * math.log(n)

    def p_value(self, ts: Sequence, t: Any) -> float:
        from scipy.special import chdtrc

        chi = max(self.fit([s for s in ts if s is not t]).deviance - self.fit(ts).deviance, 0.0)
        return float(chdtrc(len(self.col[id(t)]), chi))

    def extra(self, ts: Sequence) -> dict[str, float]:
        return {"n_coefficients": len(self.columns(ts)), "deviance": self.fit(ts).deviance}


def select_glm_terms(inp: ModelInputs, gi: GLMInputs, fam: Family, spec: ModelSpec, terms: Sequence[Term]) -> Any:
    """The terms of a GLM chosen as ``spec.reduce`` says (forward, backward, stepwise,
    all-subsets; by likelihood-ratio p-values, AICc or BIC; hierarchy kept), from the
    starting model ``terms`` (checked for aliasing and separation first)."""
    from ..choice.select import search
    from ..engines.least_squares import least_squares

    assert spec.reduce is not None
    if spec.reduce.method == "dsd":
        raise SpecError("reduce", "the definitive screening analysis is for least-squares fits, not a GLM")
    if not spec.intercept and spec.reduce.method != "backward":
        raise SpecError("reduce", f"{spec.reduce.method} selection starts from (or keeps) the intercept: the model "
                                  "needs one")
    X = inp.rows(terms)
    names = inp.column_names(terms)
    if X.shape[0] <= X.shape[1]:
        raise ValueError(f"{X.shape[0]} runs cannot fit {X.shape[1]} coefficients; start from a smaller model")
    least_squares(X, inp.y, names).require_full_rank("model to reduce")
    y, m = np.asarray(inp.y, dtype=float), gi.trials
    check_separation(X, y, m, fam, names, rows=gi.rows)
    lead = 1 if spec.intercept else 0
    pool = [t for t in terms if t.order > 0]
    col = {id(t): list(g) for t, g in zip(pool, term_columns(pool, lead))}
    return search(pool, spec.reduce, GLMScorer(X, y, m, fam, col, lead), intercept=spec.intercept,
                  start_model=spec.order if spec.terms is None else "custom")
