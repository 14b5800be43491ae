"""Fitting a Dask DataFrame partition by partition: ``rsm_lrg.fit(ddf, response, ...)``.

The runs are never collected into one process. The fit makes three passes over the
partitions, each a reduction:

1. the coding: minimum and maximum of every numeric column (a factor named without
   levels is coded from them, as :func:`rsm_lrg.fit` codes a pandas frame; the factors are
   chosen by :func:`rsm_lrg.factors.choose_factors` from those two rows), and the count and
   sum of the response (its mean is the shift that keeps an offset from costing digits);
2. per partition the triangular factor of ``[X | y - shift]``
   (:class:`~rsm_lrg.model.least_squares.Accumulator` over chunks of rows), merged pairwise
   in a tree (TSQR) into the factor of all the runs;
   In the same pass, per partition, the pure-error sums of every distinct factor setting
   (count, sum and sum of squares of ``y - shift``, keyed by a 64-bit hash of the setting,
   with a second hash kept to detect two settings sharing a key), added up setting by
   setting along the same tree: ``SS_pe = sum_g (S2_g - S1_g^2 / n_g)`` on ``n - g``
   degrees of freedom;
3. per partition the second-pass sums (residual SS, PRESS, range of the fitted values,
   total SS; :class:`~rsm_lrg.model.least_squares.PassSums`).

Each pass reads every partition once (three reads of the data in all).

The result is the same :class:`~rsm_lrg.model.fit.FitResult` (coefficients, ANOVA with
lack of fit, statistics with PRESS, canonical analysis) without the per-run arrays:
``data`` is the Dask DataFrame itself, ``y``, ``coded``, ``fitted``, ``residuals`` and
``hat`` are ``None``. Rows whose response is missing are left out (counted in a note).
Blocks are not supported here (a ValueError says so).
"""

from __future__ import annotations

import numpy as np

from .least_squares import CHUNK_ROWS, Accumulator

__all__ = ["fit_dask"]


def _space_and_notes(ddf, response: str, factors, numeric: list[str], lo, hi):
    """The factor space chosen from the columns' minimum and maximum (two rows)."""
    import pandas as pd

    from ..factors import choose_factors

    two = pd.DataFrame({c: [float(lo[c]), float(hi[c])] for c in numeric})
    if isinstance(factors, (list, tuple)) or isinstance(factors, str):
        names = [factors] if isinstance(factors, str) else list(factors)
        for it in names:
            name = it.split("=", 1)[0].strip() if isinstance(it, str) else None
            if name is not None and name not in two.columns:
                if name in ddf.columns:
                    raise ValueError(f"factor column {name!r} is not numeric")
                raise ValueError(f"factor column {name!r} is not in the data")
    choice = choose_factors(two, factors, exclude=[response])
    return choice.space, tuple(choice.notes)


def _partition_rows(pdf, space, response: str):
    """Coded settings and response of the runs of one partition that have a response."""
    pdf = pdf[pdf[response].notna()]
    x = space.encode(pdf[space.names]).to_numpy(dtype=float)
    return x, pdf[response].to_numpy(dtype=float)


def _chunks(x, y, terms, rows: int):
    from .terms import design_matrix

    for s in range(0, y.size, rows):
        yield design_matrix(x[s:s + rows], terms), y[s:s + rows]


#: Odd 64-bit multipliers of the two row hashes of :func:`_row_hash` (golden ratio; MurmurHash3's fmix).
_MULTIPLIERS = (0x9E3779B97F4A7C15, 0xFF51AFD7ED558CCD)
_AGG = {"_n": "sum", "_s1": "sum", "_s2": "sum", "_lo": "min", "_hi": "max"}


def _row_hash(values: np.ndarray, which: int) -> np.ndarray:
    """A 64-bit hash of the bit pattern of each row of ``values`` (m x k floats; -0.0 read as
    0.0), ``which`` = 0 or 1 for two different hash functions."""
    bits = np.ascontiguousarray(np.asarray(values, dtype=float) + 0.0).view(np.uint64)
    mult, shift = np.uint64(_MULTIPLIERS[which]), np.uint64(31 + 2 * which)
    h = np.full(bits.shape[0], np.uint64(which + 1), dtype=np.uint64)
    for j in range(bits.shape[1]):
        h ^= bits[:, j]
        h *= mult
        h ^= h >> shift
    return h


def _setting_sums(pdf, names, response, shift):
    """Count, sum and sum of squares of ``y - shift`` per distinct factor setting of one
    partition (the runs with a response), keyed by a 64-bit hash of the setting; ``_lo`` and
    ``_hi`` keep the smallest and largest value of a second, different hash in each group, so
    that two settings sharing a key would show (:func:`_pure_error_sums` refuses them)."""
    import pandas as pd

    pdf = pdf[pdf[response].notna()]
    yc = pdf[response].to_numpy(dtype=float) - shift
    x = pdf[list(names)].to_numpy(dtype=float)
    check = _row_hash(x, 1)
    frame = pd.DataFrame({"_key": _row_hash(x, 0), "_n": 1.0, "_s1": yc, "_s2": yc * yc, "_lo": check, "_hi": check})
    return frame.groupby("_key", sort=False).agg(_AGG)


def _factor_partition(pdf, space, response, terms, p, shift, rows):
    x, y = _partition_rows(pdf, space, response)
    acc = Accumulator(p=p, shift=shift)
    for X, yy in _chunks(x, y, terms, rows):
        acc.add(X, yy)
    return acc, _setting_sums(pdf, space.names, response, shift)


