"""Fitting a response-surface model: :func:`fit`, which returns the one result type
:class:`~rsm_lrg.model.results.result.FitResult`.

The model (a :class:`~rsm_lrg.model.build.spec.ModelSpec`: an order — linear, 2FI, quadratic as
the paper's Eq. 19, cubic — or any list of terms, with or without an intercept, on the
response or a transform of it, optionally reduced) is fitted by ordinary least squares on
the coded model matrix, in coded units ``x = (actual - centre) / half_range``, by the
regression core :mod:`rsm_lrg.model.engines.least_squares`: a Householder QR factorisation of the
column-scaled matrix with the response centred (so a response of 1e9 + small variation
loses no accuracy), accumulated over chunks of rows, and a second pass for the hat
diagonal. Everything else — the Design-Expert ANOVA (Table 5), PRESS, VIF, intervals — is
derived from that one factorisation; no term is refitted and the n x p model matrix is
never held whole, so a fit of 10^6 runs costs a small multiple of one QR.

Blocks (optional) are sum-to-zero effects, as Design-Expert shows them; they enter the
ANOVA first (sequential SS) and stay out of the model row. Predictions and the optimum are
for the average block (block effect 0).

>>> import rsm_lrg
>>> r = rsm_lrg.fit(rsm_lrg.load_table4(), "tcr_c_per_min")
>>> round(r.statistics.r2, 3), round(float(r.coefficients.loc["C", "coded"]), 5)
(0.968, 0.0075)
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, Literal, overload

from .build.data import check_group_column
from .build.inputs import ModelInputs, chosen_terms, is_dask, model_inputs
from .build.spec import FactorsArg, ModelSpec, ReduceArg, SpecError, TermsArg
from .build.terms import check_model_size, model_terms
from .engines.least_squares import CHUNK_ROWS, factorise
from .readings.actual import actual_coefficients, actual_equations
from .readings.anova import pure_error
from .results.result import COEF_COLUMNS, FitResult, assemble

if TYPE_CHECKING:
    import dask.dataframe as dd
    import numpy as np
    import pandas as pd

    from ..factors import FactorSpace
    from ..table import ColumnTable
    from .build.transform import Transform
    from .choice.dsd import TwoStage
    from .choice.reduce import Reduction
    from .choice.select import Selection
    from .engines.glm_family import Family
    from .results.glm_result import GLMResult
    from .results.gp_result import GPResult

__all__ = ["fit", "fit_transformed", "FitResult", "actual_coefficients", "actual_equations", "COEF_COLUMNS",
           "model_inputs", "ModelInputs", "ModelSpec"]


@overload
def fit(  # type: ignore[overload-overlap]  # "gp" is also a str: the first match wins
        data: pd.DataFrame | dd.DataFrame | ColumnTable, response: str, factors: FactorsArg = ..., block: str | None = ..., *,
        model: Literal["gp"], terms: TermsArg = ..., intercept: bool = ..., transform: str | Transform | None = ...,
        transform_constant: float = ..., reduce: ReduceArg = ..., chunk_rows: int = ...,
        components: Sequence[str] | None = ..., whole_plot: str | None = ..., random_block: str | None = ...,
        hard_to_change: str | Sequence[str] | None = ...,
        random_effects: Sequence[str] | None = ..., kernel: str = ..., trend: str = ...,
        nugget: float | str | None = ..., length_scales: Sequence[float] | None = ..., variance: float | None = ...,
        seed: int | None = ..., length_scale_bounds: tuple[float, float] | None = ..., family: None = ...,
        link: None = ..., trials: None = ...) -> GPResult: ...
@overload
def fit(data: pd.DataFrame | dd.DataFrame | ColumnTable, response: str, factors: FactorsArg = ..., block: str | None = ...,
        model: str | ModelSpec = ..., *, terms: TermsArg = ..., intercept: bool = ...,
        transform: str | Transform | None = ..., transform_constant: float = ..., reduce: ReduceArg = ...,
        chunk_rows: int = ..., components: Sequence[str] | None = ..., whole_plot: str | None = ...,
        random_block: str | None = ..., hard_to_change: str | Sequence[str] | None = ...,
        random_effects: Sequence[str] | None = ..., kernel: str = ...,
        trend: str = ..., nugget: float | str | None = ..., length_scales: Sequence[float] | None = ...,
        variance: float | None = ..., seed: int | None = ...,
        length_scale_bounds: tuple[float, float] | None = ..., family: str | Family, link: str | None = ...,
        trials: str | None = ...) -> GLMResult: ...
@overload
def fit(data: pd.DataFrame | dd.DataFrame | ColumnTable, response: str, factors: FactorsArg = ..., block: str | None = ...,
        model: str | ModelSpec = ..., *, terms: TermsArg = ..., intercept: bool = ...,
        transform: str | Transform | None = ..., transform_constant: float = ..., reduce: ReduceArg = ...,
        chunk_rows: int = ..., components: Sequence[str] | None = ..., whole_plot: str | None = ...,
        random_block: str | None = ..., hard_to_change: str | Sequence[str] | None = ...,
        random_effects: Sequence[str] | None = ..., kernel: str = ...,
        trend: str = ..., nugget: float | str | None = ..., length_scales: Sequence[float] | None = ...,
        variance: float | None = ..., seed: int | None = ...,
        length_scale_bounds: tuple[float, float] | None = ..., family: None = ..., link: None = ...,
        trials: None = ...) -> FitResult: ...
def fit(data: pd.DataFrame | dd.DataFrame | ColumnTable, response: str, factors: FactorsArg = None, block: str | None = None,
        model: str | ModelSpec = "quadratic", *, terms: TermsArg = None, intercept: bool = True,
        transform: str | Transform | None = None, transform_constant: float = 0.0, reduce: ReduceArg = None,
        chunk_rows: int = CHUNK_ROWS, components: Sequence[str] | None = None, whole_plot: str | None = None,
        random_block: str | None = None, hard_to_change: str | Sequence[str] | None = None,
        random_effects: Sequence[str] | None = None, kernel: str = "matern52",
        trend: str = "constant", nugget: float | str | None = None, length_scales: Sequence[float] | None = None,
        variance: float | None = None, seed: int | None = 0,
        length_scale_bounds: tuple[float, float] | None = None, family: str | Family | None = None,
        link: str | None = None, trials: str | None = None) -> FitResult | GPResult | GLMResult:
    """Fit a response-surface model by OLS in coded units (paper Eq. 19, Table 5), a Gaussian
    process (``model="gp"``, :func:`rsm_lrg.model.pipelines.gp.fit_gp`) or a generalised linear model
    (``family=``, :func:`rsm_lrg.model.pipelines.glm.fit_glm`).

    Parameters
    ----------
    data : pandas.DataFrame, dask.dataframe.DataFrame or rsm_lrg.table.ColumnTable
        One row per run. A Dask DataFrame is fitted partition by partition without being
        collected (:mod:`rsm_lrg.model.pipelines.dask_fit`; the result holds no per-run arrays).
        A :class:`~rsm_lrg.table.ColumnTable` (a plain CSV file read without pandas) is fitted
        as it is by least squares (the result's ``data`` is that table); the other engines
        (a GP, a GLM, a mixture, random effects, a reduction) are given it as a DataFrame.
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
    model : {"linear", "2fi", "quadratic", "cubic"} or ModelSpec
        The model order, or a whole specification (then give none of ``terms``,
        ``intercept``, ``transform``, ``reduce``).
    terms : str or sequence of str, optional
        Fit exactly these terms (``"A B AB A^2"`` or ``["A", "AB", "A^10"]``: letters,
        products, powers of any degree, categoric terms as for the orders); they are put in
        Design-Expert order. ``model`` then only names the starting point of a reduction.
    intercept : bool
        Whether the model has an intercept (default ``True``). Without one, give ``terms``;
        the ANOVA's model row and total are then uncorrected (``Uncor Total``, n df) and R²
        is ``1 - SS_res / sum y²``, as R's ``lm`` reports them; blocks need an intercept.
    transform : str or Transform, optional
        Fit ``g(y + transform_constant)`` (``"log"``, ``"log10"``, ``"sqrt"``,
        ``"inverse"``, ``"power=L"``): coefficients and ANOVA are on that scale;
        :meth:`FitResult.predict` back-transforms, and optimisers read goals on the
        response's scale (:meth:`FitResult.goal_on_model_scale`).
    transform_constant : float
        The constant k added before transforming (default 0).
    reduce : bool, mapping or ReduceSpec, optional
        Backward elimination keeping hierarchy (:mod:`rsm_lrg.model.choice.reduce`) before the
        final fit: ``True`` (p-value, alpha 0.1) or ``{"criterion": "aicc"}``; the result's
        ``reduction`` lists the steps.
    chunk_rows : int
        Rows of the model matrix built and factorised at a time (the full n x p matrix is
        never held; :mod:`rsm_lrg.model.engines.least_squares`).
    components : sequence of str, optional
        Mixture components (names or ``"NAME=LOW:HIGH"``), with ``model`` a Scheffé model
        (``"mixture-linear"``, ``"mixture-quadratic"``, ``"special-cubic"``) or Scheffé
        ``terms``: fitted without an intercept on L-pseudo-components, the ANOVA and R²
        about the mean (:mod:`rsm_lrg.model.build.mixture`). Every row must sum to the same
        total within 1e-6 relative.
    whole_plot : str, optional
        Whole-plot column of a split-plot experiment: the model gets a random intercept per
        whole plot and is fitted by REML (:mod:`rsm_lrg.model.engines.mixed`); the result's
        ``mixed`` holds the variance components and Kenward–Roger tests, its coefficients
        and standard errors are the GLS ones. ``reduce`` then eliminates by the
        Kenward–Roger p-values (hierarchy kept).
    random_block : str, optional
        Block column whose blocks are a random intercept (the same REML machinery; the
        variance component is named ``"block"``). Not with ``block``.
    hard_to_change : str or sequence of str, optional
        With ``whole_plot``: factors (column names) that must be constant within every whole
        plot; one that varies inside a whole plot raises ValueError naming the factor, the
        whole plot and its rows. Without it the notes list the factors found constant
        within every whole plot.
    random_effects : sequence of str, optional
        Grouping columns, one random intercept each (a variance-components model: a
        split-split-plot's whole plots and subplots, a strip-plot's rows and columns, blocks
        and the whole plots inside them), fitted by REML with Kenward–Roger tests
        (:func:`rsm_lrg.model.engines.mixed.fit_reml_several`); with ``whole_plot`` or ``random_block``
        that column comes first. The effects are nested or crossed as the data say: each
        distinct value of a column is one level, as lme4's ``(1|COL)`` takes it, so a nested
        column must label its levels uniquely (``wp3-s2``, not ``s2`` in every whole plot);
        ``"A:B"`` (two columns joined by ``:``, when no column has that name) is their
        interaction, one level per combination, as lme4's ``(1|A:B)``. When two effects'
        levels cross (a level of each meets several of the other) the notes say so. The
        variance components are named as the columns; a prediction interval is for a new run
        in new levels of every random effect (variance ``x'Φ_A x + Σ s2_k + s2``).
    kernel, trend, nugget, length_scales, variance, seed
        With ``model="gp"`` only: the Gaussian process's kernel (``"matern52"``,
        ``"matern32"``, ``"gauss"``), trend (``"constant"``, ``"linear"``,
        ``"quadratic"``), nugget (``None``, ``"estimate"`` or a value), fixed
        hyper-parameters and the seed of the likelihood's starting points
        (:func:`rsm_lrg.model.pipelines.gp.fit_gp`).
    length_scale_bounds : (float, float), optional
        With ``model="gp"`` only: bounds of the estimated length-scales as multiples of each
        factor's coded range in the data; ``None``: 1e-3 and 10
        (:data:`~rsm_lrg.model.pipelines.gp.THETA_BOUNDS`). ``(1e-3, 2.0)``
        (:data:`~rsm_lrg.model.pipelines.gp.LOOP_THETA_BOUNDS`, R ``DiceKriging::km``'s
        default upper bound) is what ``rsm-lrg loop`` and ``rsm-lrg suggest`` fit with.
    family : {"binomial", "poisson"}, optional
        A generalised linear model of a 0/1 response, successes of ``trials``, or a count,
        fitted by maximum likelihood (:func:`rsm_lrg.model.pipelines.glm.fit_glm`; returns a
        :class:`~rsm_lrg.model.results.glm_result.GLMResult`).
    link : {"logit", "probit", "cloglog", "log"}, optional
        With ``family``: the link (default logit for binomial, log for poisson).
    trials : str, optional
        With ``family="binomial"``: the column of trials; the response counts successes.

    Returns
    -------
    FitResult, or GPResult for ``model="gp"``, or GLMResult with ``family``

    Raises
    ------
    ValueError
        Unknown or non-numeric columns (naming the row), a constant factor, a constant
        response, numbers beyond 1e±100 (response) or 1e±50 (factors), fewer runs than
        model terms (counted before any term is built), aliased terms (naming them), a
        response outside the transform's domain (naming the row). A bad specification is
        a :class:`~rsm_lrg.model.build.spec.SpecError` (a ValueError whose ``option`` names the
        argument).
    """
    from ..table import check_table, is_column_table

    table: Any = data  # a DataFrame, a Dask DataFrame or a ColumnTable (a plain CSV file read without pandas)
    if is_column_table(table) and not _ols_polynomial(model, family, link, trials, components, whole_plot,
                                                      random_block, random_effects):
        table = table.to_frame()  # the other engines read a DataFrame
    if isinstance(model, str) and model.strip().lower() == "gp":  # the Gaussian-process engine
        from .pipelines.gp import THETA_BOUNDS, fit_gp, refuse_options

        refuse_options(block=block, terms=terms, intercept=intercept, transform=transform, reduce=reduce,
                       components=components, whole_plot=whole_plot, random_block=random_block, dask=is_dask(table),
                       random_effects=random_effects)
        return fit_gp(table, response, factors, kernel=kernel, trend=trend, nugget=nugget,
                      length_scales=length_scales, variance=variance, seed=seed,
                      length_scale_bounds=THETA_BOUNDS if length_scale_bounds is None else length_scale_bounds)
    if length_scale_bounds is not None:  # a Gaussian process's option: never ignored silently
        raise SpecError("length_scale_bounds", "length_scale_bounds: only with model='gp' (a Gaussian process)")
    spec = ModelSpec.build(model, terms=terms, intercept=intercept, transform=transform,
                           transform_constant=transform_constant, reduce=reduce)
    if family is not None or link is not None or trials is not None:  # a GLM (rsm_lrg.model.pipelines.glm)
        from .pipelines.glm import fit_glm

        return fit_glm(table, response, factors, spec=spec, family_name=family, link=link, trials=trials, block=block,
                       components=components,
                       random_effect=whole_plot or random_block or (list(random_effects) if random_effects else None))
    if is_dask(table):  # fitted partition by partition, never collected; OLS only
        for option, given in (("whole_plot", whole_plot), ("random_block", random_block),
                              ("random_effects", random_effects), ("hard_to_change", hard_to_change)):
            if given is not None:  # a REML fit needs every run in memory: never an OLS fit instead
                raise SpecError(option, f"{option}: a REML fit (random whole plots or blocks) is made from one "
                                        "in-memory table, not from a Dask DataFrame (call .compute() first)")
        if components is not None or spec.mixture:
            raise SpecError("model", "a mixture model is fitted from one in-memory table, not several files")
        from .pipelines.dask_fit import fit_dask

        return fit_dask(table, response, factors=factors, block=block, spec=spec, chunk_rows=chunk_rows)
    hard = _hard_names(hard_to_change, whole_plot)
    if random_effects is not None:
        return _fit_several(table, response, factors, block, spec, whole_plot, random_block, random_effects,
                            components, hard)
    if whole_plot is not None or random_block is not None:
        return _fit_mixed(table, response, factors, block, spec, whole_plot, random_block, components, hard)
    check_table(table)
    if is_column_table(table) and (spec.mixture or spec.reduce is not None):  # read from a DataFrame
        table = table.to_frame()
    if components is not None or spec.mixture:
        return _fit_mixture(table, response, components, factors, block, spec, chunk_rows)
    inp = model_inputs(table, response, factors, block, transform=spec.transform, origin=not spec.intercept)
    reduction = None
    if spec.reduce is not None:
        from dataclasses import replace

        from .choice.select import choose_terms

        reduction = choose_terms(inp, spec.reduce, model=spec.order, terms=spec.terms, intercept=spec.intercept)
        spec = replace(spec, terms=tuple(t for t in reduction.kept if t != "Intercept") or None)
        if spec.terms is None:  # every term removed: the mean-only model
            raise SpecError("alpha_out" if reduction.criterion == "p" else "criterion",
                            "backward elimination removed every term: no factor explains the response "
                            + (f"(alpha_out {reduction.alpha_out:g})" if reduction.criterion == "p" else "(AICc)"))
    return fit_inputs(inp, response, spec, chunk_rows=chunk_rows, reduction=reduction)


def _ols_polynomial(model: Any, family: Any, link: Any, trials: Any, components: Any, whole_plot: Any,
                    random_block: Any, random_effects: Any) -> bool:
    """Whether a fit is made by least squares of a polynomial or a term list (no GP, GLM,
    mixture or random effect): the fit that reads a :class:`~rsm_lrg.table.ColumnTable` as it
    is; the others are given it as a DataFrame."""
    gp = isinstance(model, str) and model.strip().lower() == "gp"
    return not gp and all(v is None for v in (family, link, trials, components, whole_plot, random_block,
                                               random_effects))


def _fit_mixture(data: pd.DataFrame, response: str, components: Sequence[str] | None, factors: FactorsArg,
                 block: str | None, spec: ModelSpec,
                 chunk_rows: int) -> FitResult:
    """A Scheffé mixture fit (:mod:`rsm_lrg.model.build.mixture`)."""
    from ..factors import FactorSpace, MixtureComponent
    from .build.inputs import mixture_inputs
    from .build.mixture import MIXTURE_ORDERS

    if not spec.mixture:
        raise SpecError("model", f"mixture components need a Scheffé model ({', '.join(MIXTURE_ORDERS)}), "
                                 f"not {spec.order!r}")
    given = factors if isinstance(factors, FactorSpace) and not components else None
    if given is not None and any(isinstance(f, MixtureComponent) for f in given.factors):
        components, factors = None, None  # a fitted mixture model's own space (FitResult.reduce)
    elif not components:
        raise SpecError("model", f"the {spec.order} model needs the mixture components (components=[...], "
                                 "--component NAME)")
    else:
        given = None
    if given is not None:  # the space of a fitted mixture model
        inp = model_inputs(data, response, given, block, transform=spec.transform)
    else:
        inp = mixture_inputs(data, response, components or (), factors, block, transform=spec.transform)
    reduction = None
    if spec.reduce is not None:  # the linear blending terms always stay
        from dataclasses import replace

        from .choice.select import choose_terms

        try:
            reduction = choose_terms(inp, spec.reduce, model=spec.order, terms=spec.terms, intercept=False,
                                     mixture=True)
        except ValueError as exc:
            if "term" in str(exc) and "mixture" in str(exc):
                raise SpecError("terms", str(exc)) from None
            raise
        spec = replace(spec, terms=reduction.kept)
    return fit_inputs(inp, response, spec, chunk_rows=chunk_rows, reduction=reduction)


def _spec_terms(inp: ModelInputs, spec: ModelSpec, block_df: int) -> tuple:
    """The terms of ``spec``'s standard model or term list over ``inp``'s factors (not a
    mixture). A standard model's size is checked against the runs before any term is built (a
    cubic in 16 factors has 969); ``block_df`` the degrees of freedom the blocks take."""
    space = inp.space
    if spec.terms is None:
        try:
            check_model_size(inp.n, len(space), spec.order, block_df, categoric=space.categoric)
        except ValueError as exc:
            raise ValueError(f"{exc}{inp.hint}") from None
        return tuple(model_terms(space.letters, spec.order, space.categoric))
    try:
        return chosen_terms(spec.terms, space.letters, space.categoric, intercept=spec.intercept)
    except ValueError as exc:
        raise SpecError("terms", str(exc)) from None


def fit_inputs(inp: ModelInputs, response: str, spec: ModelSpec, *, chunk_rows: int = CHUNK_ROWS,
               reduction: Reduction | Selection | TwoStage | None = None) -> FitResult:
    """The fit of checked inputs (:func:`~rsm_lrg.model.build.inputs.model_inputs`) to ``spec``'s
    terms (its reduction, if any, already applied)."""
    space, y, hint, nb, n = inp.space, inp.y, inp.hint, inp.nb, inp.n
    model = spec.order
    if spec.mixture:
        terms = _mixture_terms(spec, space, n, inp.settings, hint)
    else:
        terms = _spec_terms(inp, spec, nb - 1)
    if nb > 1 and not spec.intercept and not spec.mixture:
        raise SpecError("terms", "blocks need a model with an intercept (block effects sum to zero about it)")
    col_names = inp.column_names(terms)
    p = len(col_names)
    what_model = f"the {model} model" if spec.terms is None else "the model"
    if n < p:
        what = f"{p - nb + 1} coefficients" + (f" and {nb - 1} block effects" if nb > 1 else "")
        raise ValueError(f"{n} runs cannot fit {p} coefficients ({what_model} in {len(space)} factors has {what}){hint}")

    # one factorisation (in chunks of rows), one pass more for the hat diagonal and residuals
    chunks = inp.chunks(terms, int(chunk_rows))
    ls = factorise(chunks, p, col_names, shift=None if spec.intercept else 0.0)
    ls.require_full_rank(f"{model} model" if spec.terms is None else "model")
    ls = ls.second_pass(chunks)
    # pure error: residual of y ~ (blocks +) one mean per distinct setting (R rsm's PE())
    pe = pure_error(inp.settings, y - ls.shift, inp.bcodes if nb > 1 else None)
    prep = inp.prep
    return assemble(spec=spec, response=response, block=inp.block, space=space, terms=terms, col_names=col_names,
                    ls=ls, pe=pe, bkeys=inp.bkeys, blevels=inp.blevels, data=prep.data.copy(), coded=inp.coded, y=y,
                    y_response=inp.y_response, input_notes=prep.notes, omitted_rows=prep.omitted_rows,
                    omitted_data=prep.omitted_data, reduction=reduction)


def _mixture_terms(spec: ModelSpec, space: FactorSpace, n: int, settings: np.ndarray, hint: str) -> tuple:
    """The Scheffé terms of a mixture spec, checked: products of distinct components, every
    linear blending term, no more terms than distinct blends."""
    import numpy as np

    from ..factors import MixtureComponent
    from .build.mixture import check_mixture_terms, scheffe_names

    q = sum(isinstance(f, MixtureComponent) for f in space.factors)
    letters = space.letters
    names = scheffe_names(letters[:q], spec.order, letters[q:]) if spec.terms is None else spec.terms
    try:
        terms = chosen_terms(names, letters, None, intercept=False)
        check_mixture_terms(terms, q)
    except ValueError as exc:
        raise SpecError("terms", str(exc)) from None
    blends = int(np.unique(np.asarray(settings, dtype=float), axis=0).shape[0])
    if blends < len(terms):
        what = f"the {spec.order} model" if spec.terms is None else "the model"
        kind = "blends" if q == len(space) else "settings"
        raise ValueError(f"{blends} distinct {kind} cannot fit {len(terms)} terms ({what} in {q} "
                         f"components{'' if q == len(space) else ' and ' + str(len(space) - q) + ' process factors'})"
                         f"{hint}")
    return terms


def _random_column(data: pd.DataFrame, response: str, whole_plot: str | None, random_block: str | None,
                   block: str | None) -> tuple[str, str, str]:
    """``(column, kind, what)`` of the random intercept, checked on every row (exists, not the
    response or the block, no empty cell)."""

    from ..factors import quote_value

    if whole_plot is not None and random_block is not None:
        raise SpecError("random_block", "give a whole-plot column or a random block column, not both")
    col, kind, what, option = ((whole_plot, "whole_plot", "whole-plot", "whole_plot") if whole_plot is not None
                               else (random_block, "block", "random block", "random_block"))
    col = str(col)
    if block is not None:
        raise SpecError("block", f"fixed blocks together with a {what} column are not available (give the blocks as "
                                 "random_block)")
    check_group_column(data, col, response, what, f"the {what} column")
    levels = data[col].unique()
    if len(levels) < 2:
        unit = "whole plots" if kind == "whole_plot" else "blocks"
        raise ValueError(f"{what} column {quote_value(col)} has a single level ({quote_value(str(levels[0]))}); a "
                         f"random {unit[:-1]} effect needs at least two {unit}")
    return col, kind, what


def _hard_names(hard_to_change: str | Sequence[str] | None, whole_plot: str | None) -> list[str] | None:
    """The ``hard_to_change`` names as a list (None when not given), checked: only with a
    whole-plot column, no name twice."""
    if hard_to_change is None:
        return None
    names = [hard_to_change] if isinstance(hard_to_change, str) else [str(h) for h in hard_to_change]
    if whole_plot is None:
        raise SpecError("hard_to_change", "hard-to-change factors are checked against a whole-plot column: give "
                                          "whole_plot too")
    if not names:
        raise SpecError("hard_to_change", "name at least one hard-to-change factor")
    for i, h in enumerate(names):
        if h in names[:i]:
            raise SpecError("hard_to_change", f"{h!r} is given twice")
    return names


def _row_ranges(rows: Sequence[int], most: int = 4) -> str:
    """``[9, 10, 11, 12, 20]`` -> ``"rows 9-12, 20"`` (1-based rows; at most ``most`` ranges)."""
    spans: list[list[int]] = []
    for r in rows:
        if spans and r == spans[-1][1] + 1:
            spans[-1][1] = r
        else:
            spans.append([r, r])
    text = [f"{a}" if a == b else f"{a}-{b}" for a, b in spans[:most]]
    return ("row " if len(rows) == 1 else "rows ") + ", ".join(text) + (", ..." if len(spans) > most else "")


def _check_hard_to_change(data: pd.DataFrame, col: str, hard: list[str] | None, factor_names: Sequence[str],
                          response: str) -> str:
    """Check that each hard-to-change factor is constant within every whole plot (ValueError
    naming the factor, the whole plot and its rows); return the note saying which factors are
    constant within every whole plot."""
    import numpy as np

    from ..factors import quote_value

    labels = data[col].tolist()
    plots: dict = {}
    for i, lab in enumerate(labels):
        plots.setdefault(lab, []).append(i)

    def varies(name: str) -> tuple | None:
        values = data[name].tolist()
        for lab, rows in plots.items():
            first = values[rows[0]]
            if any(not (values[r] == first or (values[r] != values[r] and first != first)) for r in rows[1:]):
                return lab, rows
        return None

    if hard is not None:
        for h in hard:
            if h not in data.columns:
                raise SpecError("hard_to_change", f"hard-to-change factor {quote_value(h)} is not a column of the data")
            if h in (col, response) or h not in factor_names:
                raise SpecError("hard_to_change", f"hard-to-change factor {quote_value(h)} is not a factor of the "
                                                  f"model (factors: {', '.join(factor_names)})")
            bad = varies(h)
            if bad is not None:
                lab, rows = bad
                where = str(lab) if isinstance(lab, (int, np.integer)) else quote_value(str(lab))
                raise ValueError(f"hard-to-change factor {quote_value(h)} varies inside whole plot {where} "
                                 f"({_row_ranges([r + 1 for r in rows])})")
        return (f"Hard-to-change factors (checked constant within every whole plot): {', '.join(hard)}.")
    const = [f for f in factor_names if f in data.columns and varies(f) is None]
    return (f"Factors constant within every whole plot (whole-plot factors): {', '.join(const)}."
            if const else "No factor is constant within every whole plot (every factor varies inside some whole plot).")


def _fit_mixed(data: pd.DataFrame | dd.DataFrame, response: str, factors: FactorsArg, block: str | None,
               spec: ModelSpec, whole_plot: str | None, random_block: str | None,
               components: Sequence[str] | None, hard: list[str] | None = None) -> FitResult:
    """A REML fit with one random intercept (:mod:`rsm_lrg.model.engines.mixed`), the reduction (if
    asked) by Kenward–Roger p-values."""
    import pandas as pd

    if not isinstance(data, pd.DataFrame):
        raise TypeError("data must be a pandas DataFrame")
    col, kind, what = _random_column(data, response, whole_plot, random_block, block)
    if components is not None or spec.mixture:  # a Scheffé model (Kowalski, Cornell & Vining 2002)
        # the grouping column read as blocks are (checked, kept out of the notes), then dropped
        inp = model_inputs(data, response, _mixed_mixture_space(data, response, components, factors, spec), col,
                           transform=spec.transform)
    else:
        inp = model_inputs(data, response, factors, col, transform=spec.transform, origin=not spec.intercept)
    from dataclasses import replace

    if kind == "whole_plot":
        note = _check_hard_to_change(data, col, hard, inp.space.names, response)
        inp = replace(inp, prep=replace(inp.prep, notes=tuple(inp.prep.notes) + (note,)))
    labels = inp.prep.data[col].tolist()
    inp = replace(inp, block=None, bcodes=None, bkeys=None, blevels=None)
    reduction = None
    if spec.reduce is not None and spec.mixture:
        raise SpecError("reduce", "a REML mixture fit is not reduced here: fit the chosen Scheffé terms (terms=...)")
    if spec.reduce is not None:
        from .choice.mixed_reduce import reduce_mixed

        if spec.reduce.criterion != "p":
            raise SpecError("criterion", "a REML fit is reduced by the Kenward-Roger p-values (criterion 'p'), "
                                         f"not {spec.reduce.criterion!r}")
        reduction = reduce_mixed(lambda sp: _fit_mixed_inputs(inp, response, sp, labels, col, kind, what), spec,
                                 inp.space)
        spec = replace(spec, terms=tuple(t for t in reduction.kept if t != "Intercept") or None)
        if spec.terms is None:
            raise SpecError("alpha_out" if reduction.criterion == "p" else "criterion",
                            "backward elimination removed every term: no factor explains the response "
                            + (f"(alpha_out {reduction.alpha_out:g})" if reduction.criterion == "p" else "(AICc)"))
    return _fit_mixed_inputs(inp, response, spec, labels, col, kind, what, reduction=reduction)


def _fit_mixed_inputs(inp: ModelInputs, response: str, spec: ModelSpec, labels: list, col: str, kind: str, what: str,
                      reduction: Reduction | None = None) -> FitResult:
    """The REML fit of checked inputs to ``spec``'s terms (estimability checked first)."""
    import numpy as np

    from .engines.mixed import fit_reml, group_codes

    space, y, hint, n = inp.space, inp.y, inp.hint, inp.n
    model = spec.order
    terms = _mixture_terms(spec, space, n, inp.settings, hint) if spec.mixture else _spec_terms(inp, spec, 0)
    col_names = inp.column_names(terms)
    p = len(col_names)
    what_model = f"the {model} model" if spec.terms is None else "the model"
    if n < p:
        raise ValueError(f"{n} runs cannot fit {p} coefficients ({what_model} in {len(space)} factors){hint}")
    codes, glabels = group_codes(labels)
    G = len(glabels)
    X = inp.rows(terms)
    gsum = np.zeros((G, p))
    np.add.at(gsum, codes, X)
    m = np.bincount(codes, minlength=G).astype(float)
    within = X - (gsum / m[:, None])[codes]
    scale = np.maximum(np.abs(X).max(axis=0), 1.0)
    constant = np.all(np.abs(within) <= 1e-12 * scale, axis=0)  # the group-level (whole-plot) columns
    group_cols = [col_names[j] for j in np.flatnonzero(constant)]
    unit = "whole plots" if kind == "whole_plot" else "blocks"
    if len(group_cols) >= G:
        raise ValueError(f"{col!r}: {G} {unit} cannot estimate the {len(group_cols)} {what} terms "
                         f"({', '.join(group_cols)}) and their variance: the model needs at least "
                         f"{len(group_cols) + 1} {unit}")
    rank_within = int(np.linalg.matrix_rank(within[:, ~constant])) if (~constant).any() else 0
    if n - G - rank_within <= 0:
        singles = [str(glabels[i]) for i in np.flatnonzero(m == 1)]
        where = (f"{what.split()[-1] if kind == 'block' else 'whole plot'} {singles[0]!r} has one run"
                 if singles else f"the {unit} are too small")
        raise ValueError(f"{col!r}: {where} and the model needs more: {n} runs in {G} {unit} leave no degree of "
                         f"freedom for the residual variance within {unit} after the {rank_within} within-{unit[:-1]} "
                         "model columns")
    from .engines.least_squares import least_squares

    least_squares(X, y, col_names).require_full_rank(f"{model} model" if spec.terms is None else "model")
    mm, ls = fit_reml(X, y, codes, glabels, col_names, column=col, kind=kind)
    pe = pure_error(inp.settings, y - float(np.mean(y)), None)
    prep = inp.prep
    return assemble(spec=spec, response=response, block=None, space=space, terms=terms, col_names=col_names,
                    ls=ls, pe=pe, bkeys=None, blevels=None, data=prep.data.copy(), coded=inp.coded, y=y,
                    y_response=inp.y_response, input_notes=prep.notes, omitted_rows=prep.omitted_rows,
                    omitted_data=prep.omitted_data, reduction=reduction, mixed=mm)


