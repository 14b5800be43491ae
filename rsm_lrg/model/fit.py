"""Fitting a response-surface model: :func:`fit` and its result :class:`FitResult`.

The model (linear, 2FI, quadratic — the paper's Eq. 19 — or cubic) is fitted by ordinary
least squares on the coded design matrix, in coded units ``x = (actual - centre) /
half_range``, by the regression core :mod:`rsm_lrg.model.least_squares`: a Householder
QR factorisation of the column-scaled matrix with the response centred (so a response of
1e9 + small variation loses no accuracy), accumulated over chunks of rows, and a second
pass for the hat diagonal. Everything else — the Design-Expert ANOVA (Table 5), PRESS,
VIF, intervals — is derived from that one factorisation (:attr:`FitResult.least_squares`);
no term is refitted and the n x p model matrix is never held whole, so a fit of 10^6 runs
costs a small multiple of one QR. The statsmodels results object of the same model matrix
is built on first access of :attr:`FitResult.ols`.

Blocks (optional) are sum-to-zero effects, as Design-Expert shows them; they enter the
ANOVA first (sequential SS) and stay out of the model row. Predictions and the optimum are
for the average block (block effect 0).

>>> import rsm_lrg
>>> r = rsm_lrg.fit(rsm_lrg.load_table4(), "tcr_c_per_min")
>>> round(r.statistics.r2, 3), round(float(r.coefficients.loc["C", "coded"]), 5)
(0.968, 0.0075)
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np

from ..factors import FactorSpace, _numeric, quote_value
from ..present import clean_anova
from .anova import PureError, anova_table, pure_error
from .canonical import StationaryPoint, canonical_analysis
from .data import prepare
from .least_squares import CHUNK_ROWS, Regression, factorise
from .statistics import FitStatistics, fit_statistics
from .terms import (
    MODELS,
    Term,
    check_model_size,
    column_names,
    design_matrix,
    model_matrix,
    model_terms,
    n_columns,
    term_columns,
    term_name,
)

__all__ = ["fit", "FitResult", "actual_coefficients", "actual_equations", "COEF_COLUMNS", "model_inputs", "ModelInputs"]

#: Columns of :attr:`FitResult.coefficients`.
COEF_COLUMNS = ["coded", "std_error", "t", "p", "ci_low", "ci_high", "vif", "actual"]


# ----------------------------------------------------------------------------------------
# coded -> actual coefficients (exact algebra)
# ----------------------------------------------------------------------------------------
def actual_coefficients(coded: Mapping[str, float], terms: Sequence[Term], space: FactorSpace) -> dict:
    """Coefficients of the same polynomial in actual units (no refit).

    Each coded monomial ``prod ((x_i - c_i) / h_i) ** e_i`` is expanded by the binomial
    theorem into monomials of the actual ``x_i``; the coefficients are collected by
    monomial and returned under the same column names (``"A"`` is then the coefficient of
    the actual thickness, and so on). For a hierarchical model (every standard model) the
    keys are exactly the coded keys. A categoric factor keeps its effect coding: the
    coefficient of ``"AE[rms]"`` multiplies the actual A and the effect code of level rms
    (:func:`actual_equations` gives one plain polynomial per level combination).
    """
    acc, names = _actual_expansion(coded, terms, space)
    out = {col: acc.get(key, 0.0) for key, col in names.items()}
    for (pw, sig), v in acc.items():
        if (pw, sig) not in names and v != 0.0:
            out[_column_label(pw, sig, space)] = v
    return out


def _actual_expansion(coded: Mapping[str, float], terms: Sequence[Term], space: FactorSpace) -> tuple[dict, dict]:
    """``({(numeric exponents, categoric (factor, level) pairs): actual coefficient}, {same key: column name})``."""
    from math import comb

    k = len(space)
    num = [f.kind == "numeric" for f in space.factors]
    centres = [f.center if nu else 0.0 for f, nu in zip(space.factors, num)]
    halves = [f.half_range if nu else 1.0 for f, nu in zip(space.factors, num)]
    acc: dict[tuple, float] = {}
    names: dict[tuple, str] = {}
    for t in terms:
        npw = t.numeric_powers
        for combo, col in zip(t.level_combinations() if t.cat else [()], t.columns):
            sig = tuple((i, j) for (i, _), j in zip(t.cat, combo))
            names[(npw, sig)] = col
            c = float(coded[col])
            parts = [((), c)]  # expand factor by factor: list of (powers, coefficient)
            for i in range(k):
                e = npw[i]
                new = []
                for pw, v in parts:
                    for m in range(e + 1):
                        coef = comb(e, m) * (-centres[i]) ** (e - m) / halves[i] ** e
                        new.append((pw + (m,), v * coef))
                parts = new
            for pw, v in parts:
                acc[(pw, sig)] = acc.get((pw, sig), 0.0) + v
    return acc, names


def _column_label(pw: tuple, sig: tuple, space: FactorSpace) -> str:
    """Name of the column with numeric exponents ``pw`` and categoric ``(factor, level)`` ``sig``."""
    powers = list(pw)
    for i, _ in sig:
        powers[i] = 1
    letters = space.letters
    t = Term(tuple(powers), term_name(powers, letters), tuple((i, space.factors[i].levels) for i, _ in sig),
             tuple(letters[i] for i, _ in sig))
    return t.columns[t.level_combinations().index(tuple(j for _, j in sig))] if sig else t.name


def actual_equations(result, coded: Mapping[str, float] | None = None) -> list[tuple[dict, dict]]:
    """The fitted polynomial in actual units once per combination of categoric levels
    (Design-Expert's "stage = rfcms: ..." equations): ``[({name: level}, {term: coefficient})]``,
    the terms being numeric monomials (``"A"``, ``"AB"``, ``"A^2"``, ``"Intercept"``).
    One entry with an empty setting when every factor is numeric. ``coded`` replaces the
    fitted coded coefficients (by column name)."""
    space, letters = result.space, result.space.letters
    cats = [i for i, f in enumerate(space.factors) if f.kind == "categoric"]
    if coded is None:
        coded = dict(zip(result.coefficients.index, result.coefficients["coded"]))
    acc, _ = _actual_expansion(coded, result.terms, space)
    out = []
    for setting in space.level_combinations():
        idx = {i: space.factors[i].levels.index(setting[space.factors[i].name]) for i in cats}
        eq: dict[str, float] = {}
        for (pw, sig), v in acc.items():
            for i, j in sig:
                last = len(space.factors[i].levels) - 1
                v *= 1.0 if idx[i] == j else (-1.0 if idx[i] == last else 0.0)
            if sig and v == 0.0:
                continue
            key = term_name(pw, letters)
            eq[key] = eq.get(key, 0.0) + v
        out.append((setting, eq))
    return out


# ----------------------------------------------------------------------------------------
# the result
# ----------------------------------------------------------------------------------------
@dataclass(frozen=True)
class FitResult:
    """A fitted response-surface model (frozen).

    Attributes
    ----------
    response : str
        Response column.
    model : str
        ``"linear"``, ``"2fi"``, ``"quadratic"`` or ``"cubic"``.
    block : str or None
        Block column, if any.
    space : FactorSpace
        Factors with their coding (letters A, B, ...).
    terms : tuple of Term
        Model terms in order (``terms[0]`` is the intercept).
    data : pandas.DataFrame
        The rows used (a copy; rows without a response are in ``omitted_data``).
    coded : pandas.DataFrame
        Coded factor settings, columns = letters.
    y : ndarray
        Response [response units].
    design_matrix : ndarray
        Full model matrix (intercept, block contrasts, terms), n x p; rebuilt from
        ``coded`` on first access (a cached property: a fit never holds it whole).
    column_names : tuple of str
        Names of the ``design_matrix`` columns (blocks are ``"Block[B1]"``, ...).
    coefficients : pandas.DataFrame
        Index = term name; columns ``coded, std_error, t, p, ci_low, ci_high, vif, actual``
        (std_error, t, p, CI and VIF refer to the coded coefficient; 95 % CI).
    anova : pandas.DataFrame
        Columns ``source, sum_sq, df, mean_sq, f, p``; rows Model, each term (Type III),
        Block, Residual, Lack of Fit, Pure Error, Cor Total (as Table 5).
    statistics : FitStatistics
    stationary_point : StationaryPoint
    fitted, residuals, hat : ndarray
        ŷ, e = y - ŷ, leverage h_ii.
    cov_unscaled : ndarray
        ``(X'X)^-1`` of ``design_matrix``.
    sigma2 : float
        Residual mean square [response units²].
    df_resid : int
    block_effects : dict or None
        ``{"B1": effect, ...}`` (sum to zero) [response units].
    block_levels : dict or None
        ``{"B1": original label, ...}``.
    pure_error : PureError or None
        Pure error: residual of (blocks +) one mean per distinct factor setting, as R
        ``rsm``'s ``PE()`` test (``None`` when it has no degrees of freedom).
    actual_coefficients : dict
        ``{term: coefficient in actual units}``.
    ols : statsmodels RegressionResults
        statsmodels' OLS of ``y`` on ``design_matrix``, built on first access (a cached
        property; the numbers above come from :attr:`least_squares`, not from it).
    least_squares : Regression
        The regression core's factorisation (:mod:`rsm_lrg.model.least_squares`): ask it for
        sequential or partial sums of squares, sub-models, VIF, PRESS.
    notes : tuple of str
        Remarks for the text output: ``input_notes`` first, then the fit's own (e.g. why
        there is no lack-of-fit test).
    input_notes : tuple of str
        Remarks on the input (:func:`rsm_lrg.model.data.prepare`): which columns were taken
        as factors when they were inferred, every column left out (neither factor, response,
        block nor bookkeeping), the runs left out for want of a response.
    omitted_rows : tuple of int
        1-based data rows left out because their response cell is empty ("not run").
    omitted_data : pandas.DataFrame or None
        Those rows as given (index = 0-based position in the input); ``data`` holds the
        rows used.
    """

    response: str
    model: str
    block: str | None
    space: FactorSpace
    terms: tuple
    data: Any = field(repr=False)
    coded: Any = field(repr=False)
    y: np.ndarray = field(repr=False)
    column_names: tuple = field(repr=False)
    coefficients: Any = field(repr=False)
    anova: Any = field(repr=False)
    statistics: FitStatistics = field(repr=False)
    stationary_point: StationaryPoint = field(repr=False)
    fitted: np.ndarray = field(repr=False)
    residuals: np.ndarray = field(repr=False)
    hat: np.ndarray = field(repr=False)
    cov_unscaled: np.ndarray = field(repr=False)
    sigma2: float = field(repr=False)
    df_resid: int = field(repr=False)
    block_effects: dict | None = field(repr=False)
    block_levels: dict | None = field(repr=False)
    pure_error: PureError | None = field(repr=False)
    actual_coefficients: dict = field(repr=False)
    notes: tuple = field(default=(), repr=False)
    input_notes: tuple = field(default=(), repr=False)
    omitted_rows: tuple = field(default=(), repr=False)
    omitted_data: Any = field(default=None, repr=False)
    least_squares: Regression | None = field(default=None, repr=False)
    term_vif: dict = field(default_factory=dict, repr=False)

    @cached_property
    def design_matrix(self) -> np.ndarray:
        """Full model matrix (intercept, block contrasts, terms), n x p, rebuilt from the coded
        settings on first access: a fit builds it in chunks and never holds it whole."""
        if self.coded is None:
            raise ValueError("a fit of a Dask DataFrame holds no per-run data (no design matrix, no statsmodels results)")
        bcodes = _block_codes(self.data, self.block)[0] if self.block is not None else None
        nb = len(self.column_names) - n_columns(self.terms) + 1
        return _model_rows(self.coded.to_numpy(dtype=float), self.terms, bcodes, nb)

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
        return [t.name for t in self.terms]

    @property
    def factors(self) -> list[str]:
        """Factor column names in letter order."""
        return self.space.names

    @property
    def _term_index(self) -> np.ndarray:
        """Positions of the model terms in ``design_matrix`` (blocks skipped)."""
        nb = len(self.column_names) - n_columns(self.terms)
        return np.r_[0, np.arange(1 + nb, len(self.column_names))] if nb else np.arange(len(self.column_names))

    @property
    def studentized_residuals(self) -> np.ndarray:
        """Internally studentized residuals e_i / (σ √(1 - h_ii)) [-]."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return self.residuals / np.sqrt(self.sigma2 * (1.0 - self.hat))

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
        with np.errstate(divide="ignore", invalid="ignore"):
            return self.studentized_residuals ** 2 * self.hat / (p * (1.0 - self.hat))

    def canonical(self, threshold: float | None = None, level: Mapping[str, str] | None = None) -> StationaryPoint:
        """Canonical analysis; ``threshold`` reproduces R ``rsm``'s ``canonical(threshold=)``;
        ``level`` picks the categoric levels (``{"stage": "rms"}``; first levels by default)."""
        coefs = dict(zip(self.coefficients.index, self.coefficients["coded"]))
        return canonical_analysis(coefs, self.terms, self.space, threshold=threshold, level=level)

    # -- prediction ------------------------------------------------------------------
    def _coded_points(self, points, coded: bool) -> np.ndarray:
        import pandas as pd

        if isinstance(points, Mapping):
            vals = {k: np.atleast_1d(np.asarray(v, dtype=object if self.space.has_categoric else float))
                    for k, v in points.items()}
            points = pd.DataFrame(vals)
        if isinstance(points, pd.Series):
            points = points.to_frame().T
        if isinstance(points, pd.DataFrame):
            cols = self.space.letters if coded else self.space.names
            missing = [c for c in cols if c not in points.columns]
            if missing:
                raise ValueError(f"prediction points lack the factor column(s) {', '.join(map(repr, missing))}")
            if coded:
                return np.column_stack([_numeric(points, c).to_numpy() for c in cols])
            return self.space.encode(points[cols]).to_numpy(dtype=float)
        arr = np.asarray(points, dtype=object if self.space.has_categoric and not coded else float)
        if arr.ndim == 1:
            arr = arr[None, :]
        if arr.shape[-1] != len(self.space):
            raise ValueError(f"prediction points need {len(self.space)} columns (one per factor), got {arr.shape[-1]}")
        if not coded:
            arr = self.space.encode(arr)
        if not np.isfinite(arr).all():
            raise ValueError("prediction points must be finite numbers")
        return arr

    def predict_coded(self, coded: np.ndarray) -> np.ndarray:
        """ŷ at coded settings (n x k array), average block [response units]."""
        Xt = design_matrix(coded, self.terms)
        return Xt @ self.coefficients["coded"].to_numpy()

    def predict(self, points, interval: str | None = None, alpha: float = 0.05, *, coded: bool = False):
        """Predicted response, optionally with a confidence or prediction interval.

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

        from . import statistics as special  # the t and F tails without importing SciPy

        if interval not in (None, "confidence", "prediction", "both"):
            raise ValueError(f"interval must be None, 'confidence', 'prediction' or 'both', not {interval!r}")
        if not 0.0 < alpha < 1.0:
            raise ValueError(f"alpha must lie between 0 and 1, not {alpha!r}")
        index = points.index if isinstance(points, pd.DataFrame) else None
        with np.errstate(over="ignore"):  # a far point codes to a huge number or inf: refused below
            x = self._coded_points(points, coded)
        far = ~(np.abs(x) <= MAX_FACTOR_MAGNITUDE)
        if far.any():  # a polynomial there overflows (and says nothing): refuse with the factor named
            i, j = np.argwhere(far)[0]
            f = self.space.factors[j]
            raise ValueError(f"prediction point {i + 1}: factor {f.name!r} is more than {MAX_FACTOR_MAGNITUDE:.0e} "
                             f"half-ranges from its centre ({f.center:.6g}); the model says nothing there")
        Xt = design_matrix(x, self.terms)
        beta = self.coefficients["coded"].to_numpy()
        pred = Xt @ beta
        idx = self._term_index
        C = self.cov_unscaled[np.ix_(idx, idx)]
        q = np.einsum("ij,jk,ik->i", Xt, C, Xt)
        se = np.sqrt(q * self.sigma2)
        out = pd.DataFrame({"predicted": pred, "se_fit": se}, index=index)
        if interval:
            tq = float(special.stdtrit(self.df_resid, 1 - alpha / 2)) if self.df_resid > 0 else np.nan
            if interval in ("confidence", "both"):
                out["ci_low"] = pred - tq * se
                out["ci_high"] = pred + tq * se
            if interval in ("prediction", "both"):
                spi = np.sqrt((1.0 + q) * self.sigma2)
                out["pi_low"] = pred - tq * spi
                out["pi_high"] = pred + tq * spi
        return out

    # -- optimisation ------------------------------------------------------------------
    def optimize(self, goal="minimize", bounds=None, **kwargs):
        """Optimum of the fitted response in the factor box; see :func:`rsm_lrg.optimize.optimize`.

        A convenience: the optimize layer (above the model) provides it through
        :mod:`rsm_lrg.registry`; the model does not import it."""
        from ..registry import lookup

        return lookup("FitResult.optimize")(self, goal=goal, bounds=bounds, **kwargs)

    # -- further analysis (issue 6) ------------------------------------------------------
    def diagnostics(self, **kwargs):
        """Per-run diagnostics and Box–Cox; see :func:`rsm_lrg.model.diagnostics.diagnostics`."""
        from .diagnostics import diagnostics as _diagnostics

        return _diagnostics(self, **kwargs)

    def ridge(self, goal="maximize", radius=None, step=0.1):
        """Ridge (second order) or steepest (first order) path; see :func:`rsm_lrg.model.ridge.ridge`."""
        from .ridge import ridge as _ridge

        return _ridge(self, goal=goal, radius=radius, step=step)

    def reduce(self, alpha_out: float = 0.1, criterion: str = "p") -> FitResult:
        """The model refitted with the terms kept by hierarchical backward elimination
        (see :func:`rsm_lrg.model.reduce.reduce_terms`)."""
        from .reduce import reduce_terms

        red = reduce_terms(self.data, self.response, factors=self.space, block=self.block,
                           alpha_out=alpha_out, criterion=criterion, terms=self.term_names[1:])
        return fit(self.data, self.response, factors=self.space, block=self.block, model=self.model,
                   terms=red.kept[1:])

    # -- faces -------------------------------------------------------------------------
    def summary(self) -> str:
        """Design-Expert style text: ANOVA (Table 5 layout), statistics, coefficients,
        equations in coded and actual units, canonical analysis."""
        from .text import format_summary

        return format_summary(self)

    def __str__(self) -> str:
        return self.summary()

    def to_html(self, **kwargs) -> str:
        """The self-contained HTML report of this fit (see :func:`rsm_lrg.report.to_html`).

        A convenience: the report layer (above the model) provides it through
        :mod:`rsm_lrg.registry`; the model does not import it.
        """
        from ..registry import lookup

        return lookup("FitResult.to_html")(self, **kwargs)

    def effects(self, alpha: float = 0.05):
        """Effects of the one-df terms with Lenth's PSE, ME and SME and half-normal scores
        (:func:`rsm_lrg.model.effects.screening_effects`), for unreplicated screening fits."""
        from .effects import screening_effects

        return screening_effects(self, alpha=alpha)

    def profiler(self, **kwargs):
        """The interactive prediction profiler of this fit, shown inline in a notebook (no
        server): see :func:`rsm_lrg.report.interactive.profiler` (``.save(path)`` writes the
        page). Provided by the report layer through :mod:`rsm_lrg.registry`."""
        from ..registry import lookup

        return lookup("FitResult.profiler")(self, **kwargs)

    def _repr_html_(self) -> str:
        """Notebook face: summary, ANOVA, statistics, coefficients, equations and the
        stationary point as one small HTML fragment, without figures (a few tens of kB);
        :meth:`to_html` gives the full report with every figure (provided by the report
        layer through :mod:`rsm_lrg.registry`)."""
        from ..registry import lookup

        return lookup("FitResult.notebook_html")(self)

    def to_dict(self) -> dict:
        """The fit JSON of INTERFACE.md (plain Python; NaN becomes ``null`` in JSON)."""
        coef = self.coefficients
        out = {
            "response": self.response,
            "n": self.n,
            "model": self.model,
            "block": self.block,
            "factors": self.space.to_list(),
            "coefficients": {
                "coded": {k: _f(v) for k, v in coef["coded"].items()},
                "actual": {k: _f(v) for k, v in self.actual_coefficients.items()},
            },
            "std_errors": {"coded": {k: _f(v) for k, v in coef["std_error"].items()}},
        }
        if self.block is not None:
            out["block_effects"] = {k: _f(v) for k, v in (self.block_effects or {}).items()}
        out["anova"] = [
            {"source": r.source, "sum_sq": _f(r.sum_sq), "df": int(r.df), "mean_sq": _f(r.mean_sq), "f": _f(r.f), "p": _f(r.p)}
            for r in self.anova.itertuples(index=False)
        ]
        out["statistics"] = {k: _f(v) for k, v in self.statistics.to_dict().items()}
        out["stationary_point"] = self.stationary_point.to_dict()
        if self.term_vif:
            out["term_vif"] = {k: _f(v) for k, v in self.term_vif.items()}
        out["notes"] = list(self.notes)
        out["omitted_rows"] = list(self.omitted_rows)  # 1-based data rows without a response
        return out

    def to_frame(self):
        """Per-run diagnostics: actual and coded settings, response, fitted, residual,
        leverage, studentized residuals, Cook's distance."""
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
        return df


