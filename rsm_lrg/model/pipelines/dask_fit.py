"""Fitting a Dask DataFrame partition by partition: ``rsm_lrg.fit(ddf, response, ...)``.

The runs are never collected into one process. The fit makes three passes over the
partitions, each a reduction:

1. the coding: minimum and maximum of every numeric column (a factor named without
   levels is coded from them, as :func:`rsm_lrg.fit` codes a pandas frame), the distinct
   values, in order of first appearance, of every text column, of every column named as a
   categoric factor and of the block column (the factors are chosen by
   :func:`rsm_lrg.factors.choose_factors` from a small stand-in frame with those values,
   so the choice and its notes are the pandas fit's), and the count and sum of the
   response (its mean is the shift that keeps an offset from costing digits);
2. per partition the triangular factor of ``[X | y - shift]`` (block contrasts and
   effect-coded categoric columns included; :class:`~rsm_lrg.model.engines.least_squares.Accumulator`
   over chunks of rows), merged pairwise in a tree (TSQR) into the factor of all the runs;
   in the same pass, per partition, the pure-error sums of every distinct factor setting
   (count, sum and sum of squares of ``y - shift``, and with blocks each block's count and
   sum, keyed by a 64-bit hash of the coded setting, with a second hash kept to detect two
   settings sharing a key), added up setting by setting along the same tree
   (:func:`_pure_error_sums`);
3. per partition the second-pass sums (residual SS, PRESS, range of the fitted values,
   total SS; :class:`~rsm_lrg.model.engines.least_squares.PassSums`).

Each pass reads every partition once (three reads of the data in all).

The result is the same :class:`~rsm_lrg.model.fit.FitResult` (coefficients, block
effects, ANOVA with lack of fit, statistics with PRESS, canonical analysis) without the
per-run arrays: ``data`` is the Dask DataFrame itself, ``y``, ``coded``, ``fitted``,
``residuals`` and ``hat`` are ``None``. Rows whose response is missing are left out
(counted in a note). A text, categoric or block column may hold at most 1000 distinct
values.
"""

from __future__ import annotations

import re
from typing import Any

import numpy as np

from ...errors import ParameterError
from ..engines.least_squares import CHUNK_ROWS, Accumulator

__all__ = ["fit_dask"]


#: At most this many distinct values of a text (or categoric) column are gathered per partition.
_MAX_LEVELS = 1000


def _first_seen(pdf, cols) -> dict:
    """``{column: (distinct values in order of first appearance, up to _MAX_LEVELS + 1), has_empty}``
    of one partition."""
    import pandas as pd

    from ...io import is_empty_cell

    out = {}
    for c in cols:
        vals = pd.unique(pdf[c].to_numpy(dtype=object))
        empty = [v for v in vals if is_empty_cell(v)]
        out[c] = ([v for v in vals if not is_empty_cell(v)][:_MAX_LEVELS + 1], bool(empty))
    return out


def _first_pass(pdf, numeric, response, listed):
    """Pass 1 over one partition: minimum and maximum of the numeric columns, count and sum
    of the response, number of rows, :func:`_first_seen` of the listed columns."""
    y = pdf[response]
    return (pdf[numeric].min(), pdf[numeric].max(), int(y.count()), float(y.sum()), int(pdf.shape[0]),
            _first_seen(pdf, listed))


def _merge_seen(parts: list) -> dict:
    """The per-partition :func:`_first_seen` merged in partition order (first appearance overall)."""
    out: dict = {}
    for part in parts:
        for c, (vals, empty) in part.items():
            seen, had = out.get(c, ({}, False))
            for v in vals:
                if len(seen) <= _MAX_LEVELS:
                    seen.setdefault(v, v)
            out[c] = (seen, had or empty)
    return {c: (list(seen.values()), empty) for c, (seen, empty) in out.items()}


def _categoric_names(factors) -> list[str]:
    """Columns named as categoric factors (``NAME=cat``, a list of levels, a FactorSpace's
    categoric factors)."""
    from ...factors import FactorSpace
    from ...factors.spec import given_items

    if factors is None:
        return []
    if isinstance(factors, FactorSpace):
        return [f.name for f in factors.factors if f.kind == "categoric"]
    return [it[1] for it in given_items(factors) if it[0] == "categoric"]


def _stand_in(numeric: list[str], lo, hi, seen: dict):
    """A small frame with the same factor choice as the data: each numeric column alternates
    its minimum and maximum, each text (or categoric) column lists its distinct values in
    order of first appearance, repeated to the common length."""
    import pandas as pd

    m = max([2] + [len(v) for v, _ in seen.values()])
    cols: dict[str, Any] = {}
    for c in numeric:
        cols[c] = [float(lo[c]) if i % 2 == 0 else float(hi[c]) for i in range(m)]
    for c, (vals, _) in seen.items():
        cols[c] = pd.Series([vals[i % len(vals)] for i in range(m)] if vals else [None] * m)
    return pd.DataFrame(cols)


