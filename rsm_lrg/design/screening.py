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

from ..errors import ParameterError
from .core import Design, as_factor_space, numeric_part

__all__ = ["conference_matrix", "conference_order", "definitive_screening", "fractional_factorial",
           "plackett_burman", "hadamard_matrix", "alias_matrix", "alias_groups", "MAX_DSD_FACTORS"]

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
    elems: list[tuple[int, ...]]
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

    Parameters
    ----------
    n : int
        The order.

    Returns
    -------
    numpy.ndarray, shape (n, n)
        The matrix (integers 0, ±1).
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
        raise ParameterError("center", f"center must be a whole number >= 0 (got {center!r})")
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


#: Minimum-aberration two-level fractions for 3 to 15 factors: ``k: [(q, resolution, generators)]``
#: with ``2^q`` runs, the first ``q`` factors basic (A, B, C, ... in Yates order) and one word of
#: basic letters per added factor (all signs +). Montgomery, *Design and Analysis of
#: Experiments*, 8th ed. (2013), Table 8.14 "Selected 2^(k-p) fractional factorial designs"
#: (from Box, Hunter & Hunter 2005); the resolution of every entry is recomputed from its
#: defining relation before use.
_FF_TABLE: dict[int, list[tuple[int, int, tuple[str, ...]]]] = {
    3: [(2, 3, ("AB",))],
    4: [(3, 4, ("ABC",))],
    5: [(4, 5, ("ABCD",)), (3, 3, ("AB", "AC"))],
    6: [(5, 6, ("ABCDE",)), (4, 4, ("ABC", "BCD")), (3, 3, ("AB", "AC", "BC"))],
    7: [(6, 7, ("ABCDEF",)), (5, 4, ("ABCD", "ABDE")), (4, 4, ("ABC", "BCD", "ACD")),
        (3, 3, ("AB", "AC", "BC", "ABC"))],
    8: [(6, 5, ("ABCD", "ABEF")), (5, 4, ("ABC", "ABD", "BCDE")), (4, 4, ("BCD", "ACD", "ABC", "ABD"))],
    9: [(7, 6, ("ACDFG", "BCEFG")), (6, 4, ("ABCD", "ACEF", "CDEF")), (5, 4, ("BCDE", "ACDE", "ABDE", "ABCE")),
        (4, 3, ("ABC", "BCD", "ACD", "ABD", "ABCD"))],
    10: [(7, 5, ("ABCG", "BCDE", "ACDF")), (6, 4, ("BCDF", "ACDF", "ABDE", "ABCE")),
         (5, 4, ("ABCD", "ABCE", "ABDE", "ACDE", "BCDE")), (4, 3, ("ABC", "BCD", "ACD", "ABD", "ABCD", "AB"))],
    11: [(7, 5, ("ABCG", "BCDE", "ACDF", "ABCDEFG")), (6, 4, ("CDE", "ABCD", "ABF", "BDEF", "ADEF")),
         (5, 4, ("ABC", "BCD", "CDE", "ACD", "ADE", "BDE")),
         (4, 3, ("ABC", "BCD", "ACD", "ABD", "ABCD", "AB", "AC"))],
}
for _k in range(12, 16):  # 16-run resolution III designs, one added column per factor
    _FF_TABLE[_k] = [(4, 3, ("ABC", "BCD", "ACD", "ABD", "ABCD", "AB", "AC", "AD", "BC", "BD", "CD")[:_k - 4])]
del _k

#: Most runs of a two-level fraction built here (a guard against a typo asking for 2^30).
MAX_FRACTION_RUNS = 4096

_ROMAN = {2: "II", 3: "III", 4: "IV", 5: "V", 6: "VI", 7: "VII", 8: "VIII", 9: "IX", 10: "X"}


def _table_masks(words) -> list[int]:
    """Generator words in basic letters (A, B, ..., no I) as bit masks of the basic factors."""
    from ..factors import letters_for

    alphabet = letters_for(25)
    return [sum(1 << alphabet.index(c) for c in w) for w in words]


def _defining_words(q: int, gens: list[int]) -> list[int]:
    """Every word of the defining relation (bit masks over the q basic + p added factors)."""
    group = [0]
    for j, g in enumerate(gens):
        w = g | (1 << (q + j))
        group += [w ^ x for x in group]
    return group[1:]