def _f(v):
    try:
        x = float(v)
    except (TypeError, ValueError):
        return None
    return x if math.isfinite(x) else None


# ----------------------------------------------------------------------------------------
# fit()
# ----------------------------------------------------------------------------------------
def _block_codes(data, block: str):
    """Integer codes 0..b-1 (levels sorted), keys "B1".., level labels."""
    import pandas as pd

    col = data[block]
    if col.isna().any():
        i = int(np.flatnonzero(col.isna().to_numpy())[0])
        raise ValueError(f"block column {quote_value(block)}, row {i + 1}: is empty")
    num = pd.to_numeric(col, errors="coerce")
    if not num.isna().any():
        labels = num.to_numpy(dtype=float)
        levels = np.unique(labels)
        codes = np.searchsorted(levels, labels)
        shown = [int(v) if float(v).is_integer() else float(v) for v in levels]
    else:
        labels = col.astype(str).str.strip().to_numpy()
        levels = np.unique(labels)
        codes = np.searchsorted(levels, labels)
        shown = [str(v) for v in levels]
    if len(levels) < 2:
        raise ValueError(f"block column {quote_value(block)} has a single level ({quote_value(shown[0])}); "
                         "a block column needs at least two")
    keys = [f"B{i + 1}" for i in range(len(levels))]
    return codes.astype(int), keys, dict(zip(keys, shown))


