"""The checked inputs of a fit: data prepared, factors coded, blocks coded, the response
on the model's scale (:func:`model_inputs`), shared by :func:`rsm_lrg.model.fit.fit`, the
fit summary, backward elimination and the Dask fit; and the chosen term list of a model
(:func:`chosen_terms`)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ...errors import ParameterError
from ...factors import FactorSpace, quote_value
from ...io import float_column, float_values, remembered_float_columns
from ...table import check_table, is_column_table
from .data import CHUNK_ROWS, prepare
from .terms import Term, column_names, model_matrix, model_terms, n_columns, parse_term
from .transform import Transform

__all__ = ["coded_points", "ModelInputs", "model_inputs", "block_codes", "chosen_terms", "check_magnitudes", "model_rows",
           "is_dask", "origin_coding", "unrounded_coding", "MAX_MAGNITUDE", "MAX_FACTOR_MAGNITUDE"]


def block_codes(data, block: str):
    """Integer codes 0..b-1 (levels sorted), keys "B1".., level labels."""
    if is_column_table(data):  # numbers, none empty (rsm_lrg.table)
        labels = np.asarray(data[block], dtype=float)
    else:
        import pandas as pd

        col = data[block]
        if col.isna().any():
            i = int(np.flatnonzero(col.isna().to_numpy())[0])
            raise ValueError(f"block column {quote_value(block)}, row {i + 1}: is empty")
        num = pd.to_numeric(col, errors="coerce")
        labels = num.to_numpy(dtype=float) if not num.isna().any() else col.astype(str).str.strip().to_numpy()
    levels = np.unique(labels)
    codes = np.searchsorted(levels, labels)
    shown: list[int | float | str] = ([int(v) if float(v).is_integer() else float(v) for v in levels]
                                      if labels.dtype.kind == "f" else [str(v) for v in levels])
    if len(levels) < 2:
        raise ValueError(f"block column {quote_value(block)} has a single level ({quote_value(shown[0])}); "
                         "a block column needs at least two")
    keys = [f"B{i + 1}" for i in range(len(levels))]
    return codes.astype(int), keys, dict(zip(keys, shown))


def chosen_terms(names: Sequence[str | Term] | str, letters: Sequence[str], categoric: Any = None, *,
                 intercept: bool = True) -> tuple[Term, ...]:
    """The named terms (plus the intercept unless ``intercept=False``), without repeats, in
    Design-Expert order. ``"Intercept"`` among the names is the intercept flag's business:
    it is dropped from ``names`` (``intercept`` decides)."""
    if isinstance(names, str):
        names = names.replace(",", " ").split()
    names = [nm for nm in names if not (isinstance(nm, str) and nm.strip() == "Intercept")]
    if not names and not intercept:
        raise ValueError("a model without an intercept needs at least one term")
    chosen: dict[tuple, Term] = {}
    for nm in (["Intercept"] if intercept else []) + list(names):
        t = parse_term(str(nm).strip(), letters, categoric) if not isinstance(nm, Term) else nm
        chosen[t.key] = t
    order = {t.powers: i for i, t in enumerate(model_terms(letters, "cubic", categoric))}

    def rank(t: Term) -> tuple:  # a full-cubic AB(A-B) where A^2B stands
        return (order.get(t.monomials[0][1], len(order)), t.order, t.powers, t.diff)

    return tuple(sorted(chosen.values(), key=rank))


#: Largest magnitude of a response value (and smallest spread) that a fit accepts: sums of
#: squares of such numbers stay far from overflow and underflow.
MAX_MAGNITUDE = 1e100
#: Largest magnitude of a factor value (and smallest half-range): the actual-units
#: coefficients of a cubic, up to ``b (c/h)^3 / h^3``, then stay finite.
MAX_FACTOR_MAGNITUDE = 1e50


def check_magnitudes(space: FactorSpace, y: np.ndarray, response: str) -> None:
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


def model_rows(x: np.ndarray, terms, bcodes: np.ndarray | None, nb: int, start: int = 0,
                stop: int | None = None) -> np.ndarray:
    """Rows ``start:stop`` of the model matrix (:func:`~rsm_lrg.model.build.terms.model_matrix`)."""
    return model_matrix(x[start:stop], terms, None if bcodes is None else bcodes[start:stop], nb)


@dataclass(frozen=True)
class ModelInputs:
    """The checked inputs of a fit (:func:`model_inputs`): the same for :func:`fit`,
    :func:`~rsm_lrg.model.choice.summary.fit_summary` and :func:`~rsm_lrg.model.choice.reduce.reduce_terms`.

    Attributes
    ----------
    prep : PreparedData
    space : FactorSpace
    coded : pandas.DataFrame or rsm_lrg.table.ColumnTable
        Coded settings, columns = letters (a ColumnTable for a ColumnTable's fit).
    x : (n, k) ndarray
        The coded settings as an array, unrounded (the model matrix is built from it).
    y : (n,) ndarray
        Response on the model's scale: ``g(y + k)`` under a transform, else the response
        [response units].
    block : str or None
    bcodes : ndarray of int or None
        Block code 0..b-1 of each run.
    bkeys : list of str or None
        ``["B1", ...]``.
    blevels : dict or None
        ``{"B1": original label, ...}``.
    transform : Transform
        The response transform (``Transform()``, the identity, when none).
    y_response : (n,) ndarray
        The response as measured [response units].
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
    transform: Transform = Transform()
    y_response: np.ndarray | None = None
    keys: np.ndarray | None = None

    @property
    def settings(self) -> np.ndarray:
        """The coded settings rounded to :data:`~rsm_lrg.factors.CODED_DECIMALS` (``x`` is
        unrounded): what makes two runs the same setting (pure error)."""
        return self.x if self.keys is None else self.keys

    @property
    def n(self) -> int:
        return int(self.y.size)

    @property
    def nb(self) -> int:
        """Number of blocks (1 when unblocked)."""
        return len(self.bkeys) if self.bkeys else 1

    @property
    def mixture(self) -> bool:
        """Whether the factors are mixture components (a Scheffé model, no intercept column).

        Returns
        -------
        bool
        """
        from ...factors import MixtureComponent

        return any(isinstance(f, MixtureComponent) for f in self.space.factors)

    @property
    def hint(self) -> str:
        return self.prep.choice.hint()

    def column_names(self, terms: Sequence[Term]) -> list[str]:
        names = column_names(terms)
        if self.bkeys and len(self.bkeys) > 1:  # self.nb > 1
            if not terms or not (terms[0].order == 0 or self.mixture):
                raise ParameterError("block", "blocks need a model with an intercept (block effects sum to zero about it)")
            # after the intercept, or after a Scheffé model's first blending term (the linear
            # blending terms hold the mean)
            return names[:1] + [f"Block[{k}]" for k in self.bkeys[:-1]] + names[1:]
        return names

    def term_columns(self, terms) -> np.ndarray:
        """Positions of the model terms among the columns (blocks skipped)."""
        p = n_columns(terms) + self.nb - 1
        return np.r_[0, np.arange(self.nb, p)] if self.nb > 1 else np.arange(p)

    def rows(self, terms, start: int = 0, stop: int | None = None) -> np.ndarray:
        return model_rows(self.x, terms, self.bcodes, self.nb, start, stop)

    def chunks(self, terms, rows: int = CHUNK_ROWS):
        """``chunks()`` iterates over ``(model-matrix rows, responses)`` of ``rows`` runs each."""
        n = self.n
        return lambda: ((self.rows(terms, s, s + rows), self.y[s:s + rows]) for s in range(0, n, rows))


def unrounded_coding(space: FactorSpace, data: Any, coded: np.ndarray) -> np.ndarray:
    """The coded settings the model matrix is built from: the numeric factors' coding
    ``((x - low) - (high - x)) / (high - low)`` unrounded (the rounding of ``coded`` to
    CODED_DECIMALS would perturb the data by up to 5e-13 and cost digits, e.g. on NIST StRD);
    the other columns of ``coded`` (level indices, pseudo components) as they are."""
    x = np.array(coded, dtype=float, copy=True)
    for j, f in enumerate(space.factors):
        if f.kind == "numeric":
            v = float_values(data, f.name)
            x[:, j] = ((v - f.low) - (f.high - v)) / (f.high - f.low)
    return x


def coded_points(space: FactorSpace, points: Any, coded: bool = False) -> np.ndarray:
    """Prediction points as an (m, k) array of coded settings, for every kind of fit.

    Parameters
    ----------
    space : FactorSpace
        The fit's factors.
    points : DataFrame, Series, mapping or array-like
        A frame (or one row) with the factor columns (their names; their letters when
        ``coded``), a ``{name: values}`` mapping, or an (m, k) array in factor order.
    coded : bool
        ``points`` are coded settings already (letters as column names).

    Returns
    -------
    numpy.ndarray
        (m, k) coded settings: numeric factors coded unrounded as the runs were
        (:func:`unrounded_coding`), categoric factors as level indices, mixture components
        as L-pseudo components.

    Raises
    ------
    ValueError
        A factor column missing, the wrong number of columns, a level not in the fit, a
        value that is not a number, or a setting more than :data:`MAX_FACTOR_MAGNITUDE`
        half-ranges from its factor's centre (the point is named).
    """
    import pandas as pd

    if isinstance(points, Mapping):
        points = pd.DataFrame({k: np.atleast_1d(np.asarray(v, dtype=object if space.has_categoric else float))
                               for k, v in points.items()})
    if isinstance(points, pd.Series):
        points = points.to_frame().T
    if isinstance(points, pd.DataFrame):
        cols = space.letters if coded else space.names
        missing = [c for c in cols if c not in points.columns]
        if missing:
            raise ValueError(f"prediction points lack the factor column(s) {', '.join(map(repr, missing))}")
        if coded:
            x = np.column_stack([float_column(points, c).to_numpy(dtype=float) for c in cols])
        else:
            with np.errstate(over="ignore", invalid="ignore"):
                x = unrounded_coding(space, points, space.encode(points[cols]).to_numpy(dtype=float))
    else:
        arr = np.asarray(points, dtype=object if space.has_categoric and not coded else float)
        if arr.ndim == 1:
            arr = arr[None, :]
        if arr.ndim != 2 or arr.shape[1] != len(space):
            raise ValueError(f"prediction points need {len(space)} columns (one per factor), got {arr.shape[-1]}")
        if coded:
            x = np.asarray(arr, dtype=float)
        else:
            frame = pd.DataFrame({f.name: arr[:, j] for j, f in enumerate(space.factors)})
            with np.errstate(over="ignore", invalid="ignore"):
                x = unrounded_coding(space, frame, np.asarray(space.encode(arr), dtype=float))
    if np.isnan(x).any():
        raise ValueError("prediction points must be finite numbers")
    far = ~(np.abs(x) <= MAX_FACTOR_MAGNITUDE)
    if far.any():  # a polynomial there overflows (and says nothing): refuse with the factor named
        i, j = np.argwhere(far)[0]
        f = space.factors[j]
        where = f" ({f.center:.6g})" if f.kind == "numeric" else ""
        raise ValueError(f"prediction point {i + 1}: factor {f.name!r} is more than {MAX_FACTOR_MAGNITUDE:.0e} "
                         f"half-ranges from its centre{where}; the model says nothing there")
    return x


def origin_coding(space: FactorSpace) -> FactorSpace:
    """The factor space with every numeric factor coded about zero: low ``-M``, high ``M``
    (``M = max(|low|, |high|)``), so coded ``x / M``; categoric factors as they are."""
    from dataclasses import replace

    out = []
    for f in space.factors:
        if f.kind == "numeric":
            m = max(abs(float(f.low)), abs(float(f.high)))
            f = replace(f, low=-m, high=m)
        out.append(f)
    return replace(space, factors=tuple(out))


def is_dask(data) -> bool:
    """A Dask DataFrame (checked by its module, so dask is not imported for a pandas fit)."""
    return type(data).__module__.split(".")[0] == "dask" and hasattr(data, "map_partitions")


def mixture_inputs(data: Any, response: str, components: Sequence[str] | str, factors: Any = None,
                   block: str | None = None, transform: Transform | None = None) -> ModelInputs:
    """The checked inputs of a Scheffé mixture fit (:func:`rsm_lrg.fit` with ``components``
    and the mixture fit summary read them so): the components as L-pseudo components and the
    process factors ``factors`` (:func:`rsm_lrg.model.build.mixture.mixture_space`), then
    :func:`model_inputs`; ``block`` the column of fixed blocks (their sum-to-zero contrasts
    after the first linear blending term, as after the intercept of a polynomial)."""
    from .mixture import mixture_space

    comps = [components] if isinstance(components, str) else list(components)
    space = mixture_space(data, comps, response, process=factors)
    return model_inputs(data, response, space, block, transform=transform)


def model_inputs(data: Any, response: str, factors: Any = None, block: str | None = None,
                 transform: Transform | None = None, *, origin: bool = False,
                 exclude: Sequence[str] = ()) -> ModelInputs:
    """Check the data and code the factors as every fit does (see :func:`rsm_lrg.model.fit.fit`
    for what is refused); with ``transform`` the response is taken to the model's scale
    ``g(y + k)`` (a value outside the transform's domain is an error naming its row).

    ``origin=True`` (a model without an intercept) codes each numeric factor about zero,
    ``x / M`` with ``M`` the larger magnitude of its low and high level, so that the model
    passes through the origin of the actual units (as R's ``lm(y ~ 0 + x)``); a coding about
    the centre would hide an intercept in the actual units."""
    check_table(data)
    tr = transform if transform is not None else Transform()
    if not tr.identity and response in data.columns:
        from .data import response_values

        tr.check(response_values(data, response)[0], response)  # NaN (not run) passes; rows as in the file
    with remembered_float_columns():  # each factor column converted and checked once, not four times
        # columns, factors (inferred from a design's coded columns when not given), runs
        # without a response left out, notes on everything left out (rsm_lrg.model.build.data)
        prep = prepare(data, response, factors, block, exclude=exclude)  # exclude: random-effect columns
        data, space, y = prep.data, prep.space, prep.y
        if origin:
            space = origin_coding(space)
        coded = space.encode(data)
        keys = coded.to_numpy(dtype=float)  # rounded coding: settings equal to round-off are one setting
        x = unrounded_coding(space, data, keys)
    for j, f in enumerate(space.factors):
        if np.all(keys[:, j] == keys[0, j]):  # one setting (np.unique would load numpy.ma: 20 ms at start-up)
            raise ValueError(f"factor column {f.name!r} is constant; a factor needs at least two levels")
    y_response = y
    if not tr.identity:
        y = tr.forward(y)
    check_magnitudes(space, y, response)
    if np.all(y == y[0]):
        if not tr.identity and not np.all(y_response == y_response[0]):  # the transform's doing, not the data's
            from .spec import SpecError

            raise SpecError("transform", f"maps every value of response {response!r} to {y[0]:.6g} (the transformed "
                                         "values do not differ in double precision); choose another transform")
        raise ValueError(f"response {response!r} is constant (all {y[0]:.6g}): nothing to model")
    if block is not None:
        bcodes, bkeys, blevels = block_codes(data, block)
    else:
        bcodes, bkeys, blevels = None, None, None
    return ModelInputs(prep=prep, space=space, coded=coded, x=x, y=y, block=block, bcodes=bcodes, bkeys=bkeys,
                       blevels=blevels, transform=tr, y_response=y_response, keys=keys)

