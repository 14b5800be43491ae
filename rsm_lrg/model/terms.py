"""Model terms and the design matrix of a polynomial response-surface model.

A term is a monomial in the coded factors, held as a tuple of exponents (one per
factor). Names follow Design-Expert: ``"Intercept"``, ``"A"``, ``"AB"`` (letters in factor
order), ``"A^2"``; higher orders are ready for a cubic model (``"A^3"``, ``"A^2B"``,
``"ABC"``).

Term order is the one Design-Expert prints (and Table 5 of the paper): intercept, main
effects, two-factor interactions, pure quadratics, then cubic terms.

>>> [t.name for t in model_terms(["A", "B"], "quadratic")]
['Intercept', 'A', 'B', 'AB', 'A^2', 'B^2']
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

__all__ = ["Term", "MODELS", "model_terms", "n_model_terms", "check_model_size", "design_matrix",
           "block_contrasts", "model_matrix",
           "design_gradient", "term_name", "parse_term"]

#: Model names accepted by :func:`model_terms`.
MODELS = ("linear", "2fi", "quadratic", "cubic")

#: Largest number of model terms (columns of the model matrix) built at all; a model beyond
#: this is refused from its term count alone, before any term is built.
MAX_TERMS = 5000


def n_model_terms(k: int, model: str = "quadratic") -> int:
    """Number of terms (intercept included) of a standard model in ``k`` factors, by counting.

    linear ``1 + k``; 2FI ``1 + k + C(k, 2)``; quadratic ``C(k + 2, 2)``; cubic ``C(k + 3, 3)``
    (all monomials of total degree <= 3).

    >>> [n_model_terms(4, m) for m in MODELS], n_model_terms(16, "cubic")
    ([5, 11, 15, 35], 969)
    """
    from math import comb

    if model not in MODELS:
        raise ValueError(f"unknown model {model!r}; expected one of {', '.join(MODELS)}")
    k = int(k)
    return {"linear": 1 + k, "2fi": 1 + k + comb(k, 2), "quadratic": comb(k + 2, 2), "cubic": comb(k + 3, 3)}[model]


def check_model_size(n_runs: int, k: int, model: str, extra: int = 0, *, what: str = "runs") -> int:
    """Refuse, from the term count alone, a model the runs cannot fit (fast, builds nothing).

    Returns the number of terms; raises ``ValueError`` naming the count when
    ``n_runs < terms + extra`` (``extra``: block contrasts) or the model is beyond
    :data:`MAX_TERMS` columns.
    """
    p = n_model_terms(k, model)
    if n_runs < p + extra:
        blocks = f" and {extra} block effects" if extra else ""
        raise ValueError(f"{n_runs} {what} cannot fit {p + extra} terms (the {model} model in {k} factors has "
                         f"{p} terms{blocks}); choose a smaller model or fewer factors")
    if p > MAX_TERMS:
        raise ValueError(f"the {model} model in {k} factors has {p} terms, beyond the {MAX_TERMS} this toolkit "
                         "builds; choose a smaller model or fewer factors")
    return p


def term_name(powers: Sequence[int], letters: Sequence[str]) -> str:
    """Design-Expert name of the monomial with exponents ``powers``.

    >>> term_name((1, 0, 1), "ABC"), term_name((0, 2, 0), "ABC"), term_name((0, 0, 0), "ABC")
    ('AC', 'B^2', 'Intercept')
    """
    parts = []
    for p, L in zip(powers, letters):
        if p == 1:
            parts.append(L)
        elif p > 1:
            parts.append(f"{L}^{p}")
    return "".join(parts) if parts else "Intercept"


@dataclass(frozen=True)
class Term:
    """One model term: a monomial ``prod(x_i ** powers[i])`` in coded units."""

    powers: tuple[int, ...]
    name: str

    @property
    def order(self) -> int:
        """Total degree (0 intercept, 1 main effect, 2 interaction or square, ...)."""
        return int(sum(self.powers))

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


def _term(powers, letters) -> Term:
    powers = tuple(int(p) for p in powers)
    return Term(powers, term_name(powers, letters))


def model_terms(letters: Sequence[str], model: str = "quadratic") -> list[Term]:
    """Terms of a standard model in Design-Expert order.

    Parameters
    ----------
    letters : sequence of str
        Factor letters (``["A", "B", ...]``).
    model : {"linear", "2fi", "quadratic", "cubic"}
        ``"2fi"`` is main effects plus two-factor interactions; ``"quadratic"`` adds the
        pure squares (the paper's Eq. 19); ``"cubic"`` adds all third-order monomials.
    """
    if model not in MODELS:
        raise ValueError(f"unknown model {model!r}; expected one of {', '.join(MODELS)}")
    k = len(letters)
    if k < 1:
        raise ValueError("a model needs at least one factor")
    unit = np.eye(k, dtype=int)
    out = [_term([0] * k, letters)]
    out += [_term(unit[i], letters) for i in range(k)]
    if model in ("2fi", "quadratic", "cubic"):
        out += [_term(unit[i] + unit[j], letters) for i, j in itertools.combinations(range(k), 2)]
    if model in ("quadratic", "cubic"):
        out += [_term(2 * unit[i], letters) for i in range(k)]
    if model == "cubic":  # all monomials of degree 3, built from index triples (not 4**k candidates)
        cub = [tuple(np.bincount(c, minlength=k)) for c in itertools.combinations_with_replacement(range(k), 3)]
        # Design-Expert order: ABC-type, then A^2B-type, then A^3
        cub.sort(key=lambda p: (max(p), [-x for x in p]))
        out += [_term(p, letters) for p in cub]
    return out


def parse_term(name: str, letters: Sequence[str]) -> Term:
    """The :class:`Term` called ``name`` (``"AB"``, ``"A^2"``, ``"Intercept"``).

    >>> parse_term("A^2B", "ABC").powers
    (2, 1, 0)
    """
    import re

    letters = list(letters)
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
            raise ValueError(f"cannot read model term {name!r} (factors {', '.join(letters)})")
    return _term(powers, letters)


def design_matrix(coded: np.ndarray, terms: Sequence[Term]) -> np.ndarray:
    """Model matrix ``X`` (n x p) for coded settings ``coded`` (n x k).

    Column j holds ``prod_i coded[:, i] ** terms[j].powers[i]`` (built column by column into
    a Fortran-ordered array, each power of each factor computed once).
    """
    x = np.asarray(coded, dtype=float)
    if x.ndim == 1:
        x = x[None, :]
    n = x.shape[0]
    X = np.empty((n, len(terms)), dtype=float, order="F")
    cols = [np.ascontiguousarray(x[:, i]) for i in range(x.shape[1])]
    powers: dict = {}

    def power(i: int, p: int) -> np.ndarray:
        if p == 1:
            return cols[i]
        if (i, p) not in powers:
            powers[(i, p)] = cols[i] ** p
        return powers[(i, p)]

    for j, t in enumerate(terms):
        parts = [power(i, p) for i, p in enumerate(t.powers) if p]
        out = X[:, j]
        if not parts:
            out[:] = 1.0
        elif len(parts) == 1:
            out[:] = parts[0]
        else:
            np.multiply(parts[0], parts[1], out=out)
            for q in parts[2:]:
                out *= q
    return X


def block_contrasts(codes: np.ndarray, n_blocks: int) -> np.ndarray:
    """Sum-to-zero block contrasts (n x (b - 1)): column j is 1 in block j, -1 in the last
    block, 0 elsewhere (Design-Expert's block effects; ``codes`` are 0 .. b-1)."""
    codes = np.asarray(codes)
    B = np.zeros((codes.size, n_blocks - 1))
    for j in range(n_blocks - 1):
        B[codes == j, j] = 1.0
    B[codes == n_blocks - 1, :] = -1.0
    return B


def model_matrix(coded: np.ndarray, terms: Sequence[Term], block_codes: np.ndarray | None = None,
                 n_blocks: int = 1) -> np.ndarray:
    """Model matrix with blocks: intercept, the ``n_blocks - 1`` block contrasts
    (:func:`block_contrasts`), then the other terms (without blocks: :func:`design_matrix`)."""
    Xt = design_matrix(coded, terms)
    if n_blocks <= 1:
        return Xt
    return np.hstack([Xt[:, :1], block_contrasts(block_codes, n_blocks), Xt[:, 1:]])


def design_gradient(point: np.ndarray, terms: Sequence[Term]) -> np.ndarray:
    """Jacobian (p x k) of the model row ``x(point)`` with respect to the coded factors."""
    x = np.asarray(point, dtype=float).ravel()
    k = x.size
    G = np.zeros((len(terms), k))
    for j, t in enumerate(terms):
        for i in range(k):
            p = t.powers[i]
            if p == 0:
                continue
            v = p * x[i] ** (p - 1)
            for m, q in enumerate(t.powers):
                if m != i and q:
                    v *= x[m] ** q
            G[j, i] = v
    return G