def _chosen_terms(names, letters, categoric=None) -> tuple:
    """The named terms (plus the intercept), without repeats, in Design-Expert order."""
    from .terms import parse_term

    if isinstance(names, str):
        names = [names]
    chosen = {}
    for nm in ["Intercept", *names]:
        t = parse_term(str(nm).strip(), letters, categoric) if not isinstance(nm, Term) else nm
        chosen[t.powers] = t
    order = {t.powers: i for i, t in enumerate(model_terms(letters, "cubic", categoric))}
    return tuple(sorted(chosen.values(), key=lambda t: (order.get(t.powers, len(order)), t.order, t.powers)))


#: Largest magnitude of a response value (and smallest spread) that a fit accepts: sums of
#: squares of such numbers stay far from overflow and underflow.
MAX_MAGNITUDE = 1e100
#: Largest magnitude of a factor value (and smallest half-range): the actual-units
#: coefficients of a cubic, up to ``b (c/h)^3 / h^3``, then stay finite.
MAX_FACTOR_MAGNITUDE = 1e50


def _check_magnitudes(space: FactorSpace, y: np.ndarray, response: str) -> None:
    """Refuse numbers whose squares or cubes would overflow (a clear error, not inf/NaN later)."""
    big = float(np.max(np.abs(y))) if y.size else 0.0
    if big > MAX_MAGNITUDE:
        raise ValueError(f"response {response!r} holds {big:.3g}, beyond the ±{MAX_MAGNITUDE:.0e} a fit computes with "
                         "(its squares would overflow); rescale the column (e.g. change its unit)")
    spread = float(np.ptp(y)) if y.size else 0.0
    if 0.0 < spread < 1.0 / MAX_MAGNITUDE:
        raise ValueError(f"response {response!r} varies only by {spread:.3g}, below the {1 / MAX_MAGNITUDE:.0e} a fit "
                         "computes with (its squares would underflow); rescale the column (e.g. change its unit)")
    for f in space.numeric:
        size = max(abs(f.low), abs(f.high), abs(f.center))
        if not size <= MAX_FACTOR_MAGNITUDE:
            raise ValueError(f"factor {f.name!r} reaches {size:.3g}, beyond the ±{MAX_FACTOR_MAGNITUDE:.0e} a fit "
                             "computes with (its powers would overflow); rescale the column (e.g. change its unit)")
        if not f.half_range >= 1.0 / MAX_FACTOR_MAGNITUDE:
            raise ValueError(f"factor {f.name!r} spans only {2 * f.half_range:.3g}, below the "
                             f"{1 / MAX_FACTOR_MAGNITUDE:.0e} a fit computes with; rescale the column (e.g. change its unit)")


