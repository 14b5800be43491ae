"""Model terms and the model matrix of a polynomial response-surface model.

A term is a monomial in the coded factors, held as a tuple of exponents (one per
factor). Names follow Design-Expert: ``"Intercept"``, ``"A"``, ``"AB"`` (letters in factor
order), ``"A^2"``; higher orders are ready for a cubic model (``"A^3"``, ``"A^2B"``,
``"ABC"``).

Categoric factors (:class:`rsm_lrg.factors.CategoricFactor`) enter a term with exponent 1
only, and a term with a categoric factor of L levels has L - 1 model columns: the
sum-to-zero (effect) coding Design-Expert and R's ``contr.sum`` use, one column per level
but the last (1 at that level, -1 at the last level, 0 elsewhere); a term with several
categoric factors has the products of their columns. Columns are named by the letter with
the level in brackets: ``"E[rms]"``, ``"AE[rms]"``, ``"E[a]F[x]"``. In a coded settings
array a categoric factor holds its level index 0 .. L-1.

Term order is the one Design-Expert prints (and Table 5 of the paper): intercept, main
effects, two-factor interactions, pure quadratics, then cubic terms.

This module is part of the factor space (below both the designs and the model): optimal
designs and the fit build the same model matrix.

>>> [t.name for t in model_terms(["A", "B"], "quadratic")]
['Intercept', 'A', 'B', 'AB', 'A^2', 'B^2']
>>> ts = model_terms(["A", "E"], "quadratic", categoric={1: ("rfcms", "rms", "mixed")})
>>> [t.name for t in ts], column_names(ts)
(['Intercept', 'A', 'E', 'AE', 'A^2'], ['Intercept', 'A', 'E[rfcms]', 'E[rms]', 'AE[rfcms]', 'AE[rms]', 'A^2'])
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from .errors import ParameterError

__all__ = ["Term", "MODELS", "model_terms", "n_model_terms", "check_model_size", "design_matrix",
           "block_contrasts", "model_matrix", "column_names", "term_columns", "n_columns",
           "design_gradient", "term_name", "parse_term", "effect_codes", "MIXTURE_ORDERS", "scheffe_names"]

#: Model names accepted by :func:`model_terms`.
MODELS = ("linear", "2fi", "quadratic", "cubic")

#: The Scheffé mixture models by name (Cornell, *Experiments with Mixtures*, 3rd ed., Eqs. 2.7-2.11),
#: with the highest number of distinct components in a term.
MIXTURE_ORDERS = {"mixture-linear": 1, "mixture-quadratic": 2, "special-cubic": 3, "mixture-cubic": 3}
#: Largest number of model terms (columns of the model matrix) built at all; a model beyond
#: this is refused from its term count alone, before any term is built.
MAX_TERMS = 5000

#: ``{factor index: level names}`` of the categoric factors (empty: all numeric).
Categoric = Mapping[int, Sequence[str]]


def scheffe_names(letters: Sequence[str], order: str, process: Sequence[str] = ()) -> list[str]:
    """The term names of a Scheffé model: ``["A", "B", "C", "AB", "AC", "BC", "ABC"]`` for
    the special cubic in three components; with process factors (letters ``process``) each
    mixture term crossed with each process main effect (Cornell, Ch. 7, the combined
    model: ``AD``, ``ABD``, ...).

    >>> scheffe_names("ABC", "mixture-quadratic")
    ['A', 'B', 'C', 'AB', 'AC', 'BC']
    >>> scheffe_names("AB", "mixture-linear", "C")
    ['A', 'B', 'AC', 'BC']
    >>> scheffe_names("ABC", "mixture-cubic")
    ['A', 'B', 'C', 'AB', 'AC', 'BC', 'ABC', 'AB(A-B)', 'AC(A-C)', 'BC(B-C)']
    """
    deg = MIXTURE_ORDERS[order]
    mix = ["".join(c) for d in range(1, deg + 1) for c in itertools.combinations(list(letters), d)]
    if order == "mixture-cubic":
        mix += [f"{a}{b}({a}-{b})" for a, b in itertools.combinations(list(letters), 2)]
    return mix + [m + p for p in process for m in mix]


def _standard_powers(k: int, model: str, cats: frozenset = frozenset()) -> list[tuple[int, ...]]:
    """Exponent tuples of a standard model in Design-Expert order (categoric factors, the
    indices in ``cats``, never squared)."""
    unit = np.eye(k, dtype=int)
    out = [tuple([0] * k)]
    out += [tuple(unit[i]) for i in range(k)]
    if model in ("2fi", "quadratic", "cubic"):
        out += [tuple(unit[i] + unit[j]) for i, j in itertools.combinations(range(k), 2)]
    if model in ("quadratic", "cubic"):
        out += [tuple(2 * unit[i]) for i in range(k) if i not in cats]
    if model == "cubic":  # all monomials of degree 3, built from index triples (not 4**k candidates)
        cub = [tuple(int(v) for v in np.bincount(c, minlength=k))
               for c in itertools.combinations_with_replacement(range(k), 3)]
        cub = [p for p in cub if all(p[i] <= 1 for i in cats)]
        # Design-Expert order: ABC-type, then A^2B-type, then A^3
        cub.sort(key=lambda p: (max(p), [-x for x in p]))
        out += cub
    return out


def n_model_terms(k: int, model: str = "quadratic", categoric: Categoric | None = None) -> int:
    """Number of model columns (intercept included) of a standard model in ``k`` factors.

    All numeric, by counting: linear ``1 + k``; 2FI ``1 + k + C(k, 2)``; quadratic
    ``C(k + 2, 2)``; cubic ``C(k + 3, 3)`` (all monomials of total degree <= 3). With
    categoric factors each term counts its ``prod (L - 1)`` effect columns.

    >>> [n_model_terms(4, m) for m in MODELS], n_model_terms(16, "cubic")
    ([5, 11, 15, 35], 969)
    >>> n_model_terms(3, "quadratic", {2: "abc"})  # 1 + (1 + 1 + 2) + (1 + 2 + 2) + 2
    12
    """
    from math import comb

    if model not in MODELS:
        raise ParameterError("model", f"unknown model {model!r}; expected one of {', '.join(MODELS)}")
    k = int(k)
    if not categoric:
        return {"linear": 1 + k, "2fi": 1 + k + comb(k, 2), "quadratic": comb(k + 2, 2),
                "cubic": comb(k + 3, 3)}[model]
    dfs = {int(i): len(lv) - 1 for i, lv in categoric.items()}
    total = 0
    for p in _standard_powers(k, model, frozenset(dfs)):
        m = 1
        for i, e in enumerate(p):
            if e and i in dfs:
                m *= dfs[i]
        total += m
    return total


def check_model_size(n_runs: int, k: int, model: str, extra: int = 0, *, what: str = "runs",
                     categoric: Categoric | None = None) -> int:
    """Refuse, from the term count alone, a model the runs cannot fit (fast, builds nothing).

    Returns the number of model columns; raises ``ValueError`` naming the count when
    ``n_runs < columns + extra`` (``extra``: block contrasts) or the model is beyond
    :data:`MAX_TERMS` columns.
    """
    p = n_model_terms(k, model, categoric)
    if n_runs < p + extra:
        blocks = f" and {extra} block effects" if extra else ""
        what_p = "coefficients" if categoric else "terms"
        raise ValueError(f"{n_runs} {what} cannot fit {p + extra} {what_p} (the {model} model in {k} factors has "
                         f"{p} {what_p}{blocks}); choose a smaller model or fewer factors")
    if p > MAX_TERMS:
        raise ValueError(f"the {model} model in {k} factors has {p} terms, beyond the {MAX_TERMS} this toolkit "
                         "builds; choose a smaller model or fewer factors")
    return p


def term_name(powers: Sequence[int], letters: Sequence[str], diff: Sequence[int] = ()) -> str:
    """Design-Expert name of the monomial with exponents ``powers`` (times ``x_i - x_j``
    when ``diff = (i, j)``: a Scheffé full-cubic term, named ``"AB(A-B)"``, the other
    factors of the monomial after it: ``"AB(A-B)D"``).

    >>> term_name((1, 0, 1), "ABC"), term_name((0, 2, 0), "ABC"), term_name((0, 0, 0), "ABC")
    ('AC', 'B^2', 'Intercept')
    >>> term_name((1, 1, 0, 1), "ABCD", (0, 1))
    'AB(A-B)D'
    """
    if diff:
        i, j = diff
        rest = [p - (m in (i, j)) for m, p in enumerate(powers)]
        tail = term_name(rest, letters) if any(rest) else ""
        return f"{letters[i]}{letters[j]}({letters[i]}-{letters[j]}){tail}"
    parts = []
    for p, L in zip(powers, letters):
        if p == 1:
            parts.append(L)
        elif p > 1:
            parts.append(f"{L}^{p}")
    return "".join(parts) if parts else "Intercept"


@dataclass(frozen=True)
class Term:
    """One model term: a monomial ``prod(x_i ** powers[i])`` in coded units (times
    ``x_i - x_j`` when ``diff = (i, j)``).

    Attributes
    ----------
    powers : tuple of int
        Exponent of each factor (a categoric factor: 0 or 1).
    name : str
        Design-Expert name (``"AB"``, ``"A^2"``, ``"AE"``).
    cat : tuple of (int, tuple of str)
        The categoric factors in the term: ``(factor index, level names)``; empty for a
        numeric term (one model column).
    letters : tuple of str
        The letters of the categoric factors in ``cat`` (for the column names).
    diff : tuple of int
        ``()`` for a monomial; ``(i, j)`` (``i < j``, both in the monomial with exponent 1)
        for the Scheffé full-cubic term ``x_i x_j (x_i - x_j)`` times the rest of the
        monomial (Cornell, *Experiments with Mixtures*, 3rd ed., Eq. 2.11: the
        ``delta_ij`` terms), named ``"AB(A-B)"``. Such a term is two monomials
        (:attr:`monomials`); code that reads ``powers`` as the whole term must look at
        ``diff`` too.
    """

    powers: tuple[int, ...]
    name: str
    cat: tuple = ()
    cat_letters: tuple = ()
    diff: tuple[int, ...] = ()

    @property
    def order(self) -> int:
        """Total degree (0 intercept, 1 main effect, 2 interaction or square, 3 for
        ``AB(A-B)``, ...)."""
        return int(sum(self.powers)) + (1 if self.diff else 0)

    @property
    def key(self) -> tuple:
        """``(powers, diff)``: what tells two terms apart (``AB`` and ``AB(A-B)`` share
        their powers)."""
        return (self.powers, self.diff)

    @property
    def monomials(self) -> list[tuple[float, tuple[int, ...]]]:
        """The term as a sum of monomials ``[(coefficient, powers), ...]``: ``[(1, powers)]``,
        or for ``diff = (i, j)`` the powers with one more ``x_i`` (+1) and one more ``x_j`` (-1).

        >>> parse_term("AB(A-B)", "ABC").monomials
        [(1.0, (2, 1, 0)), (-1.0, (1, 2, 0))]
        """
        if not self.diff:
            return [(1.0, self.powers)]
        out = []
        for sign, m in ((1.0, self.diff[0]), (-1.0, self.diff[1])):
            out.append((sign, tuple(p + (f == m) for f, p in enumerate(self.powers))))
        return out

    @property
    def kind(self) -> str:
        """``"intercept"``, ``"linear"``, ``"interaction"``, ``"quadratic"`` (pure square) or ``"cubic"``."""
        o = self.order
        if o == 0:
            return "intercept"
        if o == 1:
            return "linear"
        if o == 2:
            return "quadratic" if max(self.powers) == 2 else "interaction"
        return "cubic" if o == 3 else f"order{o}"

    @property
    def df(self) -> int:
        """Degrees of freedom: the number of model columns, ``prod (L - 1)`` over its
        categoric factors (1 for a numeric term)."""
        m = 1
        for _, levels in self.cat:
            m *= len(levels) - 1
        return m

    @cached_property
    def numeric_powers(self) -> tuple[int, ...]:
        """``powers`` with the categoric factors set to 0 (the numeric monomial; computed once:
        a fit and its summary ask for it some ninety times)."""
        cats = {i for i, _ in self.cat}
        return tuple(0 if i in cats else p for i, p in enumerate(self.powers))

    def level_combinations(self) -> list[tuple[int, ...]]:
        """Level indices (one per categoric factor in ``cat``) of its columns, in column order
        (the first factor's level changing slowest).

        Returns
        -------
        list of tuple of int
            One tuple of level indices per column.
        """
        return list(itertools.product(*[range(len(lv) - 1) for _, lv in self.cat]))

    @property
    def columns(self) -> list[str]:
        """Names of its model columns: the term name itself for a numeric term, else the
        letters with the level in brackets after each categoric letter (``"AE[rms]"``)."""
        if not self.cat:
            return [self.name]
        out = []
        for combo in self.level_combinations():
            labels = {i: f"[{lv[j]}]" for (i, lv), j in zip(self.cat, combo)}
            out.append(_label(self.name, self.cat_letters, [labels[i] for i, _ in self.cat]))
        return out


def _label(name: str, letters: Sequence[str], tags: Sequence[str]) -> str:
    """``name`` with ``tags[j]`` after the categoric letter ``letters[j]`` (whole letters only)."""
    import re

    out, pos = "", 0
    for L, tag in zip(letters, tags):
        m = re.compile(re.escape(L) + r"(?![0-9])").search(name, pos)
        if m is None:
            raise ValueError(f"categoric letter {L!r} is not in the term {name!r}")
        out += name[pos:m.end()] + tag
        pos = m.end()
    return out + name[pos:]


def _term(powers, letters, categoric: Categoric | None = None) -> Term:
    powers = tuple(int(p) for p in powers)
    cat = tuple((i, tuple(str(v) for v in categoric[i])) for i, p in enumerate(powers)
                if p and categoric and i in categoric)
    return Term(powers, term_name(powers, letters), cat, tuple(letters[i] for i, _ in cat))


def _check_categoric(letters: Sequence[str], categoric: Categoric | None) -> dict:
    cats = {int(i): tuple(lv) for i, lv in (categoric or {}).items()}
    for i, lv in cats.items():
        if not 0 <= i < len(letters):
            raise ValueError(f"categoric factor index {i} is not among the {len(letters)} factors")
        if len(lv) < 2:
            raise ValueError(f"categoric factor {letters[i]} needs at least two levels")
    return cats


def model_terms(letters: Sequence[str], model: str = "quadratic", categoric: Categoric | None = None) -> list[Term]:
    """Terms of a standard model in Design-Expert order.

    Parameters
    ----------
    letters : sequence of str
        Factor letters (``["A", "B", ...]``).
    model : {"linear", "2fi", "quadratic", "cubic"}
        ``"2fi"`` is main effects plus two-factor interactions; ``"quadratic"`` adds the
        pure squares (the paper's Eq. 19); ``"cubic"`` adds all third-order monomials.
        Categoric factors are never squared: their interactions with every factor are in
        the 2FI model and up, their squares in none.
    categoric : mapping, optional
        ``{factor index: level names}`` of the categoric factors.

    Returns
    -------
    list of Term
        The terms.
    """
    if model not in MODELS:
        raise ParameterError("model", f"unknown model {model!r}; expected one of {', '.join(MODELS)}")
    k = len(letters)
    if k < 1:
        raise ValueError("a model needs at least one factor")
    cats = _check_categoric(letters, categoric)
    return [_term(p, letters, cats) for p in _standard_powers(k, model, frozenset(cats))]


def parse_term(name: str, letters: Sequence[str], categoric: Categoric | None = None) -> Term:
    """The :class:`Term` called ``name`` (``"AB"``, ``"A^2"``, ``"Intercept"``).

    >>> parse_term("A^2B", "ABC").powers
    (2, 1, 0)

    Parameters
    ----------
    name : str
        The term's name.
    letters : sequence of str
        The factors' letters.
    categoric : optional
        The categoric factors' levels.

    Returns
    -------
    Term
        The term.
    """
    import re

    letters = list(letters)
    cats = _check_categoric(letters, categoric)
    if "(" in name or ")" in name:
        return _parse_diff_term(name, letters, cats)
    powers = [0] * len(letters)
    if name != "Intercept":
        pat = "|".join(sorted(map(re.escape, letters), key=len, reverse=True))
        pos = 0
        for m in re.finditer(rf"({pat})(?:\^(\d+))?", name):
            if m.start() != pos:
                break
            powers[letters.index(m.group(1))] += int(m.group(2) or 1)
            pos = m.end()
        if pos != len(name) or not any(powers):
            raise ParameterError("terms", f"cannot read model term {name!r} (factors {', '.join(letters)})")
        bad = [letters[i] for i in cats if powers[i] > 1]
        if bad:
            raise ParameterError("terms", f"model term {name!r}: {bad[0]} is a categoric factor and has no powers")
    return _term(powers, letters, cats)


def _parse_diff_term(name: str, letters: list[str], cats: dict) -> Term:
    """A Scheffé full-cubic term ``"AB(A-B)"`` (optionally crossed: ``"AB(A-B)D"``)."""
    import re

    pat = "|".join(sorted(map(re.escape, letters), key=len, reverse=True))
    m = re.fullmatch(rf"({pat})({pat})\(({pat})-({pat})\)((?:{pat})*)", name)
    if m is None:
        raise ParameterError("terms", f"cannot read model term {name!r} (factors {', '.join(letters)}; a full-cubic term is "
                         "written AB(A-B))")
    i, j = letters.index(m.group(1)), letters.index(m.group(2))
    if (m.group(3), m.group(4)) != (m.group(1), m.group(2)) or not i < j:
        raise ParameterError("terms", f"model term {name!r}: a full-cubic term is XY(X-Y) with X before Y "
                         f"(e.g. {letters[min(i, j)]}{letters[max(i, j)]}({letters[min(i, j)]}-{letters[max(i, j)]}))")
    rest = parse_term(m.group(5), letters).powers if m.group(5) else (0,) * len(letters)
    if rest[i] or rest[j]:
        raise ParameterError("terms", f"model term {name!r}: {letters[i]} and {letters[j]} appear once, before the bracket")
    powers = tuple(p + (f in (i, j)) for f, p in enumerate(rest))
    if any(powers[f] for f in cats):
        raise ParameterError("terms", f"model term {name!r}: a full-cubic term takes numeric factors only")
    return Term(powers, term_name(powers, letters, (i, j)), (), (), (i, j))


def column_names(terms: Sequence[Term]) -> list[str]:
    """Names of the model columns of ``terms`` (:attr:`Term.columns`, in order)."""
    return [c for t in terms for c in t.columns]


def n_columns(terms: Sequence[Term]) -> int:
    """Number of model columns of ``terms``."""
    return sum(t.df for t in terms)


def term_columns(terms: Sequence[Term], start: int = 0) -> list[np.ndarray]:
    """Positions of each term's columns in the model matrix (from ``start``)."""
    out, pos = [], start
    for t in terms:
        out.append(np.arange(pos, pos + t.df))
        pos += t.df
    return out


def effect_codes(index: np.ndarray, n_levels: int) -> np.ndarray:
    """Sum-to-zero (effect) codes (m x (L - 1)) of level indices ``index``: column j is 1
    at level j, -1 at the last level, 0 elsewhere (R's ``contr.sum``).

    >>> effect_codes(np.array([0, 1, 2]), 3).tolist()
    [[1.0, 0.0], [0.0, 1.0], [-1.0, -1.0]]
    """
    idx = np.asarray(index)
    E = (idx[:, None] == np.arange(n_levels - 1)[None, :]).astype(float)
    E[idx == n_levels - 1, :] = -1.0
    return E


def _check_levels(x: np.ndarray, i: int, n_levels: int) -> np.ndarray:
    col = x[:, i]
    idx = np.rint(col)
    if not (np.all(idx == col) and np.all((idx >= 0) & (idx < n_levels))):
        raise ValueError(f"a categoric factor's coded value must be a level index 0..{n_levels - 1}")
    return idx.astype(int)


def design_matrix(coded: np.ndarray, terms: Sequence[Term]) -> np.ndarray:
    """Model matrix ``X`` (n x columns) for coded settings ``coded`` (n x k).

    The column of a numeric term holds ``prod_i coded[:, i] ** terms[j].powers[i]``; a term
    with categoric factors has one column per combination of their effect codes
    (:func:`effect_codes`) times its numeric monomial. Built column by column into a
    Fortran-ordered array, each power of each factor computed once.

    Parameters
    ----------
    coded : numpy.ndarray, shape (n, k)
        Settings in coded units.
    terms : sequence of Term
        The model's terms.

    Returns
    -------
    numpy.ndarray
        ``X``, one column per term (more for a categoric term).
    """
    x = np.asarray(coded, dtype=float)
    if x.ndim == 1:
        x = x[None, :]
    n = x.shape[0]
    X = np.empty((n, n_columns(terms)), dtype=float, order="F")
    cols = [np.ascontiguousarray(x[:, i]) for i in range(x.shape[1])]
    powers: dict = {}
    effects: dict = {}

    def power(i: int, p: int) -> np.ndarray:
        if p == 1:
            return cols[i]
        if (i, p) not in powers:
            powers[(i, p)] = cols[i] ** p
        return powers[(i, p)]

    def effect(i: int, n_levels: int) -> np.ndarray:
        if i not in effects:
            effects[i] = effect_codes(_check_levels(x, i, n_levels), n_levels)
        return effects[i]

    j = 0
    for t in terms:
        parts = [power(i, p) for i, p in enumerate(t.numeric_powers) if p]
        out = X[:, j]
        if not parts:
            out[:] = 1.0
        elif len(parts) == 1:
            out[:] = parts[0]
        else:
            np.multiply(parts[0], parts[1], out=out)
            for q in parts[2:]:
                out *= q
        if t.diff:
            out *= cols[t.diff[0]] - cols[t.diff[1]]
        if t.cat:
            base = out.copy()
            for combo in t.level_combinations():
                col = X[:, j]
                col[:] = base
                for (i, lv), lj in zip(t.cat, combo):
                    col *= effect(i, len(lv))[:, lj]
                j += 1
        else:
            j += 1
    return X


def block_contrasts(codes: np.ndarray, n_blocks: int) -> np.ndarray:
    """Sum-to-zero block contrasts (n x (b - 1)): column j is 1 in block j, -1 in the last
    block, 0 elsewhere (Design-Expert's block effects; ``codes`` are 0 .. b-1)."""
    return effect_codes(np.asarray(codes), n_blocks)


def model_matrix(coded: np.ndarray, terms: Sequence[Term], block_codes: np.ndarray | None = None,
                 n_blocks: int = 1) -> np.ndarray:
    """Model matrix with blocks: intercept, the ``n_blocks - 1`` block contrasts
    (:func:`block_contrasts`), then the other terms (without blocks: :func:`design_matrix`)."""
    Xt = design_matrix(coded, terms)
    if n_blocks <= 1:
        return Xt
    if block_codes is None:
        raise ValueError(f"{n_blocks} blocks need their block_codes")
    return np.hstack([Xt[:, :1], block_contrasts(block_codes, n_blocks), Xt[:, 1:]])


def design_gradient(point: np.ndarray, terms: Sequence[Term]) -> np.ndarray:
    """Jacobian (columns x k) of the model row ``x(point)`` with respect to the coded
    factors (zero along a categoric factor, whose level is held)."""
    x = np.asarray(point, dtype=float).ravel()
    k = x.size
    rows = []
    for t in terms:
        g = np.zeros(k)
        npw = t.numeric_powers
        for i in range(k):
            p = npw[i]
            if p == 0:
                continue
            v = p * x[i] ** (p - 1)
            for m, q in enumerate(npw):
                if m != i and q:
                    v *= x[m] ** q
            g[i] = v
        if t.diff:  # product rule: d[m (x_a - x_b)] = dm (x_a - x_b) + m (e_a - e_b)
            a, b = t.diff
            mono = float(np.prod([x[m] ** q for m, q in enumerate(npw) if q]))
            g = g * (x[a] - x[b])
            g[a] += mono
            g[b] -= mono
        if t.cat:
            codes = [effect_codes(np.array([int(round(x[i]))]), len(lv))[0] for i, lv in t.cat]
            for combo in t.level_combinations():
                w = 1.0
                for c, lj in zip(codes, combo):
                    w *= c[lj]
                rows.append(g * w)
        else:
            rows.append(g)
    return np.array(rows).reshape(len(rows), k)