def _mixed_mixture_space(data: pd.DataFrame, response: str, components: Sequence[str] | None, factors: FactorsArg,
                         spec: ModelSpec) -> FactorSpace:
    """The factors of a Scheffé model with random effects: the components as L-pseudo
    components and the process factors, as :func:`_fit_mixture` reads them (or the space of
    a fitted mixture model given as ``factors``, as a refit passes it)."""
    from ..factors import FactorSpace, MixtureComponent
    from .build.mixture import MIXTURE_ORDERS, mixture_space

    if (not components and isinstance(factors, FactorSpace)
            and any(isinstance(f, MixtureComponent) for f in factors.factors)):
        return factors
    if not spec.mixture:
        raise SpecError("model", f"mixture components need a Scheffé model ({', '.join(MIXTURE_ORDERS)}), "
                                 f"not {spec.order!r}")
    if not components:
        raise SpecError("model", f"the {spec.order} model needs the mixture components (components=[...], "
                                 "--component NAME)")
    comps = [components] if isinstance(components, str) else list(components)
    return mixture_space(data, comps, response, process=factors)


def _effect_columns(data: pd.DataFrame, response: str, whole_plot: str | None, random_block: str | None,
                    random_effects: Sequence[str] | str, block: str | None) -> tuple[pd.DataFrame, list[str], list[str]]:
    """``(data, columns, used)``: the random-effect columns in order (``whole_plot`` or
    ``random_block`` first), checked on every row, the data with the ``"A:B"`` interaction
    columns added, and every data column they use (kept out of the inferred factors)."""

    from ..factors import quote_value

    if whole_plot is not None and random_block is not None:
        raise SpecError("random_block", "give a whole-plot column or a random block column, not both (give several "
                                        "grouping columns as random_effects)")
    given = [random_effects] if isinstance(random_effects, str) else [str(c) for c in random_effects]
    cols = [str(c) for c in (whole_plot, random_block) if c is not None] + given
    if not cols:
        raise SpecError("random_effects", "name at least one random-effect column")
    for i, c in enumerate(cols):
        if c in cols[:i]:
            raise SpecError("random_effects", f"random-effect column {quote_value(c)} is given twice")
    if block is not None:
        raise SpecError("block", "fixed blocks together with random effects are not available (give the blocks as a "
                                 "random effect)")
    used: list[str] = []
    out = data
    for c in cols:
        parts = c.split(":") if c not in data.columns and ":" in c else [c]
        for part in parts:
            check_group_column(data, part, response, "random-effect", "a random-effect column")
            used.append(part)
        if len(parts) > 1:  # the interaction: one level per combination of the columns' values
            if out is data:
                out = data.copy()
            out[c] = [":".join(str(v) for v in row) for row in zip(*(data[q].tolist() for q in parts))]
        levels = out[c].unique()
        if len(levels) < 2:
            raise ValueError(f"random-effect column {quote_value(c)} has a single level ({quote_value(str(levels[0]))})"
                             "; a random effect needs at least two levels")
    return out, cols, used