def _model_rows(x: np.ndarray, terms, bcodes: np.ndarray | None, nb: int, start: int = 0,
                stop: int | None = None) -> np.ndarray:
    """Rows ``start:stop`` of the model matrix (:func:`~rsm_lrg.model.terms.model_matrix`)."""
    return model_matrix(x[start:stop], terms, None if bcodes is None else bcodes[start:stop], nb)


@dataclass(frozen=True)
class ModelInputs:
    """The checked inputs of a fit (:func:`model_inputs`): the same for :func:`fit`,
    :func:`~rsm_lrg.model.summary.fit_summary` and :func:`~rsm_lrg.model.reduce.reduce_terms`.

    Attributes
    ----------
    prep : PreparedData
    space : FactorSpace
    coded : pandas.DataFrame
        Coded settings, columns = letters.
    x : (n, k) ndarray
        The same as an array.
    y : (n,) ndarray
        Response [response units].
    block : str or None
    bcodes : ndarray of int or None
        Block code 0..b-1 of each run.
    bkeys : list of str or None
        ``["B1", ...]``.
    blevels : dict or None
        ``{"B1": original label, ...}``.
    """

    prep: Any
    space: FactorSpace
    coded: Any
    x: np.ndarray
    y: np.ndarray
    block: str | None
    bcodes: np.ndarray | None
    bkeys: list | None
    blevels: dict | None

    @property
    def n(self) -> int:
        return int(self.y.size)

    @property
    def nb(self) -> int:
        """Number of blocks (1 when unblocked)."""
        return len(self.bkeys) if self.bkeys else 1

    @property
    def hint(self) -> str:
        return self.prep.choice.hint()

    def column_names(self, terms) -> list[str]:
        names = column_names(terms)
        if self.nb > 1:
            return ["Intercept"] + [f"Block[{k}]" for k in self.bkeys[:-1]] + names[1:]
        return names

    def term_columns(self, terms) -> np.ndarray:
        """Positions of the model terms among the columns (blocks skipped)."""
        p = n_columns(terms) + self.nb - 1
        return np.r_[0, np.arange(self.nb, p)] if self.nb > 1 else np.arange(p)

    def rows(self, terms, start: int = 0, stop: int | None = None) -> np.ndarray:
        return _model_rows(self.x, terms, self.bcodes, self.nb, start, stop)

    def chunks(self, terms, rows: int = CHUNK_ROWS):
        """``chunks()`` iterates over ``(model-matrix rows, responses)`` of ``rows`` runs each."""
        n = self.n
        return lambda: ((self.rows(terms, s, s + rows), self.y[s:s + rows]) for s in range(0, n, rows))


