"""Screening designs: definitive screening, two-level fractional factorials, Plackett–Burman,
and the alias map.

Definitive screening designs (Jones, B. & Nachtsheim, C. J. (2011). A class of three-level
designs for definitive screening in the presence of second-order effects. *Journal of
Quality Technology* 43(1), 1-15; Xiao, Lin & Bai (2012), *JQT* 44(1), 2-8, for the
construction from conference matrices): with ``C`` a conference matrix of order n (zero
diagonal, ±1 elsewhere, ``C'C = (n - 1) I``) the design is ``[C; -C; 0]`` (2n + 1 runs).
Every column has three levels; main effects are mutually orthogonal (``C'C`` diagonal) and,
because the runs come in fold-over pairs, orthogonal to every two-factor interaction and
every pure square. For m factors the order is m when a conference matrix of order m exists
(m even), else the next order that has one, with the extra columns dropped (odd m, and m =
22: no conference matrix of order 22 exists since 21 is not a sum of two squares; Belevitch
1950), as Jones & Nachtsheim do. Conference matrices are built exactly, never approximated:

* Paley's construction from the quadratic character of GF(q), q a prime power, gives order
  q + 1: symmetric for q ≡ 1 (mod 4), antisymmetric for q ≡ 3 (mod 4) (Paley 1933);
  GF(p^2) is built as GF(p)[x] / (x^2 - r) with r a quadratic non-residue.
* Doubling: if ``C`` is an antisymmetric conference matrix of order n, ``H = C + I`` is a
  skew-Hadamard matrix and ``[[H, H], [-H', H']] - I`` an antisymmetric conference matrix of
  order 2n (order 16 from Paley's order 8, since 15 is not a prime power).

Every matrix is checked (``C'C = (n - 1) I``, zero diagonal) before use.
"""

from __future__ import annotations

import itertools
from typing import Any

import numpy as np

from .core import Design, as_factor_space, numeric_part

__all__ = ["conference_matrix", "conference_order", "definitive_screening", "fractional_factorial",
           "plackett_burman", "alias_matrix", "alias_groups", "MAX_DSD_FACTORS"]

#: Largest number of factors of :func:`definitive_screening`.
MAX_DSD_FACTORS = 48


def _prime_power(q: int) -> tuple[int, int] | None:
    for p in range(2, q + 1):
        if q % p == 0:
            e, r = 0, q
            while r % p == 0:
                r //= p
                e += 1
            return (p, e) if r == 1 else None
    return None


def _field(p: int, e: int):
    """Elements (as tuples) of GF(p^e) for e in (1, 2), with subtraction and the quadratic
    character."""
    if e == 1:
        elems = [(a,) for a in range(p)]

        def sub(x, y):
            return ((x[0] - y[0]) % p,)

        def mul(x, y):
            return ((x[0] * y[0]) % p,)
    elif e == 2 and p % 2 == 1:
        squares_p = {(a * a) % p for a in range(1, p)}
        r = next(a for a in range(2, p) if a not in squares_p)  # x^2 = r, r a non-residue
        elems = [(a, b) for a in range(p) for b in range(p)]

        def sub(x, y):
            return ((x[0] - y[0]) % p, (x[1] - y[1]) % p)

        def mul(x, y):
            return ((x[0] * y[0] + r * x[1] * y[1]) % p, (x[0] * y[1] + x[1] * y[0]) % p)
    else:
        raise ValueError(f"GF({p}^{e}) is not built here")
    zero = elems[0]
    squares = {mul(x, x) for x in elems if x != zero}

    def chi(x):
        return 0 if x == zero else (1 if x in squares else -1)

    return elems, sub, chi


def _paley(q: int) -> np.ndarray:
    pe = _prime_power(q)
    if pe is None or pe[0] == 2:
        raise ValueError(f"Paley's construction needs an odd prime power, not {q}")
    elems, sub, chi = _field(*pe)
    Q = np.array([[chi(sub(a, b)) for b in elems] for a in elems], dtype=int)
    n = q + 1
    C = np.zeros((n, n), dtype=int)
    C[0, 1:] = 1
    C[1:, 0] = 1 if q % 4 == 1 else -1
    C[1:, 1:] = Q
    return C