def _crossing_notes(effects: Sequence[Any]) -> list[str]:
    """A note for each pair of random effects whose levels cross (a level of each meets several
    levels of the other): fitted as crossed, as given."""
    notes = []
    for i, a in enumerate(effects):
        for b in effects[i + 1:]:
            pairs = set(zip(a.codes.tolist(), b.codes.tolist()))
            if len(pairs) > max(a.n_levels, b.n_levels):  # neither nested in the other
                notes.append(f"Random effects {a.column!r} and {b.column!r} are crossed (a level of each meets several "
                             "levels of the other) and are fitted so, each value one level as given; if one is nested "
                             "in the other with its labels reused (1, 2, ... inside every level), give it unique "
                             f"labels or name the interaction ('{a.column}:{b.column}').")
    return notes


def _fit_several(data: pd.DataFrame | dd.DataFrame, response: str, factors: FactorsArg, block: str | None,
                 spec: ModelSpec, whole_plot: str | None, random_block: str | None, random_effects: Sequence[str] | str,
                 components: Sequence[str] | None, hard: list[str] | None = None) -> FitResult:
    """A REML fit with the random intercepts of ``random_effects`` (and ``whole_plot`` or
    ``random_block``): one effect goes to :func:`_fit_mixed`'s engine, several to
    :func:`rsm_lrg.model.engines.mixed.fit_reml_several`; the reduction (if asked) by Kenward–Roger p."""
    import pandas as pd

    from .engines.mixed import RandomEffect, group_codes

    if not isinstance(data, pd.DataFrame):
        raise TypeError("data must be a pandas DataFrame")
    frame, cols, used = _effect_columns(data, response, whole_plot, random_block, random_effects, block)
    if len(cols) == 1 and (whole_plot is not None or random_block is not None):
        return _fit_mixed(data, response, factors, block, spec, whole_plot, random_block, components, hard)
    if components is not None or spec.mixture:  # a Scheffé model (the effect columns are no factors)
        inp = model_inputs(frame, response, _mixed_mixture_space(frame, response, components, factors, spec), None,
                           transform=spec.transform, exclude=cols + used)
    else:
        inp = model_inputs(frame, response, factors, None, transform=spec.transform, origin=not spec.intercept,
                           exclude=cols + (used if factors is None else []))
    from dataclasses import replace

    extra = []
    if whole_plot is not None:
        extra.append(_check_hard_to_change(frame, whole_plot, hard, inp.space.names, response))
    effects = []
    for c in cols:
        codes, labels = group_codes(inp.prep.data[c].tolist())
        effects.append(RandomEffect(column=c, codes=codes, labels=labels))
    for i, a in enumerate(effects):
        for b in effects[i + 1:]:
            if len(set(zip(a.codes.tolist(), b.codes.tolist()))) == a.n_levels == b.n_levels:
                raise ValueError(f"random effects {a.column!r} and {b.column!r} group the runs the same way: their "
                                 "variances cannot be told apart; give one of them")
    extra += _crossing_notes(effects)
    inp = replace(inp, prep=replace(inp.prep, notes=tuple(inp.prep.notes) + tuple(extra)))
    if len(effects) == 1:  # random_effects=[COL]: the one-effect engine, the component named as the column
        labels1 = inp.prep.data[cols[0]].tolist()

        def refit1(sp: ModelSpec, reduction: Reduction | None = None) -> FitResult:
            return _fit_mixed_inputs(inp, response, sp, labels1, cols[0], "effect", "random-effect",
                                     reduction=reduction)
        refit = refit1
    else:
        def refit_k(sp: ModelSpec, reduction: Reduction | None = None) -> FitResult:
            return _fit_several_inputs(inp, response, sp, effects, reduction=reduction)
        refit = refit_k
    reduction = None
    if spec.reduce is not None and spec.mixture:
        raise SpecError("reduce", "a REML mixture fit is not reduced here: fit the chosen Scheffé terms (terms=...)")
    if spec.reduce is not None:
        from .choice.mixed_reduce import reduce_mixed

        if spec.reduce.criterion != "p":
            raise SpecError("criterion", "a REML fit is reduced by the Kenward-Roger p-values (criterion 'p'), "
                                         f"not {spec.reduce.criterion!r}")
        reduction = reduce_mixed(lambda sp: refit(sp), spec, inp.space)
        spec = replace(spec, terms=tuple(t for t in reduction.kept if t != "Intercept") or None)
        if spec.terms is None:
            raise SpecError("alpha_out", "backward elimination removed every term: no factor explains the response "
                                         f"(alpha_out {reduction.alpha_out:g})")
    return refit(spec, reduction)