def _merge(a, b):
    """Two partitions' (factor, setting sums) merged: the factor of all their rows, the sums
    added setting by setting."""
    import pandas as pd

    return a[0].merge(b[0]), pd.concat([a[1], b[1]]).groupby(level=0, sort=False).agg(_AGG)


def _pure_error_sums(agg) -> tuple[int, float]:
    """``(number of distinct settings, SS_pe)`` from the merged setting sums."""
    if np.any(agg["_lo"].to_numpy() != agg["_hi"].to_numpy()):
        raise ValueError("two different factor settings share a 64-bit hash (a chance of about n^2 / 2^65); "
                         "fit these data as a pandas DataFrame")
    s1 = agg["_s1"].to_numpy(dtype=float)
    cnt = agg["_n"].to_numpy(dtype=float)
    s2 = agg["_s2"].to_numpy(dtype=float)
    return int(cnt.size), float(max(np.sum(s2 - s1 ** 2 / cnt), 0.0))


def _sums_partition(pdf, space, response, terms, ls, rows):
    x, y = _partition_rows(pdf, space, response)
    return ls.pass_sums_of(_chunks(x, y, terms, rows))


def fit_dask(ddf, response: str, factors=None, block: str | None = None, model: str = "quadratic", *,
             terms=None, chunk_rows: int = CHUNK_ROWS):
    """Fit a Dask DataFrame without collecting it (see the module docstring); arguments as
    for :func:`rsm_lrg.fit`."""
    import dask
    import pandas as pd

    from ..factors import FactorSpace
    from .anova import PureError
    from .fit import _assemble, _check_magnitudes, _chosen_terms
    from .terms import check_model_size, model_terms

    if block is not None:
        raise ValueError("a block column is not supported for a Dask DataFrame; fit blocked data as a pandas DataFrame")
    if response not in ddf.columns:
        raise ValueError(f"response column {response!r} not found (columns: {', '.join(map(str, ddf.columns))})")
    if not pd.api.types.is_numeric_dtype(ddf.dtypes[response]):
        raise ValueError(f"response column {response!r} is not numeric")
    numeric = [c for c in ddf.columns if pd.api.types.is_numeric_dtype(ddf.dtypes[c])
               and not pd.api.types.is_bool_dtype(ddf.dtypes[c])]
    # every row codes the factors, as prepare() does for a pandas frame; the response ignores missing cells
    lo, hi, n, total, n_all = dask.compute(ddf[numeric].min(), ddf[numeric].max(), ddf[response].count(),
                                           ddf[response].sum(), ddf.shape[0])
    n, n_all = int(n), int(n_all)
    if n == 0:
        raise ValueError(f"response column {response!r} is empty on every row: there is nothing to fit")
    if isinstance(factors, FactorSpace):
        space, notes = factors, ()
        missing = [f.name for f in space.factors if f.name not in ddf.columns]
        if missing:
            raise ValueError(f"factor column {missing[0]!r} is not in the data")
    else:
        space, notes = _space_and_notes(ddf, response, factors, numeric, lo, hi)
    if space.has_categoric:
        raise ValueError("categoric factors are not supported for a Dask DataFrame yet; fit it as a pandas "
                         "DataFrame (or fit each level's partitions separately)")
    for f in space.factors:
        if not lo[f.name] < hi[f.name]:
            raise ValueError(f"factor column {f.name!r} is constant; a factor needs at least two levels")
    _check_magnitudes(space, np.array([lo[response], hi[response]], dtype=float), response)
    if lo[response] == hi[response]:
        raise ValueError(f"response {response!r} is constant (all {lo[response]:.6g}): nothing to model")
    if n < n_all:
        k = n_all - n
        notes = notes + (f"{k} run{'s' if k > 1 else ''} without a response left out of the fit (not run).",)
    if terms is None:
        check_model_size(n, len(space), model)
        terms = tuple(model_terms(space.letters, model))
    else:
        terms = _chosen_terms(terms, space.letters)
    names = [t.name for t in terms]
    p = len(terms)
    if n < p:
        raise ValueError(f"{n} runs cannot fit {p} terms (the {model} model in {len(space)} factors)")
    shift = float(total) / n
    rows = int(chunk_rows)

    # pass 2: one factor and the setting sums per partition, merged in a tree
    parts = ddf[space.names + [response]].to_delayed()
    accs = [dask.delayed(_factor_partition)(d, space, response, terms, p, shift, rows) for d in parts]
    while len(accs) > 1:
        accs = [dask.delayed(_merge)(accs[i], accs[i + 1]) if i + 1 < len(accs) else accs[i]
                for i in range(0, len(accs), 2)]
    acc, agg = dask.compute(accs[0])[0]
    if not np.all(np.isfinite(acc.raug)):
        raise ValueError("a factor or response cell is empty or not a number; every run needs numeric factor settings")
    ls = acc.result(names)
    ls.require_full_rank(f"{model} model")

    # pass 3: second-pass sums per partition
    sums = [dask.delayed(_sums_partition)(d, space, response, terms, ls, rows) for d in parts]
    ls = ls.with_pass_sums(dask.compute(*sums))
    n_groups, ss_pe = _pure_error_sums(agg)  # pure error from the setting sums
    pe = PureError(groups=np.zeros(0, dtype=int), n_groups=n_groups, ss=ss_pe, df=int(n - n_groups))
    return _assemble(response=response, model=model, block=None, space=space, terms=terms, col_names=names,
                     ls=ls, pe=pe, bkeys=None, blevels=None, data=ddf, coded=None, y=None, input_notes=notes)
