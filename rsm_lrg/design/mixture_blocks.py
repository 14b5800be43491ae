"""D-optimal blocking of a design chosen from a candidate set: blocks as fixed effects (issue 35).

The model of a blocked design is the treatment model ``f(x)`` (a Scheffé model for a mixture,
whose linear blending terms hold the mean) beside the ``b - 1`` sum-to-zero block contrasts
``c(block)``, as ``fit --block`` fits it: a run's row is ``[f(x), c(block)]`` and the design
maximises ``det(M)``, ``M = sum [f, c][f, c]'``. With the block sizes fixed this is the same
as maximising the determinant of the information on the treatment effects after the block
means are removed (``det(X_c' X_c)``, the rows of the model without its constant centred in
their block: R AlgDesign's ``optBlock`` criterion), since ``[F, C] = [Z, X] Q`` for the block
indicators ``Z``, the non-constant columns ``X`` and a constant nonsingular ``Q``, and
``det([Z, X]'[Z, X]) = prod(n_b) det(X' (I - P_Z) X)``.

The search (Cook & Nachtsheim 1989; Atkinson, Donev & Tobias 2007, ch. 15) alternates two
moves until neither gains:

* **exchange**: a run replaced by any candidate in the same block (every run x candidate
  pair ranked at once by the rank-two determinant update ``(1 + g'Ag)(1 - f'Af) + (f'Ag)^2``,
  ``A = M^-1``);
* **interchange**: two runs of different blocks swap blocks (every pair ranked by the
  determinant of ``I + C W'AW`` for its four changed rows ``W``).

Every accepted move is confirmed by the exact log-determinant. The best of a sequential
(greedy) start and ``starts`` random ones is kept.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..errors import ParameterError

__all__ = ["block_sizes", "block_exchange", "block_rows", "blocked_log_det"]


def block_sizes(runs: int, blocks: Any, sizes: Any = None) -> list[int]:
    """The size of every block: ``sizes`` (one whole number per block, or one for all) checked
    against ``runs`` (None: as equal as possible, the larger blocks first).

    Parameters
    ----------
    runs : int
        The design's runs.
    blocks : int
        The number of blocks (at least 2).
    sizes : int, sequence of int or None
        The runs of each block.

    Returns
    -------
    list of int
        ``blocks`` sizes summing to ``runs``.

    >>> block_sizes(14, 3)
    [5, 5, 4]
    """
    if isinstance(blocks, (bool, np.bool_)) or not isinstance(blocks, (int, np.integer)) or blocks < 2:
        raise ParameterError("blocks", f"blocks must be a whole number >= 2 (got {blocks!r})")
    b = int(blocks)
    if sizes is None:
        base, extra = divmod(int(runs), b)
        out = [base + (i < extra) for i in range(b)]
    else:
        given = [sizes] if isinstance(sizes, (int, np.integer)) else list(sizes)
        if any(isinstance(s, (bool, np.bool_)) or not isinstance(s, (int, np.integer)) or s < 1 for s in given):
            raise ParameterError("block_size", f"block sizes must be whole numbers >= 1 (got {sizes!r})")
        if len(given) == 1:
            given = given * b
        if len(given) != b:
            raise ParameterError("block_size", f"{len(given)} block sizes for {b} blocks")
        out = [int(s) for s in given]
        if sum(out) != runs:
            raise ParameterError("block_size", f"the block sizes sum to {sum(out)} runs, not the design's {runs}")
    if min(out) < 1:
        raise ParameterError("blocks", f"{runs} runs cannot fill {b} blocks")
    return out


def block_rows(blocks: np.ndarray, n_blocks: int) -> np.ndarray:
    """The sum-to-zero block contrasts of block codes: column j is 1 in block j, -1 in the last
    block (:func:`rsm_lrg.terms.block_contrasts`).

    Parameters
    ----------
    blocks : numpy.ndarray of int, shape (n,)
        Block codes 0..b-1.
    n_blocks : int
        The number of blocks b.

    Returns
    -------
    numpy.ndarray, shape (n, b - 1)
        The contrasts.
    """
    from ..terms import block_contrasts

    return block_contrasts(np.asarray(blocks, dtype=int), int(n_blocks))


def blocked_log_det(F: np.ndarray, blocks: np.ndarray, n_blocks: int) -> float:
    """``log det M`` of model rows ``F`` (n x p) beside the block contrasts; -inf when singular.

    Parameters
    ----------
    F : numpy.ndarray, shape (n, p)
        The treatment model's rows.
    blocks : numpy.ndarray of int, shape (n,)
        Block codes 0..b-1.
    n_blocks : int
        The number of blocks.

    Returns
    -------
    float
        The log-determinant (-inf for a singular design).
    """
    R = np.hstack([F, block_rows(blocks, n_blocks)])
    sign, logdet = np.linalg.slogdet(R.T @ R)
    return float(logdet) if sign > 0 else -math.inf


def _gain(v: float, cur: float) -> bool:
    return v > cur + 1e-10 * max(1.0, abs(cur))


def _exchange_step(Fc: np.ndarray, C: np.ndarray, idx: np.ndarray, blk: np.ndarray, A: np.ndarray
                   ) -> tuple[float, int, int]:
    """The best run-for-candidate exchange within its block: ``(log det ratio, run, candidate)``.

    With ``g = [f_j, c_b]`` split at the model's ``p`` columns: ``g'Ag = f_j'A11 f_j + 2 f_j'A12 c_b
    + c_b'A22 c_b`` and ``r'Ag = (r'A)_1 f_j + (r'A)_2 c_b``, one product over the candidates for
    every run and block."""
    p = Fc.shape[1]
    R = np.hstack([Fc[idx], C[blk]])
    FA = Fc @ A[:p]  # (m, P)
    base = np.einsum("ij,ij->i", FA[:, :p], Fc)  # f'A11 f
    cross = FA[:, p:] @ C.T  # (m, b): f'A12 c_b
    cc = np.einsum("bj,jk,bk->b", C, A[p:, p:], C)  # c_b'A22 c_b
    gAg = base[:, None] + 2.0 * cross + cc[None, :]  # (m, b)
    RA = R @ A
    fAf = np.einsum("ij,ij->i", RA, R)
    fAg = RA[:, :p] @ Fc.T + (RA[:, p:] * C[blk]).sum(axis=1)[:, None]  # (n, m), each run in its block
    with np.errstate(all="ignore"):
        r = (1.0 + gAg[:, blk].T) * (1.0 - fAf[:, None]) + fAg ** 2
    r = np.where(np.isfinite(r), r, -np.inf)
    a, j = np.unravel_index(int(np.argmax(r)), r.shape)
    return (math.log(r[a, j]) if r[a, j] > 0 else -math.inf), int(a), int(j)


def _interchange_step(Fc: np.ndarray, C: np.ndarray, idx: np.ndarray, blk: np.ndarray, A: np.ndarray
                      ) -> tuple[float, int, int]:
    """The best swap of the blocks of two runs: ``(log det ratio, run, run)``."""
    n = len(idx)
    i, k = np.triu_indices(n, 1)
    keep = (blk[i] != blk[k]) & (idx[i] != idx[k])
    i, k = i[keep], k[keep]
    if not i.size:
        return -math.inf, -1, -1
    F = Fc[idx]
    old_i = np.hstack([F[i], C[blk[i]]])
    old_k = np.hstack([F[k], C[blk[k]]])
    new_i = np.hstack([F[i], C[blk[k]]])
    new_k = np.hstack([F[k], C[blk[i]]])
    W = np.stack([old_i, old_k, new_i, new_k], axis=1)  # (pairs, 4, P)
    G = (W @ A) @ W.transpose(0, 2, 1)
    sgn = np.array([-1.0, -1.0, 1.0, 1.0])
    Mx = np.eye(4)[None, :, :] + sgn[:, None] * G  # I + C W'AW, C = diag(sgn)
    with np.errstate(all="ignore"):
        s, ld = np.linalg.slogdet(Mx)
    ld = np.where((s > 0) & np.isfinite(ld), ld, -np.inf)
    j = int(np.argmax(ld))
    return float(ld[j]), int(i[j]), int(k[j])


def _climb(Fc: np.ndarray, C: np.ndarray, idx: np.ndarray, blk: np.ndarray, ridge: float) -> tuple[np.ndarray, float]:
    """Exchanges and interchanges from ``(idx, blk)`` until none gains: ``(idx, log det)``;
    ``ridge`` > 0 lets a singular start climb (the exact value decides once it is regular)."""
    idx = idx.copy()
    nb = C.shape[0]
    P = Fc.shape[1] + C.shape[1]

    def exact(ix: np.ndarray) -> float:
        R = np.hstack([Fc[ix], C[blk]])
        sign, ld = np.linalg.slogdet(R.T @ R + ridge * np.eye(P))
        return float(ld) if sign > 0 else -math.inf

    cur = exact(idx)
    for _ in range(100 * len(idx) + 100):
        R = np.hstack([Fc[idx], C[blk]])
        M = R.T @ R + ridge * np.eye(P)
        try:
            A = np.linalg.inv(M)
        except np.linalg.LinAlgError:
            break
        A = 0.5 * (A + A.T)
        ex = _exchange_step(Fc, C, idx, blk, A)
        sw = _interchange_step(Fc, C, idx, blk, A) if nb > 1 else (-math.inf, -1, -1)
        moved = False
        for kind, (v, a, b) in sorted((("x", ex), ("s", sw)), key=lambda t: -t[1][0]):
            if not v > 1e-12:
                continue
            if kind == "x":
                trial = idx.copy()
                trial[a] = b
                new = exact(trial)
                if _gain(new, cur):
                    idx, cur, moved = trial, new, True
                    break
            else:
                blk[a], blk[b] = blk[b], blk[a]
                new = exact(idx)
                if _gain(new, cur):
                    cur, moved = new, True
                    break
                blk[a], blk[b] = blk[b], blk[a]
        if not moved:
            break
    return idx, cur


def _greedy(Fc: np.ndarray, C: np.ndarray, blk: np.ndarray, ridge: float) -> np.ndarray:
    """A sequential start: each run in turn (blocks as given) the candidate that most
    increases ``det`` of the runs so far (from a small ridge)."""
    P = Fc.shape[1] + C.shape[1]
    M = ridge * 1e3 * np.eye(P)
    out = []
    for b in blk:
        G = np.hstack([Fc, np.broadcast_to(C[b], (len(Fc), C.shape[1]))])
        A = np.linalg.inv(M)
        j = int(np.argmax(np.einsum("ij,jk,ik->i", G, A, G)))
        out.append(j)
        M = M + np.outer(G[j], G[j])
    return np.array(out, dtype=int)


def block_exchange(Fc: np.ndarray, sizes: Sequence[int], rng: np.random.Generator, starts: int
                   ) -> tuple[np.ndarray, np.ndarray, float]:
    """A D-optimal blocked design from the candidate rows ``Fc`` (module docstring).

    Parameters
    ----------
    Fc : numpy.ndarray, shape (m, p)
        The treatment model's row of every candidate point.
    sizes : sequence of int
        The runs of each block.
    rng : numpy.random.Generator
        Draws the random starts.
    starts : int
        Random starts besides the sequential one.

    Returns
    -------
    (numpy.ndarray, numpy.ndarray, float)
        The candidate index and the block code (0..b-1) of every run, block by block, and
        ``log det M``.
    """
    nb = len(sizes)
    C = block_rows(np.arange(nb), nb)
    blk0 = np.repeat(np.arange(nb), sizes)
    n = int(blk0.size)
    ridge = 1e-9 * n
    best: tuple[np.ndarray, np.ndarray] | None = None
    best_v = -math.inf
    for s in range(int(starts) + 1):
        blk = blk0.copy() if s == 0 else rng.permutation(blk0)
        idx = _greedy(Fc, C, blk, ridge) if s == 0 else rng.integers(0, len(Fc), size=n)
        idx, _ = _climb(Fc, C, idx, blk, ridge)  # with the ridge: a singular start climbs
        idx, v = _climb(Fc, C, idx, blk, 0.0)
        if v > best_v or best is None:
            best, best_v = (idx.copy(), blk.copy()), v
    assert best is not None
    idx, blk = best
    order = np.argsort(blk, kind="stable")
    return idx[order], blk[order], best_v