def _fit_several_inputs(inp: ModelInputs, response: str, spec: ModelSpec, effects: Sequence[Any],
                        reduction: Reduction | None = None) -> FitResult:
    """The REML fit of checked inputs with several random intercepts (estimability checked
    first: every effect adds to the fixed terms' span, and a residual degree of freedom is left)."""
    import numpy as np

    from .engines.least_squares import least_squares
    from .engines.mixed import fit_reml_several

    space, y, hint, n = inp.space, inp.y, inp.hint, inp.n
    terms = _mixture_terms(spec, space, n, inp.settings, hint) if spec.mixture else _spec_terms(inp, spec, 0)
    col_names = inp.column_names(terms)
    p = len(col_names)
    what_model = f"the {spec.order} model" if spec.terms is None else "the model"
    if n < p:
        raise ValueError(f"{n} runs cannot fit {p} coefficients ({what_model} in {len(space)} factors){hint}")
    X = inp.rows(terms)
    least_squares(X, y, col_names).require_full_rank(f"{spec.order} model" if spec.terms is None else "model")
    Z = [np.eye(e.n_levels)[e.codes] for e in effects]
    rank_x = int(np.linalg.matrix_rank(X))
    for e, z in zip(effects, Z):
        if int(np.linalg.matrix_rank(np.hstack([X, z]))) == rank_x:
            raise ValueError(f"random effect {e.column!r}: its {e.n_levels} levels are explained by the model's fixed "
                             "terms (each level's mean is a fixed effect), so it has no variance to estimate; leave "
                             "it out or drop the terms that are constant within its levels")
    rank_all = int(np.linalg.matrix_rank(np.hstack([X] + Z)))
    if n - rank_all <= 0:
        raise ValueError(f"{n} runs leave no degree of freedom for the residual variance once the {p} model columns "
                         f"and the levels of {', '.join(repr(e.column) for e in effects)} are fitted: REML needs "
                         "replication within the random-effect levels")
    mm, ls = fit_reml_several(X, y, effects, col_names)
    pe = pure_error(inp.settings, y - float(np.mean(y)), None)
    prep = inp.prep
    return assemble(spec=spec, response=response, block=None, space=space, terms=terms, col_names=col_names,
                    ls=ls, pe=pe, bkeys=None, blevels=None, data=prep.data.copy(), coded=inp.coded, y=y,
                    y_response=inp.y_response, input_notes=prep.notes, omitted_rows=prep.omitted_rows,
                    omitted_data=prep.omitted_data, reduction=reduction, mixed=mm)


def fit_transformed(data: pd.DataFrame | dd.DataFrame, response: str, transform: str | Transform, *,
                    constant: float = 0.0, **fit_kwargs: Any) -> FitResult:
    """Fit ``g(response + constant)``: the same as ``fit(data, response, transform=transform,
    transform_constant=constant, ...)`` (kept for older code; returns a :class:`FitResult`).

    Parameters
    ----------
    data : pandas.DataFrame or dask.dataframe.DataFrame
        The runs, as for :func:`~rsm_lrg.fit`.
    response : str
        The response column [response units].
    transform : str or Transform
        ``"log"``, ``"log10"``, ``"sqrt"``, ``"inverse"``, ``"power=λ"`` or a :class:`Transform`.
    constant : float, default 0.0
        k added to the response before transforming [response units].
    **fit_kwargs
        Any other keyword argument of :func:`~rsm_lrg.fit`.

    Returns
    -------
    FitResult
        The fit on the transformed scale; predictions and goals on the response's own scale.
    """
    return fit(data, response, transform=transform, transform_constant=constant, **fit_kwargs)