def _fraction_resolution(q: int, gens: list[int]) -> int | None:
    """Resolution: the length of the shortest word of the defining relation (None: no words).

    With up to 2^16 words every word is listed; beyond, the shortest word is searched by
    length (a set of r columns whose masks over the basic factors cancel), meeting in the
    middle (all r//2-subsets against the rest), which stays quick for the short words that
    designs with that many added factors have."""
    if not gens:
        return None
    if len(gens) <= 16:
        return min(bin(w).count("1") for w in _defining_words(q, gens))
    cols = [1 << j for j in range(q)] + list(gens)
    n = len(cols)
    for r in range(2, n + 1):
        a = r // 2
        half: dict[int, list[tuple[int, ...]]] = {}
        for combo in itertools.combinations(range(n), a):
            x = 0
            for i in combo:
                x ^= cols[i]
            half.setdefault(x, []).append(combo)
        for combo in itertools.combinations(range(n), r - a):
            x = 0
            for i in combo:
                x ^= cols[i]
            for other in half.get(x, ()):
                if not set(other) & set(combo):
                    return r
    return None


def _fraction_runs(q: int, gens: list[int]) -> np.ndarray:
    """The 2^q runs in Yates standard order (first basic factor changing fastest), one column
    per basic factor and then one per generator (the product of its basic columns)."""
    r = np.arange(2 ** q)
    base = np.column_stack([np.where((r >> j) & 1, 1.0, -1.0) for j in range(q)])
    cols = [np.prod(base[:, [j for j in range(q) if g >> j & 1]], axis=1) for g in gens]
    return np.column_stack([base, *cols]) if cols else base


def _fraction_by_resolution(k: int, resolution: int) -> tuple[int, list[int], str]:
    """(q, generator masks, source) of the smallest two-level fraction of k factors with
    resolution >= ``resolution``: the table above for 3 to 15 factors, else a construction
    (resolution III: distinct interaction columns of a 2^q; IV: odd-length words, a fold-over;
    V and more: a greedy search); the full factorial when no fraction reaches it."""
    entries = [e for e in _FF_TABLE.get(k, []) if e[1] >= resolution]
    if entries:
        q, _, words = min(entries, key=lambda e: e[0])
        return q, _table_masks(words), "Montgomery (2013), Table 8.14 (minimum aberration)"
    if resolution > k:
        # every fraction has a word of length <= k (the half fraction I = AB...K is the best)
        return k, [], "full factorial: no fraction reaches the resolution"
    q = 1
    while True:
        q += 1
        if 2 ** q > MAX_FRACTION_RUNS:
            raise ParameterError("resolution", f"no {k}-factor fraction of resolution {resolution} with at most "
                             f"{MAX_FRACTION_RUNS} runs is built here; give --generator")
        cands = [m for m in range(1, 2 ** q) if bin(m).count("1") >= max(2, resolution - 1)]
        if resolution == 4:
            cands = [m for m in cands if bin(m).count("1") % 2 == 1]
        if len(cands) < k - q:
            continue
        order = sorted(cands, key=lambda m: (-bin(m).count("1"), m))
        if resolution <= 4:
            return q, order[:k - q], "constructed (resolution III: distinct interactions; IV: odd-length words)"
        for ranked in (order, sorted(cands, key=lambda m: (bin(m).count("1"), m))):
            gens: list[int] = []
            for m in ranked:
                res = _fraction_resolution(q, gens + [m])
                if res is not None and res >= resolution:
                    gens.append(m)
                    if len(gens) == k - q:
                        return q, gens, ("constructed by a greedy search (not necessarily minimum aberration or "
                                         "the fewest runs)")