def _is_dask(data) -> bool:
    """A Dask DataFrame (checked by its module, so dask is not imported for a pandas fit)."""
    return type(data).__module__.split(".")[0] == "dask" and hasattr(data, "map_partitions")


def model_inputs(data, response: str, factors=None, block: str | None = None) -> ModelInputs:
    """Check the data and code the factors as every fit does (see :func:`fit` for what is refused)."""
    import pandas as pd

    if not isinstance(data, pd.DataFrame):
        raise TypeError("data must be a pandas DataFrame")
    # columns, factors (inferred from a design's coded columns when not given), runs
    # without a response left out, notes on everything left out (rsm_lrg.model.data)
    prep = prepare(data, response, factors, block)
    data, space, y = prep.data, prep.space, prep.y
    coded = space.encode(data)
    x = coded.to_numpy(dtype=float)
    for j, f in enumerate(space.factors):
        if np.unique(x[:, j]).size < 2:
            raise ValueError(f"factor column {f.name!r} is constant; a factor needs at least two levels")
    _check_magnitudes(space, y, response)
    if np.all(y == y[0]):
        raise ValueError(f"response {response!r} is constant (all {y[0]:.6g}): nothing to model")
    if block is not None:
        bcodes, bkeys, blevels = _block_codes(data, block)
    else:
        bcodes, bkeys, blevels = None, None, None
    return ModelInputs(prep=prep, space=space, coded=coded, x=x, y=y, block=block, bcodes=bcodes, bkeys=bkeys,
                       blevels=blevels)