def _check(C: np.ndarray) -> np.ndarray:
    n = C.shape[0]
    if not (np.all(np.diag(C) == 0) and np.array_equal(C.T @ C, (n - 1) * np.eye(n, dtype=int))
            and np.all(np.abs(C[~np.eye(n, dtype=bool)]) == 1)):
        raise ArithmeticError(f"the constructed matrix of order {n} is not a conference matrix")
    return C


def conference_matrix(n: int) -> np.ndarray:
    """An exact conference matrix of order ``n`` (n x n, entries 0 on the diagonal and ±1
    elsewhere, ``C'C = (n - 1) I``), by Paley's construction or doubling.

    Raises ``ValueError`` for an order this module cannot build (none exists for n = 22).

    >>> C = conference_matrix(6)
    >>> (C.T @ C).tolist()[0]
    [5, 0, 0, 0, 0, 0]
    """
    n = int(n)
    if n < 2 or n % 2:
        raise ValueError(f"conference matrices have even order >= 2 (got {n})")
    if n == 2:
        return _check(np.array([[0, 1], [-1, 0]]))
    pe = _prime_power(n - 1)
    if pe is not None and pe[0] != 2 and pe[1] <= 2:
        return _check(_paley(n - 1))
    if n % 4 == 0:
        half = n // 2
        try:
            C = conference_matrix(half)
        except ValueError:
            C = None
        if C is not None and np.array_equal(C.T, -C):
            H = C + np.eye(half, dtype=int)
            K = np.block([[H, H], [-H.T, H.T]])
            return _check(K - np.eye(n, dtype=int))
    raise ValueError(f"no conference matrix of order {n} is built here")


def conference_order(m: int) -> int:
    """The order of the conference matrix a definitive screening design of m factors uses:
    the smallest even order >= m that :func:`conference_matrix` builds."""
    n = m + (m % 2)
    while True:
        try:
            conference_matrix(n)
            return n
        except ValueError:
            n += 2
            if n > 4 * m + 8:
                raise


def definitive_screening(factors: Any, center: int | None = None, seed: Any = None, randomize: bool = True) -> Design:
    """Definitive screening design (Jones & Nachtsheim 2011) for 4 or more factors.

    Parameters
    ----------
    factors : FactorSpace, mapping or list
        Numeric factors, and optionally two-level categoric factors (the extension of
        Jones & Nachtsheim 2013, *JQT* 45(2), 121-129: a categoric factor takes a column
        of the conference matrix with its zero replaced by +1 in ``C`` and -1 in ``-C``,
        so the fold-over pairs stay; the centre runs alternate its two levels).
    center : int or None
        Centre runs (numeric factors at 0). Default 1 (the published design), 2 with
        categoric factors (one at each level).
    seed, randomize
        Run order, as for the other designs.

    Returns
    -------
    Design
        ``2n + center`` runs with n = :func:`conference_order` (m) : ``C``, ``-C`` (the first m
        columns of a conference matrix of order n), then the centre runs.

    >>> d = definitive_screening([f"x{i}=0:1" for i in range(6)], randomize=False)
    >>> d.n_runs, sorted(set(d.coded_runs.ravel().tolist()))
    (13, [-1.0, 0.0, 1.0])
    """
    space = as_factor_space(factors)
    _, mn = numeric_part(space)
    cats = [f for f in space.factors if f.kind == "categoric"]
    bad = [f.name for f in cats if f.n_levels != 2]
    if bad:
        raise ValueError(f"a definitive screening design takes two-level categoric factors only ({bad[0]!r} has "
                         "more levels)")
    m = len(space)
    if not 4 <= m <= MAX_DSD_FACTORS:
        raise ValueError(f"a definitive screening design needs 4 to {MAX_DSD_FACTORS} factors (got {m})")
    if center is None:
        center = 2 if cats else 1
    if isinstance(center, (bool, np.bool_)) or int(center) != center or center < 0:
        raise ValueError(f"center must be a whole number >= 0 (got {center!r})")
    center = int(center)
    n = conference_order(m)
    C = conference_matrix(n)[:, :m].astype(float)
    top, bottom = C.copy(), -C
    for j in range(mn, m):  # categoric columns: the zero becomes +1 / -1, levels coded 0 / 1
        top[j, j], bottom[j, j] = 1.0, -1.0
    mid = np.zeros((center, m))
    for r in range(center):
        mid[r, mn:] = 1.0 if r % 2 == 0 else -1.0
    coded = np.vstack([top, bottom, mid])
    coded[:, mn:] = (coded[:, mn:] + 1.0) / 2.0  # -1 -> first level, +1 -> second
    options = {"conference_order": n, "center": center, "columns_dropped": n - m, "categoric": len(cats),
               "source": "Jones & Nachtsheim (2011), JQT 43(1):1-15; categoric: Jones & Nachtsheim (2013), "
                         "JQT 45(2):121-129; conference matrix by Paley (1933) or doubling"}
    return Design.from_standard(space, "definitive-screening", coded, seed=seed, randomize=randomize,
                                options=options)