def fractional_factorial(factors: Any, resolution: int | None = None, generators: str | None = None,
                         center: int = 0, seed: Any = None, randomize: bool = True) -> Design:
    """Two-level fractional factorial by resolution or by generators.

    Parameters
    ----------
    resolution : int or None
        The least resolution wanted (III, IV, V, ... as 3, 4, 5). The design is the smallest
        fraction of that resolution or more: the minimum-aberration fractions of Montgomery,
        *Design and Analysis of Experiments*, 8th ed., Table 8.14, for 3 to 15 factors (e.g.
        2^(4-1)_IV with D = ABC, 2^(7-4)_III, 2^(8-2)_V); the full factorial when no fraction
        reaches the resolution (4 factors at resolution V), as ``options["note"]`` says.
    generators : str or None
        One word per factor in the factor letters, e.g. ``"A B C ABC"`` (a factor whose word
        is its own letter is a basic factor; here D = ABC), or the added factors only,
        ``"D=ABC"`` (every factor not named is basic); a word may start with ``-``.
        Lower-case works too. The basic factors are the first ones.
    center : int
        Centre runs added.

    Returns
    -------
    Design
        The fraction in coded and actual units, ``kind="fractional-factorial"``.

    Notes
    -----
    The runs are in Yates standard order (the first basic factor changing fastest).
    ``options`` records the generators (``"D = ABC"``), the ``resolution`` (``None`` for
    a full factorial) and the alias groups of main effects and two-factor interactions
    (:func:`alias_groups`).

    >>> d = fractional_factorial([f"x{i}=0:1" for i in range(4)], resolution=4, randomize=False)
    >>> d.n_runs, d.options["resolution"], d.options["generators"]
    (8, 4, 'D = ABC')
    """
    space = as_factor_space(factors)
    _, k = numeric_part(space)
    if space.has_categoric:
        raise ParameterError("factors", "a two-level fractional factorial here takes numeric factors only")
    if k < 3:
        raise ParameterError("factors", f"a fractional factorial needs at least 3 factors (got {k})")
    if (resolution is None) == (generators is None):
        raise ValueError("give either a resolution or generators")
    if isinstance(center, (bool, np.bool_)) or int(center) != center or center < 0:
        raise ParameterError("center", f"center must be a whole number >= 0 (got {center!r})")
    letters = space.letters
    source = None
    if generators is not None:
        q, gens, signs = _parse_generators(generators, letters)
    else:
        assert resolution is not None  # exactly one of resolution and generators (checked above)
        if isinstance(resolution, (bool, np.bool_)) or int(resolution) != resolution or resolution < 3:
            raise ParameterError("resolution", f"resolution must be a whole number >= 3 (got {resolution!r})")
        q, gens, source = _fraction_by_resolution(k, int(resolution))
        signs = [1.0] * len(gens)
    if 2 ** q > MAX_FRACTION_RUNS:
        what = "generators" if generators is not None else "resolution"
        raise ParameterError(what, f"2^{q} = {2 ** q} runs is more than this generator makes ({MAX_FRACTION_RUNS})")
    X = _fraction_runs(q, gens) * np.array([1.0] * q + list(signs))
    res = _fraction_resolution(q, gens)
    if resolution is not None and res is not None and res < resolution:  # never a lower resolution silently
        raise ArithmeticError(f"the {k}-factor fraction built has resolution {res}, not {resolution}")
    gen_text = ", ".join(f"{letters[q + j]} = {'-' if s < 0 else ''}{''.join(letters[i] for i in range(q) if g >> i & 1)}"
                         for j, (g, s) in enumerate(zip(gens, signs)))
    coded = np.vstack([X, np.zeros((int(center), k))])
    groups = alias_groups(X, letters)
    if gens and res is not None:  # res is None only without generators
        head = f"2^({k}-{k - q}) fraction, resolution {_ROMAN.get(res, res)}, generators {gen_text}"
    else:
        head = f"full 2^{k} factorial" + (f" (no fraction of {k} factors has resolution {resolution} or more)"
                                          if resolution is not None else "")
    aliased = "; ".join(" = ".join(g) for g in groups if len(g) > 1)
    options = {"generators": gen_text or None, "resolution": res, "center": int(center), "aliases": groups,
               "note": f"{head}\naliases: {aliased or 'none among main effects and two-factor interactions'}"}
    if source:
        options["source"] = source
    return Design.from_standard(space, "fractional-factorial", coded, seed=seed, randomize=randomize,
                                options=options)