def fit(data, response: str, factors=None, block: str | None = None, model: str = "quadratic", *,
        terms=None, chunk_rows: int = CHUNK_ROWS) -> FitResult:
    """Fit a response-surface model by OLS in coded units (paper Eq. 19, Table 5).

    Parameters
    ----------
    data : pandas.DataFrame or dask.dataframe.DataFrame
        One row per run. A Dask DataFrame is fitted partition by partition without being
        collected (:mod:`rsm_lrg.model.dask_fit`; the result holds no per-run arrays).
    response : str
        Response column (e.g. ``"tcr_c_per_min"`` [°C/min]).
    factors : None, sequence or FactorSpace
        ``None``: inferred (:func:`rsm_lrg.factors.choose_factors`): data carrying a
        design's ``coded_A``, ``coded_B``, ... columns (a design CSV or ``simulate``'s
        output) are fitted on the design's factors, coded as the design codes them;
        other data on every numeric column except the response, the block and
        bookkeeping columns. The notes say which columns were taken and which left out.
        Or names, ``"NAME=LOW:HIGH"`` strings (levels coded -1 and +1), or a
        :class:`~rsm_lrg.factors.FactorSpace`. A name without levels is coded from the
        observed minimum and maximum. Rows whose response cell is empty are left out
        (``omitted_rows``, a note).
    block : str, optional
        Block column (any labels); block effects sum to zero.
    model : {"linear", "2fi", "quadratic", "cubic"}
    terms : sequence of str, optional
        Fit only these terms (names as ``"A"``, ``"AC"``, ``"C^2"``; the intercept is always
        included), e.g. the terms kept by :func:`rsm_lrg.model.reduce.reduce_terms`; they are
        put in Design-Expert order. ``model`` then only labels the result.
    chunk_rows : int
        Rows of the model matrix built and factorised at a time (the full n x p matrix is
        never held; :mod:`rsm_lrg.model.least_squares`).

    Returns
    -------
    FitResult

    Raises
    ------
    ValueError
        Unknown or non-numeric columns (naming the row), a constant factor, a constant
        response, numbers beyond 1e±100 (response) or 1e±50 (factors), fewer runs than
        model terms (counted before any term is built), aliased terms (naming them).
    """
    import pandas as pd

    if model not in MODELS:
        raise ValueError(f"unknown model {model!r}; expected one of {', '.join(MODELS)}")
    if _is_dask(data):  # fitted partition by partition, never collected
        from .dask_fit import fit_dask

        return fit_dask(data, response, factors=factors, block=block, model=model, terms=terms,
                        chunk_rows=chunk_rows)
    if not isinstance(data, pd.DataFrame):
        raise TypeError("data must be a pandas DataFrame")
    if model not in MODELS:
        raise ValueError(f"unknown model {model!r}; expected one of {', '.join(MODELS)}")
    inp = model_inputs(data, response, factors, block)
    data, space, y, hint, nb, n = inp.prep.data, inp.space, inp.y, inp.hint, inp.nb, inp.n
    if terms is None:  # count the terms before building any (a cubic in 16 factors has 969)
        try:
            check_model_size(n, len(space), model, nb - 1, categoric=space.categoric)
        except ValueError as exc:
            raise ValueError(f"{exc}{hint}") from None
    terms = (tuple(model_terms(space.letters, model, space.categoric)) if terms is None
             else _chosen_terms(terms, space.letters, space.categoric))
    col_names = inp.column_names(terms)
    p = len(col_names)
    if n < p:
        what = f"{p - nb + 1} coefficients" + (f" and {nb - 1} block effects" if nb > 1 else "")
        raise ValueError(f"{n} runs cannot fit {p} coefficients (the {model} model in {len(space)} factors has {what}){hint}")

    # one factorisation (in chunks of rows), one pass more for the hat diagonal and residuals
    chunks = inp.chunks(terms, int(chunk_rows))
    ls = factorise(chunks, p, col_names)
    ls.require_full_rank(f"{model} model")
    ls = ls.second_pass(chunks)
    # pure error: residual of y ~ (blocks +) one mean per distinct setting (R rsm's PE())
    pe = pure_error(inp.x, y - ls.shift, inp.bcodes if nb > 1 else None)
    prep = inp.prep
    return _assemble(response=response, model=model, block=block, space=space, terms=terms, col_names=col_names,
                     ls=ls, pe=pe, bkeys=inp.bkeys, blevels=inp.blevels, data=data.copy(), coded=inp.coded, y=y,
                     input_notes=prep.notes, omitted_rows=prep.omitted_rows, omitted_data=prep.omitted_data)