def fractional_factorial(factors: Any, resolution: int | None = None, generators: str | None = None,
                         center: int = 0, seed: Any = None, randomize: bool = True) -> Design:
    """Two-level fractional factorial by resolution or by generators (pyDOE3 ``fracfact``).

    Parameters
    ----------
    resolution : int or None
        The resolution wanted (III, IV, V, ... as 3, 4, 5); pyDOE3's ``fracfact_by_res``
        picks the generators.
    generators : str or None
        pyDOE3's generator string in the factor letters, e.g. ``"A B C ABC"`` (the fourth
        factor D = ABC); lower-case works too.
    center : int
        Centre runs added.

    ``options["aliases"]`` lists the alias groups of main effects and two-factor
    interactions (:func:`alias_groups`).
    """
    space = as_factor_space(factors)
    _, k = numeric_part(space)
    if space.has_categoric:
        raise ValueError("a two-level fractional factorial here takes numeric factors only")
    if k < 3:
        raise ValueError("a fractional factorial needs at least 3 factors")
    if (resolution is None) == (generators is None):
        raise ValueError("give either a resolution or generators")
    import pyDOE3

    if generators is not None:
        gen = _generator_string(generators, space.letters)
        X = np.asarray(pyDOE3.fracfact(gen), dtype=float)
        if X.shape[1] != k:
            raise ValueError(f"generators {generators!r} give {X.shape[1]} columns for {k} factors")
    else:
        if isinstance(resolution, (bool, np.bool_)) or int(resolution) != resolution or resolution < 3:
            raise ValueError(f"resolution must be a whole number >= 3 (got {resolution!r})")
        try:
            X = np.asarray(pyDOE3.fracfact_by_res(k, int(resolution)), dtype=float)
        except ValueError as exc:
            raise ValueError(f"no {k}-factor fractional factorial of resolution {resolution}: {exc}") from None
        gen = None
    if isinstance(center, (bool, np.bool_)) or int(center) != center or center < 0:
        raise ValueError(f"center must be a whole number >= 0 (got {center!r})")
    coded = np.vstack([X, np.zeros((int(center), k))])
    groups = alias_groups(X, space.letters)
    res = _resolution(X)
    options = {"generators": gen, "resolution": res, "center": int(center),
               "aliases": groups,
               "note": "aliases: " + "; ".join(" = ".join(g) for g in groups if len(g) > 1)}
    return Design.from_standard(space, "fractional-factorial", coded, seed=seed, randomize=randomize,
                                options=options)