def _parse_generators(gen: str, letters: list[str]) -> tuple[int, list[int], list[float]]:
    """``(q, generator masks over the basic factors, signs)`` from ``"A B C ABC"`` or ``"D=ABC"``;
    the basic factors must be the first q factors (A, B, ...), the generated ones the rest."""
    import re

    text = str(gen)
    upper = [L.upper() for L in letters]
    k = len(letters)
    spaced = re.sub(r"\s*=\s*", "=", text.replace(",", " "))
    toks = spaced.split()
    if not toks:
        raise ParameterError("generators", "empty; give one word per factor ('A B C ABC') or the added ones ('D=ABC')")
    pattern = re.compile("|".join(re.escape(L) for L in sorted(upper, key=len, reverse=True)))

    def split(word: str, tok: str) -> list[int]:
        w = word.upper()
        if not w:
            raise ParameterError("generators", f"generators {text!r}: {tok!r} has an empty word")
        pos, out = 0, []
        while pos < len(w):
            m = pattern.match(w, pos)
            if not m:
                raise ParameterError("generators", f"generators {text!r}: {w[pos]!r} in {tok!r} is not a factor letter "
                                 f"({', '.join(letters)})")
            out.append(upper.index(m.group()))
            pos = m.end()
        return out

    words: dict[int, tuple[list[int], float]] = {}
    if any("=" in t for t in toks):
        for t in toks:
            name, eq, word = t.partition("=")
            if not eq or not name or not word:
                raise ParameterError("generators", f"generators {text!r}: {t!r} is not of the form D=ABC")
            who = split(name, t)
            if len(who) != 1:
                raise ParameterError("generators", f"generators {text!r}: {name!r} in {t!r} is not one factor letter")
            if who[0] in words:
                raise ParameterError("generators", f"generators {text!r}: factor {letters[who[0]]} has two generators")
            words[who[0]] = (split(word.lstrip("+-"), t), -1.0 if word.startswith("-") else 1.0)
        basic = [i for i in range(k) if i not in words]
    else:
        if len(toks) != k:
            raise ParameterError("generators", f"generators {text!r}: expected {k} words (one per factor), got {len(toks)}")
        basic = []
        for i, t in enumerate(toks):
            idx, sign = split(t.lstrip("+-"), t), (-1.0 if t.startswith("-") else 1.0)
            if idx == [i] and sign > 0:
                basic.append(i)
            else:
                words[i] = (idx, sign)
    q = len(basic)
    if basic != list(range(q)):
        raise ParameterError("generators", f"generators {text!r}: the basic factors (whose word is their own letter) must be the "
                         f"first ones ({', '.join(letters[:q])}) and the generated ones follow")
    if q < 2:
        raise ParameterError("generators", f"generators {text!r}: at least two basic factors are needed")
    gens, signs = [], []
    for i in range(q, k):
        idx, sign = words[i]
        bad = [j for j in idx if j >= q]
        if bad:
            raise ParameterError("generators", f"generators {text!r}: the word of {letters[i]} uses {letters[bad[0]]}, which is not a "
                             f"basic factor ({', '.join(letters[:q])})")
        if len(set(idx)) != len(idx):
            raise ParameterError("generators", f"generators {text!r}: the word of {letters[i]} repeats a letter")
        if len(idx) < 2:
            raise ParameterError("generators", f"generators {text!r}: {letters[i]} = {'-' if sign < 0 else ''}{letters[idx[0]]} "
                             "confounds two main effects (resolution II)")
        gens.append(sum(1 << j for j in idx))
        signs.append(sign)
    res = _fraction_resolution(q, gens)
    if res is not None and res < 3:
        raise ParameterError("generators", f"generators {text!r}: two factors get the same column (main effects confounded, "
                         "resolution II)")
    return q, gens, signs


#: First rows of Plackett & Burman's (1946) cyclic designs (Biometrika 33, 305-325, Table 1;
#: as printed in Montgomery, Design and Analysis of Experiments, 8th ed., Table 8.22): the
#: runs are the N - 1 cyclic shifts of the row, then a row of minus signs.
PB_GENERATORS = {
    8: "+++-+--",
    12: "++-+++---+-",
    20: "++--++++-+-+----++-",
    24: "+++++-+-++--++--+-+----",
}

#: Largest Plackett-Burman design built (runs).
MAX_PB_RUNS = 4096


