"""Scheffé mixture models (no intercept) on L-pseudo-components.

The components ``x_1 .. x_q`` of a blend sum to a total ``T``. They are coded as
L-pseudo-components ``x'_i = (x_i - L_i) / (T - sum L)`` (:class:`~rsm_lrg.factors.MixtureComponent`;
``L_i`` the component's lower bound, or its observed minimum) and fitted by the Scheffé
canonical polynomials (Cornell, *Experiments with Mixtures*, 3rd ed., Eqs. 2.7-2.10),

    linear          E[y] = sum b_i x'_i
    quadratic       ... + sum_{i<j} b_ij x'_i x'_j
    special cubic   ... + sum_{i<j<k} b_ijk x'_i x'_j x'_k
    full cubic      quadratic + sum_{i<j} d_ij x'_i x'_j (x'_i - x'_j) + sum_{i<j<k} b_ijk x'_i x'_j x'_k

(Eq. 2.11 for the full cubic, whose ``d_ij`` terms are keyed ``AB(A-B)``), which have no intercept: the mean is in them implicitly (``sum x'_i = 1``), so the ANOVA
and R² are about the mean (Design-Expert's mixture ANOVA): ``Model`` on p - 1 df,
``Linear Mixture`` on q - 1 df (the linear model's sum of squares about the mean, taken
first), one row per non-linear term (its partial sum of squares), ``Residual``, ``Lack of
Fit``, ``Pure Error``, ``Cor Total``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ...factors import Factor, FactorSpace, MixtureComponent, letters_for, parse_factor_spec, quote_value
from ...io import cell_error
from .terms import MIXTURE_ORDERS, Term, scheffe_names, term_name

__all__ = ["MIXTURE_MODELS", "MIXTURE_ORDERS", "SUM_RTOL", "scheffe_names", "mixture_space", "check_mixture_terms",
           "pseudo_to_actual", "mixture_sums"]

#: Every mixture model name a command accepts.
MIXTURE_MODELS = tuple(MIXTURE_ORDERS)
#: A row's components must sum to the total within this relative tolerance.
SUM_RTOL = 1e-4


def mixture_space(data: Any, components: Sequence[Any], response: str | None = None,
                  process: Any = None) -> FactorSpace:
    """The components as :class:`~rsm_lrg.factors.MixtureComponent` (letters A, B, ...),
    coded as L-pseudo-components, then the process factors ``process`` (names or
    ``"NAME=LOW:HIGH"``, coded -1 .. +1 as every factor; letters after the components).

    ``components`` are names or ``"NAME=LOW:HIGH"`` strings: ``LOW`` is the L-pseudo origin
    and the bounds are checked; a bare name takes its observed minimum as ``LOW`` (and no
    upper bound). The total ``T`` is read from the data: the median row sum of the rows
    with a response; every such row must sum to ``T`` within ``SUM_RTOL`` (1e-4) relative
    (published tables print 1/3 as 0.33333).

    Raises
    ------
    ValueError
        Fewer than two components, a repeated one, a missing or non-numeric column, a
        negative proportion, a row whose components do not sum to the total or that is
        outside a component's bounds (naming the row, 1-based as in the file), lower bounds
        that sum to the total or beyond.
    """
    import pandas as pd

    if isinstance(components, str):
        components = [components]
    items = []
    for c in components:
        try:
            items.append(c if isinstance(c, tuple) else parse_factor_spec(str(c)))
        except ValueError as exc:  # the spec parser speaks of factors
            raise ValueError(str(exc).replace("factor ", "component ", 1)) from None
    names = [str(it[0]) for it in items]
    if response is not None and response in names:
        raise ValueError(f"component {quote_value(response)} is the response")
    if len(names) < 2:
        raise ValueError("a mixture needs at least two components (--component once per name)")
    for nm in names:
        if names.count(nm) > 1:
            raise ValueError(f"component {quote_value(nm)} is given twice")
        if nm not in data.columns:
            raise ValueError(f"component column {quote_value(nm)} is not in the data")
    if not isinstance(data, pd.DataFrame):
        raise TypeError("data must be a pandas DataFrame")
    rows = np.arange(len(data))
    if response is not None and response in data.columns:
        keep = ~pd.isna(data[response]).to_numpy()
        data, rows = data[keep], rows[keep]
    cols = []
    for nm in names:  # as float_column, naming the row of the file (rows without a response skipped)
        num = pd.to_numeric(data[nm], errors="coerce").to_numpy(dtype=float, na_value=np.nan)
        bad = np.flatnonzero(~np.isfinite(num))
        if bad.size:
            raise cell_error(nm, int(rows[bad[0]]) + 1, data[nm].iloc[int(bad[0])])
        cols.append(num)
    x = np.column_stack(cols)
    neg = np.argwhere(x < 0)
    if neg.size:
        i, j = neg[0]
        raise ValueError(f"row {rows[i] + 1}: component {quote_value(names[j])} is negative ({x[i, j]:g})")
    sums = x.sum(axis=1)
    total = float(np.median(sums))
    if not total > 0:
        raise ValueError("the components sum to zero: not a mixture")
    off = np.flatnonzero(np.abs(sums - total) > SUM_RTOL * total)
    if off.size:
        i = int(off[0])
        raise ValueError(f"row {rows[i] + 1}: the components sum to {sums[i]:.12g}, not the total {total:.12g} of "
                         f"the other rows (tolerance {SUM_RTOL:g} relative)")
    tol = SUM_RTOL * total
    lowers = [float(x[:, j].min()) if lo is None else float(lo) for j, (_, lo, _) in enumerate(items)]
    uppers = [total if hi is None else float(hi) for (_, _, hi) in items]
    pseudo_range = total - math.fsum(lowers)
    if not pseudo_range > tol:
        raise ValueError(f"the components' lower bounds sum to {math.fsum(lowers):g}, leaving no room below the "
                         f"total {total:g}")
    for j, nm in enumerate(names):
        bad = np.flatnonzero((x[:, j] < lowers[j] - tol) | (x[:, j] > uppers[j] + tol))
        if bad.size:
            i = int(bad[0])
            raise ValueError(f"row {rows[i] + 1}: component {quote_value(nm)} is {x[i, j]:.12g}, outside its bounds "
                             f"{lowers[j]:g}..{uppers[j]:g}")
    from dataclasses import replace

    proc = [] if not process else list(FactorSpace.from_data(data, process).factors)
    for f in proc:
        if f.name in names:
            raise ValueError(f"{quote_value(f.name)} is given both as a component and as a process factor")
        if f.kind != "numeric":
            raise ValueError(f"process factor {quote_value(f.name)} is categoric; mixture-process models take "
                             "numeric process factors")
    letters = letters_for(len(names) + len(proc))
    comps = [MixtureComponent.build(nm, L, lo, hi, total, pseudo_range)
             for nm, L, lo, hi in zip(names, letters, lowers, uppers)]
    return FactorSpace(tuple(comps) + tuple(replace(f, letter=L) for f, L in zip(proc, letters[len(names):])))


def check_mixture_terms(terms: Sequence[Term], q: int) -> None:
    """A Scheffé term list: every term a product of distinct factors (no powers) with at least
    one of the ``q`` components (a process term alone is the sum of its crossings), or a
    full-cubic term ``AB(A-B)`` of two components (crossed: ``AB(A-B)D``), and every linear
    blending term present (they stand for the intercept)."""
    for t in terms:
        if any(p > 1 for p in t.powers) or t.order == 0:
            raise ValueError(f"term {t.name} is not a Scheffé mixture term (products of distinct components "
                             "such as A, AB, ABC, full-cubic AB(A-B), crossed with process factors: AD, ABD)")
        if t.diff and (max(t.diff) >= q or sum(t.powers[:q]) != 2):
            raise ValueError(f"term {t.name} is not a Scheffé mixture term (a full-cubic term is XY(X-Y) of two "
                             "components, crossed only with process factors)")
        if not any(t.powers[:q]):
            raise ValueError(f"term {t.name} has no mixture component (a process term enters crossed with the "
                             "blending terms: AD, BD, ...)")
    linear = {t.powers.index(1) for t in terms if t.order == 1 and any(t.powers[:q])}
    missing = [letters_for(q)[j] for j in range(q) if j not in linear]
    if missing:
        raise ValueError(f"a mixture model keeps every linear blending term (missing {', '.join(missing)})")


def pseudo_to_actual(coded: dict[str, float], terms: Sequence[Term], space: FactorSpace) -> dict[str, float]:
    """The Scheffé polynomial in real proportions (and process factors in actual units) from
    its coded coefficients.

    Every factor's coding is affine in its own coordinate, ``x' = (x - o) / s`` (a component:
    ``o = L``, ``s = T - sum L``; a process factor: its centre and half-range), so each term
    (a product of distinct factors, times ``x'_i - x'_j`` for a full-cubic ``AB(A-B)``)
    expands exactly into monomials of the real coordinates. Their mixture parts are then
    written in the Scheffé basis on the simplex ``sum x = T``: a part without a component is
    ``m sum x_i / T``; a square ``x_i^2 = x_i (T - sum_{k != i} x_k)``; and
    ``x_i^2 x_j = (x_i x_j (x_i + x_j) + x_i x_j (x_i - x_j)) / 2`` with
    ``x_i + x_j = T - sum_{k != i, j} x_k``. Keys are term names (``A``, ``AB``, ``AB(A-B)``,
    ``AD``, ...); monomials beyond the model's terms (a model without ``AB`` whose ``ABC``
    brings one) are listed too.
    """
    factors = list(space.factors)
    comps = [i for i, f in enumerate(factors) if isinstance(f, MixtureComponent)]
    first = factors[comps[0]]
    assert isinstance(first, MixtureComponent)
    T = first.total
    k = len(factors)
    origin: list[float] = []
    scale: list[float] = []
    for f in factors:
        if isinstance(f, MixtureComponent):
            origin.append(f.lower)
            scale.append(f.pseudo_range)
        elif isinstance(f, Factor):  # a numeric process factor (categoric ones are refused)
            origin.append(f.center)
            scale.append(f.half_range)
        else:
            raise ValueError(f"process factor {f.name!r} is categoric; a mixture model takes numeric ones")
    unit = [tuple(int(m == i) for m in range(k)) for i in range(k)]
    zero = (0,) * k

    def times(poly: dict[tuple[int, ...], float], lin: dict[tuple[int, ...], float]) -> dict[tuple[int, ...], float]:
        out: dict[tuple[int, ...], float] = {}
        for p1, c1 in poly.items():
            for p2, c2 in lin.items():
                key = tuple(a + b for a, b in zip(p1, p2))
                out[key] = out.get(key, 0.0) + c1 * c2
        return out

    def coded_factor(i: int) -> dict[tuple[int, ...], float]:  # x'_i = x_i / s_i - o_i / s_i
        return {unit[i]: 1.0 / scale[i], zero: -origin[i] / scale[i]}

    parts: dict[tuple[tuple[int, ...], tuple[int, ...]], list[float]] = {}
    for t in terms:
        poly: dict[tuple[int, ...], float] = {zero: float(coded[t.name])}
        for i, p in enumerate(t.powers):
            for _ in range(p):
                poly = times(poly, coded_factor(i))
        if t.diff:
            a, b = t.diff
            poly = times(poly, {unit[a]: 1.0 / scale[a], unit[b]: -1.0 / scale[b],
                                zero: -origin[a] / scale[a] + origin[b] / scale[b]})
        for powers, c in poly.items():
            for (sub, diff), w in _scheffe_basis(tuple(powers[i] for i in comps), T).items():
                full = [0] * k
                for i, p in enumerate(powers):
                    if i not in comps:
                        full[i] = p
                for j in sub:
                    full[comps[j]] = 1
                d = tuple(comps[j] for j in diff)
                parts.setdefault((tuple(full), d), []).append(c * w)
    letters = space.letters

    def rank(key: tuple[tuple[int, ...], tuple[int, ...]]) -> tuple:
        powers, d = key
        return (sum(powers) + bool(d), bool(d), [i for i, p in enumerate(powers) if p], d)

    return {term_name(p, letters, d): math.fsum(parts[(p, d)]) for p, d in sorted(parts, key=rank)}


def _scheffe_basis(m: tuple[int, ...], T: float) -> dict[tuple[tuple[int, ...], tuple[int, ...]], float]:
    """The monomial ``prod x_i^m_i`` of the components (mixture degree <= 3) in the Scheffé
    basis on ``sum x = T``: ``{(distinct components, diff pair): weight}``, ``diff = ()`` for
    the product of the distinct components, ``(i, j)`` for ``x_i x_j (x_i - x_j)``."""
    q = len(m)
    deg = sum(m)
    if deg > 3:
        raise ValueError("a Scheffé polynomial of degree above 3 has no full-cubic form")
    out: dict[tuple[tuple[int, ...], tuple[int, ...]], float] = {}

    def add(d: dict[tuple[tuple[int, ...], tuple[int, ...]], float], w: float) -> None:
        for key, v in d.items():
            out[key] = out.get(key, 0.0) + w * v

    def mono(*idx: int) -> tuple[int, ...]:
        v = [0] * q
        for i in idx:
            v[i] += 1
        return tuple(v)

    if deg == 0:  # 1 = sum x_i / T
        for i in range(q):
            add({((i,), ()): 1.0}, 1.0 / T)
        return out
    if max(m) <= 1:
        return {(tuple(i for i in range(q) if m[i]), ()): 1.0}
    i = next(j for j in range(q) if m[j] >= 2)
    others = [j for j in range(q) if m[j] and j != i]
    if deg == 3 and m[i] == 2 and len(others) == 1:  # x_i^2 x_j = (x_i x_j (x_i + x_j) + x_i x_j (x_i - x_j)) / 2
        j = others[0]
        pair = (min(i, j), max(i, j))
        add({(pair, pair): 1.0}, 0.5 if i < j else -0.5)
        add(_scheffe_basis(mono(i, j), T), 0.5 * T)  # x_i + x_j = T - sum of the others
        for r in range(q):
            if r not in (i, j):
                add(_scheffe_basis(mono(i, j, r), T), -0.5)
        return out
    # x_i^p rest = x_i^(p-1) rest (T - sum_{r != i} x_r)
    lower = list(m)
    lower[i] -= 1
    add(_scheffe_basis(tuple(lower), T), T)
    for r in range(q):
        if r != i:
            v = list(lower)
            v[r] += 1
            add(_scheffe_basis(tuple(v), T), -1.0)
    return out


def mixture_sums(ls: Any, terms: Sequence[Term], blocks: np.ndarray | None = None,
                 y: np.ndarray | None = None) -> dict[str, Any]:
    """The mixture ANOVA's sums of squares from the regression core of a Scheffé fit (no
    intercept column; linear terms first): ``Linear Mixture`` = the linear model's SS about
    the mean (q - 1 df), the partial SS of each non-linear term, the model about the mean.

    With fixed blocks (``blocks``: the block code 0..b-1 of each run, ``y`` the response on
    the model's scale; the block contrasts are columns 1..b-1, after the first linear term)
    the blocks come first, as Design-Expert orders them: ``ss_block`` is the block means'
    SS about the mean (b - 1 df), ``Linear Mixture`` the linear terms' SS after the blocks,
    the model the SS after the blocks; the non-linear terms are partial (Type III) as always.
    """
    nb = 1 if blocks is None else int(np.max(blocks)) + 1
    col = np.r_[0, np.arange(nb, nb + len(terms) - 1)]  # each term's column (blocks skipped)
    lin = [j for j, t in enumerate(terms) if t.order == 1]  # the linear blending terms (process terms are crossed)
    q = len(lin)
    ss_total = float(ls.ss_total)
    ss_block, base = 0.0, ss_total  # the residual of the blocks alone (the mean alone without them)
    if nb > 1:
        assert blocks is not None and y is not None
        yv = np.asarray(y, dtype=float)
        means = np.bincount(blocks, weights=yv, minlength=nb) / np.bincount(blocks, minlength=nb)
        base = float(np.sum((yv - means[blocks]) ** 2))
        ss_block = max(ss_total - base, 0.0)
    keep = np.r_[col[lin], np.arange(1, nb)].astype(int)
    ss_lin = max(base - float(ls.submodel(np.sort(keep)).ss_res), 0.0)
    nonlin = [j for j, t in enumerate(terms) if t.order > 1]
    names = ["Linear Mixture"] + [terms[j].name for j in nonlin]
    term_ss = [ss_lin] + [float(ls.partial_ss(int(col[j]))) for j in nonlin]
    return {"ss_block": ss_block, "ss_model": max(base - float(ls.ss_res), 0.0), "ss_total": ss_total,
            "df_model": len(terms) - 1, "names": names, "term_ss": term_ss, "term_df": [q - 1] + [1] * len(nonlin),
            "groups": [np.asarray(lin)] + [np.array([j]) for j in nonlin]}