def _space_and_notes(ddf, response: str, factors, numeric: list[str], lo, hi, seen: dict):
    """The factor space chosen from the stand-in frame of :func:`_stand_in` (the columns'
    minimum and maximum, the text columns' distinct values)."""
    from ...factors import choose_factors

    frame = _stand_in(numeric, lo, hi, seen)
    frame = frame[[c for c in ddf.columns if c in frame.columns]]  # the data's column order
    if isinstance(factors, (list, tuple)) or isinstance(factors, str):
        names = [factors] if isinstance(factors, str) else list(factors)
        for it in names:
            name = it.split("=", 1)[0].strip() if isinstance(it, str) else None
            if name is not None and name not in frame.columns:
                if name in ddf.columns:
                    raise ValueError(f"factor column {name!r} is neither numeric nor text")
                raise ValueError(f"factor column {name!r} is not in the data")
    try:
        choice = choose_factors(frame, factors, exclude=[response])
    except ValueError as exc:  # a row of the stand-in frame is no row of the data: name the column only
        raise ValueError(re.sub(r", row \d+:", ":", str(exc))) from None
    for f in choice.space.factors:
        if f.kind == "numeric" and f.name not in numeric:
            raise ValueError(f"factor column {f.name!r} is stored as text in the Dask DataFrame; convert it to "
                             f"numbers first (ddf[{f.name!r}] = ddf[{f.name!r}].astype(float))")
        if f.kind != "categoric":
            continue
        vals, empty = seen[f.name]
        if empty:
            raise ValueError(f"categoric factor column {f.name!r} has an empty cell; every run needs a level")
        if len(vals) > _MAX_LEVELS:
            raise ValueError(f"categoric factor column {f.name!r} has more than {_MAX_LEVELS} distinct values")
    return choice.space, tuple(choice.notes)


def _partition_rows(pdf, space, response: str, block=None):
    """Coded settings, response and block codes (``None`` unblocked) of the runs of one
    partition that have a response; ``block`` is ``(column, {label: code})``."""
    pdf = pdf[pdf[response].notna()]
    x = space.encode(pdf[space.names]).to_numpy(dtype=float)
    codes = None if block is None else pdf[block[0]].map(block[1]).to_numpy(dtype=float).astype(int)
    return x, pdf[response].to_numpy(dtype=float), codes


def _chunks(x, y, codes, terms, nb: int, rows: int):
    from ..build.terms import model_matrix

    for s in range(0, y.size, rows):
        yield (model_matrix(x[s:s + rows], terms, None if codes is None else codes[s:s + rows], nb),
               y[s:s + rows])


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


def _setting_sums(x, yc, codes=None, nb: int = 1):
    """Count, sum and sum of squares of ``yc`` (the response less the shift) per distinct
    coded setting ``x``, keyed by a 64-bit hash of the setting; ``_lo`` and ``_hi`` keep the
    smallest and largest value of a second, different hash in each group, so that two
    settings sharing a key would show (:func:`_pure_error_sums` refuses them). With blocks
    (``codes`` 0..nb-1), also the count ``_c{j}`` and sum ``_t{j}`` of each block's runs."""
    import pandas as pd

    check = _row_hash(x, 1)
    cols = {"_key": _row_hash(x, 0), "_n": 1.0, "_s1": yc, "_s2": yc * yc, "_lo": check, "_hi": check}
    if nb > 1:
        for j in range(nb):
            inj = (codes == j).astype(float)
            cols[f"_c{j}"], cols[f"_t{j}"] = inj, inj * yc
    frame = pd.DataFrame(cols)
    return frame.groupby("_key", sort=False).agg(_aggregations(nb))


def _aggregations(nb: int) -> dict:
    return {**_AGG, **{f"_{w}{j}": "sum" for j in range(nb if nb > 1 else 0) for w in "ct"}}


def _factor_partition(pdf, space, response, terms, p, shift, rows, block, nb):
    x, y, codes = _partition_rows(pdf, space, response, block)
    acc = Accumulator(p=p, shift=shift)
    for X, yy in _chunks(x, y, codes, terms, nb, rows):
        acc.add(X, yy)
    return acc, _setting_sums(x, y - shift, codes, nb)


def _merge(a, b, nb: int = 1):
    """Two partitions' (factor, setting sums) merged: the factor of all their rows, the sums
    added setting by setting."""
    import pandas as pd

    return a[0].merge(b[0]), pd.concat([a[1], b[1]]).groupby(level=0, sort=False).agg(_aggregations(nb))