def _assemble(*, response, model, block, space, terms, col_names, ls: Regression, pe: PureError, bkeys, blevels,
              data, coded, y, input_notes=(), omitted_rows=(), omitted_data=None) -> FitResult:
    """The :class:`FitResult` of a factorised fit (both passes done) and its pure error."""
    import pandas as pd

    from . import statistics as special  # the t and F tails without importing SciPy

    names = [t.name for t in terms]
    nb = len(col_names) - n_columns(terms) + 1
    n, p = ls.n, ls.p
    beta, C = ls.params, ls.cov_unscaled
    df_res, ss_res, ss_total, sigma2 = ls.df_resid, ls.ss_res, ls.ss_total, ls.sigma2
    tidx = np.r_[0, np.arange(nb, p)] if nb > 1 else np.arange(p)
    # blocks enter first (sequential SS), the model row is the rest; terms are Type III
    ss_block = ls.sequential_ss(np.arange(1, nb)) if nb > 1 else 0.0
    ss_model = ls.sequential_ss(tidx[1:]) if tidx.size > 1 else 0.0
    df_model = len(tidx) - 1
    groups = term_columns(terms[1:], 1)  # each term's columns among tidx (multi-df categoric terms)
    term_ss = [ls.partial_ss(tidx[g]) for g in groups]
    notes = []
    if pe.df == 0:
        pe_used = None
        notes.append("No lack-of-fit test: no factor setting is replicated"
                     + (" (once the block effects are removed)" if nb > 1 else "") + ", so there is no pure error.")
    else:
        pe_used = pe
        if df_res - pe.df == 0:
            notes.append("No lack-of-fit test: the model uses every degree of freedom beyond pure error.")
    if df_res == 0:
        notes.append("The model is saturated (no residual degrees of freedom): no F tests.")
    elif ss_res <= 1e-20 * ss_total:  # residual RMS below 1e-10 of the response's spread
        notes.append("The model fits the data exactly (residuals at round-off level): its F-values, p-values "
                     "and standard errors measure round-off, not noise.")

    # Sums of squares that are round-off against the total (e.g. 2.5e-34 for a term whose
    # coefficient is zero by symmetry) are stored as 0 with F 0 and p 1, as every face shows them.
    anova = clean_anova(anova_table(term_names=names[1:], term_ss=term_ss, ss_model=ss_model, df_model=df_model,
                                    ss_block=ss_block, df_block=nb - 1, ss_res=ss_res, df_res=df_res,
                                    ss_total=ss_total, df_total=n - 1, pe=pe_used,
                                    term_df=[t.df for t in terms[1:]]))

    # coefficients (coded), errors, VIF, actual
    b_t = beta[tidx]
    se = ls.std_errors[tidx]
    with np.errstate(divide="ignore", invalid="ignore"):
        tval = b_t / se
    if df_res > 0:
        pval = 2.0 * special.stdtr(df_res, -np.abs(tval))
        tq = float(special.stdtrit(df_res, 0.975))
    else:
        pval = np.full_like(b_t, np.nan)
        tq = np.nan
    vif = np.r_[np.nan, ls.vif(tidx[1:])]
    # generalised VIF of each term (one per multi-df categoric term; the VIF for a 1-df term)
    term_vif = dict(zip([t.name for t in terms[1:]], ls.gvif([tidx[g] for g in groups]).tolist())) \
        if any(t.df > 1 for t in terms) else {}
    cols = column_names(terms)
    coded_coefs = dict(zip(cols, b_t.tolist()))
    actual = actual_coefficients(coded_coefs, terms, space)
    coef = pd.DataFrame(
        {"coded": b_t, "std_error": se, "t": tval, "p": pval, "ci_low": b_t - tq * se,
         "ci_high": b_t + tq * se, "vif": vif, "actual": [actual[nm] for nm in cols]},
        index=pd.Index(cols, name="term"),
    )
    fitted_range = ls.pass_sums.fitted_max - ls.pass_sums.fitted_min
    statistics = fit_statistics(n=n, mean=ls.ybar, fitted_range=fitted_range, ss_res=ss_res,
                                df_res=df_res, ss_total=ss_total, ss_block=ss_block, df_model=df_model,
                                n_params=p, press=ls.press)
    sp = canonical_analysis(coded_coefs, terms, space)
    if nb > 1:
        eff = beta[1:nb].tolist()
        eff.append(-float(np.sum(eff)))
        block_effects = dict(zip(bkeys, eff))
    else:
        block_effects = None
    return FitResult(
        response=response, model=model, block=block, space=space, terms=terms, data=data,
        coded=coded, y=y, column_names=tuple(col_names), coefficients=coef,
        anova=anova, statistics=statistics, stationary_point=sp, fitted=ls.fitted, residuals=ls.residuals,
        hat=ls.hat, cov_unscaled=C, sigma2=float(sigma2), df_resid=int(df_res),
        block_effects=block_effects, block_levels=blevels, pure_error=pe_used,
        actual_coefficients=actual, notes=tuple(input_notes) + tuple(notes),
        input_notes=tuple(input_notes), omitted_rows=tuple(omitted_rows), omitted_data=omitted_data,
        least_squares=ls, term_vif=term_vif,
    )
