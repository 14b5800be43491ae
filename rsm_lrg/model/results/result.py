"""The one fitted-model type, :class:`FitResult`, and its assembly from the regression core.

Every fit — an order or a list of terms, with or without an intercept, on a transformed
response, reduced, blocked, with categoric factors, from pandas or Dask — is one
:class:`FitResult`. It holds the model specification (:class:`~rsm_lrg.model.build.spec.ModelSpec`,
the transform included), the factor space and the regression core
(:class:`~rsm_lrg.model.engines.least_squares.Regression`); coefficients, ANOVA, statistics and the
stationary point come from them. The transform lives here: :meth:`FitResult.predict`
back-transforms predictions and intervals in one place, and
:meth:`FitResult.goal_on_model_scale` maps a goal onto the model's scale for every optimiser.
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np

from ...errors import ParameterError
from ...factors import FactorSpace
from ...io import float_values
from ...table import column_values
from ..build.goals import parse_goal
from ..build.inputs import block_codes, coded_points, model_rows, unrounded_coding
from ..build.spec import ModelSpec, ReduceSpec
from ..build.terms import Term, column_names, design_matrix, n_columns
from ..build.transform import Transform
from ..contract.prediction import IntervalForm
from ..contract.statistics import FitStatistics
from ..contract.tolerance import TOLERANCE_PAIRS, add_tolerance_interval
from ..engines.least_squares import Regression
from ..readings.anova import PureError
from ..readings.canonical import StationaryPoint, canonical_analysis
from .kinds import LeastSquaresReading, PolynomialForm, REMLReading, form_of, json_number, reading_of

if TYPE_CHECKING:
    import dask.dataframe as dd
    import pandas as pd

    from ..choice.dsd import TwoStage
    from ..choice.reduce import Reduction
    from ..choice.select import Selection
    from ..engines.mixed import MixedModel

__all__ = ["FitResult", "assemble", "COEF_COLUMNS"]

#: Columns of :attr:`FitResult.coefficients`.
COEF_COLUMNS = ["coded", "std_error", "t", "p", "ci_low", "ci_high", "vif", "actual"]


@dataclass(frozen=True)
class FitResult:
    """A fitted model (frozen): the specification, the factor space and the regression core;
    everything else is derived from them on first use (cached), as statsmodels' results derive
    from ``params`` and ``normalized_cov_params``.

    Attributes
    ----------
    response : str
        Response column.
    spec : ModelSpec
        What was fitted: order or terms, intercept, transform, reduction
        (``model``, ``transform``, ``intercept`` and ``label`` read it).
    block : str or None
        Block column, if any.
    space : FactorSpace
        Factors with their coding (letters A, B, ...; about zero without an intercept).
    terms : tuple of Term
        Model terms in order (``terms[0]`` is the intercept when the model has one).
    least_squares : Regression
        The regression core's factorisation (:mod:`rsm_lrg.model.engines.least_squares`): sequential
        or partial sums of squares, sub-models, VIF, PRESS.
    raw_pure_error : PureError
        Residual of (blocks +) one mean per distinct setting (``pure_error`` is None when it
        has no degrees of freedom).
    column_names : tuple of str
        Names of the model matrix columns (blocks are ``"Block[B1]"``, ...).
    data : pandas.DataFrame
        The rows used (rows without a response are in ``omitted_data``).
    coded : pandas.DataFrame
        Coded factor settings, columns = letters (None for a Dask fit).
    y : ndarray
        Response on the model's scale (``g(y + k)`` under a transform).
    y_response : ndarray or None
        The response as measured.
    block_keys, block_levels
        ``("B1", ...)`` and ``{"B1": original label}``.
    input_notes : tuple of str
        Remarks on the input (columns taken as factors, left out, runs not run).
    omitted_rows : tuple of int
        1-based data rows left out because their response cell is empty.
    reduction : Reduction or None
        The backward elimination that chose the terms.
    mixed : MixedModel or None
        The mixed-model part of a REML fit (``fit(..., whole_plot=COL)`` or
        ``random_block=COL``; :mod:`rsm_lrg.model.engines.mixed`): variance components, Kenward–Roger
        tests, BLUPs. ``least_squares`` is then the regression core of the *whitened* data
        (``V^-1/2 X``, ``V^-1/2 y`` at the REML variance ratio), so coefficients, their
        covariance and ``sigma2`` are the GLS ones; ``fitted`` is ``X b`` (marginal),
        ``residuals`` the conditional residuals ``y - X b - Z u``, ``hat`` the leverages of the
        whitened model; the ANOVA holds the Kenward–Roger tests (no sums of squares) and
        PRESS, R² and lack of fit are not computed (NaN / none).

    Notes
    -----
    Derived (cached): ``coefficients`` (columns ``coded, std_error, t, p, ci_low, ci_high,
    vif, actual``), ``anova`` (Table 5 layout), ``statistics``, ``stationary_point``,
    ``fitted``, ``residuals``, ``hat``, ``cov_unscaled``, ``sigma2``, ``df_resid``,
    ``pure_error``, ``block_effects``, ``actual_coefficients``, ``actual_std_errors``,
    ``term_vif``, ``notes``, ``actual_deferred``, ``actual_solution``, ``design_matrix``,
    ``ols`` (statsmodels, built lazily),
    ``tests`` (the Kenward–Roger tests of a REML fit).
    """

    response: str
    spec: ModelSpec
    block: str | None
    space: FactorSpace
    terms: tuple
    least_squares: Regression = field(repr=False)
    raw_pure_error: PureError = field(repr=False)
    column_names: tuple = field(repr=False)
    data: pd.DataFrame | dd.DataFrame = field(repr=False)
    coded: pd.DataFrame | None = field(repr=False)
    y: np.ndarray | None = field(repr=False)
    y_response: np.ndarray | None = field(default=None, repr=False)
    block_keys: tuple | None = field(default=None, repr=False)
    block_levels: dict | None = field(default=None, repr=False)
    input_notes: tuple = field(default=(), repr=False)
    omitted_rows: tuple = field(default=(), repr=False)
    omitted_data: pd.DataFrame | None = field(default=None, repr=False)
    reduction: Reduction | Selection | TwoStage | None = field(default=None, repr=False)
    mixed: MixedModel | None = field(default=None, repr=False)
    reading: LeastSquaresReading | REMLReading = field(default_factory=LeastSquaresReading, repr=False)
    form: PolynomialForm = field(default_factory=PolynomialForm, repr=False)

    # -- what the regression core says ------------------------------------------------
    @property
    def model(self) -> str:
        """The model's order (``"linear"`` ... ``"cubic"``), or ``"custom"`` for chosen terms."""
        if self.reduction is not None:  # the model the elimination started from
            return self.spec.order if self.reduction.start_model != "custom" else "custom"
        return self.spec.order if self.spec.terms is None else "custom"

    @property
    def n_blocks(self) -> int:
        """Number of blocks (1 when unblocked)."""
        return len(self.column_names) - n_columns(self.terms) + 1

    @property
    def estimation(self) -> Regression | MixedModel:
        """The engine's part of the fit, which answers for the kind: the regression core (least
        squares) or the mixed model (REML). Fitted values, residuals, the interval form, the
        separate tests and the random effect come from it."""
        return self.reading.estimation(self)

    @property
    def fitted(self) -> np.ndarray | None:
        """ŷ on the model's scale (None for a Dask fit, which keeps no per-run arrays); for a
        REML fit the conditional ``X b + Z u`` (BLUPs u; nlme's default), so that
        ``y = fitted + residuals``; the marginal ``X b`` is ``mixed.marginal_fitted``."""
        return self.estimation.fitted

    @property
    def residuals(self) -> np.ndarray | None:
        """e = y - ŷ on the model's scale (None for a Dask fit); for a REML fit the
        conditional residuals ``y - X b - Z u`` (the estimated within-group errors)."""
        return self.estimation.residuals

    @property
    def hat(self) -> np.ndarray | None:
        """Leverage h_ii (None for a Dask fit)."""
        return self.least_squares.hat

    @property
    def cov_unscaled(self) -> np.ndarray:
        """``(X'X)^-1`` of the model matrix (intercept, block contrasts, terms)."""
        return self.least_squares.cov_unscaled

    @property
    def sigma2(self) -> float:
        """Residual mean square (NaN without residual degrees of freedom)."""
        return float(self.least_squares.sigma2)

    @property
    def df_resid(self) -> int:
        """Residual degrees of freedom, n - p."""
        return int(self.least_squares.df_resid)

    @cached_property
    def pure_error(self) -> PureError | None:
        """Pure error (R ``rsm``'s ``PE()``), or None when no setting is replicated (and for a
        REML fit: no lack-of-fit test against a pure error that mixes whole-plot variation)."""
        return self.reading.pure_error(self)

    @cached_property
    def tests(self) -> list:
        """The Kenward–Roger F tests of the model terms of a REML fit
        (:class:`~rsm_lrg.model.engines.mixed.KRTest`, one per term, no intercept); empty for OLS."""
        return self.estimation.contrast_tests(self.form.test_contrasts(self))

    @cached_property
    def sums(self) -> dict[str, Any]:
        """The sums of squares of the ANOVA from the core, by the model's form
        (:meth:`~rsm_lrg.model.results.kinds.PolynomialForm.sums`)."""
        return self.form.sums(self)

    @cached_property
    def anova(self) -> pd.DataFrame:
        """The Design-Expert ANOVA (Table 5 layout): columns ``source, sum_sq, df, mean_sq, f, p``.

        For a REML fit, one row per term with the Kenward–Roger test (``df`` its numerator df,
        a ``den_df`` column, ``sum_sq`` and ``mean_sq`` NaN: a GLS fit has no sums of squares
        that add up)."""
        return self.reading.anova(self)

    @cached_property
    def anova_rows(self) -> list[dict]:
        """:attr:`anova` as rows, ``{source, sum_sq, df, mean_sq, f, p}`` each (Python numbers;
        what the JSON and the text summary read, without building a DataFrame).

        Returns
        -------
        list of dict
            One dict per row of the ANOVA, in order.
        """
        return self.reading.anova_rows(self)

    @cached_property
    def notes(self) -> tuple:
        """Remarks for the text output: ``input_notes`` first, then the fit's own."""
        return tuple(self.input_notes) + self.reading.notes(self)

    @cached_property
    def actual_deferred(self) -> Any:
        """The model solved in actual units to the accuracy of the data up to the change of
        basis (:func:`rsm_lrg.model.readings.actual_units.solve_actual_deferred`: exact Gram
        matrix, refinement in double-double; its ``rss`` is what the statistics use), or None
        for a Dask fit (no per-run data), a mixture or REML fit, or when that solve refuses the
        data."""
        from ..readings.actual_units import is_closed_under_shift, solve_actual_deferred

        if (self.coded is None or self.y is None or not self.form.solves_in_actual_units
                or not self.reading.solves_in_actual_units):
            return None  # mixture, REML: the exact change of basis of the coded coefficients
        x = np.column_stack([np.asarray(column_values(self.coded, f.letter), dtype=float) if f.kind == "categoric"
                             else float_values(self.data, f.name) for f in self.space.factors])
        nb = self.n_blocks
        blocks = block_codes(self.data, self.block)[0] if self.block is not None and nb > 1 else None
        try:
            return solve_actual_deferred(
                x, np.asarray(self.y, dtype=float), self.terms, intercept=self.intercept, blocks=blocks, n_blocks=nb,
                decimal_inputs=self.transform.identity,  # a transformed response is not the file's decimals
                centre=[f.center if f.kind == "numeric" else 0.0 for f in self.space.factors],
                scale=[f.half_range if f.kind == "numeric" else 1.0 for f in self.space.factors],
                block_names=list(self.column_names[1:nb]),
                basis="actual" if is_closed_under_shift(self.terms, intercept=self.intercept) else "coded",
                letters=self.space.letters)
        except ValueError:
            return None

    @cached_property
    def actual_solution(self) -> Any:
        """The model solved in actual units to the accuracy of the data
        (:func:`rsm_lrg.model.readings.actual_units.solve_actual`: exact Gram matrix, refinement in
        double-double, an exact change of basis; :attr:`actual_deferred` carried through the
        change of basis), or None for a Dask fit (no per-run data) or when that solve refuses
        the data (the exact expansion of the coded coefficients is used then)."""
        deferred = self.actual_deferred
        if deferred is None:
            return None
        try:
            return deferred.solution()
        except ValueError:
            return None

    @cached_property
    def actual_coefficients(self) -> dict:
        """``{term: coefficient in actual units}``: the model solved in actual units
        (:attr:`actual_solution`), else the exact change of basis of the coded coefficients.
        A model not closed under the change of basis (``A^2`` without ``A``) has monomials
        beyond its terms in actual units; they are listed too."""
        sol = self.actual_solution
        if sol is not None:
            blocks = set(self.column_names[1:self.n_blocks])
            return {k: float(v) for k, v in sol.coefficients.items() if k not in blocks}
        return self._to_actual(dict(zip(column_names(self.terms), self.least_squares.params[self.term_index].tolist())))

    def _to_actual(self, coded: Mapping[str, float]) -> dict:
        """``{monomial: coefficient}`` in actual units of coded coefficients ``{column: value}``:
        the exact, linear change of basis (L-pseudo components to real proportions for a
        Scheffé model, coded to actual factors otherwise)."""
        return self.form.to_actual(dict(coded), self)

    @property
    def actual_std_errors(self) -> dict | None:
        """``{term: standard error in actual units}``: those of the actual-units solve (OLS), else
        the change of basis ``M`` (linear in the coefficients) applied to the coefficients'
        covariance, ``M cov M'`` (mixture, REML; None for a Dask fit, whose actual-units
        coefficients are not solved)."""
        sol = self.actual_solution
        if sol is not None:
            blocks = set(self.column_names[1:self.n_blocks])
            return {k: float(v) for k, v in sol.std_errors.items() if k not in blocks}
        if self.coded is None:
            return None
        cols = column_names(self.terms)
        basis = [self._to_actual(dict(zip(cols, e))) for e in np.eye(len(cols)).tolist()]
        names = list(dict.fromkeys(k for b in basis for k in b))
        M = np.array([[b.get(nm, 0.0) for b in basis] for nm in names])
        cov = M @ self.interval_form.cov_se @ M.T
        return dict(zip(names, np.sqrt(np.clip(np.diag(cov), 0.0, None)).tolist()))

    @cached_property
    def coefficient_columns(self) -> dict[str, Any]:
        """The columns of :attr:`coefficients` but ``actual`` (which needs the change of basis to
        actual units), as arrays: ``term`` (the names, a list), ``coded, std_error, t, p,
        ci_low, ci_high, vif`` and, for a REML fit, ``den_df`` (what the text summary prints,
        without building a DataFrame)."""
        from ..contract.statistics import stdtr, stdtrit  # the t and F tails without importing SciPy

        ls, tidx = self.least_squares, self.term_index
        b_t, se = ls.params[tidx], ls.std_errors[tidx]
        # the one-df tests of the coefficients from the interval form: OLS t = b / se on n - p df;
        # REML t = b / se_A (Kenward-Roger's adjusted covariance) on each coefficient's KR den df
        form = self.interval_form
        _, var_t, _, df = form.at(np.eye(len(tidx)))
        se_t = np.sqrt(var_t) if form.kenward_roger else se
        with np.errstate(divide="ignore", invalid="ignore"):
            tval = b_t / se_t
            pval = 2.0 * stdtr(df, -np.abs(tval))
            tq = stdtrit(df, 0.975)
        # VIF (Design-Expert's: the diagonal of the inverse correlation matrix) needs the
        # intercept to centre the columns; without one it is not defined (NaN); it is a property
        # of X'X, so none for a GLS fit
        vif = (np.r_[np.nan, ls.vif(tidx[1:])] if self.intercept and not form.kenward_roger
               else np.full(b_t.size, np.nan))
        out: dict[str, Any] = {"term": column_names(self.terms), "coded": b_t, "std_error": se, "t": tval, "p": pval,
                               "ci_low": b_t - tq * se_t, "ci_high": b_t + tq * se_t, "vif": vif}
        if form.kenward_roger:
            out["den_df"] = df
        return out

    @cached_property
    def coefficients(self) -> pd.DataFrame:
        """Index = term name; columns ``coded, std_error, t, p, ci_low, ci_high, vif, actual``."""
        import pandas as pd

        c = self.coefficient_columns
        cols = c["term"]
        actual = self.actual_coefficients
        frame = pd.DataFrame(
            {"coded": c["coded"], "std_error": c["std_error"], "t": c["t"], "p": c["p"], "ci_low": c["ci_low"],
             "ci_high": c["ci_high"], "vif": c["vif"], "actual": [actual.get(nm, 0.0) for nm in cols]},
            index=pd.Index(cols, name="term"))
        if "den_df" in c:
            frame["den_df"] = c["den_df"]
        return frame

    @cached_property
    def term_vif(self) -> dict:
        """Generalised VIF of each term when a categoric term has several columns (else empty)."""
        return self.reading.term_vif(self)

    @cached_property
    def statistics(self) -> FitStatistics:
        """R², adjusted and predicted R², PRESS, adequate precision, std dev, mean, C.V."""
        return self.reading.statistics(self)

    @cached_property
    def stationary_point(self) -> StationaryPoint:
        """The stationary point and canonical analysis (first categoric levels); none for a
        mixture model, whose components are not free."""
        coded = dict(zip(column_names(self.terms), self.least_squares.params[self.term_index].tolist()))
        return self.form.stationary_point(coded, self)

    @cached_property
    def block_effects(self) -> dict | None:
        """``{"B1": effect, ...}`` (sum to zero) [response units], or None."""
        nb = self.n_blocks
        if nb <= 1 or self.block_keys is None:
            return None
        eff = self.least_squares.params[1:nb].tolist()
        eff.append(-float(np.sum(eff)))
        return dict(zip(self.block_keys, eff))

    # -- the specification -------------------------------------------------------------
    @property
    def transform(self) -> Transform:
        """The response transform (the identity when the response is fitted as it is)."""
        return self.spec.transform

    @property
    def mixture(self) -> bool:
        """Whether this is a Scheffé mixture model (components coded as L-pseudo-components; no
        intercept column, the mean held implicitly; ANOVA and R² about the mean)."""
        return self.spec.mixture

    @property
    def intercept(self) -> bool:
        """Whether the model has an intercept."""
        return bool(self.terms) and self.terms[0].order == 0

    @property
    def model_terms(self) -> tuple:
        """The terms other than the intercept (the ANOVA's term rows)."""
        return tuple(t for t in self.terms if t.order > 0)

    @property
    def label(self) -> str:
        """The model in words: ``"quadratic, reduced (removed AB, B^2), log transform"``,
        ``"terms A B A^2, no intercept"``."""
        spec, red = self.spec, self.reduction
        if red is not None:
            parts = [f"{red.start_model}, reduced (removed {', '.join(red.removed) or 'nothing'})"]
        else:
            parts = [spec.order if spec.terms is None else "terms " + " ".join(t.name for t in self.model_terms)]
        parts += self.form.label_parts(self)
        if not self.transform.identity:
            parts.append(f"{self.transform.label} transform")
        return ", ".join(parts)

    def goal_on_model_scale(self, goal: Any) -> tuple[str, float | None, str, float | None]:
        """``(kind, target, kind on the model's scale, target on the model's scale)`` of a goal
        (``"minimize"``, ``"maximize"``, ``"target=V"``, ``("target", V)``): the one mapping
        of a goal onto a transformed response's scale (a decreasing transform swaps minimum
        and maximum, a target T becomes g(T + k)).

        Parameters
        ----------
        goal : str or tuple
            ``"minimize"``, ``"maximize"``, ``"target=V"`` or ``("target", V)`` (V in response units).

        Returns
        -------
        tuple
            ``(kind, target, kind on the model's scale, target on the model's scale)``.
        """
        kind, target = parse_goal(goal)
        mk, mt = self.transform.goal_on_model_scale(kind, target)
        return kind, target, mk, mt

    @cached_property
    def design_matrix(self) -> np.ndarray:
        """Full model matrix (intercept, block contrasts, terms), n x p, rebuilt from the coded
        settings on first access: a fit builds it in chunks and never holds it whole."""
        if self.coded is None:
            raise ValueError("a fit of a Dask DataFrame holds no per-run data (no design matrix, no statsmodels results)")
        bcodes = block_codes(self.data, self.block)[0] if self.block is not None else None
        nb = len(self.column_names) - n_columns(self.terms) + 1
        x = unrounded_coding(self.space, self.data, self.coded.to_numpy(dtype=float))  # as the fit built it
        return model_rows(x, self.terms, bcodes, nb)

    @cached_property
    def ols(self):
        """statsmodels ``RegressionResults`` of ``y`` on :attr:`design_matrix`, built lazily."""
        import statsmodels.api as sm

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return sm.OLS(self.y, self.design_matrix).fit()

    # -- views -----------------------------------------------------------------------
    @property
    def n(self) -> int:
        """Number of runs."""
        return int(self.least_squares.n) if self.least_squares is not None else int(self.y.size)

    @property
    def run_rows(self) -> list[int]:
        """1-based data rows of the runs used (``data``, ``y``, ``fitted``... in this order);
        the rows missing from it are ``omitted_rows`` (no response: "not run")."""
        left = set(self.omitted_rows)
        return [i for i in range(1, self.n + len(left) + 1) if i not in left]

    @property
    def term_names(self) -> list[str]:
        """The model's column names (``Intercept``, ``A``, ``AB``, ``A^2`` ...), in column order."""
        return [t.name for t in self.terms]

    @property
    def factors(self) -> list[str]:
        """Factor column names in letter order."""
        return self.space.names

    @property
    def term_index(self) -> np.ndarray:
        """Positions of the model's columns (intercept and terms) in ``design_matrix``
        (block contrasts skipped)."""
        nb = len(self.column_names) - n_columns(self.terms)
        return np.r_[0, np.arange(1 + nb, len(self.column_names))] if nb else np.arange(len(self.column_names))

    def _residuals_and_hat(self) -> tuple[np.ndarray, np.ndarray]:
        """``(residuals, hat)``; a Dask fit keeps no per-run arrays. For a REML fit those of the
        whitened model (scaled residuals ``V^-1/2 (y - X b)``)."""
        e, h = self.reading.scaled_residuals(self), self.hat
        if e is None or h is None:
            raise ValueError("a Dask fit keeps no per-run residuals or leverages")
        return e, h

    @property
    def studentized_residuals(self) -> np.ndarray:
        """Internally studentized residuals e_i / (σ √(1 - h_ii)) [-]."""
        e, h = self._residuals_and_hat()
        with np.errstate(divide="ignore", invalid="ignore"):
            return e / np.sqrt(self.sigma2 * (1.0 - h))

    @property
    def externally_studentized_residuals(self) -> np.ndarray:
        """Externally studentized (deleted) residuals, Design-Expert's "externally studentized" [-]."""
        r = self.studentized_residuals
        dfe = self.df_resid
        with np.errstate(divide="ignore", invalid="ignore"):
            return r * np.sqrt((dfe - 1) / (dfe - r ** 2))

    @property
    def cooks_distance(self) -> np.ndarray:
        """Cook's distance D_i = r_i² h_ii / (p (1 - h_ii)) [-]."""
        p = len(self.column_names)
        _, h = self._residuals_and_hat()
        with np.errstate(divide="ignore", invalid="ignore"):
            return self.studentized_residuals ** 2 * h / (p * (1.0 - h))

    def canonical(self, threshold: float | None = None, level: Mapping[str, str] | None = None) -> StationaryPoint:
        """Canonical analysis; ``threshold`` reproduces R ``rsm``'s ``canonical(threshold=)``;
        ``level`` picks the categoric levels (``{"stage": "rms"}``; first levels by default).

        Parameters
        ----------
        threshold : float, optional
            Eigenvalues smaller than this in absolute value are treated as zero, as R ``rsm``'s
            ``canonical(threshold=)``.
        level : mapping, optional
            The categoric levels to analyse at (``{"stage": "rms"}``; the first levels by default).

        Returns
        -------
        StationaryPoint
            The stationary point in coded and actual units, the prediction there, the eigenvalues
            and the kind (minimum, maximum or saddle).
        """
        coefs = dict(zip(self.coefficients.index, self.coefficients["coded"]))
        return canonical_analysis(coefs, self.terms, self.space, threshold=threshold, level=level)

    # -- prediction ------------------------------------------------------------------
    def predict_coded(self, coded: np.ndarray) -> np.ndarray:
        """ŷ at coded settings (n x k array), average block [response units].

        Parameters
        ----------
        coded : numpy.ndarray, shape (n, k)
            Settings in coded units (factor order).

        Returns
        -------
        numpy.ndarray, shape (n,)
            ŷ [response units].
        """
        Xt = design_matrix(coded, self.terms)
        return Xt @ self.coefficients["coded"].to_numpy()

    def predict(self, points: Any, interval: str | None = None, alpha: float = 0.05, *,
                coded: bool = False, tolerance: float | None = None) -> pd.DataFrame:
        """Predicted response in response units, optionally with a confidence or prediction
        interval; under a transform the prediction and the interval ends are back-transformed
        (ends ordered; ``predicted_transformed`` and ``se_fit`` stay on the model's scale).
        See :meth:`predict_model` for the parameters. ``tolerance=P`` adds the tolerance
        interval for a proportion P of runs with confidence ``1 - alpha``
        (:mod:`rsm_lrg.model.contract.tolerance`: ``ti_low``, ``ti_high`` and the one-sided bounds).

        Parameters
        ----------
        points : pandas.DataFrame, mapping or array_like
            Settings: a frame with the factor columns, ``{name: value(s)}`` or an (n, k) array in
            factor order; actual units unless ``coded``.
        interval : {None, "confidence", "prediction"}, optional
            Add the interval's ends (``ci_low``/``ci_high`` or ``pi_low``/``pi_high``).
        alpha : float, default 0.05
            1 - the interval's confidence.
        coded : bool, default False
            ``points`` are in coded units.
        tolerance : float, optional
            P of a two-sided tolerance interval (``ti_low``, ``ti_high``) covering P of new runs.

        Returns
        -------
        pandas.DataFrame
            One row per point: ``predicted`` [response units], ``se_fit``, and the interval ends
            asked for.
        """
        out = self.predict_model(points, interval=interval, alpha=alpha, coded=coded)
        if tolerance is not None:
            out = add_tolerance_interval(self, out, points, tolerance, alpha, coded=coded)
        tr = self.transform
        if tr.identity:
            return out
        out["predicted_transformed"] = out["predicted"]
        out["predicted"] = tr.inverse(out["predicted"].to_numpy())
        for lo, hi in (("ci_low", "ci_high"), ("pi_low", "pi_high"), *TOLERANCE_PAIRS):
            if lo in out:
                _, a, b = tr.back(out["predicted_transformed"].to_numpy(), out[lo].to_numpy(), out[hi].to_numpy())
                out[lo], out[hi] = a, b
        return out

    def predict_model(self, points: Any, interval: str | None = None, alpha: float = 0.05, *,
                      coded: bool = False) -> pd.DataFrame:
        """Prediction on the model's scale (the transformed response under a transform),
        optionally with a confidence or prediction interval.

        Parameters
        ----------
        points : DataFrame, mapping or array
            Settings in actual units: a frame (or ``{name: values}``) with the factor
            columns, or an (n, k) array in factor order. With ``coded=True`` the frame
            columns are the letters and values are coded.
        interval : {None, "confidence", "prediction", "both"}
            Which interval to add (``ci_low/ci_high``, ``pi_low/pi_high``).
        alpha : float
            1 - confidence level (0.05 gives 95 % intervals).

        Returns
        -------
        pandas.DataFrame
            Columns ``predicted`` and ``se_fit`` [response units] and the interval bounds;
            predictions are for the average block.
        """
        import pandas as pd

        from ..contract.statistics import stdtrit  # the t and F tails without importing SciPy

        if interval not in (None, "confidence", "prediction", "both"):
            raise ValueError(f"interval must be None, 'confidence', 'prediction' or 'both', not {interval!r}")
        if not 0.0 < alpha < 1.0:
            raise ParameterError("alpha", f"alpha must lie between 0 and 1, not {alpha!r}")
        index = points.index if isinstance(points, pd.DataFrame) else None
        with np.errstate(over="ignore"):  # a far point codes to a huge number or inf: refused there
            x = coded_points(self.space, points, coded)
        self.form.check_points(self.space, x)  # a Scheffé model speaks of blends that sum to the total
        Xt = design_matrix(x, self.terms)
        beta = self.coefficients["coded"].to_numpy()
        pred = Xt @ beta
        se, var_mean, var_new, df = self.interval_form.at(Xt)
        out = pd.DataFrame({"predicted": pred, "se_fit": se}, index=index)
        if interval:
            with np.errstate(invalid="ignore"):
                tq = stdtrit(df, 1 - alpha / 2)
            if interval in ("confidence", "both"):
                out["ci_low"] = pred - tq * np.sqrt(var_mean)
                out["ci_high"] = pred + tq * np.sqrt(var_mean)
            if interval in ("prediction", "both"):
                out["pi_low"] = pred - tq * np.sqrt(var_new)
                out["pi_high"] = pred + tq * np.sqrt(var_new)
        return out

    def coded_runs(self) -> pd.DataFrame:
        """The coded settings of the runs fitted (columns = letters); ValueError for a fit of a
        Dask frame, which keeps no per-run data.

        Returns
        -------
        pandas.DataFrame
            The table described above.
        """
        if self.coded is None:
            raise ValueError("a fit of a Dask DataFrame keeps no per-run data (fit an in-memory table)")
        return self.coded

    @cached_property
    def run_extent(self) -> dict[str, float]:
        """``{letter: largest |coded setting| over the runs}`` of the numeric factors, at least 1
        (the box; a CCD's axial runs reach beyond it); 1 for a Dask fit, which keeps no runs."""
        out = {}
        for f in self.space.factors:
            if f.kind == "categoric":
                continue
            col = np.zeros(0) if self.coded is None else np.abs(np.asarray(column_values(self.coded, f.letter), dtype=float))
            out[f.letter] = max(1.0, float(np.max(col, initial=0.0)))
        return out

    @cached_property
    def interval_form(self) -> IntervalForm:
        """How the uncertainty of a prediction follows from the model row (the prediction
        contract, :class:`~rsm_lrg.model.contract.prediction.IntervalForm`): OLS ``C σ²`` and ``n - p``
        df; REML the GLS ``Φ``, Kenward–Roger's ``Φ_A`` and a den df per point, a new run in a
        new whole plot or block."""
        return self.estimation.interval_form(self.term_index)

    def predictive(self, coded: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The prediction contract's predictive distribution of a new run at coded settings
        (n x k), on the model's scale: ``(mean, variance of a new run, df)`` — ``x b``,
        ``var_mean + s2_new`` and the t quantile's df of the interval form (average block).

        Parameters
        ----------
        coded : numpy.ndarray, shape (n, k)
            Settings in coded units (factor order).

        Returns
        -------
        tuple of numpy.ndarray
            ``(mean, variance of a new run, df)`` on the model's scale.
        """
        X = design_matrix(np.atleast_2d(np.asarray(coded, dtype=float)), self.terms)
        _, _, var_new, df = self.interval_form.at(X)
        return X @ self.coefficients["coded"].to_numpy(dtype=float), var_new, df

    def kr_mean(self, points: Any, *, coded: bool = False) -> tuple[np.ndarray, np.ndarray]:
        """For a REML fit: ``(x' Phi_A x, Kenward-Roger den df)`` of the predicted mean at each
        point (points as for :meth:`predict`) [model-scale units², -].

        Parameters
        ----------
        points : pandas.DataFrame, mapping or array_like
            Settings: a frame with the factor columns, ``{name: value(s)}`` or an (n, k) array in
            factor order; actual units unless ``coded``.
        coded : bool, default False
            ``points`` are in coded units.

        Returns
        -------
        tuple of numpy.ndarray
            ``(x' Phi_A x, den df)`` per point [model-scale units², -].
        """
        if not self.interval_form.kenward_roger:
            raise ValueError("kr_mean needs a REML fit (whole_plot=, random_block= or random_effects=)")
        _, var_mean, _, df = self.interval_form.at(design_matrix(coded_points(self.space, points, coded), self.terms))
        return var_mean, df

    # -- optimisation ------------------------------------------------------------------
    def optimize(self, goal="minimize", bounds=None, **kwargs):
        """Optimum of the fitted response in the factor box; see :func:`rsm_lrg.optimize.optimize`.

        A convenience: the optimize layer (above the model) provides it through
        :mod:`rsm_lrg.registry`; the model does not import it.

        Parameters
        ----------
        goal : str or tuple, default "minimize"
            ``"minimize"``, ``"maximize"``, ``"target=V"`` (on the response's own scale).
        bounds : mapping or list of str, optional
            Narrower bounds ``{name: (low, high)}`` in actual units (``["NAME=LOW:HIGH"]``).
        **kwargs
            Any other keyword argument of :func:`rsm_lrg.optimize.optimize`.

        Returns
        -------
        OptimumResult
            The best setting, its prediction [response units] and its confidence and prediction
            intervals.
        """
        from ...registry import lookup

        return lookup("FitResult.optimize")(self, goal=goal, bounds=bounds, **kwargs)

    # -- further analysis (issue 6) ------------------------------------------------------
    def diagnostics(self, **kwargs):
        """Per-run diagnostics and Box–Cox; see :func:`rsm_lrg.model.readings.diagnostics.diagnostics`.

        Parameters
        ----------
        **kwargs
            ``alpha`` and ``boxcox_rule``, as for :func:`rsm_lrg.model.readings.diagnostics.diagnostics`.

        Returns
        -------
        Diagnostics
            Per-run leverage, residuals (studentized), Cook's distance, DFFITS, and the Box–Cox
            search.
        """
        from ..readings.diagnostics import diagnostics as _diagnostics

        return _diagnostics(self, **kwargs)

    def ridge(self, goal="maximize", radius=None, step=0.1):
        """Ridge (second order) or steepest (first order) path; see :func:`rsm_lrg.model.readings.ridge.ridge`.

        Parameters
        ----------
        goal : {"maximize", "minimize"}, default "maximize"
            The direction of the path.
        radius : float, optional
            The path's end [coded units]; by default the largest distance of a design point
        from the centre.
        step : float, default 0.1
            The distance between the path's points [coded units].

        Returns
        -------
        RidgePath
            The path: per radius the coded and actual settings and the prediction.
        """
        from ..readings.ridge import ridge as _ridge

        return _ridge(self, goal=goal, radius=radius, step=step)

    def reduce(self, alpha_out: float = 0.1, criterion: str = "p") -> FitResult:
        """The model refitted with the terms kept by hierarchical backward elimination
        (see :func:`rsm_lrg.model.choice.reduce.reduce_terms`), on the same scale (transform).

        Parameters
        ----------
        alpha_out : float, default 0.1
            A term leaves while its p-value exceeds this (``criterion="p"``).
        criterion : {"p", "aicc", "bic"}, default "p"
            What backward elimination minimises.

        Returns
        -------
        FitResult
            The reduced model, refitted.
        """
        from dataclasses import replace

        from ...registry import lookup

        spec = replace(self.spec, terms=tuple(t.name for t in self.model_terms),
                       reduce=ReduceSpec(criterion=criterion, alpha_out=alpha_out))
        return lookup("fit")(self.data, self.response, factors=self.space, block=self.block, model=spec,
                             **self.random_effect)

    @property
    def random_effect(self) -> dict:
        """``{"whole_plot": COL}`` or ``{"random_block": COL}`` of a REML fit (the keyword
        :func:`rsm_lrg.fit` takes to refit it), else empty."""
        return self.estimation.random_effect

    # -- faces -------------------------------------------------------------------------
    def summary(self) -> str:
        """Design-Expert style text: ANOVA (Table 5 layout), statistics, coefficients,
        equations in coded and actual units, canonical analysis (under a transform, a first
        line says which: coefficients and ANOVA are on the transformed scale).

        Returns
        -------
        str
            Text for people, several lines.
        """
        from ..faces.text import format_summary

        text = format_summary(self)
        if not self.transform.identity:
            text = (f"Response {self.response} transformed: {self.transform.label} "
                    "(coefficients and ANOVA on the transformed scale)\n" + text)
        return text

    def __str__(self) -> str:
        return self.summary()

    def to_html(self, **kwargs) -> str:
        """The self-contained HTML report of this fit (see :func:`rsm_lrg.report.to_html`).

        A convenience: the report layer (above the model) provides it through
        :mod:`rsm_lrg.registry`; the model does not import it.

        Parameters
        ----------
        **kwargs
            ``title``, ``source_name``, ``goal``, ``hold``, ``optimum``: see
            :func:`rsm_lrg.report.report_context`.

        Returns
        -------
        str
            The HTML page, self-contained (no scripts, no network requests).
        """
        from ...registry import lookup

        return lookup("FitResult.to_html")(self, **kwargs)

    def effects(self, alpha: float = 0.05):
        """Effects of the one-df terms with Lenth's PSE, ME and SME and half-normal scores
        (:func:`rsm_lrg.model.readings.effects.screening_effects`), for unreplicated screening fits.

        Parameters
        ----------
        alpha : float, default 0.05
            The level of Lenth's margin of error (ME) and simultaneous margin (SME).

        Returns
        -------
        EffectsResult
            The effects, PSE, ME, SME and half-normal scores.
        """
        from ..readings.effects import screening_effects

        return screening_effects(self, alpha=alpha)

    def profiler(self, **kwargs):
        """The interactive prediction profiler of this fit, shown inline in a notebook (no
        server): see :func:`rsm_lrg.report.interactive.profiler` (``.save(path)`` writes the
        page). Provided by the report layer through :mod:`rsm_lrg.registry`.

        Parameters
        ----------
        **kwargs
            As for :func:`rsm_lrg.report.interactive.profiler` (``height``, ``tables``, goals ...).

        Returns
        -------
        Profiler
            Shown inline by a notebook; ``.save(path)`` writes the page.
        """
        from ...registry import lookup

        return lookup("FitResult.profiler")(self, **kwargs)

    def _repr_html_(self) -> str:
        """Notebook face: summary, ANOVA, statistics, coefficients, equations and the
        stationary point as one small HTML fragment, without figures (a few tens of kB);
        :meth:`to_html` gives the full report with every figure (provided by the report
        layer through :mod:`rsm_lrg.registry`)."""
        from ...registry import lookup

        return lookup("FitResult.notebook_html")(self)

    def to_dict(self) -> dict:
        """The fit JSON of INTERFACE.md (plain Python; NaN becomes ``null`` in JSON).

        Returns
        -------
        dict
            The ``fit --json`` document: plain Python, NaN where JSON writes ``null``.
        """
        coef = self.coefficient_columns  # the table's columns (no pandas.DataFrame built for the JSON)
        terms = coef["term"]
        out: dict[str, Any] = {
            "response": self.response,
            "n": self.n,
            "model": self.model,
            "block": self.block,
            "factors": self.space.to_list(),
            "coefficients": {
                "coded": {k: json_number(v) for k, v in zip(terms, coef["coded"])},
                "actual": {k: json_number(v) for k, v in self.actual_coefficients.items()},
            },
            "std_errors": {"coded": {k: json_number(v) for k, v in zip(terms, coef["std_error"])}},
        }
        if self.actual_std_errors is not None:
            out["std_errors"]["actual"] = {k: json_number(v) for k, v in self.actual_std_errors.items()}

        if self.block is not None:
            out["block_effects"] = {k: json_number(v) for k, v in (self.block_effects or {}).items()}
        out.update(self.reading.json_parts(self))
        out["statistics"] = {k: json_number(v) for k, v in self.statistics.to_dict().items()}
        out["stationary_point"] = self.stationary_point.to_dict()
        if self.term_vif:
            out["term_vif"] = {k: json_number(v) for k, v in self.term_vif.items()}
        out["notes"] = list(self.notes)
        out["omitted_rows"] = list(self.omitted_rows)  # 1-based data rows without a response
        out["terms"] = [t.name for t in self.model_terms]
        out["intercept"] = self.intercept
        if not self.transform.identity:
            out["transform"] = self.transform.to_dict()
        if self.reduction is not None:
            out["reduction"] = self.reduction.to_dict()
        return out

    def to_frame(self):
        """Per-run diagnostics: actual and coded settings, response, fitted, residual,
        leverage, studentized residuals, Cook's distance.

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
        if self.block is not None:
            df[self.block] = self.data[self.block].to_numpy()
        df[self.response] = self.y
        df["fitted"] = self.fitted
        df["residual"] = self.residuals
        df["leverage"] = self.hat
        df["studentized"] = self.studentized_residuals
        df["externally_studentized"] = self.externally_studentized_residuals
        df["cooks_distance"] = self.cooks_distance
        self.reading.add_run_columns(self, df)
        return df


def assemble(*, spec: ModelSpec, response: str, block: str | None, space: FactorSpace, terms: Sequence[Term],
             col_names: Sequence[str], ls: Regression, pe: PureError, bkeys: list | None, blevels: dict | None,
             data: pd.DataFrame | dd.DataFrame, coded: pd.DataFrame | None, y: np.ndarray | None,
             y_response: np.ndarray | None = None, input_notes: Sequence = (), omitted_rows: Sequence[int] = (),
             omitted_data: pd.DataFrame | None = None, reduction: Reduction | Selection | TwoStage | None = None,
             mixed: MixedModel | None = None) -> FitResult:
    """The :class:`FitResult` of a factorised fit (both passes done) and its pure error; every
    statistic is derived from them on first use.

    Without an intercept the model row and the total are uncorrected (``sum y^2``, n df),
    as R's ``lm`` and ``anova`` report them; R² is then ``1 - SS_res / sum y^2``.
    """
    return FitResult(response=response, spec=spec, block=block, space=space, terms=tuple(terms), least_squares=ls,
                     raw_pure_error=pe, column_names=tuple(col_names), data=data, coded=coded, y=y,
                     y_response=y_response, block_keys=None if bkeys is None else tuple(bkeys), block_levels=blevels,
                     input_notes=tuple(input_notes), omitted_rows=tuple(omitted_rows), omitted_data=omitted_data,
                     reduction=reduction, mixed=mixed, reading=reading_of(mixed), form=form_of(spec.mixture))
