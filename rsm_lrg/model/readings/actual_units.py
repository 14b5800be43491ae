"""Least squares in actual units to the accuracy of the data (issue 21, item 4).

The fit itself runs in coded units ``x = (actual - centre) / half_range``
(:mod:`rsm_lrg.model.engines.least_squares`); the coefficients of the same polynomial in actual units
follow from an exact change of basis. Done in double precision, the coded coefficients'
rounding errors are multiplied by up to ``prod (1 + |centre| / half_range)^degree`` in that
change of basis (measured on the NIST StRD sets with ``rsm_lrg.fit`` and
``actual_coefficients``: 7.8 correct digits on Wampler5, 9.4 on Wampler1, 10.0 on Longley
and Norris). :func:`solve_actual` does the whole solve in double-double arithmetic (about
32 digits) instead, so that the actual-unit coefficients, their standard errors and the
residual standard deviation are correct to the last digit the data carry (the eleven NIST
StRD linear sets: 14.3 to 15 correct digits on every certified number; R 4.2.2 ``lm``: 5.5
to 15; ``tests/model/test_nist_strd.py``):

1. *The Gram matrix, exactly.* The model matrix of a well-conditioned basis ``Z`` (the same
   terms in ``(x - c) / h`` with ``c``, ``h`` the data's mid-range and half-range) is built
   in double-double (each value ``hi + lo``), and ``[Z y]' [Z y]`` is accumulated over chunks
   of rows with the error-free splitting of Ozaki et al. (2012, *Numer. Algorithms* 59:95):
   each column is cut into slices of 19 bits, so that the product of two slices summed over
   the at most 2^15 rows of a block is exact in double precision, and eight BLAS matrix
   products give ``Z'Z`` to about 2^-100 of ``|Z|'|Z|`` (:func:`_gram`). The n x p
   model matrix is never held (one chunk at a time).
2. *The normal equations of ``Z``, refined.* ``Z'Z b = Z'y`` is solved by iterative
   refinement (Moler 1967; Higham, *Accuracy and Stability*, 2002, §12.1): the residual
   ``Z'y - Z'Z b`` in double-double, the correction from the Cholesky factor of the
   equilibrated ``Z'Z`` in double precision. ``Z`` being well conditioned (kappa^2 u << 1),
   each step gains about 16 - 2 log10 kappa digits; it stops at the double-double floor
   ``u^2 kappa(Z)^2``. The inverse ``(Z'Z)^-1`` is refined the same way (Newton–Schulz form
   ``C <- C + P (I - Z'Z C)``). When ``Z`` is too ill conditioned for that (kappa^2 u >~ 1,
   e.g. a factor that cannot be centred, far from 0), the Cholesky factor and the inverse are
   computed in double-double instead (floor ``u^2 kappa^2`` still; ``converged`` is False
   when that floor is above 2^-60).
3. *Back to actual units, exactly.* ``Z = X M`` with ``M`` the binomial expansion of each
   coded monomial into actual monomials (exact rationals of the floats ``c`` and ``h``);
   ``b_actual = M b`` and ``cov_actual = M (Z'Z)^-1 M'`` are formed in double-double.
4. *The residual standard deviation* from a second pass over the rows, the residuals
   ``y - Z b`` in double-double.

**Decimal inputs.** A number read from a file is the decimal written there; the double
holding it differs by up to half an ulp, and on sensitive data that representation error
alone costs digits: the exact least-squares solution of Wampler2's doubles (``y`` exact
decimals, coefficients 1, 0.1, ..., 1e-5) has 13.2 correct digits on B3, where R ``lm``
happens to reach 14.5. With ``decimal_inputs`` (the default) each value is taken as the
decimal of at most 15 significant digits that reads back as the same double (``repr`` for
such numbers), carried as its double plus the correction (:func:`decimal_correction`): the
fit is then that of the data as written, to about 30 digits. Integers below 2^53 and
numbers with no such short decimal (computed values) are taken as they are. Without it the
result is the least-squares solution of the doubles themselves (on the NIST sets that is
behind R by up to 1.3 digits on Wampler2 and 0.1 on Norris' standard errors and SD).

**When actual units and coded units are the same model.** Shifting a factor,
``x -> (x - c) / h``, maps the span of the model's columns onto itself only when every
monomial the binomial expansion creates is a term of the model: the term list must be
*closed downward* in that factor (shifting A, ``A^2B`` needs ``AB`` and ``B``; ``A^3`` needs
``A^2``, ``A`` and the intercept; ``AE`` with E categoric needs ``E``).
:func:`shiftable_factors` says which factors are; :func:`is_closed_under_shift` whether all
are. A model without an intercept is never closed for a factor appearing alone
(``A -> A - c`` creates a constant): there the coded model ``y = b (x - c)/h`` and the actual
model ``y = b x`` are *different models* (the first has an implicit intercept ``-b c / h``),
and the model as given is the one in actual units. Such a factor is therefore only scaled
here (``c = 0``), which is exact for any term list; the caller must not centre it either
(code it as ``x / h``) if the coded coefficients are to describe the same fit. For a closed
term list the result is the coded fit's polynomial in actual units, to the accuracy above.
With ``basis="coded"`` the terms are taken as monomials of the coded values instead (the
coded fit's model, closed or not): the same solve, and the exact expansion then yields the
monomials the term list lacks as well (:attr:`ActualSolution.extra`, named as
``actual_coefficients`` in :mod:`rsm_lrg.model.fit` names them), so no term list needs the
double-precision expansion.

>>> import numpy as np
>>> from rsm_lrg.terms import parse_term
>>> x = np.arange(21.0)[:, None]
>>> y = 1 + x[:, 0] + x[:, 0] ** 2 + x[:, 0] ** 3            # Wampler-like, exact cubic
>>> terms = [parse_term(t, "A") for t in ("A", "A^2", "A^3")]
>>> s = solve_actual(x, y, terms, intercept=True)
>>> [s.coefficients[k] for k in ("Intercept", "A", "A^2", "A^3")], s.sigma < 1e-25
([1.0, 1.0, 1.0, 1.0], True)
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from functools import lru_cache
from math import comb

import numpy as np

from ...factors import letters_for
from ...terms import Term, effect_codes, term_name

__all__ = ["ActualSolution", "DeferredActual", "solve_actual", "solve_actual_deferred", "solve_actual_chunks",
           "is_closed_under_shift", "shiftable_factors", "decimal_correction", "CHUNK_ROWS", "DECIMAL_DIGITS"]

#: Rows of the model matrix built at a time (the exact products split a chunk into blocks of
#: at most 2^15 rows anyway).
CHUNK_ROWS = 32768

#: ``(x, y, block codes or None)`` chunks of rows, iterated once per pass.
Chunks = Callable[[], Iterable[tuple[np.ndarray, np.ndarray, np.ndarray | None]]]

_DD = tuple[np.ndarray, np.ndarray]


# ----------------------------------------------------------------------------------------
# double-double arithmetic on arrays (Dekker 1971; Knuth TAOCP vol. 2, 4.2.2)
# ----------------------------------------------------------------------------------------
def _two_sum(a: np.ndarray, b: np.ndarray) -> _DD:
    s = a + b
    bb = s - a
    return s, (a - (s - bb)) + (b - bb)


def _quick_two_sum(a: np.ndarray, b: np.ndarray) -> _DD:
    s = a + b
    return s, b - (s - a)


def _split(a: np.ndarray) -> _DD:
    c = 134217729.0 * a  # 2^27 + 1
    hi = c - (c - a)
    return hi, a - hi


def _two_prod(a: np.ndarray, b: np.ndarray) -> _DD:
    p = a * b
    ah, al = _split(a)
    bh, bl = _split(b)
    return p, ((ah * bh - p) + ah * bl + al * bh) + al * bl


def _dd_add(ah: np.ndarray, al: np.ndarray, bh: np.ndarray, bl: np.ndarray) -> _DD:
    s, e = _two_sum(ah, bh)
    t, f = _two_sum(al, bl)
    e = e + t
    s, e = _quick_two_sum(s, e)
    e = e + f
    return _quick_two_sum(s, e)


def _dd_add_d(ah: np.ndarray, al: np.ndarray, b: np.ndarray) -> _DD:
    """``(ah + al) + b`` for a double ``b``: :func:`_dd_add` with ``bl = 0`` (the same roundings,
    the steps on the zero part left out; ``+ 0.0`` keeps the sign of a zero as they leave it)."""
    s, e = _two_sum(ah, b)
    return _quick_two_sum(s, (e + al) + 0.0)


def _dd_mul(ah: np.ndarray, al: np.ndarray, bh: np.ndarray, bl: np.ndarray) -> _DD:
    p, e = _two_prod(ah, bh)
    e = e + (ah * bl + al * bh)
    return _quick_two_sum(p, e)


def _dd_div(ah: np.ndarray, al: np.ndarray, b: np.ndarray | float) -> _DD:
    """``(ah + al) / b`` for a double ``b``."""
    q = ah / b
    p, e = _two_prod(q, np.broadcast_to(np.asarray(b, dtype=float), np.shape(q)))
    r = ((ah - p) - e + al) / b
    return _quick_two_sum(q, r)


# ----------------------------------------------------------------------------------------
# error-free matrix products (Ozaki, Ogita, Oishi & Rump 2012)
# ----------------------------------------------------------------------------------------
#: Rows summed by one exact product: 2 * 19 bits per slice + 15 bits of sum fit in 53.
_MAX_INNER = 1 << 15


def _row_slices(A: np.ndarray, bits: int, count: int) -> list[np.ndarray]:
    """``A`` (r x k) as a sum of slices ``S_1 + S_2 + ...`` (at most ``count``; the rest,
    below ``2^-(count*bits)`` of each row's largest entry, dropped; trailing zero slices left
    out): row ``i`` of ``S_s`` holds integer multiples of ``2^(e_i - s*bits)`` below
    ``2^(e_i - (s-1)*bits)`` in magnitude, ``2^e_i`` bounding the row (every step is exact).
    ``S_1 + ... + S_s`` is ``A`` rounded (to nearest, ties to even) to multiples of
    ``2^(e_i - s*bits)``: rounding the rest of the coarser slices at a finer grid shifts by a
    multiple of an even number of grid steps, which leaves the rounding (and its ties) as it is;
    so all the slices come from one rounding of ``A`` at every grid."""
    _, e = np.frexp(np.max(np.abs(A), axis=1, initial=0.0))
    g = e[None, :, None] - (bits * np.arange(1, count + 1))[:, None, None]
    S = np.ldexp(A[None], -g)  # (count, r, k): A at each grid, then the differences
    np.rint(S, out=S)
    np.ldexp(S, g, out=S)
    np.subtract(S[1:], S[:-1], out=S[1:])
    nz = np.flatnonzero(S.reshape(count, -1).any(axis=1))
    used = int(nz[-1]) + 1 if nz.size else 1
    return list(S[:used])


def _slice_bits(k: int) -> tuple[int, int]:
    """``(bits, count)`` of the slices for an exact product with inner dimension ``k``."""
    bits = (53 - max(1, math.ceil(math.log2(max(k, 2))))) // 2
    return bits, -(-108 // bits)


def _left_slices(A: np.ndarray) -> list[np.ndarray]:
    """The row slices of ``A`` that :func:`_exact_product` cuts (for a left factor used in
    several products: cut once)."""
    bits, count = _slice_bits(A.shape[1])
    return _row_slices(A, bits, count)


def _exact_product(A: np.ndarray, B: np.ndarray, sa: list[np.ndarray] | None = None) -> _DD:
    """``A @ B`` (doubles, inner dimension k at most 2^15) as a double-double pair, to about
    2^-106 of ``|A| |B|``: rows of ``A`` and columns of ``B`` are cut into slices of
    ``bits = (53 - ceil(log2 k)) // 2`` bits (:func:`_row_slices`; ``sa``: those of ``A``,
    already cut by :func:`_left_slices`), so that each entry of a product of two slices is a
    sum of k integers below ``2^(2 bits)`` times one power of two, exact in double precision
    (in any order of summation, so all the products come from one matrix product of the
    stacked slices); those products are added in double-double."""
    bits, count = _slice_bits(A.shape[1])
    if sa is None:
        sa = _row_slices(A, bits, count)
    sb = _row_slices(np.ascontiguousarray(B.T), bits, count)
    m, q = A.shape[0], B.shape[1]
    P = (np.concatenate(sa) if len(sa) > 1 else sa[0]) @ (np.concatenate(sb).T if len(sb) > 1 else sb[0].T)
    ch = cl = None
    for s in range(len(sa)):
        for t in range(len(sb)):
            if s + t <= count - 1:
                block = P[s * m:(s + 1) * m, t * q:(t + 1) * q]  # exact
                if ch is None:
                    ch, cl = block + 0.0, np.zeros((m, q))
                else:
                    assert cl is not None
                    ch, cl = _dd_add_d(ch, cl, block)
    assert ch is not None and cl is not None
    return ch, cl


def _dd_matmul(Ah: np.ndarray, Al: np.ndarray, Bh: np.ndarray, Bl: np.ndarray,
               sa: list[np.ndarray] | None = None) -> _DD:
    """``(Ah + Al) @ (Bh + Bl)`` in double-double: the product of the high parts exact
    (:func:`_exact_product`, in blocks of 2^15 of the inner dimension; ``sa`` the slices of
    ``Ah`` from :func:`_left_slices` when it has at most 2^15 columns), the cross terms in
    double precision (they are 2^-53 smaller), ``Al @ Bl`` dropped."""
    k = Ah.shape[1]
    if k <= _MAX_INNER:
        ch, cl = _exact_product(Ah, Bh, sa)
    else:
        ch = np.zeros((Ah.shape[0], Bh.shape[1]))
        cl = np.zeros_like(ch)
        for s in range(0, k, _MAX_INNER):
            e = min(k, s + _MAX_INNER)
            ph, pl = _exact_product(Ah[:, s:e], Bh[s:e])
            ch, cl = _dd_add(ch, cl, ph, pl)
    cross = Ah @ Bl + Al @ Bh
    return _dd_add_d(ch, cl, cross)


def _gram(Ah: np.ndarray, Al: np.ndarray) -> _DD:
    """``A'A`` for ``A = Ah + Al`` (m x q double-double, m at most 2^15) to about 2^-100 of
    ``|A|'|A|``, in eight matrix products: each column's high part is cut into slices
    ``S1 + S2 + S3 + T`` of 19 bits below the column's largest power of two (``T`` the rest,
    below 2^-57 of it); the products above 2^-53 of the whole (``S1'S1``, ``S1'S2``,
    ``S2'S2``, ``S1'S3`` and their transposes) are exact in double precision (see
    :func:`_exact_product`), the smaller ones (``S1'T``, ``S2'(S3 + T)``, ``(S3 + T)'(S3 + T)``,
    ``Ah'Al``) are rounded once, which costs no more than 2^-53 of their size."""
    bits = 19
    _, e = np.frexp(np.max(np.abs(Ah), axis=0, initial=0.0))

    def cut(rest: np.ndarray, s: int) -> np.ndarray:
        g = (e - s * bits)[None, :]
        return np.ldexp(np.rint(np.ldexp(rest, -g)), g)

    S1 = cut(Ah, 1)
    R = Ah - S1
    S2 = cut(R, 2)
    U = R - S2
    S3 = cut(U, 3)
    T = U - S3
    q = Ah.shape[1]
    zero = np.zeros((q, q))
    gh, gl = S1.T @ S1, zero
    for P in (S1.T @ S2, S1.T @ S3):
        gh, gl = _dd_add(gh, gl, P, zero)
        gh, gl = _dd_add(gh, gl, P.T, zero)
    gh, gl = _dd_add(gh, gl, S2.T @ S2, zero)
    F = S1.T @ T + S2.T @ U + Ah.T @ Al
    F = F + F.T + U.T @ U
    return _dd_add(gh, gl, F, zero)


def _dd_sum_rows(h: np.ndarray, lo: np.ndarray) -> _DD:
    """Row sums of a double-double matrix (p x q), in double-double."""
    sh = np.zeros(h.shape[0])
    sl = np.zeros(h.shape[0])
    for j in range(h.shape[1]):
        sh, sl = _dd_add(sh, sl, h[:, j], lo[:, j])
    return sh, sl


# ----------------------------------------------------------------------------------------
# decimal inputs
# ----------------------------------------------------------------------------------------
_POW10_RANGE = (-320, 300)
_POW10: list[np.ndarray] = []


def _pow10(q: np.ndarray) -> _DD:
    """``10^q`` (integers in -320 .. 300) as double-double pairs (the exact rationals rounded
    twice; the table is made once)."""
    if not _POW10:
        lo_q, hi_q = _POW10_RANGE
        fr = [Fraction(10) ** t for t in range(lo_q, hi_q + 1)]
        his = [float(f) for f in fr]
        _POW10.extend([np.array(his), np.array([float(f - Fraction(h)) for f, h in zip(fr, his)])])
    idx = q - _POW10_RANGE[0]
    return _POW10[0][idx], _POW10[1][idx]


#: Most significant digits of a number taken as a decimal (an integer mantissa below 2^53).
DECIMAL_DIGITS = 15


def decimal_correction(values: np.ndarray) -> np.ndarray:
    """``d - v`` for each double ``v``: ``d`` the decimal of at most 15 significant digits
    that reads back as ``v`` (the number as written in a file: ``repr(v)`` when that is at
    most 15 digits long), 0 when there is none (a computed value such as 0.1 + 0.2, whose
    double is then taken as it is), for 0, non-finite values and magnitudes beyond 1e+-290. The correction is below
    half an ulp of ``v``; it is found with the shortest mantissa ``M`` (``d = M 10^q``) whose
    double-double value lies within half an ulp of ``v``.

    >>> float(decimal_correction(np.array([0.1]))[0])  # 0.1 - 0.1000000000000000055511151231257827
    -5.551115123125783e-18
    """
    v = np.asarray(values, dtype=float)
    out = np.zeros(v.shape)
    flat = v.ravel()
    res = out.reshape(-1)
    size = np.abs(flat)
    todo = np.flatnonzero((size > 1e-290) & (size < 1e290) & ~((flat == np.round(flat)) & (size < 2.0 ** 53)))
    if not todo.size:
        return out
    w = flat[todo]
    half = 0.5 * np.spacing(np.abs(w))
    e = np.floor(np.log10(np.abs(w))).astype(int)
    for digits in range(1, DECIMAL_DIGITS + 1):
        q = e - digits + 1
        ph, pl = _pow10(q)
        m = np.rint(w / ph)  # the mantissa (|m| < 10^16, exact)
        dh, dl = _two_prod(m, ph)
        dh, dl = _quick_two_sum(dh, dl + m * pl)
        ch, _ = _dd_add(dh, dl, -w, np.zeros_like(w))
        ok = np.abs(ch) <= half  # a tie (10^23) reads back by rounding to even
        res[todo[ok]] = ch[ok]
        keep = ~ok
        todo, w, half, e = todo[keep], w[keep], half[keep], e[keep]
        if not todo.size:
            break
    return out


# ----------------------------------------------------------------------------------------
# the model's columns and the change of basis
# ----------------------------------------------------------------------------------------
def _is_intercept(t: Term) -> bool:
    return not t.cat and not any(t.powers)


def _model_terms(terms: Sequence[Term], intercept: bool) -> list[Term]:
    """The terms without the intercept (it is the ``intercept`` flag), checked."""
    rest = [t for t in terms if not _is_intercept(t)]
    if not intercept and len(rest) < len(terms):
        raise ValueError("the terms include the intercept but intercept=False")
    if not rest and not intercept:
        raise ValueError("a model needs at least one term")
    ks = {len(t.powers) for t in terms}
    if len(ks) > 1:
        raise ValueError("the terms are not in the same factors")
    return rest


def _term_key(t: Term) -> tuple[tuple[int, ...], tuple[int, ...]]:
    return t.numeric_powers, tuple(i for i, _ in t.cat)


def shiftable_factors(terms: Sequence[Term], *, intercept: bool = True) -> tuple[bool, ...]:
    """For each factor, whether shifting it (``x -> x - c``) maps the span of the model's
    columns onto itself: every term holding the factor to a power ``e`` has the terms with
    the same other exponents and each lower power ``0 .. e-1`` of it (the intercept for a pure
    power, the categoric term ``E`` for ``AE``). A factor in no term is shiftable.

    >>> from rsm_lrg.terms import parse_term
    >>> shiftable_factors([parse_term(t, "AB") for t in ("A", "B", "A^2", "AB")])
    (True, True)
    >>> shiftable_factors([parse_term(t, "AB") for t in ("A", "A^2B")]), shiftable_factors([parse_term("A", "A")], intercept=False)
    ((False, False), (False,))
    """
    return _shiftable(tuple(terms), bool(intercept))


@lru_cache(maxsize=256)
def _shiftable(terms: tuple[Term, ...], intercept: bool) -> tuple[bool, ...]:
    """:func:`shiftable_factors` of a tuple of terms (remembered: a fit and its actual-units
    solve ask twice)."""
    rest = _model_terms(terms, intercept)
    if not terms:
        return ()
    k = len(terms[0].powers)
    present = {_term_key(t) for t in rest}
    if intercept:
        present.add(((0,) * k, ()))
    out = []
    for f in range(k):
        ok = True
        for npw, cats in present:
            for m in range(npw[f]):
                lower = npw[:f] + (m,) + npw[f + 1:]
                if (lower, cats) not in present:
                    ok = False
        out.append(ok)
    return tuple(out)


def is_closed_under_shift(terms: Sequence[Term], *, intercept: bool = True) -> bool:
    """Whether the coded model (every factor centred and scaled) and the actual-units model
    with these terms are the same model (:func:`shiftable_factors` for every factor): then
    :func:`solve_actual` gives the coded fit's polynomial in actual units; otherwise the
    coded fit's actual-unit polynomial has other monomials (the exact expansion) and
    :func:`solve_actual` fits the terms as given in actual units (a different model).

    >>> from rsm_lrg.terms import model_terms, parse_term
    >>> is_closed_under_shift(model_terms("ABC", "quadratic")), is_closed_under_shift([parse_term("A^2", "A")])
    (True, False)
    """
    return all(shiftable_factors(terms, intercept=intercept))


@dataclass(frozen=True)
class _Layout:
    """The model's columns: intercept, block contrasts, then each term's columns."""

    k: int
    intercept: bool
    n_blocks: int
    terms: tuple[Term, ...]
    names: tuple[str, ...]
    keys: tuple[tuple, ...]  # ("t", numeric powers, ((factor, level index), ...)) or ("b", j)

    @property
    def p(self) -> int:
        return len(self.keys)


def _layout(terms: Sequence[Term], intercept: bool, n_blocks: int, block_names: Sequence[str] | None) -> _Layout:
    rest = _model_terms(terms, intercept)
    k = len(terms[0].powers) if terms else 0
    if n_blocks > 1 and not intercept:
        raise ValueError("block effects (sum-to-zero contrasts) need the intercept")
    names: list[str] = []
    keys: list[tuple] = []
    if intercept:
        names.append("Intercept")
        keys.append(("t", (0,) * k, ()))
    if n_blocks > 1:
        bn = list(block_names) if block_names is not None else [f"Block[{j + 1}]" for j in range(n_blocks - 1)]
        if len(bn) != n_blocks - 1:
            raise ValueError(f"{len(bn)} block names for {n_blocks - 1} block contrasts")
        names += bn
        keys += [("b", j) for j in range(n_blocks - 1)]
    for t in rest:
        for combo, col in zip(t.level_combinations() if t.cat else [()], t.columns):
            names.append(col)
            keys.append(("t", t.numeric_powers, tuple((i, j) for (i, _), j in zip(t.cat, combo))))
    if len(set(keys)) != len(keys):
        raise ValueError("a term is listed twice")
    return _Layout(k=k, intercept=intercept, n_blocks=n_blocks, terms=tuple(rest), names=tuple(names),
                   keys=tuple(keys))


def _monomial_name(pw: tuple[int, ...], sig: tuple[tuple[int, int], ...], letters: Sequence[str],
                   levels: dict[int, tuple[str, ...]]) -> str:
    """Column name of the monomial with numeric exponents ``pw`` times the effect codes
    ``sig`` (``(factor, level index)``), as :attr:`Term.columns` names it (``"AE[rms]"``)."""
    powers = list(pw)
    for f, _ in sig:
        powers[f] = 1
    name = term_name(powers, letters)
    if not sig:
        return name
    t = Term(tuple(powers), name, tuple((f, levels[f]) for f, _ in sig), tuple(letters[f] for f, _ in sig))
    return t.columns[t.level_combinations().index(tuple(lj for _, lj in sig))]


def _basis_change(lay: _Layout, centre: np.ndarray, scale: np.ndarray,
                  letters: Sequence[str]) -> tuple[np.ndarray, np.ndarray, tuple[str, ...]]:
    """``M`` (q x p, double-double of the exact rationals) with ``Z = X M``: column ``j`` of
    ``M`` expands the coded monomial ``prod ((x_f - c_f) / h_f)^e_f`` of column ``j`` into
    actual monomials (binomial theorem); block contrasts and categoric codes are unchanged.
    The rows are the model's columns, then (``q > p`` only for a term list not closed under
    the shift) the monomials the expansion adds, named as columns are (third value)."""
    index = {key: i for i, key in enumerate(lay.keys)}
    extra: list[tuple] = []
    # exact rationals as (numerator, denominator) pairs of integers, not reduced (Fraction's
    # gcd at every step costs more than the whole rest): a double c is cn / cd exactly
    entries: list[tuple[tuple, int, int, int]] = []
    cs = [float(c).as_integer_ratio() for c in centre]
    hs = [float(h).as_integer_ratio() for h in scale]
    powers: dict[tuple[int, int], list[tuple[int, int, int]]] = {}

    def expand(f: int, e: int) -> list[tuple[int, int, int]]:
        """``((x - c_f) / h_f)^e`` as ``[(m, num, den)]``: the coefficient of ``x^m``."""
        if (f, e) not in powers:
            (cn, cd), (hn, hd) = cs[f], hs[f]
            lows = range(e + 1) if cn != 0 else (e,)
            powers[(f, e)] = [(m, comb(e, m) * (-cn) ** (e - m) * hd ** e, cd ** (e - m) * hn ** e) for m in lows]
        return powers[(f, e)]

    for j, key in enumerate(lay.keys):
        if key[0] == "b":
            entries.append((key, j, 1, 1))
            continue
        _, npw, sig = key
        parts: list[tuple[tuple[int, ...], int, int]] = [((), 1, 1)]
        for f, e in enumerate(npw):
            if not e:
                parts = [(pw + (0,), num, den) for pw, num, den in parts]
                continue
            parts = [(pw + (m,), num * a, den * b) for pw, num, den in parts for m, a, b in expand(f, e)]
        for pw, num, den in parts:
            k = ("t", pw, sig)
            if k not in index and k not in extra:
                extra.append(k)
            entries.append((k, j, num, den))
    extra.sort(key=lambda k: (sum(k[1]), len(k[2]), [-e for e in k[1]], k[2]))
    for k in extra:
        index[k] = len(index)
    q, p = len(index), lay.p
    Mh = np.zeros((q, p))
    Ml = np.zeros((q, p))
    acc: dict[tuple[int, int], tuple[int, int]] = {}
    for k, j, num, den in entries:
        at = (index[k], j)
        if at in acc:
            n0, d0 = acc[at]
            num, den = n0 * den + num * d0, d0 * den
        acc[at] = (num, den)
    for (i, j), (num, den) in acc.items():
        if den < 0:
            num, den = -num, -den
        hi = num / den  # correctly rounded (as float(Fraction(num, den)))
        a, b = hi.as_integer_ratio()
        Mh[i, j] = hi
        Ml[i, j] = (num * b - a * den) / (den * b)
    levels = {f: lv for t in lay.terms for f, lv in t.cat}
    return Mh, Ml, tuple(_monomial_name(k[1], k[2], letters, levels) for k in extra)


def _rows(lay: _Layout, xh: np.ndarray, xl: np.ndarray, blocks: np.ndarray | None, centre: np.ndarray,
          scale: np.ndarray, numeric: np.ndarray) -> _DD:
    """Rows of ``Z`` (m x p) in double-double: the model's columns at ``(x - centre) / scale``
    (numeric factors; categoric ones hold level indices and enter by their effect codes)."""
    m = xh.shape[0]
    Zh = np.empty((m, lay.p))
    Zl = np.zeros((m, lay.p))
    coded: dict[int, _DD] = {}
    powers: dict[tuple[int, int], _DD] = {}
    codes: dict[int, np.ndarray] = {}

    def coded_col(f: int) -> _DD:
        if f not in coded:
            s, e = _two_sum(xh[:, f], np.full(m, -centre[f]))
            s, e = _quick_two_sum(s, e + xl[:, f])
            coded[f] = _dd_div(s, e, float(scale[f]))
        return coded[f]

    def power(f: int, e: int) -> _DD:
        if e == 1:
            return coded_col(f)
        if (f, e) not in powers:
            h1, l1 = power(f, e // 2)
            h2, l2 = power(f, e - e // 2)
            powers[(f, e)] = _dd_mul(h1, l1, h2, l2)
        return powers[(f, e)]

    levels = {i: len(lv) for t in lay.terms for i, lv in t.cat}

    def effect(f: int) -> np.ndarray:
        if f not in codes:
            col = xh[:, f]
            idx = np.rint(col)
            if not (np.all(idx == col) and np.all((idx >= 0) & (idx < levels[f]))):
                raise ValueError(f"a categoric factor's value must be a level index 0..{levels[f] - 1} "
                                 f"(factor {f})")
            codes[f] = effect_codes(idx.astype(int), levels[f])
        return codes[f]

    bcodes = None
    if lay.n_blocks > 1:
        if blocks is None:
            raise ValueError(f"{lay.n_blocks} blocks but no block codes")
        b = np.asarray(blocks)
        if b.shape != (m,) or not np.all((b >= 0) & (b < lay.n_blocks) & (b == np.rint(b))):
            raise ValueError(f"block codes must be integers 0..{lay.n_blocks - 1}, one per row")
        bcodes = effect_codes(b.astype(int), lay.n_blocks)
    for j, key in enumerate(lay.keys):
        if key[0] == "b":
            assert bcodes is not None
            Zh[:, j] = bcodes[:, key[1]]
            continue
        _, npw, sig = key
        h, lo = np.ones(m), np.zeros(m)
        first = True
        for f, e in enumerate(npw):
            if e:
                if not numeric[f]:
                    raise ValueError(f"factor {f} is categoric and has no powers")
                ph, pl = power(f, e)
                h, lo = (ph, pl) if first else _dd_mul(h, lo, ph, pl)
                first = False
        for f, lj in sig:
            c = effect(f)[:, lj]
            h, lo = h * c, lo * c
        Zh[:, j] = h
        Zl[:, j] = lo
    return Zh, Zl


# ----------------------------------------------------------------------------------------
# the result
# ----------------------------------------------------------------------------------------
@dataclass(frozen=True)
class ActualSolution:
    """Least-squares fit of a model in actual units (:func:`solve_actual`; frozen).

    Attributes
    ----------
    names : tuple of str
        Column names in model order (``"Intercept"``, block contrasts, the terms' columns).
    extra : tuple of str
        The actual-unit monomials beyond the model's columns that a model defined in coded
        units (``basis="coded"``) and not closed under the shift has (``"A"`` for the coded
        ``A^2`` alone); empty otherwise.
    coefficients : dict
        ``{name: coefficient}`` in actual units for ``names`` and ``extra`` [response units /
        actual units^degree].
    std_errors : dict
        ``{name: standard error}`` in the same units (``sigma * sqrt(cov_jj)``, ``cov`` the
        covariance of the coefficients, ``M (Z'Z)^-1 M'`` with ``Z = X M``).
    coded_coefficients, coded_std_errors : dict
        The same fit in the basis ``(x - centre) / scale`` [response units].
    centre, scale : tuple of float
        The basis the solve ran in (per factor; ``centre`` 0 for a factor that cannot be
        shifted, see :func:`shiftable_factors`; categoric factors 0 and 1) [actual units].
    sigma : float
        Residual standard deviation ``sqrt(RSS / (n - p))`` (NaN without residual degrees
        of freedom) [response units].
    rss : float
        Residual sum of squares [response units^2].
    n, df_resid : int
    iterations : int
        Refinement steps of the coefficients.
    converged : bool
        The refinement reached the double-double floor (False: the basis was too ill
        conditioned, ``kappa(Z)^2 u >~ 1``; the result is then that of the last step).
    """

    names: tuple[str, ...]
    extra: tuple[str, ...]
    coefficients: dict[str, float]
    std_errors: dict[str, float]
    coded_coefficients: dict[str, float]
    coded_std_errors: dict[str, float]
    centre: tuple[float, ...]
    scale: tuple[float, ...]
    sigma: float
    rss: float
    n: int
    df_resid: int
    iterations: int
    converged: bool


class DeferredActual:
    """The solve of :func:`solve_actual_deferred` before the change of basis: the coefficients
    in the basis ``Z``, the residual sum of squares and standard deviation (what a fit's
    statistics need) are computed; the coefficients and standard errors in actual units,
    :meth:`solution`, on the first call (the exact change of basis and ``M (Z'Z)^-1 M'``). When
    the coefficients' refinement met its strict criterion (the last correction at most
    ``2^-104`` of them: the double-double floor) the inverse ``(Z'Z)^-1`` is refined then too
    (with the double-double Cholesky factor if the double one does not converge, as the whole
    solve does); the coefficients cannot move by more than that floor whatever preconditioner
    refines them, so they are kept.

    Attributes
    ----------
    rss : float
        Residual sum of squares [response units^2].
    sigma : float
        Residual standard deviation (NaN without residual degrees of freedom) [response units].
    n, df_resid : int
    iterations : int
        Refinement steps of the coefficients.
    converged : bool
        The coefficients' refinement converged (:attr:`ActualSolution.converged` also asks it
        of the inverse).
    """

    def __init__(self, *, rss: float, sigma: float, n: int, df_resid: int, iterations: int, converged: bool,
                 finish: Callable[[], ActualSolution]) -> None:
        self.rss, self.sigma, self.n, self.df_resid = rss, sigma, n, df_resid
        self.iterations, self.converged = iterations, converged
        self._finish: Callable[[], ActualSolution] | None = finish
        self._solution: ActualSolution | None = None
        self._error: str | None = None

    def solution(self) -> ActualSolution:
        """The whole solution (computed once).

        Returns
        -------
        ActualSolution

        Raises
        ------
        ValueError
            The inverse cannot be formed (the columns are dependent to double-double precision).
        """
        if self._solution is None:
            if self._finish is None:
                raise ValueError(self._error or "the actual-units solution was not kept")
            self._solution, self._finish = self._finish(), None
        return self._solution

    def __getstate__(self) -> dict:
        # the rest of the solve is a closure over the Gram matrix: finished before pickling (a fit
        # sent to a worker process), so that what travels is the solution itself
        try:
            self.solution()
        except ValueError as exc:
            self._finish, self._error = None, str(exc)
        return {k: v for k, v in self.__dict__.items() if k != "_finish"} | {"_finish": None}


def _refine_solve(Gh: np.ndarray, Gl: np.ndarray, bh: np.ndarray, bl: np.ndarray,
                  P: Callable[[np.ndarray], np.ndarray], max_iter: int = 40) -> tuple[_DD, int, bool, bool]:
    """Solve ``G x = b`` (double-double ``G``, ``b``) by iterative refinement with the
    approximate inverse ``P`` (a function of a vector or matrix): ``x <- x + P (b - G x)``,
    the residual in double-double. Returns the solution, the steps, whether it converged and
    whether it did so strictly (the last correction at most ``2^-104`` of the solution; else
    the corrections stalled, below ``2^-60`` of it when converged)."""
    p = Gh.shape[0]
    w = np.sqrt(np.abs(np.diag(Gh)))
    xh, xl = np.zeros(p), np.zeros(p)
    prev = math.inf
    stalled = 0
    sg = _left_slices(Gh) if Gh.shape[1] <= _MAX_INNER else None
    for it in range(1, max_iter + 1):
        gh, gl = _dd_matmul(Gh, Gl, xh[:, None], xl[:, None], sg)
        rh, _ = _dd_add(bh, bl, -gh[:, 0], -gl[:, 0])
        d = P(rh)
        xh, xl = _dd_add(xh, xl, d, np.zeros(p))
        size = float(np.max(w * np.abs(d)))
        whole = float(np.max(w * np.abs(xh)))
        if size <= 2.0 ** -104 * whole:
            return (xh, xl), it, True, True
        # at the double-double floor the corrections stop shrinking: done when they are far
        # below what the double result can show
        stalled = stalled + 1 if size > 0.25 * prev else 0
        if stalled >= 2:
            return (xh, xl), it, size <= 2.0 ** -60 * whole, False
        prev = size
    return (xh, xl), max_iter, False, False


def _refine_inverse(Gh: np.ndarray, Gl: np.ndarray, P: Callable[[np.ndarray], np.ndarray], start: _DD,
                    max_iter: int = 40) -> tuple[_DD, bool]:
    """``G^-1`` in double-double by ``C <- C + P (I - G C)`` from ``C = start``."""
    p = Gh.shape[0]
    ch, cl = start[0].copy(), start[1].copy()
    eye = np.eye(p)
    zero = np.zeros((p, p))
    prev = math.inf
    stalled = 0
    sg = _left_slices(Gh) if Gh.shape[1] <= _MAX_INNER else None
    for _ in range(max_iter):
        gh, gl = _dd_matmul(Gh, Gl, ch, cl, sg)
        eh, _ = _dd_add(eye, zero, -gh, -gl)
        d = P(eh)
        ch, cl = _dd_add(ch, cl, d, zero)
        # relative to the diagonal (sqrt(C_ii C_jj) bounds |C_ij|)
        s = np.sqrt(np.abs(np.diag(ch)))
        s = np.where(s > 0, s, 1.0)
        size = float(np.max(np.abs(d) / np.outer(s, s)))
        if size <= 2.0 ** -104:
            return (ch, cl), True
        stalled = stalled + 1 if size > 0.25 * prev else 0
        if stalled >= 2:
            return (ch, cl), size <= 2.0 ** -60
        prev = size
    return (ch, cl), False


def _dd_sqrt(ah: np.ndarray, al: np.ndarray) -> _DD:
    x = np.sqrt(ah)
    p, e = _two_prod(x, x)
    return _quick_two_sum(x, ((ah - p) - e + al) / (2.0 * x))


def _dd_div_dd(ah: np.ndarray, al: np.ndarray, bh: np.ndarray, bl: np.ndarray) -> _DD:
    q = ah / bh
    ph, pl = _dd_mul(q, np.zeros_like(q), bh, bl)
    rh, _ = _dd_add(ah, al, -ph, -pl)
    return _quick_two_sum(q, rh / bh)


def _dd_inverse_spd(Gh: np.ndarray, Gl: np.ndarray, names: Sequence[str]) -> _DD:
    """``G^-1`` of a symmetric positive definite double-double matrix (p x p) from its
    Cholesky factor computed in double-double (column by column, the dot products exact by
    :func:`_dd_matmul`); for a Gram matrix too ill conditioned for a double-precision
    factor (kappa^2 u >~ 1). Raises ``ValueError`` (naming the column) when a pivot is not
    positive: the columns are linearly dependent to double-double precision."""
    p = Gh.shape[0]
    Lh, Ll = np.zeros((p, p)), np.zeros((p, p))
    for j in range(p):
        sh, sl = Gh[j:, j].copy(), Gl[j:, j].copy()
        if j:
            th, tl = _dd_matmul(Lh[j:, :j], Ll[j:, :j], Lh[j, :j][:, None], Ll[j, :j][:, None])
            sh, sl = _dd_add(sh, sl, -th[:, 0], -tl[:, 0])
        if not sh[0] > 2.0 ** -100 * Gh[j, j]:
            raise ValueError(f"the model matrix does not have full rank: column {names[j]} is a linear "
                             "combination of the columns before it")
        rh, rl = _dd_sqrt(sh[:1], sl[:1])
        Lh[j, j], Ll[j, j] = rh[0], rl[0]
        if j + 1 < p:
            qh, ql = _dd_div_dd(sh[1:], sl[1:], np.full(p - j - 1, rh[0]), np.full(p - j - 1, rl[0]))
            Lh[j + 1:, j], Ll[j + 1:, j] = qh, ql
    # X = L^-1 by forward substitution, row by row
    Xh, Xl = np.zeros((p, p)), np.zeros((p, p))
    for i in range(p):
        eh, el = np.zeros(p), np.zeros(p)
        eh[i] = 1.0
        if i:
            th, tl = _dd_matmul(Lh[i:i + 1, :i], Ll[i:i + 1, :i], Xh[:i], Xl[:i])
            eh, el = _dd_add(eh, el, -th[0], -tl[0])
        Xh[i], Xl[i] = _dd_div_dd(eh, el, np.full(p, Lh[i, i]), np.full(p, Ll[i, i]))
    return _dd_matmul(np.ascontiguousarray(Xh.T), np.ascontiguousarray(Xl.T), Xh, Xl)


def _split_chunk(x: np.ndarray, rows: int) -> list[slice]:
    return [slice(s, s + rows) for s in range(0, max(x.shape[0], 1), rows)]


def solve_actual(x_actual: np.ndarray, y: np.ndarray, terms: Sequence[Term], *, intercept: bool = True,
                 blocks: np.ndarray | None = None, n_blocks: int = 1, chunk_rows: int = CHUNK_ROWS,
                 decimal_inputs: bool = True, centre: Sequence[float] | None = None,
                 scale: Sequence[float] | None = None, block_names: Sequence[str] | None = None,
                 basis: str = "actual", letters: Sequence[str] | None = None) -> ActualSolution:
    """:func:`solve_actual_deferred` (the same parameters) carried through the change of basis:
    the whole :class:`ActualSolution`.

    Parameters
    ----------
    x_actual, y, terms, intercept, blocks, n_blocks, chunk_rows, decimal_inputs, centre, scale, block_names, basis, letters
        As for :func:`solve_actual_deferred`.

    Returns
    -------
    ActualSolution

    Raises
    ------
    ValueError
        As :func:`solve_actual_deferred`.
    """
    return solve_actual_deferred(x_actual, y, terms, intercept=intercept, blocks=blocks, n_blocks=n_blocks,
                                 chunk_rows=chunk_rows, decimal_inputs=decimal_inputs, centre=centre, scale=scale,
                                 block_names=block_names, basis=basis, letters=letters).solution()


def solve_actual_deferred(x_actual: np.ndarray, y: np.ndarray, terms: Sequence[Term], *, intercept: bool = True,
                          blocks: np.ndarray | None = None, n_blocks: int = 1, chunk_rows: int = CHUNK_ROWS,
                          decimal_inputs: bool = True, centre: Sequence[float] | None = None,
                          scale: Sequence[float] | None = None, block_names: Sequence[str] | None = None,
                          basis: str = "actual", letters: Sequence[str] | None = None) -> DeferredActual:
    """Least squares of ``y`` on the model's columns evaluated at the actual (uncoded) factor
    values, to the accuracy of the data (see the module docstring).

    Parameters
    ----------
    x_actual : (n, k) ndarray
        Factor values in actual units; a categoric factor holds its level index 0 .. L-1.
    y : (n,) ndarray
        Response [response units].
    terms : sequence of Term
        The model's terms (:func:`rsm_lrg.terms.parse_term`, any degree: ``A^10``); an
        intercept term, if listed, must agree with ``intercept``.
    intercept : bool
        Whether the model has an intercept (with ``False`` the model is the one in actual
        units; see the module docstring).
    blocks : (n,) int ndarray, optional
        Block codes 0 .. ``n_blocks - 1`` (sum-to-zero contrasts after the intercept, as
        :func:`rsm_lrg.terms.model_matrix` builds them).
    n_blocks : int
    chunk_rows : int
        Rows of the model matrix built at a time (the n x p matrix is never held).
    decimal_inputs : bool
        Take each value as the shortest decimal that reads back as its double (the number as
        written in a file; :func:`decimal_correction`). ``False``: the doubles themselves.
    centre, scale : sequence of float, optional
        The basis ``(x - centre) / scale`` the solve runs in (e.g. the design's coding, so that
        ``coded_coefficients`` are the coded fit's); default the data's mid-range and
        half-range. A factor that cannot be shifted (:func:`shiftable_factors`) gets centre 0.
    block_names : sequence of str, optional
        Names of the ``n_blocks - 1`` block contrasts (default ``Block[1]`` ...).
    basis : {"actual", "coded"}
        What the terms are monomials of. ``"actual"``: the actual values (the model as given
        in actual units; a factor that cannot be shifted is only scaled). ``"coded"``: the
        coded values ``(x - centre) / scale`` (the coded fit's model, whatever the term
        list; its actual-unit polynomial may have monomials beyond the terms, ``extra``).
        The two are the same model when :func:`is_closed_under_shift` holds.
    letters : sequence of str, optional
        Factor letters for the names of ``extra`` monomials (default A, B, ... without I).

    Returns
    -------
    DeferredActual
        The residual sum of squares and standard deviation now; the coefficients and standard
        errors in actual units (the change of basis) when :meth:`DeferredActual.solution` is
        called (a summary needs only the first).

    Raises
    ------
    ValueError
        Shapes that do not match, non-finite values, fewer runs than columns, a model matrix
        without full rank (its Gram matrix not positive definite), bad level or block codes.
    """
    x = np.asarray(x_actual, dtype=float)
    yv = np.asarray(y, dtype=float).ravel()
    if x.ndim == 1:
        x = x[:, None]
    if x.ndim != 2 or x.shape[0] != yv.size:
        raise ValueError(f"x ({x.shape}) and y ({yv.size}) do not match")
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(yv))):
        raise ValueError("x and y must be finite")
    b = None if blocks is None else np.asarray(blocks).ravel()
    if b is not None and b.size != yv.size:
        raise ValueError(f"{b.size} block codes for {yv.size} rows")
    rows = max(1, int(chunk_rows))
    sl = _split_chunk(x, rows)
    xl_all = decimal_correction(x) if decimal_inputs else None
    yl_all = decimal_correction(yv) if decimal_inputs else None

    def chunks() -> Iterable[tuple[np.ndarray, np.ndarray, np.ndarray | None, np.ndarray | None, np.ndarray | None]]:
        for s in sl:
            yield (x[s], yv[s], None if b is None else b[s], None if xl_all is None else xl_all[s],
                   None if yl_all is None else yl_all[s])

    return _solve(chunks, terms, intercept=intercept, n_blocks=n_blocks, decimal_inputs=decimal_inputs,
                  centre=centre, scale=scale, block_names=block_names, k=x.shape[1], basis=basis, letters=letters)


def solve_actual_chunks(chunks: Chunks, terms: Sequence[Term], *, intercept: bool = True, n_blocks: int = 1,
                        decimal_inputs: bool = True, centre: Sequence[float] | None = None,
                        scale: Sequence[float] | None = None, block_names: Sequence[str] | None = None,
                        basis: str = "actual", letters: Sequence[str] | None = None) -> ActualSolution:
    """:func:`solve_actual` (same options) over chunks of rows: ``chunks()`` yields ``(x, y,
    block codes or None)`` and is iterated two or three times (range of the factors unless ``centre`` and
    ``scale`` are given, the Gram matrix, the residuals), e.g. over the partitions of a Dask
    DataFrame."""
    def wrapped() -> Iterable[tuple[np.ndarray, np.ndarray, np.ndarray | None, np.ndarray | None, np.ndarray | None]]:
        for xc, yc, bc in chunks():
            xa = np.asarray(xc, dtype=float)
            xa = xa[:, None] if xa.ndim == 1 else xa
            ya = np.asarray(yc, dtype=float).ravel()
            yield xa, ya, bc, None, None

    return _solve(wrapped, terms, intercept=intercept, n_blocks=n_blocks, decimal_inputs=decimal_inputs,
                  centre=centre, scale=scale, block_names=block_names, k=None, basis=basis,
                  letters=letters).solution()


def _solve(chunks: Callable[[], Iterable[tuple[np.ndarray, np.ndarray, np.ndarray | None, np.ndarray | None,
                                                  np.ndarray | None]]],
           terms: Sequence[Term], *, intercept: bool, n_blocks: int, decimal_inputs: bool,
           centre: Sequence[float] | None, scale: Sequence[float] | None, block_names: Sequence[str] | None,
           k: int | None, basis: str, letters: Sequence[str] | None) -> DeferredActual:
    if basis not in ("actual", "coded"):
        raise ValueError(f"basis must be 'actual' or 'coded', not {basis!r}")
    if not terms and not intercept:
        raise ValueError("a model needs at least one term")
    lay = _layout(terms, intercept, int(n_blocks), block_names)
    if k is not None and lay.k and k != lay.k:
        raise ValueError(f"the terms are in {lay.k} factors but x has {k} columns")
    kf = lay.k if lay.k else (k or 0)
    cat = {i for t in lay.terms for i, _ in t.cat}
    numeric = np.array([f not in cat for f in range(kf)], dtype=bool)
    shift = shiftable_factors(terms, intercept=intercept) if terms else (True,) * kf
    if basis == "coded":
        shift = (True,) * kf  # the model is defined in the coded values: centre every factor

    # the basis: data mid-range and half-range unless given
    lo = np.full(kf, np.inf)
    hi = np.full(kf, -np.inf)
    if centre is None or scale is None or not all(shift):
        for xc, *_ in chunks():
            if xc.shape[1] != kf:
                raise ValueError(f"the terms are in {kf} factors but x has {xc.shape[1]} columns")
            if not np.all(np.isfinite(xc)):
                raise ValueError("x and y must be finite")
            if xc.shape[0]:
                lo = np.minimum(lo, xc.min(axis=0))
                hi = np.maximum(hi, xc.max(axis=0))
    seen = np.isfinite(lo)
    lo, hi = np.where(seen, lo, 0.0), np.where(seen, hi, 0.0)
    mid = lo + (hi - lo) / 2
    half = np.where(seen, (hi - lo) / 2, 1.0)
    big = np.where(seen, np.maximum(np.abs(lo), np.abs(hi)), 1.0)
    c = np.array([float(v) for v in centre], dtype=float) if centre is not None else mid
    h = np.array([float(v) for v in scale], dtype=float) if scale is not None else half
    if c.shape != (kf,) or h.shape != (kf,):
        raise ValueError(f"centre and scale need one value per factor ({kf})")
    for f in range(kf):
        if not numeric[f]:
            c[f], h[f] = 0.0, 1.0
        elif not shift[f]:
            c[f] = 0.0
            if scale is None:
                h[f] = big[f]
        if h[f] == 0.0 and scale is None:
            h[f] = 1.0  # a constant factor: any scale (its columns are then collinear with others)
        if not (np.isfinite(c[f]) and np.isfinite(h[f]) and h[f] > 0):
            raise ValueError(f"factor {f}: centre {c[f]} and scale {h[f]} do not define a coding")

    p = lay.p
    # pass 1: [Z y]' [Z y] exactly (double-double), chunk by chunk
    Gh = np.zeros((p + 1, p + 1))
    Gl = np.zeros((p + 1, p + 1))
    n = 0

    def model_rows(xc: np.ndarray, yc: np.ndarray, bc: np.ndarray | None, xlc: np.ndarray | None,
                   ylc: np.ndarray | None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """A chunk's model rows in double-double and the low part of its responses (the
        decimal corrections of the values as written, or zero), for both passes."""
        if decimal_inputs and xlc is None:
            xlc, ylc = decimal_correction(xc), decimal_correction(yc)
        xlc = np.zeros_like(xc) if xlc is None else xlc
        ylc = np.zeros_like(yc) if ylc is None else ylc
        Zh, Zl = _rows(lay, xc, xlc, bc, c, h, numeric)
        return Zh, Zl, ylc

    kept: list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]] | None = []  # one chunk: its rows for pass 2
    for xc, yc, bc, xlc, ylc in chunks():
        if xc.shape[1] != kf or yc.size != xc.shape[0]:
            raise ValueError(f"a chunk of {xc.shape} factor values and {yc.size} responses does not fit")
        if not (np.all(np.isfinite(xc)) and np.all(np.isfinite(yc))):
            raise ValueError("x and y must be finite")
        if not xc.shape[0]:
            continue
        Zh, Zl, ylc = model_rows(xc, yc, bc, xlc, ylc)
        kept = [(yc, Zh, Zl, ylc)] if kept == [] else None
        Ah = np.column_stack([Zh, yc])
        Al = np.column_stack([Zl, ylc])
        for s in range(0, Ah.shape[0], _MAX_INNER):
            th, tl = _gram(Ah[s:s + _MAX_INNER], Al[s:s + _MAX_INNER])
            Gh, Gl = _dd_add(Gh, Gl, th, tl)
        n += xc.shape[0]
    if n < p:
        raise ValueError(f"{n} runs cannot fit {p} coefficients")

    # the normal equations of Z, refined; the preconditioner from the equilibrated Cholesky factor
    Zh_, Zl_ = Gh[:p, :p], Gl[:p, :p]
    bh, bl = Gh[:p, p], Gl[:p, p]
    diag = np.diag(Zh_)
    if not np.all(diag > 0):
        zero_cols = [lay.names[j] for j in range(p) if not diag[j] > 0]
        raise ValueError(f"the model matrix has a zero column: {', '.join(zero_cols)}")
    d = 1.0 / np.sqrt(diag)
    Gs = (Zh_ * d[:, None]) * d[None, :]
    zero_p = np.zeros((p, p))
    conv = strict = False
    P0: np.ndarray | None = None
    try:
        Linv = np.linalg.inv(np.linalg.cholesky(Gs))
        P0 = (Linv.T @ Linv) * d[:, None] * d[None, :]
    except np.linalg.LinAlgError:
        pass

    def fallback() -> tuple[Callable[[np.ndarray], np.ndarray], _DD]:
        """kappa(Z)^2 u >~ 1: the preconditioner from a Cholesky factor in double-double."""
        d2 = np.exp2(np.round(np.log2(d)))  # powers of two: the scaling stays exact
        D = d2[:, None] * d2[None, :]
        Ph, Pl = _dd_inverse_spd(Zh_ * D, Zl_ * D, lay.names)
        Ph, Pl = Ph * D, Pl * D

        def apply(r: np.ndarray) -> np.ndarray:
            r2 = r[:, None] if r.ndim == 1 else r
            out, _ = _dd_matmul(Ph, Pl, r2, np.zeros_like(r2))
            return out[:, 0] if r.ndim == 1 else out

        return apply, (Ph, Pl)

    if P0 is not None:
        P0_ = P0
        (zh, zl), iters, conv, strict = _refine_solve(Zh_, Zl_, bh, bl, lambda r: P0_ @ r)
    if conv and strict:
        # the coefficients are at the double-double floor (the last correction below 2^-104 of
        # them): no other preconditioner would move them, so the inverse (the standard errors)
        # waits for the change of basis, which a fit's statistics do not need
        def inverse() -> tuple[np.ndarray, np.ndarray, bool]:
            (ch, cl), conv_c = _refine_inverse(Zh_, Zl_, lambda r: P0_ @ r, (P0_, zero_p))
            if not conv_c:
                apply, start = fallback()
                (ch, cl), conv_c = _refine_inverse(Zh_, Zl_, apply, start)
            return ch, cl, conv_c
    else:
        conv_c = False
        if P0 is not None:
            (ch, cl), conv_c = _refine_inverse(Zh_, Zl_, lambda r: P0_ @ r, (P0_, zero_p))
        if not (conv and conv_c):
            apply, start = fallback()
            (zh, zl), iters, conv, _ = _refine_solve(Zh_, Zl_, bh, bl, apply)
            (ch, cl), conv_c = _refine_inverse(Zh_, Zl_, apply, start)
        done = (ch, cl, conv_c)

        def inverse() -> tuple[np.ndarray, np.ndarray, bool]:
            return done

    # pass 2: the residuals in double-double
    rss_parts: list[float] = []
    def pass_rows() -> Iterable[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]:
        if kept:  # the one chunk's rows, already built
            yield from kept
            return
        for xc, yc, bc, xlc, ylc in chunks():
            if xc.shape[0]:
                yield (yc, *model_rows(xc, yc, bc, xlc, ylc))

    for yc, Zh, Zl, ylc in pass_rows():
        fh, fl = _dd_matmul(Zh, Zl, zh[:, None], zl[:, None])
        rh, rl = _dd_add(yc, ylc, -fh[:, 0], -fl[:, 0])
        rss_parts.append(float(np.sum(rh * rh)) + 2.0 * float(np.sum(rh * rl)))
    rss = max(math.fsum(rss_parts), 0.0)
    df = n - p
    sigma = math.sqrt(rss / df) if df > 0 else math.nan

    def finish() -> ActualSolution:
        ch, cl, conv_c = inverse()
        # back to actual units: b = M z, cov = M C M'
        Mh, Ml, extra = _basis_change(lay, c, h, letters_for(kf) if letters is None else list(letters))
        ah, _ = _dd_matmul(Mh, Ml, zh[:, None], zl[:, None])
        mch, mcl = _dd_matmul(Mh, Ml, ch, cl)
        vh, vl = _dd_mul(mch, mcl, Mh, Ml)
        var_a, _ = _dd_sum_rows(vh, vl)
        var_z = np.diag(ch)
        se_a = sigma * np.sqrt(np.maximum(var_a, 0.0))
        se_z = sigma * np.sqrt(np.maximum(var_z, 0.0))
        names = lay.names
        return ActualSolution(
            names=names, extra=extra,
            coefficients={nm: float(v) for nm, v in zip(names + extra, ah[:, 0])},
            std_errors={nm: float(v) for nm, v in zip(names + extra, se_a)},
            coded_coefficients={nm: float(v) for nm, v in zip(names, zh)},
            coded_std_errors={nm: float(v) for nm, v in zip(names, se_z)},
            centre=tuple(float(v) for v in c), scale=tuple(float(v) for v in h),
            sigma=sigma, rss=rss, n=n, df_resid=df, iterations=iters, converged=conv and conv_c)

    return DeferredActual(rss=rss, sigma=sigma, n=n, df_resid=df, iterations=iters, converged=conv, finish=finish)