def _pure_error_sums(agg, nb: int = 1) -> tuple[int, float, int]:
    """``(number of distinct settings, SS_pe, block df)`` from the merged setting sums.

    Without blocks ``SS_pe = sum_g (S2_g - S1_g^2 / n_g)``. With blocks it is the residual
    of ``y ~ block + setting`` as :func:`rsm_lrg.model.readings.anova.pure_error` computes it: the
    setting means absorbed (Frisch–Waugh–Lovell), ``SS_pe = SS_within - h' G^+ h`` with
    ``G`` the within-setting cross-products of the block contrasts ``E`` and ``h`` their
    within-setting cross-products with ``y``, both from each setting's block counts
    ``C`` and block sums ``T``: ``G = E' (diag(1'C) - C' diag(1/n) C) E``,
    ``h = E' (1'T - C' (S1/n))``; the block df is the rank of ``G``.
    """
    from ..build.terms import block_contrasts

    if np.any(agg["_lo"].to_numpy() != agg["_hi"].to_numpy()):
        raise ValueError("two different factor settings share a 64-bit hash (a chance of about n^2 / 2^65); "
                         "fit these data as a pandas DataFrame")
    s1 = agg["_s1"].to_numpy(dtype=float)
    cnt = agg["_n"].to_numpy(dtype=float)
    s2 = agg["_s2"].to_numpy(dtype=float)
    within = float(np.sum(s2 - s1 ** 2 / cnt))
    block_df = 0
    if nb > 1:
        C = agg[[f"_c{j}" for j in range(nb)]].to_numpy(dtype=float)
        T = agg[[f"_t{j}" for j in range(nb)]].to_numpy(dtype=float)
        E = block_contrasts(np.arange(nb), nb)
        G = E.T @ (np.diag(C.sum(axis=0)) - C.T @ (C / cnt[:, None])) @ E
        h = E.T @ (T.sum(axis=0) - C.T @ (s1 / cnt))
        w, V = np.linalg.eigh((G + G.T) / 2.0)
        keep = w > 1e-11 * max(float(w.max()), 1.0)
        block_df = int(keep.sum())
        if block_df:
            z = V[:, keep].T @ h
            within -= float(np.sum(z * z / w[keep]))
    return int(cnt.size), float(max(within, 0.0)), block_df


def _sums_partition(pdf, space, response, terms, ls, rows, block, nb):
    x, y, codes = _partition_rows(pdf, space, response, block)
    return ls.pass_sums_of(_chunks(x, y, codes, terms, nb, rows))


def _block_map(seen: dict, block: str):
    """``(codes by label, keys, shown levels)`` of the block column from its distinct values
    (levels sorted, numbers as numbers, as :func:`rsm_lrg.model.fit._block_codes` codes a
    pandas column)."""
    import pandas as pd

    from ..build.inputs import block_codes

    vals, empty = seen[block]
    if empty:
        raise ValueError(f"block column {block!r} has an empty cell; every run needs a block")
    if len(vals) > _MAX_LEVELS:
        raise ValueError(f"block column {block!r} has more than {_MAX_LEVELS} distinct values")
    codes, keys, shown = block_codes(pd.DataFrame({block: pd.Series(vals, dtype=object)}), block)
    return dict(zip(vals, (int(c) for c in codes))), keys, shown


