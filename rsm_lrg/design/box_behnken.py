"""Box–Behnken designs for 3 to 7, 9 to 12 and 16 factors, as published.

Box, G. E. P. & Behnken, D. W. (1960). Some new three level designs for the study of
quantitative variables. *Technometrics* 2(4), 455–475.

Each design combines a balanced incomplete block design (BIBD) on the factors with a
two-level full factorial: in every block of the BIBD the factors of that block run through
all ±1 combinations while the other factors stay at 0. Centre runs are added.

=======  ==================================================  =========  ==========
factors  factor sets varied together                         edge runs  blocks
=======  ==================================================  =========  ==========
3        all 3 pairs (2^2 each)                              12         1
4        all 6 pairs (2^2 each)                              24         1 or 3
5        all 10 pairs (2^2 each)                             40         1 or 2
6        6 triples (2^3 each); every factor in 3 triples,    48         1
         pairs {1,4},{2,5},{3,6} together twice, others once
7        7 triples (2^3 each), the Fano plane: every pair    56         1
         of factors together exactly once (BIBD, λ = 1)
9        15 triples (2^3 each): the 12 lines of the affine   120        1 or 5
         plane of order 3 (every pair once) and its first
         parallel class again; every factor in 5 triples
10       10 quadruples (2^4 each); every factor in 4         160        1
11       11 quintuples (2^(5-1) each, E = ABCD): the         176        1
         symmetric (11, 5, 2) BIBD, every pair twice
12       12 quadruples (2^4 each); every factor in 4         192        1
16       24 quadruples (2^4 each); every factor in 6         384        1 or 6
=======  ==================================================  =========  ==========

The designs for 3, 4, 5 and 7 factors and for 11 (a BIBD) have every pair of factors varied
together equally often; the others rest on partially balanced designs (pairs together once or
twice). Only the 4- and 7-factor designs are rotatable (fourth moments ``[iiii] = 3 [iijj]``).

The factor sets and their order are those of the published tables as transcribed in
R ``rsm``'s ``bbd()`` (R. V. Lenth, file ``R/bbd.R``, internal ``reftbl``):

* k = 4: {1,2},{3,4} | {1,4},{2,3} | {1,3},{2,4} — each ``|`` starts a new orthogonal
  block (3 blocks of two disjoint pairs, 8 runs each);
* k = 5: {1,2},{1,3},{3,4},{4,5},{2,5} | {1,4},{1,5},{2,3},{2,4},{3,5} (2 blocks of 20);
* k = 6: {1,2,4},{2,3,5},{3,4,6},{1,4,5},{2,5,6},{1,3,6};
* k = 7: {4,5,6},{1,6,7},{2,5,7},{1,2,4},{3,4,7},{1,3,5},{2,3,6}.

The sets for 9 to 12 and 16 factors, and the blockings of 9 (5 blocks of three triples, each
block one parallel class: every factor once) and 16 factors (6 blocks of four quadruples, each
holding every factor once), are those of the published tables as transcribed in MATLAB's
``bbdesign`` (and its Python ports); the 11-factor sets run the half fraction 2^(5-1) with
E = ABCD (resolution V), 16 runs a set, as published (188 runs with 12 centre runs).

pyDOE3's ``bbdesign`` gives the same runs for k = 3, 4, 5 (all pairs) but, because it
pairs every two factors for any k, 60 and 84 edge runs instead of the published 48 and 56
for k = 6 and 7; this module therefore takes the factor sets from the published table and
builds the two-level factorials itself (:func:`two_level_factorial`).

Blocking for 4 and 5 factors follows R ``rsm``'s ``bbd()`` (its documentation: "Only BBDs with
4 or 5 factors can be blocked. A 4-factor BBD has three orthogonal blocks, and a 5-factor BBD
has two"); 9 and 16 factors as published (above).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import ParameterError
from .core import Design, as_factor_space, check_center, cross_categoric, numeric_part

__all__ = ["box_behnken", "BBD_SETS", "BBD_BLOCKS", "BBD_HALF_FRACTION", "bbd_edge_runs", "two_level_factorial"]

#: Published factor sets (1-based), in the order of the published table (R rsm ``reftbl``).
BBD_SETS: dict[int, tuple[tuple[int, ...], ...]] = {
    3: ((1, 2), (1, 3), (2, 3)),
    4: ((1, 2), (3, 4), (1, 4), (2, 3), (1, 3), (2, 4)),
    5: ((1, 2), (1, 3), (3, 4), (4, 5), (2, 5), (1, 4), (1, 5), (2, 3), (2, 4), (3, 5)),
    6: ((1, 2, 4), (2, 3, 5), (3, 4, 6), (1, 4, 5), (2, 5, 6), (1, 3, 6)),
    7: ((4, 5, 6), (1, 6, 7), (2, 5, 7), (1, 2, 4), (3, 4, 7), (1, 3, 5), (2, 3, 6)),
    9: ((1, 4, 7), (2, 5, 8), (3, 6, 9), (1, 2, 3), (4, 5, 6), (7, 8, 9), (1, 5, 9), (3, 4, 8), (2, 6, 7),
        (1, 6, 8), (2, 4, 9), (3, 5, 7), (1, 4, 7), (2, 5, 8), (3, 6, 9)),
    10: ((2, 6, 7, 10), (1, 2, 5, 10), (2, 3, 7, 8), (2, 4, 6, 9), (1, 8, 9, 10), (3, 4, 5, 10), (1, 4, 7, 8),
         (3, 5, 7, 9), (1, 3, 6, 9), (4, 5, 6, 8)),
    11: ((3, 7, 8, 9, 11), (1, 4, 8, 9, 10), (2, 5, 9, 10, 11), (1, 3, 6, 10, 11), (1, 2, 4, 7, 11),
         (1, 2, 3, 5, 8), (2, 3, 4, 6, 9), (3, 4, 5, 7, 10), (4, 5, 6, 8, 11), (1, 5, 6, 7, 9), (2, 6, 7, 8, 10)),
    12: ((1, 2, 5, 7), (2, 3, 6, 8), (3, 4, 7, 9), (4, 5, 8, 10), (5, 6, 9, 11), (6, 7, 10, 12), (1, 7, 8, 11),
         (2, 8, 9, 12), (1, 3, 9, 10), (2, 4, 10, 11), (3, 5, 11, 12), (1, 4, 6, 12)),
    16: ((1, 2, 6, 9), (3, 4, 8, 11), (5, 10, 13, 14), (7, 12, 15, 16), (2, 3, 7, 10), (1, 4, 5, 12),
         (6, 11, 14, 15), (8, 9, 13, 16), (2, 5, 6, 13), (4, 7, 8, 15), (1, 9, 10, 14), (3, 11, 12, 16),
         (3, 6, 7, 14), (1, 5, 8, 16), (2, 10, 11, 15), (4, 9, 12, 13), (1, 3, 13, 15), (2, 4, 14, 16),
         (5, 7, 9, 11), (6, 8, 10, 12), (4, 6, 10, 16), (3, 5, 9, 15), (1, 7, 11, 13), (2, 8, 12, 14)),
}

#: Designs whose sets run a half fraction 2^(m-1) (last factor of the set = product of the
#: others, resolution V for m = 5) instead of the full 2^m.
BBD_HALF_FRACTION = frozenset({11})

#: Published orthogonal blockings: k -> number of blocks -> block of each factor set.
BBD_BLOCKS: dict[int, dict[int, tuple[int, ...]]] = {
    4: {3: (1, 1, 2, 2, 3, 3)},
    5: {2: (1, 1, 1, 1, 1, 2, 2, 2, 2, 2)},
    9: {5: (1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4, 4, 5, 5, 5)},
    16: {6: (1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 6, 6, 6, 6)},
}


def two_level_factorial(m: int, half: bool = False) -> np.ndarray:
    """The 2^m factorial in coded units, standard (Yates) order: the first factor changes
    fastest (as pyDOE3's ``ff2n`` sorted by Yates). With ``half``, the 2^(m-1) half fraction
    whose last factor is the product of the others (``E = ABCD`` for m = 5).

    >>> two_level_factorial(2).tolist()
    [[-1.0, -1.0], [1.0, -1.0], [-1.0, 1.0], [1.0, 1.0]]
    >>> two_level_factorial(3, half=True).tolist()
    [[-1.0, -1.0, 1.0], [1.0, -1.0, -1.0], [-1.0, 1.0, -1.0], [1.0, 1.0, 1.0]]
    """
    base = m - 1 if half else m
    bits = (np.arange(2 ** base)[:, None] >> np.arange(base)) & 1
    runs = 2.0 * bits - 1.0
    if half:
        runs = np.column_stack([runs, np.prod(runs, axis=1)])
    return runs


def bbd_edge_runs(k: int) -> tuple[np.ndarray, np.ndarray]:
    """The published edge (non-centre) runs of a k-factor BBD, in standard order.

    Returns
    -------
    runs : numpy.ndarray, shape (n_edge, k)
        Coded settings; within each factor set the two-level factorial is in standard
        (Yates) order, first factor of the set changing fastest (pyDOE3 ``ff2n``).
    set_index : numpy.ndarray, shape (n_edge,)
        Index (0-based) of the factor set each run belongs to.

    >>> runs, _ = bbd_edge_runs(3)
    >>> runs[:4].tolist()
    [[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [-1.0, 1.0, 0.0], [1.0, 1.0, 0.0]]
    """
    if k not in BBD_SETS:
        raise ValueError(_k_message(k))
    rows, which = [], []
    for s, fs in enumerate(BBD_SETS[k]):
        fact = two_level_factorial(len(fs), half=k in BBD_HALF_FRACTION)
        block = np.zeros((fact.shape[0], k))
        block[:, [i - 1 for i in fs]] = fact
        rows.append(block)
        which.extend([s] * fact.shape[0])
    return np.vstack(rows), np.asarray(which)


def _k_message(k: int) -> str:
    return (f"a Box-Behnken design needs 3 to 7, 9 to 12 or 16 factors (the designs published by Box & "
            f"Behnken 1960); got {k}")


def box_behnken(
    factors: Any,
    center: int = 3,
    blocks: int | None = None,
    seed: Any = None,
    randomize: bool = True,
) -> Design:
    """Box–Behnken design for 3 to 7, 9 to 12 or 16 factors (Box & Behnken 1960), as published.

    Parameters
    ----------
    factors : FactorSpace, mapping or list
        The factors: a :class:`~rsm_lrg.factors.FactorSpace`, ``{name: (low, high)}``, or
        ``["NAME=LOW:HIGH", ...]``. Low and high [factor units] are coded -1 and +1.
    center : int, default 3
        Centre runs; **per block** when the design is blocked. Any number ≥ 0 (the paper's
        design: 4 factors with 3 centre runs = 27 runs).
    blocks : int or None
        ``None`` or 1: one block. 3 for 4 factors, 2 for 5, 5 for 9 or 6 for 16 factors: the
        published orthogonal blocking (block effects uncorrelated with every model term).
    seed : int, numpy.random.Generator or None
        Randomisation of the run order (within blocks when blocked). The same seed gives
        the same order. ``None`` draws a seed and records it in ``options["seed"]``.
    randomize : bool, default True
        ``False``: run order = standard order.

    Returns
    -------
    Design
        Standard order: the factor sets in the published order, each with its 2^m
        factorial in Yates order, then the centre runs (block by block when blocked).

    Raises
    ------
    ValueError
        A number of factors without a published design, a negative number of centre runs, or a
        blocking the published designs do not have.

    Examples
    --------
    >>> d = box_behnken({"thickness_m": (1e-4, 5e-4), "stroke_m": (0.04, 0.06),
    ...                  "velocity_m_s": (0.4, 0.6), "acceleration_m_s2": (20, 40)},
    ...                 center=3, seed=1)
    >>> d.n_runs, d.n_center
    (27, 3)
    """
    space = as_factor_space(factors)
    k = numeric_part(space)[1]
    if k not in BBD_SETS:
        raise ValueError(_k_message(k))
    center = check_center(center)
    nb = _check_blocks(blocks, k)
    edge, which = bbd_edge_runs(k)
    if nb == 1:
        coded = np.vstack([edge, np.zeros((center, k))])
        bstd = None
    else:
        set_block = np.asarray(BBD_BLOCKS[k][nb])
        eblock = set_block[which]
        parts, bparts = [], []
        for b in range(1, nb + 1):
            parts += [edge[eblock == b], np.zeros((center, k))]
            bparts += [np.full(int(np.sum(eblock == b)) + center, b)]
        coded = np.vstack(parts)
        bstd = np.concatenate(bparts)
    options = {
        "center": center,
        "center_per_block": nb > 1,
        "blocks": nb,
        "edge_runs": int(edge.shape[0]),
        "factor_sets": [list(s) for s in BBD_SETS[k]],
        "source": ("Box & Behnken (1960), Technometrics 2(4):455-475; sets as in R rsm bbd() (3-7 factors) "
                   "and MATLAB bbdesign (9-12, 16 factors)"),
    }
    coded, bstd = cross_categoric(space, coded, bstd)
    return Design.from_standard(space, "box-behnken", coded, blocks_std=bstd, seed=seed,
                                randomize=randomize, options=options)


def _check_blocks(blocks: Any, k: int) -> int:
    if blocks is None:
        return 1
    if isinstance(blocks, (bool, np.bool_)) or int(blocks) != blocks:
        raise ParameterError("blocks", f"blocks must be a whole number (got {blocks!r})")
    nb = int(blocks)
    if nb == 1:
        return 1
    allowed = BBD_BLOCKS.get(k, {})
    if nb not in allowed:
        if allowed:
            ok = " or ".join(["1"] + [str(b) for b in allowed])
            raise ValueError(f"a {k}-factor Box-Behnken design can be blocked orthogonally only "
                             f"into {ok} blocks (got {nb})")
        raise ValueError(f"a {k}-factor Box-Behnken design has no published orthogonal blocking; "
                         f"only 4 factors (3 blocks), 5 (2 blocks), 9 (5 blocks) and 16 (6 blocks) can be "
                         f"blocked (got blocks={nb})")
    return nb
