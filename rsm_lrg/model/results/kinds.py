"""How a :class:`~rsm_lrg.model.results.result.FitResult` reads, by the engine that estimated it
and by the form of its model — chosen once, when the result is assembled, so that no method of
the result (and no consumer above it) branches on a kind.

* The *reading* follows the engine: :class:`LeastSquaresReading` (the QR core: sums of squares,
  pure error and lack of fit, R², PRESS, VIF) or :class:`REMLReading` (a mixed model: Kenward–Roger
  tests in the ANOVA's place, the variance components, no sums of squares).
* The *form* follows the model: :class:`PolynomialForm` (coded factors, canonical analysis,
  actual units by the change of coding) or :class:`ScheffeForm` (a Scheffé mixture model on
  L-pseudo components: the mixture ANOVA, real proportions, blends that sum to the total).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

from ..build.terms import term_columns
from ..contract.statistics import FitStatistics, fit_statistics
from ..readings.actual import actual_coefficients
from ..readings.anova import TOTAL_UNCORRECTED, PureError, anova_rows, anova_table
from ..readings.canonical import StationaryPoint, canonical_analysis

if TYPE_CHECKING:
    import pandas as pd

    from ...factors import FactorSpace
    from ..engines.least_squares import Regression
    from ..engines.mixed import MixedModel

__all__ = ["json_number", "LeastSquaresReading", "REMLReading", "PolynomialForm", "ScheffeForm", "reading_of", "form_of"]


class ReadFit(Protocol):
    """The parts of a :class:`rsm_lrg.model.results.result.FitResult` that a reading and a form
    read (a protocol: the result module imports this one, not the other way round)."""

    @property
    def response(self) -> str: ...

    @property
    def space(self) -> FactorSpace: ...

    @property
    def terms(self) -> tuple: ...

    @property
    def least_squares(self) -> Regression: ...

    @property
    def raw_pure_error(self) -> PureError: ...

    @property
    def data(self) -> Any: ...

    @property
    def block(self) -> str | None: ...

    @property
    def y(self) -> np.ndarray | None: ...

    @property
    def form(self) -> PolynomialForm: ...

    @property
    def intercept(self) -> bool: ...

    @property
    def model_terms(self) -> Any: ...

    @property
    def n_blocks(self) -> int: ...

    @property
    def term_index(self) -> np.ndarray: ...

    @property
    def sums(self) -> dict[str, Any]: ...

    @property
    def pure_error(self) -> PureError | None: ...

    @property
    def residuals(self) -> np.ndarray | None: ...

    @property
    def tests(self) -> Any: ...

    @property
    def anova(self) -> Any: ...

    @property
    def anova_rows(self) -> list[dict]: ...

    @property
    def actual_deferred(self) -> Any: ...

    @property
    def actual_solution(self) -> Any: ...


def json_number(v: Any) -> float | None:
    """A number for JSON: NaN and infinities become None.

    Parameters
    ----------
    v : Any
        A number, or anything else.

    Returns
    -------
    float or None
    """
    try:
        x = float(v)
    except (TypeError, ValueError):
        return None
    return x if math.isfinite(x) else None


# -- the form of the model ----------------------------------------------------------------
class PolynomialForm:
    """A polynomial in coded factors (blocks, categoric factors, an intercept or none)."""

    #: The model can be solved again in actual units to the accuracy of the data.
    solves_in_actual_units = True

    def sums(self, r: ReadFit) -> dict[str, Any]:
        """The sums of squares of the ANOVA from the core (blocks first, sequential; terms Type III).

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        dict
            ``ss_block``, ``ss_model``, ``ss_total``, ``df_model``, ``groups`` (each term's
            columns) and ``term_ss``.
        """
        ls, nb, tidx = r.least_squares, r.n_blocks, r.term_index
        mcols = tidx[1:] if r.intercept else tidx
        ss_block = ls.sequential_ss(np.arange(1, nb)) if nb > 1 else 0.0
        ss_model = ls.sequential_ss(mcols) if mcols.size else 0.0
        ss_total = ls.ss_total if r.intercept else ss_model + ls.ss_res  # uncorrected: sum y^2
        groups = term_columns(r.model_terms, 1 if r.intercept else 0)
        return {"ss_block": ss_block, "ss_model": ss_model, "ss_total": ss_total, "df_model": int(mcols.size),
                "groups": groups, "term_ss": [ls.partial_ss(tidx[g]) for g in groups]}

    def anova_rows(self, r: ReadFit) -> list[dict]:
        """The Design-Expert ANOVA of a least-squares fit (Table 5 layout), as rows.

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        list of dict
            ``{source, sum_sq, df, mean_sq, f, p}`` per row
            (:func:`~rsm_lrg.model.readings.anova.anova_rows`).
        """
        s, ls = r.sums, r.least_squares
        n, nb = ls.n, r.n_blocks
        # Sums of squares that are round-off against the total (e.g. 2.5e-34 for a term whose
        # coefficient is zero by symmetry) are stored as 0 with F 0 and p 1, as every face shows them.
        return anova_rows(
            term_names=[t.name for t in r.model_terms], term_ss=s["term_ss"], ss_model=s["ss_model"],
            df_model=s["df_model"], ss_block=s["ss_block"], df_block=nb - 1, ss_res=ls.ss_res, df_res=ls.df_resid,
            ss_total=s["ss_total"], df_total=n - 1 if r.intercept else n, pe=r.pure_error,
            term_df=[t.df for t in r.model_terms],
            total_label="Cor Total" if r.intercept else TOTAL_UNCORRECTED, clean=True)

    def test_contrasts(self, r: ReadFit) -> list[tuple[str, np.ndarray]]:
        """The hypotheses a REML fit tests, one per model term: all its columns zero.

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        list of (str, numpy.ndarray)
            ``(term name, L)``: the test of ``L b = 0`` (L one row per column of the term,
            over every model column).
        """
        groups = term_columns(r.model_terms, 1 if r.intercept else 0)
        tidx = r.term_index
        p = len(r.least_squares.params)
        out = []
        for t, g in zip(r.model_terms, groups):
            L = np.zeros((len(g), p))
            L[np.arange(len(g)), tidx[g]] = 1.0
            out.append((t.name, L))
        return out

    def to_actual(self, coded: dict, r: ReadFit) -> dict:
        """``{monomial: coefficient}`` in actual units of coded coefficients (the exact change of coding).

        Parameters
        ----------
        coded : dict
            ``{column: coefficient}`` in coded units.
        r : FitResult
            The fit (its terms and factors).

        Returns
        -------
        dict
            ``{monomial: coefficient}`` in actual units.
        """
        return actual_coefficients(dict(coded), r.terms, r.space)

    def stationary_point(self, coded: dict, r: ReadFit) -> StationaryPoint:
        """The stationary point and canonical analysis (first categoric levels).

        Parameters
        ----------
        coded : dict
            ``{column: coefficient}`` in coded units.
        r : FitResult
            The fit.

        Returns
        -------
        StationaryPoint
        """
        return canonical_analysis(coded, r.terms, r.space)

    def check_points(self, space: FactorSpace, x: np.ndarray) -> None:
        """Refuse settings the model says nothing about (none for a polynomial: far points are
        refused by magnitude before this).

        Parameters
        ----------
        space : FactorSpace
            The fit's factors.
        x : numpy.ndarray, shape (m, k)
            Coded settings.
        """

    def label_parts(self, r: ReadFit) -> list[str]:
        """Words of the model's label beyond its terms (``no intercept``).

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        list of str
        """
        return [] if r.intercept else ["no intercept"]


class ScheffeForm(PolynomialForm):
    """A Scheffé mixture model (no intercept) on L-pseudo components, with process factors or not."""

    solves_in_actual_units = False  # the exact change of basis of the coded coefficients instead

    def sums(self, r: ReadFit) -> dict[str, Any]:
        """The mixture ANOVA's sums: about the mean, linear blending first
        (:func:`rsm_lrg.model.build.mixture.mixture_sums`).

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        dict
            ``names``, ``term_ss``, ``term_df``, ``ss_model``, ``df_model``, ``ss_total`` ...
        """
        from ..build.mixture import mixture_sums

        if r.n_blocks > 1:
            from ..build.inputs import block_codes

            assert r.block is not None and r.y is not None  # an in-memory fit with fixed blocks
            return mixture_sums(r.least_squares, r.terms, block_codes(r.data, r.block)[0], r.y)
        return mixture_sums(r.least_squares, r.terms)

    def anova_rows(self, r: ReadFit) -> list[dict]:
        """Design-Expert's mixture ANOVA: Linear Mixture, the non-linear terms, Cor Total.

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        list of dict
            ``{source, sum_sq, df, mean_sq, f, p}`` per row.
        """
        s, ls = r.sums, r.least_squares
        return anova_rows(
            term_names=s["names"], term_ss=s["term_ss"], ss_model=s["ss_model"], df_model=s["df_model"],
            ss_block=s["ss_block"], df_block=r.n_blocks - 1, ss_res=ls.ss_res, df_res=ls.df_resid, ss_total=s["ss_total"],
            df_total=ls.n - 1, pe=r.pure_error, term_df=s["term_df"], total_label="Cor Total", clean=True)

    def test_contrasts(self, r: ReadFit) -> list[tuple[str, np.ndarray]]:
        """The hypotheses a REML fit of a Scheffé model tests, as the mixture ANOVA's rows:
        ``Linear Mixture`` (the linear blending coefficients all equal, q - 1 df: a flat
        surface, the counterpart of Design-Expert's row in the full model) and every
        non-linear term (its coefficient zero).

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        list of (str, numpy.ndarray)
            ``(row name, L)``: the test of ``L b = 0`` over every model column.
        """
        tidx = r.term_index
        p = len(r.least_squares.params)
        lin = [int(tidx[j]) for j, t in enumerate(r.terms) if t.order == 1]
        L = np.zeros((len(lin) - 1, p))
        for i, j in enumerate(lin[:-1]):
            L[i, j], L[i, lin[-1]] = 1.0, -1.0
        out = [("Linear Mixture", L)]
        for j, t in enumerate(r.terms):
            if t.order > 1:
                row = np.zeros((1, p))
                row[0, tidx[j]] = 1.0
                out.append((t.name, row))
        return out

    def to_actual(self, coded: dict, r: ReadFit) -> dict:
        """``{monomial: coefficient}`` in real proportions of L-pseudo-component coefficients.

        Parameters
        ----------
        coded : dict
            ``{column: coefficient}`` on the L-pseudo components.
        r : FitResult
            The fit.

        Returns
        -------
        dict
            ``{monomial: coefficient}`` in real proportions.
        """
        from ..build.mixture import pseudo_to_actual

        return pseudo_to_actual(dict(coded), r.terms, r.space)

    def stationary_point(self, coded: dict, r: ReadFit) -> StationaryPoint:
        """None: the mixture components are not free (they sum to the total).

        Parameters
        ----------
        coded : dict
            ``{column: coefficient}`` (unused).
        r : FitResult
            The fit.

        Returns
        -------
        StationaryPoint
            Empty, with the note saying why.
        """
        return StationaryPoint(None, None, None, note="no canonical analysis: the mixture components are not free "
                               "(they sum to the total)", letters=tuple(r.space.letters))

    def check_points(self, space: FactorSpace, x: np.ndarray) -> None:
        """ValueError naming the first point whose components do not sum to the total (the
        L-pseudo components sum to one; tolerance :data:`~rsm_lrg.model.build.mixture.SUM_RTOL`),
        or whose share of a component is negative or above the total.

        Parameters
        ----------
        space : FactorSpace
            The fit's factors.
        x : numpy.ndarray, shape (m, k)
            Coded settings (L-pseudo components).
        """
        from ...factors import MixtureComponent
        from ..build.mixture import SUM_RTOL

        comps = [j for j, f in enumerate(space.factors) if isinstance(f, MixtureComponent)]
        f0 = space.factors[comps[0]]
        assert isinstance(f0, MixtureComponent)
        sums = x[:, comps].sum(axis=1)
        bad = np.flatnonzero(~(np.abs(sums - 1.0) <= SUM_RTOL * f0.total / f0.pseudo_range))
        if bad.size:
            i = int(bad[0])
            raise ValueError(f"prediction point {i + 1}: the components sum to {f0.lower_sum + sums[i] * f0.pseudo_range:.12g}, "
                             f"not the total {f0.total:.12g} (tolerance {SUM_RTOL:g} of the total)")
        tol = SUM_RTOL * f0.total
        for j in comps:  # a share below zero or above the total is no blend (the sum alone passes 2 - 1 + 0)
            f = space.factors[j]
            assert isinstance(f, MixtureComponent)
            share = f.lower + x[:, j] * f.pseudo_range
            out = np.flatnonzero(~((share >= -tol) & (share <= f.total + tol)))
            if out.size:
                i = int(out[0])
                where = "negative" if share[i] < 0 else f"above the total {f.total:.12g}"
                raise ValueError(f"prediction point {i + 1}: component {f.name!r} is {where} ({share[i]:.12g}); a "
                                 "blend's shares lie between 0 and the total")

    def label_parts(self, r: ReadFit) -> list[str]:
        """None: a Scheffé model has no intercept by its form.

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        list of str
        """
        return []


# -- the reading of the engine ------------------------------------------------------------
class LeastSquaresReading:
    """A fit by the least-squares core: sums of squares, pure error and lack of fit, R², PRESS."""

    #: The coefficients can be solved again in actual units (the model's form permitting).
    solves_in_actual_units = True
    #: The sections of the text summary (:func:`rsm_lrg.model.faces.text.format_summary`).
    text_sections = ("anova", "statistics")
    #: The ANOVA's title when it is not the least-squares one (None: the faces compose it).
    anova_title: str | None = None
    #: Why lack of fit is not tested, when it cannot be (None: the ANOVA says).
    lack_of_fit_note: str | None = None

    def fitted_by(self, r: ReadFit) -> str:
        """How the coefficients were estimated, for a summary line.

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        str
        """
        return "least squares in coded units"

    def variance_components(self, r: ReadFit) -> dict:
        """The variance components beside the residual (none for least squares).

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        dict
            Empty.
        """
        return {}

    def estimation(self, r: ReadFit) -> Regression:
        """The engine's part: the regression core.

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        Regression
        """
        return r.least_squares

    def pure_error(self, r: ReadFit) -> PureError | None:
        """The pure error, or None when no setting is replicated.

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        PureError or None
        """
        return None if r.raw_pure_error.df == 0 else r.raw_pure_error

    def anova(self, r: ReadFit) -> pd.DataFrame:
        """The ANOVA of the model's form.

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        pandas.DataFrame
            :meth:`anova_rows` as a frame (columns ``source, sum_sq, df, mean_sq, f, p``).
        """
        return anova_table(r.anova_rows)

    def anova_rows(self, r: ReadFit) -> list[dict]:
        """The ANOVA of the model's form, as rows (what the JSON and the text read; no
        pandas.DataFrame is built for them).

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        list of dict
            ``{source, sum_sq, df, mean_sq, f, p}`` per row.
        """
        return r.form.anova_rows(r)

    def notes(self, r: ReadFit) -> tuple:
        """The fit's own remarks (lack of fit, saturation, an exact fit).

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        tuple of str
        """
        ls, nb = r.least_squares, r.n_blocks
        notes = []
        if r.raw_pure_error.df == 0:
            notes.append("No lack-of-fit test: no factor setting is replicated"
                         + (" (once the block effects are removed)" if nb > 1 else "") + ", so there is no pure error.")
        elif ls.df_resid - r.raw_pure_error.df == 0:
            notes.append("No lack-of-fit test: the model uses every degree of freedom beyond pure error.")
        if ls.df_resid == 0:
            notes.append("The model is saturated (no residual degrees of freedom): no F tests.")
        elif ls.ss_res <= 1e-20 * r.sums["ss_total"]:  # residual RMS below 1e-10 of the response's spread
            notes.append("The model fits the data exactly (residuals at round-off level): its F-values, p-values "
                         "and standard errors measure round-off, not noise.")
        return tuple(notes)

    def statistics(self, r: ReadFit) -> FitStatistics:
        """R², adjusted and predicted R², PRESS, adequate precision, std dev, mean, C.V.

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        FitStatistics
        """
        ls, s = r.least_squares, r.sums
        if ls.pass_sums is None:
            raise ValueError("the fit's statistics need the second pass over the rows")
        sol = r.actual_deferred  # its residual sum of squares is exact to the data's digits (NIST StRD)
        ss_res = float(sol.rss) if sol is not None and math.isfinite(sol.rss) else ls.ss_res
        return fit_statistics(n=ls.n, mean=ls.ybar, fitted_range=ls.pass_sums.fitted_max - ls.pass_sums.fitted_min,
                              ss_res=ss_res, df_res=ls.df_resid, ss_total=s["ss_total"], ss_block=s["ss_block"],
                              df_model=s["df_model"], n_params=ls.p, press=ls.press)

    def term_vif(self, r: ReadFit) -> dict:
        """Generalised VIF of each term when a categoric term has several columns (else empty).

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        dict
        """
        if not (r.intercept and any(t.df > 1 for t in r.terms)):
            return {}
        tidx = r.term_index
        gv = r.least_squares.gvif([tidx[g] for g in r.sums["groups"]])
        return dict(zip([t.name for t in r.model_terms], gv.tolist()))

    def scaled_residuals(self, r: ReadFit) -> np.ndarray | None:
        """The residuals the studentized residuals and Cook's distance are computed from.

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        numpy.ndarray or None
            ``y - ŷ`` (None for a Dask fit).
        """
        return r.residuals

    def json_parts(self, r: ReadFit) -> dict:
        """The fit JSON's ANOVA rows.

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        dict
            ``{"anova": [...]}``.
        """
        return {"anova": [
            {"source": row["source"], "sum_sq": json_number(row["sum_sq"]), "df": int(row["df"]), "mean_sq": json_number(row["mean_sq"]),
             "f": json_number(row["f"]), "p": json_number(row["p"])}
            for row in r.anova_rows]}

    def add_run_columns(self, r: ReadFit, frame: pd.DataFrame) -> None:
        """Add the reading's own per-run columns to the diagnostics table (none).

        Parameters
        ----------
        r : FitResult
            The fit.
        frame : pandas.DataFrame
            The table, changed in place.
        """


class REMLReading:
    """A mixed model fitted by REML: Kenward–Roger tests, the variance components, no sums of squares.

    Parameters
    ----------
    mixed : MixedModel
        The engine's result (:mod:`rsm_lrg.model.engines.mixed`).
    """

    solves_in_actual_units = False  # the change of basis M cov M' of the GLS coefficients instead
    text_sections = ("mixed",)
    anova_title: str | None = "Fixed effects of the REML fit: Kenward-Roger F tests (no sums of squares)"
    lack_of_fit_note: str | None = "not tested (REML fit)"

    def __init__(self, mixed: MixedModel) -> None:
        self.mixed = mixed

    def estimation(self, r: ReadFit) -> MixedModel:
        """The engine's part: the mixed model.

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        MixedModel
        """
        return self.mixed

    def fitted_by(self, r: ReadFit) -> str:
        """How the coefficients were estimated, for a summary line.

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        str
            REML and the random effects.
        """
        return f"REML in coded units with {self.mixed.describe()}"

    def variance_components(self, r: ReadFit) -> dict:
        """The variance components (each random effect and the residual) with their intervals.

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        dict
            ``{name: VarianceComponent}``.
        """
        return dict(self.mixed.variance_components)

    def pure_error(self, r: ReadFit) -> PureError | None:
        """None: no lack-of-fit test against a pure error that mixes the groups' variation.

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        None
        """
        return None

    def anova_rows(self, r: ReadFit) -> list[dict]:
        """:meth:`anova` as rows (``DataFrame.to_dict(orient="records")``).

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        list of dict
            One dict per term.
        """
        return r.anova.to_dict(orient="records")

    def anova(self, r: ReadFit) -> pd.DataFrame:
        """One row per term with its Kenward–Roger test (``df`` the numerator df, ``den_df``
        added, ``sum_sq`` and ``mean_sq`` NaN: a GLS fit has no sums of squares that add up).

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        pandas.DataFrame
        """
        import pandas as pd

        return pd.DataFrame({"source": [t.term for t in r.tests], "sum_sq": math.nan,
                             "df": [t.num_df for t in r.tests], "mean_sq": math.nan,
                             "f": [t.f for t in r.tests], "p": [t.p for t in r.tests],
                             "den_df": [t.den_df for t in r.tests]},
                            columns=["source", "sum_sq", "df", "mean_sq", "f", "p", "den_df"])

    def notes(self, r: ReadFit) -> tuple:
        """What a REML fit is and is not (its tests, intervals and residuals).

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        tuple of str
        """
        from ..engines.mixed import CI_METHOD

        mm = self.mixed
        if mm.kind not in ("whole_plot", "block"):
            return self._several_notes()
        what = "whole plot" if mm.kind == "whole_plot" else "block"
        notes = [f"REML fit with a random intercept per {what} ({mm.column!r}, {mm.n_groups} {what}s): coefficients "
                 "and standard errors are generalised least squares at the REML variance ratio; F tests use the "
                 "Kenward–Roger adjusted covariance and den df (pbkrtest's computation, den df not clamped); "
                 "t and p of the coefficients are the one-df Kenward–Roger tests.",
                 "No sums of squares, PRESS, R², adequate precision or lack-of-fit test: they are ordinary "
                 "least-squares quantities with no counterpart in a REML fit.",
                 f"Variance component intervals: {CI_METHOD}.",
                 "Residuals are conditional (y - Xb - Zu, BLUPs u); studentized residuals and leverages are those of "
                 "the whitened (V^-1/2) model; prediction intervals are for a new run in a new "
                 f"{what} (variance x'Φ_A x + s2_{'wp' if mm.kind == 'whole_plot' else 'block'} + s2)."]
        if mm.boundary:
            notes.append(f"The {what} variance component is estimated at zero (REML on the boundary): the coefficients "
                         "and their standard errors equal the ordinary least-squares ones, but the zero component "
                         "stays in the Kenward–Roger computation (as pbkrtest and lmerTest keep it), so the den df, F "
                         f"and p still count the {what}-to-{what} variation the data could hold; they are not the OLS "
                         "tests.")
        return tuple(notes)

    def _several_notes(self) -> tuple:
        mm = self.mixed
        notes = [f"REML fit with {mm.describe()}: coefficients and standard errors are generalised least squares at "
                 "the REML variance ratios; F tests use the Kenward–Roger adjusted covariance and den df (pbkrtest's "
                 "computation with one variance parameter per random effect and the residual, den df not clamped); "
                 "t and p of the coefficients are the one-df Kenward–Roger tests.",
                 "No sums of squares, PRESS, R², adequate precision or lack-of-fit test: they are ordinary "
                 "least-squares quantities with no counterpart in a REML fit.",
                 "Variance component intervals: Wald on the log scale: log(s2_k) ± z·se(log s2_k), se from the "
                 "inverse expected (REML) information of the variance components, the W of Kenward–Roger.",
                 "Residuals are conditional (y - Xb - Σ Z_k u_k, BLUPs u_k); studentized residuals and leverages are "
                 "those of the whitened model; prediction intervals are for a new run in new levels of every random "
                 "effect (variance x'Φ_A x + the sum of the random-effect variances + s2)."]
        zero = [n for n, v in zip(mm.component_names, mm.component_variances) if v == 0.0]
        if zero:
            notes.append(f"Variance component{'s' if len(zero) > 1 else ''} {', '.join(repr(z) for z in zero)} "
                         "estimated at zero (REML on the boundary): kept in the Kenward–Roger computation, as pbkrtest "
                         "and lmerTest keep it.")
        return tuple(notes)

    def statistics(self, r: ReadFit) -> FitStatistics:
        """The std dev of the residual (within-group) component, the mean and C.V.; R², PRESS
        and adequate precision NaN.

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        FitStatistics
        """
        ybar = float(np.mean(self.mixed.y))
        sd = math.sqrt(self.mixed.sigma2)
        return FitStatistics(r2=math.nan, adj_r2=math.nan, pred_r2=math.nan, press=math.nan,
                             adeq_precision=math.nan, std_dev=sd, mean=ybar,
                             cv_percent=100.0 * sd / abs(ybar) if ybar != 0 else math.nan)

    def term_vif(self, r: ReadFit) -> dict:
        """None (a property of X'X, not of a GLS fit).

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        dict
            Empty.
        """
        return {}

    def scaled_residuals(self, r: ReadFit) -> np.ndarray | None:
        """The residuals of the whitened model ``V^-1/2 (y - X b)``.

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        numpy.ndarray or None
        """
        return r.least_squares.residuals

    def json_parts(self, r: ReadFit) -> dict:
        """The REML block of the fit JSON (variance components, Kenward–Roger tests, random
        effects) and its ``anova``: the tests in the ANOVA's shape (unused numbers null).

        Parameters
        ----------
        r : FitResult
            The fit.

        Returns
        -------
        dict
        """
        from ..engines.mixed import CI_METHOD

        mm = self.mixed
        vc = {k: {kk: json_number(vv) for kk, vv in c.to_dict().items()} for k, c in mm.variance_components.items()}
        tests = [{k: (json_number(v) if k not in ("term", "num_df") else v) for k, v in t.to_dict().items()} for t in r.tests]
        if mm.kind not in ("whole_plot", "block"):  # random_effects=[...]: one entry per grouping column
            assert mm.kind == "effect" or mm.etas is not None
            ratios = [mm.eta] if mm.kind == "effect" else list(mm.etas)  # type: ignore[arg-type]
            out: dict[str, Any] = {
                "random_effect_columns": list(mm.columns), "method": "REML",
                "variance_ratio": {c: json_number(q) for c, q in zip(mm.columns, ratios)},
                "variance_components": vc, "variance_component_ci": CI_METHOD, "tests": tests,
                "den_df_method": "Kenward-Roger",
                "random_effects": ({mm.column: {k: json_number(v) for k, v in mm.random_effects_table.items()}}
                                   if mm.kind == "effect" else
                                   {c: {k: json_number(v) for k, v in t.items()} for c, t in mm.random_effects_table.items()}),
            }
        else:
            key = "whole_plot" if mm.kind == "whole_plot" else "random_block"
            out = {
                key: mm.column, "method": "REML", "variance_ratio": json_number(mm.eta),
                "variance_components": vc, "variance_component_ci": CI_METHOD, "tests": tests,
                "den_df_method": "Kenward-Roger",
                "random_effects": {str(lab): json_number(u) for lab, u in zip(mm.labels, mm.blups)},
            }
        out["anova"] = [{"source": t["term"], "sum_sq": None, "df": t["num_df"], "mean_sq": None,
                         "f": t["f"], "p": t["p"], "den_df": t["den_df"]} for t in tests]
        return out

    def add_run_columns(self, r: ReadFit, frame: pd.DataFrame) -> None:
        """Add the grouping columns and the marginal and conditional residuals and fitted values.

        Parameters
        ----------
        r : FitResult
            The fit.
        frame : pandas.DataFrame
            The diagnostics table, changed in place.
        """
        mm = self.mixed
        for c in mm.columns:
            frame.insert(list(frame.columns).index(r.response), c, r.data[c].to_numpy())
        frame["marginal_residual"] = mm.marginal_residuals
        frame["conditional_residual"] = mm.conditional_residuals
        frame["marginal_fitted"] = mm.marginal_fitted


def reading_of(mixed: MixedModel | None) -> LeastSquaresReading | REMLReading:
    """The reading of the engine that estimated a fit: REML when a mixed model was fitted.

    Parameters
    ----------
    mixed : MixedModel or None
        The mixed-model part of a REML fit.

    Returns
    -------
    LeastSquaresReading or REMLReading
    """
    return LeastSquaresReading() if mixed is None else REMLReading(mixed)


def form_of(mixture: bool) -> PolynomialForm:
    """The form of a fitted model: Scheffé for a mixture model.

    Parameters
    ----------
    mixture : bool
        The specification's ``mixture``.

    Returns
    -------
    PolynomialForm or ScheffeForm
    """
    return ScheffeForm() if mixture else PolynomialForm()