def hadamard_matrix(n: int) -> np.ndarray:
    """An exact Hadamard matrix of order ``n`` (``H H' = n I``, entries ±1).

    Built from Plackett & Burman's cyclic rows (n = 8, 12, 20, 24), Paley's first
    construction (n - 1 an odd prime power ≡ 3 mod 4: ``H = I + C``, C the antisymmetric
    conference matrix), Paley's second (n/2 - 1 ≡ 1 mod 4: ``[[C+I, C-I], [C-I, -C-I]]``,
    C symmetric) or doubling (``[[H, H], [H, -H]]``, Sylvester 1867). Orders 4..100 are all
    built but 92 (a Williamson matrix, not built here). Every matrix is checked.

    >>> H = hadamard_matrix(28)
    >>> bool((H @ H.T == 28 * np.eye(28)).all())
    True
    """
    n = int(n)
    if n in (1, 2):
        return np.array([[1]]) if n == 1 else np.array([[1, 1], [1, -1]])
    if n < 4 or n % 4:
        raise ValueError(f"Hadamard matrices have order 1, 2 or a multiple of 4 (got {n})")
    H: np.ndarray | None = None
    if n in PB_GENERATORS:
        g = np.array([1 if c == "+" else -1 for c in PB_GENERATORS[n]])
        rows = np.array([np.roll(g, i) for i in range(n - 1)])
        H = np.hstack([np.ones((n, 1), dtype=int), np.vstack([rows, -np.ones((1, n - 1), dtype=int)])])
    if H is None:
        pe = _prime_power(n - 1)
        if pe is not None and pe[0] != 2 and pe[1] <= 2 and (n - 1) % 4 == 3:
            H = _paley(n - 1) + np.eye(n, dtype=int)
    if H is None and n % 8 == 4:
        pe = _prime_power(n // 2 - 1)
        if pe is not None and pe[0] != 2 and pe[1] <= 2 and (n // 2 - 1) % 4 == 1:
            C = _paley(n // 2 - 1)
            eye = np.eye(n // 2, dtype=int)
            H = np.block([[C + eye, C - eye], [C - eye, -C - eye]])
    if H is None and n % 8 == 0:
        try:
            h = hadamard_matrix(n // 2)
        except ValueError:
            h = None
        if h is not None:
            H = np.block([[h, h], [h, -h]])
    if H is None:
        raise ValueError(f"no Hadamard matrix of order {n} is built here")
    if not np.array_equal(H @ H.T, n * np.eye(n, dtype=int)):
        raise ArithmeticError(f"the constructed matrix of order {n} is not a Hadamard matrix")
    return H


def plackett_burman(factors: Any, center: int = 0, seed: Any = None, randomize: bool = True) -> Design:
    """Plackett–Burman two-level screening design (Plackett & Burman 1946, *Biometrika* 33,
    305-325): N runs, N the smallest multiple of 4 above the number of factors k.

    The runs are Plackett & Burman's cyclic designs for N = 8, 12, 20, 24 (first row as
    published, then its cyclic shifts and a row of minus signs), else the columns 2..N of a
    normalised Hadamard matrix of order N (:func:`hadamard_matrix`; N = 4, 16, 28, 32, 36,
    ...); the factors take the first k columns. Every column is balanced and orthogonal to
    the others (``X'X = N I``). N = 92 (89 to 91 factors) is not built.

    Parameters
    ----------
    factors : FactorSpace, mapping or list
        As for :func:`~rsm_lrg.design.box_behnken` (numeric factors, two levels each).
    center : int, default 0
        Centre runs added.
    seed, randomize
        As for :func:`~rsm_lrg.design.box_behnken`.

    Returns
    -------
    Design
        The runs in coded and actual units, in run order (:meth:`~rsm_lrg.design.Design.to_frame`
        gives the design CSV layout).
    """
    space = as_factor_space(factors)
    if space.has_categoric:
        raise ValueError("a Plackett-Burman design here takes numeric factors only")
    k = len(space)
    if k < 2:
        raise ValueError(f"a Plackett-Burman design needs at least 2 factors (got {k})")
    if isinstance(center, (bool, np.bool_)) or int(center) != center or center < 0:
        raise ParameterError("center", f"center must be a whole number >= 0 (got {center!r})")
    n = 4 * (k // 4 + 1)
    if n > MAX_PB_RUNS:
        raise ValueError(f"a Plackett-Burman design of {k} factors needs {n} runs, more than this generator "
                         f"makes ({MAX_PB_RUNS})")
    try:
        H = hadamard_matrix(n)
    except ValueError:
        raise ValueError(f"a Plackett-Burman design of {k} factors needs {n} runs, and no Hadamard matrix of "
                         f"order {n} is built here; use fewer or more factors") from None
    if n in PB_GENERATORS:
        X = H[:, 1:]
    else:
        H = H * H[:, :1]  # rows signed so that the first column is +1: the others are balanced
        X = H[:, 1:]
    X = np.asarray(X[:, :k], dtype=float)
    coded = np.vstack([X, np.zeros((int(center), k))])
    source = ("Plackett & Burman (1946), cyclic first row" if n in PB_GENERATORS
              else "Plackett & Burman (1946) via a Hadamard matrix (Paley 1933 / Sylvester 1867)")
    return Design.from_standard(space, "plackett-burman", coded, seed=seed, randomize=randomize,
                                options={"center": int(center), "runs": n, "source": source})


def alias_matrix(coded: np.ndarray, letters, model: str = "linear", potential: str = "2fi") -> tuple:
    """Alias matrix ``A = (X1'X1)^-1 X1'X2`` (Myers, Montgomery & Anderson-Cook 2009, section
    3.?; the bias of the fitted terms when the potential terms are active).

    Returns ``(A, fitted term names, potential term names)``; ``model`` are the fitted terms,
    ``potential`` the bigger model whose extra terms may bias them.

    Parameters
    ----------
    coded : numpy.ndarray, shape (n, k)
        The runs in coded units.
    letters : sequence of str
        The factors' letters.
    model : str, default "linear"
        The fitted model.
    potential : str, default "2fi"
        The model whose extra terms may be active.

    Returns
    -------
    tuple
        ``(A, fitted term names, potential term names)``, ``A`` of shape (p1, p2).
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
