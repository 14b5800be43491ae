"""The result of a generalised linear model fit, :class:`GLMResult`
(:func:`rsm_lrg.model.pipelines.glm.fit_glm`).

It has the face of every fit — ``response``, ``space``, ``terms``, ``coefficients`` (coded
and actual units), ``notes``, ``predict(points, interval=..., alpha=..., coded=...)``,
``to_dict()``, ``summary()`` — with what differs for a GLM: no sums of squares; the analysis
of deviance (likelihood-ratio chi-square of each term dropped from the full model) in
``anova``; the residual and null deviance, Pearson's chi-square, log-likelihood, AIC, AICc and
BIC in ``statistics``; Wald standard errors and ``z`` tests; predictions on the response
scale (the probability of a success, or the mean count) with confidence intervals made on
the link scale and mapped through the inverse link (so they stay inside 0..1 or above 0).

There is no prediction interval: a new binary outcome is 0 or 1 and a new count a whole
number, so an interval "for a new run" is a statement about the distribution of the
outcome (a binomial or Poisson quantile at the predicted mean), not an interval estimate;
``predict(..., interval="prediction")`` returns ``pi_low``/``pi_high`` as NaN and the notes
say so.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import asdict, dataclass, field
from functools import cached_property
from typing import Any

import numpy as np

from ...errors import ParameterError
from ...factors import FactorSpace
from ..build.inputs import coded_points
from ..build.spec import ModelSpec
from ..build.terms import column_names, design_matrix
from ..engines.glm_family import Family
from ..readings.actual import actual_coefficients

__all__ = ["GLMResult", "DevianceRow", "GLM_COEF_COLUMNS", "DEVIANCE_COLUMNS", "NO_PREDICTION_INTERVAL"]

#: Columns of :attr:`GLMResult.coefficients`.
GLM_COEF_COLUMNS = ["coded", "std_error", "z", "p", "ci_low", "ci_high", "actual"]
#: Columns of :attr:`GLMResult.anova` and :attr:`GLMResult.sequential_anova`.
DEVIANCE_COLUMNS = ["source", "df", "chi_square", "p", "resid_df", "resid_deviance"]
#: Why a GLM gives no prediction interval (a note, and the docstring of :meth:`GLMResult.predict`).
NO_PREDICTION_INTERVAL = ("No prediction interval: a new run's outcome is a 0/1 result or a whole count, not a "
                          "continuous value about the mean; pi_low and pi_high are left empty (NaN). The confidence "
                          "interval is for the probability (mean count).")


@dataclass(frozen=True)
class DevianceRow:
    """One likelihood-ratio test of the analysis of deviance.

    Attributes
    ----------
    source : str
        The term (``"A"``, ``"AB"``, ``"A^2"``, ``"E"``; ``"Model"`` for all terms at once).
    df : int
        Its columns (the chi-square's degrees of freedom).
    chi_square : float
        The likelihood-ratio chi-square: the deviance gained by dropping the term from the
        full model (``drop``) or lost by adding it after the terms before it (``sequential``).
    p : float
        Upper tail of the chi-square(df) distribution at ``chi_square``.
    resid_df, resid_deviance : int, float
        Residual df and deviance of the model without the term (drop), or with the terms up
        to it (sequential).
    """

    source: str
    df: int
    chi_square: float
    p: float
    resid_df: int
    resid_deviance: float

    def to_dict(self) -> dict:
        return {k: (_f(v) if isinstance(v, float) else v) for k, v in asdict(self).items()}


def _f(v: Any) -> float | None:
    try:
        x = float(v)
    except (TypeError, ValueError):
        return None
    return x if math.isfinite(x) else None


@dataclass(frozen=True)
class GLMResult:
    """A fitted generalised linear model (frozen); derived quantities are cached.

    Attributes
    ----------
    response : str
        Response column (0/1 outcome, successes, or count).
    spec : ModelSpec
        The model's order or terms and intercept.
    family : Family
        Distribution and link.
    space : FactorSpace
        Factors with their coding (letters A, B, ...).
    terms : tuple of Term
        Model terms (``terms[0]`` the intercept when there is one).
    column_names : tuple of str
        Model-matrix columns (coefficient keys).
    params, cov : ndarray
        Coefficients on the link scale in coded units, and their covariance (inverse Fisher
        information; dispersion 1).
    mu, eta : ndarray
        Fitted means (probability per trial, or mean count) and linear predictors.
    y : ndarray
        The response as fitted: the proportion of successes (binomial) or the count.
    trials : ndarray
        Trials per run (ones for a 0/1 response or a count).
    trials_column : str or None
    deviance, null_deviance, log_likelihood : float
    iterations : int
        IRLS iterations.
    drop_table, sequential_table : tuple of DevianceRow
        The analysis of deviance (each term dropped from the full model; terms added in order).
    data : pandas.DataFrame
        The rows used.
    coded : pandas.DataFrame
        Coded settings (columns = letters).
    input_notes : tuple of str
    omitted_rows : tuple of int
    omitted_data : pandas.DataFrame
    reduction : Selection or None
        The term selection that chose the terms (:mod:`rsm_lrg.model.choice.select`).
    start_model : str or None
        The model the selection started from.
    """

    response: str
    spec: ModelSpec
    family: Family
    space: FactorSpace
    terms: tuple
    column_names: tuple
    params: np.ndarray = field(repr=False)
    cov: np.ndarray = field(repr=False)
    mu: np.ndarray = field(repr=False)
    eta: np.ndarray = field(repr=False)
    y: np.ndarray = field(repr=False)
    trials: np.ndarray = field(repr=False)
    trials_column: str | None
    deviance: float
    null_deviance: float
    log_likelihood: float
    iterations: int
    drop_table: tuple = field(repr=False)
    sequential_table: tuple = field(repr=False)
    data: Any = field(repr=False)
    coded: Any = field(repr=False)
    input_notes: tuple = field(default=(), repr=False)
    omitted_rows: tuple = field(default=(), repr=False)
    omitted_data: Any = field(default=None, repr=False)
    reduction: Any = field(default=None, repr=False)
    start_model: str | None = field(default=None, repr=False)

    # -- the model -----------------------------------------------------------------------
    @property
    def intercept(self) -> bool:
        """Whether the model has an intercept."""
        return bool(self.spec.intercept)

    @property
    def model(self) -> str:
        """The model's order, or ``"custom"`` for chosen terms (after a term selection: the
        model it started from)."""
        if self.start_model is not None:
            return self.start_model
        return self.spec.order if self.spec.terms is None else "custom"

    @property
    def model_terms(self) -> tuple:
        """The terms without the intercept."""
        return tuple(t for t in self.terms if t.order != 0) if self.intercept else self.terms

    @property
    def term_names(self) -> list[str]:
        """The model's column names, in column order."""
        return list(self.column_names)

    @property
    def factors(self) -> list[str]:
        """The factors' names, in letter order."""
        return list(self.space.names)

    @property
    def n(self) -> int:
        """Rows fitted."""
        return int(self.y.size)

    @property
    def n_params(self) -> int:
        """The number of coefficients p."""
        return int(self.params.size)

    @property
    def df_resid(self) -> int:
        """Residual degrees of freedom, n - p."""
        return self.n - self.n_params

    @property
    def df_null(self) -> int:
        """Degrees of freedom of the null model, n - 1 (n without an intercept)."""
        return self.n - (1 if self.intercept else 0)

    @property
    def fitted(self) -> np.ndarray:
        """Fitted means: probability of a success, or mean count."""
        return self.mu

    @cached_property
    def pearson_chi2(self) -> float:
        """Pearson's goodness-of-fit chi-square ``sum m (y - mu)^2 / V(mu)``."""
        return float(np.sum(self.trials * (self.y - self.mu) ** 2 / self.family.variance(self.mu)))

    @cached_property
    def residuals(self) -> np.ndarray:
        """Deviance residuals ``sign(y - mu) sqrt(d_i)`` (R's default ``residuals.glm``)."""
        d = self.family.unit_deviance(self.y, self.mu, self.trials)
        return np.sign(self.y - self.mu) * np.sqrt(np.maximum(d, 0.0))

    @cached_property
    def pearson_residuals(self) -> np.ndarray:
        """``(y - mu) sqrt(m / V(mu))``."""
        return (self.y - self.mu) * np.sqrt(self.trials / self.family.variance(self.mu))

    @cached_property
    def statistics(self) -> dict[str, float]:
        """Deviance, null deviance, their df, Pearson chi-square, log-likelihood, AIC, AICc
        (``AIC + 2p(p+1)/(n-p-1)``, n = rows), BIC, and the deviance goodness-of-fit p-value
        (upper chi-square(df_resid) tail; meaningful for grouped binomial data and counts, not
        for 0/1 responses)."""
        from scipy.special import chdtrc

        n, p = self.n, self.n_params
        aic = -2.0 * self.log_likelihood + 2.0 * p
        aicc = aic + 2.0 * p * (p + 1) / (n - p - 1) if n - p - 1 > 0 else math.nan
        df = self.df_resid
        grouped = df > 0 and not (self.family.name == "binomial" and self.trials_column is None)
        return {"deviance": self.deviance, "df_resid": float(df), "null_deviance": self.null_deviance,
                "df_null": float(self.df_null), "pearson_chi2": self.pearson_chi2,
                "deviance_p": float(chdtrc(df, self.deviance)) if grouped else math.nan,
                "pearson_p": float(chdtrc(df, self.pearson_chi2)) if grouped else math.nan,
                "log_likelihood": self.log_likelihood, "aic": aic, "aicc": aicc,
                "bic": -2.0 * self.log_likelihood + p * math.log(n),
                "deviance_r2": 1.0 - self.deviance / self.null_deviance if self.null_deviance > 0 else math.nan}

    @cached_property
    def anova(self) -> Any:
        """The analysis of deviance: a ``Model`` row (every term at once: null deviance minus
        residual deviance) then one row per term, its likelihood-ratio chi-square with the term
        dropped from the full model (R ``drop1(fit, test = "LRT")`` over every term);
        columns :data:`DEVIANCE_COLUMNS`."""
        import pandas as pd
        from scipy.special import chdtrc

        k = self.n_params - (1 if self.intercept else 0)
        chi = max(self.null_deviance - self.deviance, 0.0)
        model = DevianceRow(source="Model", df=k, chi_square=chi, p=float(chdtrc(k, chi)) if k > 0 else math.nan,
                            resid_df=self.df_null, resid_deviance=self.null_deviance)
        rows = [model, *self.drop_table]
        return pd.DataFrame([asdict(r) for r in rows], columns=DEVIANCE_COLUMNS)

    @cached_property
    def sequential_anova(self) -> Any:
        """The sequential analysis of deviance (terms added in order; R ``anova(fit, test =
        "LRT")``), columns :data:`DEVIANCE_COLUMNS`."""
        import pandas as pd

        return pd.DataFrame([asdict(r) for r in self.sequential_table], columns=DEVIANCE_COLUMNS)

    @cached_property
    def coefficients(self) -> Any:
        """Index = coefficient name; columns :data:`GLM_COEF_COLUMNS` (coded units, link
        scale; Wald z, p and 95 % interval; ``actual``: the same linear predictor in actual
        units)."""
        import pandas as pd
        from scipy.special import ndtr, ndtri

        b = self.params
        se = np.sqrt(np.clip(np.diag(self.cov), 0.0, None))
        z = b / se
        q = float(ndtri(0.975))
        act = self.actual_coefficients
        return pd.DataFrame({"coded": b, "std_error": se, "z": z, "p": 2.0 * ndtr(-np.abs(z)),
                             "ci_low": b - q * se, "ci_high": b + q * se,
                             "actual": [act.get(c, math.nan) for c in self.column_names]},
                            index=list(self.column_names), columns=GLM_COEF_COLUMNS)

    @cached_property
    def actual_coefficients(self) -> dict:
        """``{term: coefficient}`` of the linear predictor in actual units (the exact change of
        basis of the coded polynomial, :func:`rsm_lrg.model.readings.actual.actual_coefficients`)."""
        return actual_coefficients(dict(zip(column_names(self.terms), self.params.tolist())), self.terms, self.space)

    @cached_property
    def actual_std_errors(self) -> dict:
        """``{term: standard error}`` in actual units (the change of basis is linear:
        ``cov = M C M'``)."""
        cols = column_names(self.terms)
        basis = [actual_coefficients(dict(zip(cols, e)), self.terms, self.space) for e in np.eye(len(cols)).tolist()]
        names = list(basis[0])
        M = np.array([[bb.get(nm, 0.0) for bb in basis] for nm in names])
        cov = M @ self.cov @ M.T
        return dict(zip(names, np.sqrt(np.clip(np.diag(cov), 0.0, None)).tolist()))

    @cached_property
    def notes(self) -> tuple:
        """Remarks: the input notes, then how the model was fitted and what it does not give."""
        fam = self.family
        what = ("a 0/1 response" if fam.name == "binomial" and self.trials_column is None else
                f"successes out of the trials in {self.trials_column!r}" if fam.name == "binomial" else "counts")
        notes = [f"Generalised linear model, {fam.label}, of {what}: maximum likelihood by iteratively reweighted "
                 f"least squares ({self.iterations} iterations); dispersion 1; Wald standard errors, z tests and "
                 "intervals; the analysis of deviance drops each term from the full model (likelihood-ratio "
                 "chi-square).",
                 NO_PREDICTION_INTERVAL]
        if fam.name == "binomial" and self.trials_column is None:
            notes.append("With a 0/1 response the deviance and Pearson chi-square are no test of fit (their "
                         "goodness-of-fit p-values are left out).")
        return tuple(self.input_notes) + tuple(notes)

    # -- what the optimisers read (rsm_lrg.optimize: the linear predictor and the goal) -----
    @property
    def sigma2(self) -> float:
        """The dispersion: 1 (binomial, poisson)."""
        return 1.0

    @property
    def mixture(self) -> bool:
        """A GLM is not a mixture model."""
        return False

    @property
    def transform(self) -> Any:
        """The identity: the response is modelled through the link, not transformed (the
        optimisers' notes read it)."""
        from ..build.transform import Transform

        return Transform()

    @cached_property
    def stationary_point(self) -> Any:
        """The stationary point of the linear predictor (second-order models; the optimisers
        start a search there); ``coded`` is None for a model of another order. The inverse
        links are increasing, so the probability (mean count) is extreme where the linear
        predictor is."""
        from ..readings.canonical import canonical_analysis

        if self.space.has_categoric or any(t.order > 2 for t in self.terms):
            return _NoPoint()
        return canonical_analysis(dict(zip(self.column_names, self.params.tolist())), self.terms, self.space)

    def goal_on_model_scale(self, goal: Any) -> tuple[str, float | None, str, float | None]:
        """``(kind, target, kind on the link scale, target on the link scale)``: the inverse
        link is increasing, so minimise and maximise keep their sense and a target T (a
        probability strictly between 0 and 1, or a mean count above 0) becomes ``g(T)``.

        Parameters
        ----------
        goal : str or tuple
            ``"minimize"``, ``"maximize"``, ``"target=V"`` or ``("target", V)`` (V in a probability or a mean count).

        Returns
        -------
        tuple
            ``(kind, target, kind on the link scale, target on the link scale)``.
        """
        from ..build.goals import parse_goal

        kind, target = parse_goal(goal)
        if target is None:
            return kind, None, kind, None
        binomial = self.family.name == "binomial"
        if not ((0.0 < target < 1.0) if binomial else target > 0.0):
            what = "a probability strictly between 0 and 1" if binomial else "a mean count above 0"
            raise ParameterError("goal", f"goal target {target:g}: the {self.family.label} model predicts {what}")
        return kind, target, kind, float(self.family.linkfun(np.array([target]))[0])

    def optimize(self, goal: Any = "maximize", bounds: Any = None, **kwargs: Any) -> Any:
        """The optimum of the probability (mean count) in the factor box; see
        :func:`rsm_lrg.optimize.optimize` (provided by the optimize layer through
        :mod:`rsm_lrg.registry`; the model does not import it). Its prediction interval is
        empty (NaN), as :meth:`predict`'s.

        Parameters
        ----------
        goal : str or tuple, default "maximize"
            ``"minimize"``, ``"maximize"`` or ``"target=V"`` (a probability or mean count).
        bounds : mapping or list of str, optional
            Narrower bounds in actual units.
        **kwargs
            Any other keyword argument of :func:`rsm_lrg.optimize.optimize`.

        Returns
        -------
        OptimumResult
            The best setting and the predicted probability (mean count) there.
        """
        from ...registry import lookup

        return lookup("FitResult.optimize")(self, goal=goal, bounds=bounds, **kwargs)

    # -- prediction ----------------------------------------------------------------------
    def coded_points(self, points: Any, coded: bool = False) -> np.ndarray:
        """Settings (a frame with the factor columns, a ``{name: values}`` mapping or an
        (n, k) array in factor order; actual units unless ``coded``) as coded values.

        Parameters
        ----------
        points : pandas.DataFrame, mapping or array_like
            Settings: a frame with the factor columns, ``{name: value(s)}`` or an (n, k) array in
            factor order; actual units unless ``coded``.
        coded : bool, default False
            ``points`` are in coded units.

        Returns
        -------
        numpy.ndarray, shape (n, k)
            The coded settings (:func:`rsm_lrg.model.build.inputs.coded_points`).
        """
        return coded_points(self.space, points, coded)

    def predict_link(self, coded: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(eta, se_eta)``: the linear predictor and its standard error at coded settings.

        Parameters
        ----------
        coded : numpy.ndarray, shape (n, k)
            Settings in coded units (factor order).

        Returns
        -------
        tuple of numpy.ndarray
            ``(eta, se_eta)`` on the link scale.
        """
        Xt = design_matrix(np.asarray(coded, dtype=float), self.terms)
        eta = Xt @ self.params
        se = np.sqrt(np.clip(np.einsum("ij,jk,ik->i", Xt, self.cov, Xt), 0.0, None))
        return eta, se

    def predict_coded(self, coded: np.ndarray) -> np.ndarray:
        """The predicted probability (mean count) at coded settings (n x k).

        Parameters
        ----------
        coded : numpy.ndarray, shape (n, k)
            Settings in coded units (factor order).

        Returns
        -------
        numpy.ndarray, shape (n,)
            The probability (binomial) or mean count (Poisson).
        """
        return self.family.linkinv(self.predict_link(coded)[0])

    def predictive(self, coded: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The prediction contract's predictive distribution of a new run: a GLM's new run is a
        0/1 outcome or a whole count, not a Student t about the mean, so it has none here
        (``ParameterError`` naming ``family``; the probability or rate itself is ``predict``).

        Parameters
        ----------
        coded : numpy.ndarray, shape (n, k)
            Settings in coded units (factor order).

        Returns
        -------
        tuple of numpy.ndarray
            Never: it raises ``ParameterError`` (a GLM has no t predictive distribution).
        """
        raise ParameterError("family", f"a {self.family.name} GLM has no continuous predictive distribution of a new "
                                       "run: its probability or rate is the prediction (predict); a design space "
                                       "or a specification on it is not available yet")

    def predict(self, points: Any, interval: str | None = None, alpha: float = 0.05, *, coded: bool = False) -> Any:
        """The predicted probability of a success (binomial) or mean count (poisson).

        Parameters
        ----------
        points : DataFrame, mapping or array
            Settings in actual units (coded with ``coded=True``), as for
            :meth:`rsm_lrg.model.results.result.FitResult.predict`.
        interval : {None, "confidence", "prediction", "both"}
            ``confidence``: ``g^-1(eta ± z se_eta)``, the Wald interval on the link scale
            mapped to the response scale (R: ``predict(type = "link", se.fit = TRUE)``). A
            GLM gives no prediction interval: ``prediction`` adds ``pi_low``/``pi_high`` as
            NaN (see :data:`NO_PREDICTION_INTERVAL`).
        alpha : float
            1 - confidence level.
        coded : bool
            Points in coded units (columns = letters).

        Returns
        -------
        pandas.DataFrame
            ``predicted`` (response scale), ``se_fit`` (its delta-method standard error, R's
            ``predict(type = "response", se.fit = TRUE)``), ``link`` and ``se_link`` (the
            linear predictor and its standard error), and the interval columns asked for.
        """
        import pandas as pd
        from scipy.special import ndtri

        if interval not in (None, "confidence", "prediction", "both"):
            raise ValueError(f"interval must be None, 'confidence', 'prediction' or 'both', not {interval!r}")
        if not 0.0 < alpha < 1.0:
            raise ParameterError("alpha", f"alpha must lie between 0 and 1, not {alpha!r}")
        index = points.index if isinstance(points, pd.DataFrame) else None
        with np.errstate(over="ignore", invalid="ignore"):
            x = self.coded_points(points, coded)
        eta, se_eta = self.predict_link(x)
        fam = self.family
        mu = fam.linkinv(eta)
        out = pd.DataFrame({"predicted": mu, "se_fit": np.abs(fam.mu_eta(eta)) * se_eta, "link": eta,
                            "se_link": se_eta}, index=index)
        if interval in ("confidence", "both"):
            q = float(ndtri(1.0 - alpha / 2.0))
            out["ci_low"] = fam.linkinv(eta - q * se_eta)
            out["ci_high"] = fam.linkinv(eta + q * se_eta)
        if interval in ("prediction", "both"):
            out["pi_low"] = math.nan
            out["pi_high"] = math.nan
        return out

    # -- faces -------------------------------------------------------------------------
    def to_dict(self) -> dict:
        """The fit JSON: the keys of every fit (``coefficients.coded``/``actual``,
        ``std_errors.coded``/``actual``, ``anova``: the analysis of deviance rows) and the
        GLM's own (``family``, ``link``, ``deviance``, ``statistics``, ``sequential_anova``).

        Returns
        -------
        dict
            The ``fit --json`` document of a GLM: plain Python.
        """
        coef = self.coefficients
        st = self.statistics
        out: dict[str, Any] = {
            "response": self.response, "n": self.n, "model": self.model, "block": None,
            "family": self.family.name, "link": self.family.link, "trials": self.trials_column,
            "method": "maximum likelihood (IRLS)",
            "factors": self.space.to_list(),
            "coefficients": {"coded": {k: _f(v) for k, v in coef["coded"].items()},
                             "actual": {k: _f(v) for k, v in self.actual_coefficients.items()}},
            "std_errors": {"coded": {k: _f(v) for k, v in coef["std_error"].items()},
                           "actual": {k: _f(v) for k, v in self.actual_std_errors.items()}},
            "z": {k: _f(v) for k, v in coef["z"].items()},
            "p": {k: _f(v) for k, v in coef["p"].items()},
            "deviance": _f(self.deviance), "null_deviance": _f(self.null_deviance),
            "df_resid": self.df_resid, "df_null": self.df_null,
            "anova": [{k: (_f(v) if k in ("chi_square", "p", "resid_deviance") else
                           (int(v) if k in ("df", "resid_df") else v)) for k, v in r.items()}
                      for r in self.anova.to_dict(orient="records")],
            "sequential_anova": [r.to_dict() for r in self.sequential_table],
            "statistics": {k: _f(v) for k, v in st.items()},
            "iterations": self.iterations,
            "notes": list(self.notes),
            "omitted_rows": list(self.omitted_rows),
            "terms": [t.name for t in self.model_terms],
            "intercept": self.intercept,
        }
        if self.reduction is not None:
            out["reduction"] = self.reduction.to_dict()
        return out

    def summary(self) -> str:
        """The text face: family and link, the analysis of deviance, the goodness of fit, the
        coefficients (coded units, Wald) and the linear predictor in coded and actual units.

        Returns
        -------
        str
            Text for people, several lines.
        """
        from ...present import format_p as fmt_p

        fam = self.family
        st = self.statistics
        lines = [f"Generalised linear model: {fam.label}, response {self.response}"
                 + (f" (successes of {self.trials_column})" if self.trials_column else "")
                 + f", {self.n} runs, {self.n_params} coefficients ({self.model} model)"]
        if self.reduction is not None:
            lines.append(self.reduction.describe().replace("p >", "likelihood-ratio p >").replace("p <",
                                                                                                  "likelihood-ratio p <"))
        lines.append("Factors: " + "; ".join(
            f"{f.letter} = {f.name} " + (f"[{f.low:g}, {f.high:g}]" if f.kind == "numeric" else
                                         "(" + ", ".join(map(str, getattr(f, "levels", ()))) + ")")
            for f in self.space.factors))
        lines.append("")
        lines.append("Analysis of deviance (likelihood-ratio tests; each term dropped from the full model)")
        w = max([len("Source")] + [len(s) for s in self.anova["source"]])
        lines.append(f"{'Source':<{w}}  {'df':>4}  {'Chi-square':>12}  {'p-value':>9}  {'Resid. dev.':>12}")
        for r in self.anova.itertuples(index=False):
            lines.append(f"{r.source:<{w}}  {r.df:>4d}  {r.chi_square:>12.6g}  {fmt_p(r.p):>9}  "
                         f"{r.resid_deviance:>12.6g}")
        lines.append("")
        gof = (f"Residual deviance {st['deviance']:.6g} on {self.df_resid} df; null deviance "
               f"{st['null_deviance']:.6g} on {self.df_null} df; Pearson chi-square {st['pearson_chi2']:.6g}")
        lines.append(gof)
        lines.append(f"Log-likelihood {st['log_likelihood']:.6g}; AIC {st['aic']:.6g}; AICc {st['aicc']:.6g}; "
                     f"BIC {st['bic']:.6g}")
        lines.append("")
        lines.append(f"Coefficients (coded units, {fam.link} scale; Wald)")
        coef = self.coefficients
        w = max([len("Term")] + [len(s) for s in coef.index])
        lines.append(f"{'Term':<{w}}  {'Estimate':>12}  {'Std. error':>12}  {'z':>9}  {'p-value':>9}")
        for name, r in coef.iterrows():
            lines.append(f"{name:<{w}}  {r['coded']:>12.6g}  {r['std_error']:>12.6g}  {r['z']:>9.4g}  "
                         f"{fmt_p(r['p']):>9}")
        lines.append("")
        g = f"{fam.link}({fam.mean_name})"
        lines.append(f"{g} in coded units = " + _equation(dict(zip(coef.index, coef["coded"]))))
        lines.append(f"{g} in actual units = " + _equation(self.actual_coefficients))
        lines.append("")
        lines.extend(f"Note: {n}" for n in self.notes)
        return "\n".join(lines) + "\n"

    def __str__(self) -> str:
        return self.summary()

    def to_frame(self) -> Any:
        """Per-run table: the factor settings (actual and coded), the response as fitted
        (proportion or count), the trials, the fitted mean, the linear predictor, the deviance
        and Pearson residuals and the leverage ``h_ii`` of the weighted fit.

        Returns
        -------
        pandas.DataFrame
            The table described above.
        """
        import pandas as pd

        df = pd.DataFrame({f.name: self.data[f.name].to_numpy(dtype=float if f.kind == "numeric" else object)
                           for f in self.space.factors})
        for L in self.space.letters:
            df[f"coded_{L}"] = self.coded[L].to_numpy()
        df[self.response] = self.y
        df["trials"] = self.trials
        df["fitted"] = self.mu
        df["link"] = self.eta
        df["deviance_residual"] = self.residuals
        df["pearson_residual"] = self.pearson_residuals
        X = design_matrix(self.coded[list(self.space.letters)].to_numpy(dtype=float), self.terms)
        d = self.family.mu_eta(self.eta)
        w = self.trials * d * d / self.family.variance(self.mu)
        df["leverage"] = w * np.einsum("ij,jk,ik->i", X, self.cov, X)
        return df


class _NoPoint:
    """No stationary point (a model beyond second order, or with categoric factors)."""

    coded = None


def _equation(coefs: Mapping[str, float]) -> str:
    parts: list[str] = []
    for k, v in coefs.items():
        term = f"{abs(v):.6g}" + ("" if k == "Intercept" else f"*{k}")
        parts.append(("-" if v < 0 else "+") + " " + term if parts else ("-" if v < 0 else "") + term)
    return " ".join(parts)