def fit_dask(ddf, response: str, factors=None, block: str | None = None, model: str = "quadratic", *,
             terms=None, chunk_rows: int = CHUNK_ROWS, spec=None):
    """Fit a Dask DataFrame without collecting it (see the module docstring); arguments as
    for :func:`rsm_lrg.fit` (``spec``, a :class:`~rsm_lrg.model.build.spec.ModelSpec`, replaces
    ``model`` and ``terms``). A transform or a reduction is not done on a Dask DataFrame
    (a ValueError says so)."""
    import dask
    import pandas as pd

    from ...factors import FactorSpace
    from ..build.data import check_response_block
    from ..build.inputs import check_magnitudes, chosen_terms
    from ..build.spec import ModelSpec
    from ..build.terms import check_model_size, column_names, model_terms
    from ..readings.anova import PureError
    from ..results.result import assemble

    if spec is None:
        spec = ModelSpec.build(model, terms=terms)
    if not spec.transform.identity or spec.reduce is not None:
        raise ValueError("a Dask DataFrame is fitted as it is: a response transform or a reduction needs the "
                         "data in memory (fit a pandas DataFrame)")
    model, terms, intercept = spec.order, spec.terms, spec.intercept

    check_response_block(ddf, response, block)
    if not pd.api.types.is_numeric_dtype(ddf.dtypes[response]):
        raise ValueError(f"response column {response!r} is not numeric")
    numeric = [c for c in ddf.columns if pd.api.types.is_numeric_dtype(ddf.dtypes[c])
               and not pd.api.types.is_bool_dtype(ddf.dtypes[c]) and c != block]
    # distinct values (in order of first appearance) of the text columns, of columns named
    # as categoric factors and of the block column
    listed = [c for c in ddf.columns if c not in numeric and c != response]
    listed += [c for c in _categoric_names(factors) if c in numeric and c not in listed]
    # pass 1: every row codes the factors, as prepare() does for a pandas frame; the response ignores missing cells
    cols = list(dict.fromkeys(numeric + listed + [response]))
    firsts = dask.compute(*[dask.delayed(_first_pass)(d, numeric, response, listed)
                            for d in ddf[cols].to_delayed()])
    lo = pd.concat([f[0] for f in firsts], axis=1).min(axis=1)
    hi = pd.concat([f[1] for f in firsts], axis=1).max(axis=1)
    n, total, n_all = (sum(f[i] for f in firsts) for i in (2, 3, 4))
    seen = _merge_seen([f[5] for f in firsts])
    n, n_all = int(n), int(n_all)
    if n == 0:
        raise ValueError(f"response column {response!r} is empty on every row: there is nothing to fit")
    notes: tuple[str, ...]
    if isinstance(factors, FactorSpace):
        space, notes = factors, ()
        missing = [f.name for f in space.factors if f.name not in ddf.columns]
        if missing:
            raise ValueError(f"factor column {missing[0]!r} is not in the data")
    else:
        space, notes = _space_and_notes(ddf, response, factors, numeric, lo, hi,
                                        {c: v for c, v in seen.items() if c != block})
    if not intercept:  # coded about zero: the model passes through the origin of the actual units
        from ..build.inputs import origin_coding

        space = origin_coding(space)
    for f in space.factors:
        if f.kind == "numeric" and not lo[f.name] < hi[f.name]:
            raise ValueError(f"factor column {f.name!r} is constant; a factor needs at least two levels")
    check_magnitudes(space, np.array([lo[response], hi[response]], dtype=float), response)
    if lo[response] == hi[response]:
        raise ValueError(f"response {response!r} is constant (all {lo[response]:.6g}): nothing to model")
    if n < n_all:
        k = n_all - n
        notes = notes + (f"{k} run{'s' if k > 1 else ''} without a response left out of the fit (not run).",)
    bmap, bkeys, blevels = _block_map(seen, block) if block is not None else (None, None, None)
    nb = len(bkeys) if bkeys else 1
    cat = space.categoric
    if terms is None:
        check_model_size(n, len(space), model, nb - 1, categoric=cat)
        terms = tuple(model_terms(space.letters, model, cat))
    else:
        terms = chosen_terms(terms, space.letters, cat, intercept=intercept)
    names = column_names(terms)
    if bkeys and nb > 1:
        if not intercept:
            raise ParameterError("block", "blocks need a model with an intercept (block effects sum to zero about it)")
        names = ["Intercept"] + [f"Block[{k}]" for k in bkeys[:-1]] + names[1:]
    p = len(names)
    if n < p:
        raise ValueError(f"{n} runs cannot fit {p} coefficients (the {model} model in {len(space)} factors"
                         + (f", {nb - 1} block effects)" if nb > 1 else ")"))
    shift = float(total) / n if intercept else 0.0
    rows = int(chunk_rows)
    blk = (block, bmap) if block is not None else None

    # pass 2: one factor and the setting sums per partition, merged in a tree
    parts = ddf[list(dict.fromkeys(space.names + [response] + ([block] if block else [])))].to_delayed()
    accs = [dask.delayed(_factor_partition)(d, space, response, terms, p, shift, rows, blk, nb) for d in parts]
    while len(accs) > 1:
        accs = [dask.delayed(_merge)(accs[i], accs[i + 1], nb) if i + 1 < len(accs) else accs[i]
                for i in range(0, len(accs), 2)]
    acc, agg = dask.compute(accs[0])[0]
    if not np.all(np.isfinite(acc.raug)):
        raise ValueError("a factor or response cell is empty or not a number; every run needs numeric factor settings")
    ls = acc.result(names)
    ls.require_full_rank(f"{model} model")

    # pass 3: second-pass sums per partition
    sums = [dask.delayed(_sums_partition)(d, space, response, terms, ls, rows, blk, nb) for d in parts]
    ls = ls.with_pass_sums(dask.compute(*sums))
    n_groups, ss_pe, block_df = _pure_error_sums(agg, nb)  # pure error from the setting sums
    pe = PureError(groups=np.zeros(0, dtype=int), n_groups=n_groups, ss=ss_pe, df=int(n - n_groups - block_df),
                   block_df=block_df)
    return assemble(spec=spec, response=response, block=block, space=space, terms=terms, col_names=names,
                     ls=ls, pe=pe, bkeys=bkeys, blevels=blevels, data=ddf, coded=None, y=None, input_notes=notes)