def _generator_string(gen: str, letters: list[str]) -> str:
    import re

    toks = gen.replace(",", " ").split()
    if len(toks) != len(letters):
        raise ValueError(f"generators {gen!r}: expected {len(letters)} words (one per factor), got {len(toks)}")
    known = {L.lower() for L in letters}
    for t in toks:
        if not re.fullmatch(r"[+-]?[A-Za-z]+", t):
            raise ValueError(f"generators {gen!r}: {t!r} is not a word of factor letters")
        bad = [c for c in t.lstrip("+-").lower() if c not in known]
        if bad:
            raise ValueError(f"generators {gen!r}: {bad[0].upper()!r} in {t!r} is not a factor letter "
                             f"({', '.join(letters)})")
    return " ".join(t.lower() for t in toks)


def _resolution(X: np.ndarray) -> int | None:
    """Shortest word of the defining relation (the smallest set of columns whose product
    is constant)."""
    k = X.shape[1]
    for r in range(2, k + 1):
        for combo in itertools.combinations(range(k), r):
            v = np.prod(X[:, combo], axis=1)
            if np.all(v == v[0]):
                return r
    return None


def plackett_burman(factors: Any, center: int = 0, seed: Any = None, randomize: bool = True) -> Design:
    """Plackett–Burman two-level screening design (pyDOE3 ``pbdesign``: runs a multiple of 4
    above the number of factors; Plackett & Burman 1946, *Biometrika* 33, 305-325)."""
    space = as_factor_space(factors)
    if space.has_categoric:
        raise ValueError("a Plackett-Burman design here takes numeric factors only")
    k = len(space)
    if k < 2:
        raise ValueError("a Plackett-Burman design needs at least 2 factors")
    import pyDOE3

    X = np.asarray(pyDOE3.pbdesign(k), dtype=float)
    if isinstance(center, (bool, np.bool_)) or int(center) != center or center < 0:
        raise ValueError(f"center must be a whole number >= 0 (got {center!r})")
    coded = np.vstack([X, np.zeros((int(center), k))])
    return Design.from_standard(space, "plackett-burman", coded, seed=seed, randomize=randomize,
                                options={"center": int(center), "source": "Plackett & Burman (1946) via pyDOE3"})


def alias_matrix(coded: np.ndarray, letters, model: str = "linear", potential: str = "2fi") -> tuple:
    """Alias matrix ``A = (X1'X1)^-1 X1'X2`` (Myers, Montgomery & Anderson-Cook 2009, section
    3.?; the bias of the fitted terms when the potential terms are active).

    Returns ``(A, fitted term names, potential term names)``; ``model`` are the fitted terms,
    ``potential`` the bigger model whose extra terms may bias them.
    """
    from ..terms import column_names, design_matrix, model_terms

    t1 = model_terms(list(letters), model)
    t2 = [t for t in model_terms(list(letters), potential) if t.name not in {u.name for u in t1}]
    X1 = design_matrix(coded, t1)
    X2 = design_matrix(coded, t2)
    A = np.linalg.pinv(X1.T @ X1) @ X1.T @ X2
    A[np.abs(A) < 1e-12] = 0.0
    return A + 0.0, column_names(t1), column_names(t2)


def alias_groups(X: np.ndarray, letters, max_order: int = 2) -> list[list[str]]:
    """Groups of effects (main effects and interactions up to ``max_order``) whose columns
    in the two-level design ``X`` are equal or opposite (fully aliased); ``-`` marks an
    opposite sign."""
    k = X.shape[1]
    effects = []
    for r in range(1, max_order + 1):
        for combo in itertools.combinations(range(k), r):
            effects.append(("".join(letters[i] for i in combo), np.prod(X[:, combo], axis=1)))
    groups: list[list[str]] = []
    seen: dict[bytes, int] = {}
    for name, col in effects:
        key, neg = col.tobytes(), (-col).tobytes()
        if key in seen:
            groups[seen[key]].append(name)
        elif neg in seen:
            groups[seen[neg]].append("-" + name)
        else:
            seen[key] = len(groups)
            groups.append([name])
    return groups
