"""D-, I- or A-optimal mixture and mixture-process designs on a constrained simplex (issue 22).

The region is the one of :func:`~rsm_lrg.design.mixture.extreme_vertices`: component bounds
``L_i <= x_i <= U_i``, ``sum x_i = T`` and linear constraints. As Design-Expert does for
mixtures, the design is chosen from a candidate set
(:func:`~rsm_lrg.design.mixture.candidate_blends`: vertices, edge centroids, thirds of
edges, constraint-plane centroids, the overall centroid and the axial check blends), crossed
with the process factors' levels -1, 0, +1 for a mixture-process design. The model is a
Scheffé model in the L-pseudo components (:func:`rsm_lrg.terms.scheffe_names`; with process
factors every mixture term crossed with each process main effect, the model ``fit`` fits
under the same name), so ``det(X'X)`` and the prediction variance are those of the fit.

The search is Fedorov's candidate exchange (Fedorov 1972): every exchange of a run for a
candidate is ranked at once by the rank-two updates of
:meth:`~rsm_lrg.design.exchange.ExchangeProblem.batch_pairs`, the best one that the exact
criterion confirms is made, until none gains; from a sequential (greedy) start and random
starts, the best design is kept. Then, as in :func:`~rsm_lrg.design.optimal.optimal`,
``replicates`` repeats of model points (each the repeat that best improves the criterion)
and ``lof_points`` lack-of-fit points (each the candidate farthest, in coded units, from
every run so far).

The I criterion's moment matrix ``W = E[f(x) f(x)']`` is the mean over points uniform on the
constrained region (uniform on the L-pseudo simplex, kept where they meet the upper bounds
and constraints; process factors uniform on [-1, 1]), 16 384 of them from a fixed seed.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import replace
from typing import Any

import numpy as np

from ..errors import ParameterError
from ..factors import Factor, FactorSpace, letters_for
from ..terms import MIXTURE_ORDERS, Term, design_matrix, parse_term, scheffe_names
from .core import resolve_seed
from .exchange import MAX_RUNS, MAX_STARTS, ExchangeProblem, check_columns, check_criterion, criterion_value
from .mixture import CandidateSet, MixtureDesign, candidate_blends, finish_mixture, process_space
from .optimal import farthest_candidates, run_budget

__all__ = ["mixture_optimal"]

#: Points of the I criterion's moment matrix.
N_MOMENT = 2 ** 14
#: Most candidate points searched.
MAX_CANDIDATES = 20000


def _moments(terms: Sequence[Term], cs: CandidateSet, r: float, k: int, seed: int = 12345) -> np.ndarray:
    """``W = E[f f']`` over the region (see the module docstring)."""
    rng = np.random.default_rng(seed)
    q = len(cs.lows)
    kept: list[np.ndarray] = []
    got = 0
    for _ in range(200):
        z = rng.dirichlet(np.ones(q), size=N_MOMENT)
        # the sum is T up to rounding: only the bounds and constraints decide
        x = cs.lows[None, :] + r * z
        x[:, -1] = cs.total - (x[:, :-1].sum(axis=1))
        ok = cs.inside(x)
        kept.append(z[ok])
        got += int(ok.sum())
        if got >= N_MOMENT:
            break
    Z = np.vstack(kept)[:N_MOMENT]
    if len(Z) < 256:
        raise ParameterError("constraints", "too few points of the region were found for the I criterion's moments; "
                         "use --criterion D")
    if k:
        Z = np.hstack([Z, rng.uniform(-1.0, 1.0, size=(len(Z), k))])
    F = design_matrix(Z, terms)
    return F.T @ F / len(F)


def mixture_optimal(bounds: Mapping[str, tuple[float, float]] | Sequence[tuple[str, float, float]],
                    model: str = "mixture-quadratic", criterion: str = "D", runs: int | None = None,
                    lof_points: int | None = None, replicates: int | None = None, constraints: Any = None,
                    total: float = 1.0, process: Any = None, seed: Any = None, starts: int | None = None,
                    randomize: bool = True, blocks: int | None = None, block_size: Any = None) -> MixtureDesign:
    """An exact D-, I- or A-optimal mixture (or mixture-process) design by candidate exchange.

    Parameters
    ----------
    bounds : mapping or sequence
        ``{name: (low, high)}`` or ``[(name, low, high), ...]``: every component and its
        bounds in real proportions [units of the total] (``(0, total)`` for none).
    model : {"mixture-linear", "mixture-quadratic", "special-cubic", "mixture-cubic"}
        The Scheffé model the design supports (with ``process``: crossed with each process
        main effect, as ``fit --component ... --factor ...`` fits it).
    criterion : {"D", "I", "A"}
        As :func:`~rsm_lrg.design.optimal.optimal` (default D).
    runs : int or None
        Total runs; ``None``: the model's terms + 5 lack-of-fit points + 5 replicates.
    lof_points, replicates : int or None
        Lack-of-fit points and replicates (default 5 each without ``runs``, else 0).
    constraints : str, list of str or None
        Linear inequalities in the component names and real proportions.
    total : float
        The total ``T`` the proportions sum to [default 1].
    process : list of str or None
        Numeric process factors ``"NAME=LOW:HIGH"`` (letters after the components).
    seed, starts, randomize
        Seed of the random starts and the run order; random starts besides the greedy one
        (default 20 up to 10 model terms, 10 up to 30, 5 beyond); run order (within blocks).
    blocks : int or None
        Blocks (batches, days) as fixed effects: the design is D-optimal for the Scheffé model
        beside the ``blocks - 1`` block contrasts, as ``fit --block`` fits it, every run chosen
        by exchange and interchange over the candidates
        (:mod:`rsm_lrg.design.mixture_blocks`); criterion D only, no separate lack-of-fit
        points or replicates; ``runs`` defaults to the terms + ``blocks - 1`` + 10.
    block_size : int, sequence of int or None
        The runs of every block (one number for all); default as equal as possible.

    Returns
    -------
    MixtureDesign
        ``kind="optimal"``; standard order: model points, replicates, lack-of-fit points
        (with blocks: block by block, a ``block`` column 1..b). ``options`` holds the
        criterion and its value (:func:`~rsm_lrg.design.optimal.criterion_value` in the
        L-pseudo coding; with blocks ``det(M)^(1/P) / n`` of the P columns of the model and
        the block contrasts), the model, the counts and the candidate set's size.

    >>> d = mixture_optimal({"a": (0.1, 0.8), "b": (0.1, 0.8), "c": (0.0, 0.5)}, runs=8, seed=1)
    >>> d.n_runs, bool(np.allclose(d.proportions.sum(axis=1), 1.0, rtol=0, atol=1e-12))
    (8, True)
    """
    crit = check_criterion(criterion)
    if model not in MIXTURE_ORDERS:
        raise ParameterError("model", f"a mixture design needs a Scheffé model ({', '.join(MIXTURE_ORDERS)}), not {model!r}")
    cs = candidate_blends(bounds, constraints, total)
    names, cands, ctypes, lows, t = cs.names, cs.points, cs.types, cs.lows, cs.total
    q = len(names)
    proc = process_space(process, names) if process else None
    k = 0 if proc is None else len(proc)
    letters = letters_for(q + k)
    terms = [parse_term(nm, letters) for nm in scheffe_names(letters[:q], model, letters[q:])]
    p = len(terms)
    try:
        check_columns(p, model, q + k)
    except ValueError as exc:
        raise ParameterError("model", f"{exc}") from None
    what = f"the {model} model in {q} components" + (f" and {k} process factor{'s' * (k > 1)}" if k else "")
    if blocks is not None:
        return _blocked(cs=cs, terms=terms, what=what, crit=crit, runs=runs, lof_points=lof_points,
                        replicates=replicates, blocks=blocks, block_size=block_size, proc=proc, seed=seed,
                        starts=starts, randomize=randomize, model=model)
    if block_size is not None:
        raise ParameterError("block_size", "block sizes need blocks (blocks=N)")
    runs, n_lof, n_rep = run_budget(p, runs, lof_points, replicates, starts)
    n_model = runs - n_lof - n_rep
    if n_model < p:
        raise ParameterError("runs", f"{runs} runs leave {n_model} model points after {n_lof} lack-of-fit points and "
                         f"{n_rep} replicates; {what} needs at least {p} (one per term)")
    if runs > MAX_RUNS:
        raise ParameterError("runs", f"at most {MAX_RUNS} runs (got {runs})")
    pool, blend_of, r, Fc = _checked_candidates(cs, k, terms, what)
    space = FactorSpace(tuple(Factor(nm, float(lo) - r, float(lo) + r, L) for nm, lo, L in zip(names, lows, letters))
                        + (() if proc is None else tuple(replace(f, letter=L) for f, L in zip(proc.factors, letters[q:]))))
    W = _moments(terms, cs, r, k) if crit == "I" else None
    prob = ExchangeProblem(space, terms, crit, W, None, pool)
    rng, used_seed = resolve_seed(seed)
    if starts is None:
        starts = 20 if p <= 10 else (10 if p <= 30 else 5)
    starts = min(max(1, int(starts)), MAX_STARTS)
    best, best_v = None, np.inf
    for s in range(starts + 1):
        idx = _greedy(prob, Fc, n_model) if s == 0 else rng.integers(0, len(pool), size=n_model)
        idx, v = _fedorov(prob, pool, Fc, idx, exact=False)  # with the small ridge: a singular start climbs
        idx, v = _fedorov(prob, pool, Fc, idx, exact=True)
        if best is None or v < best_v:
            best, best_v = idx, v
    assert best is not None
    D = pool[best]
    for _ in range(n_rep):
        uniq = np.unique(D, axis=0)
        scores = [prob.score(np.vstack([D, u])) for u in uniq]
        D = np.vstack([D, uniq[int(np.argmin(scores))]])
    if n_lof:
        D = np.vstack([D, farthest_candidates(D, pool, space, n_lof)])
    # every run is a candidate: its exact proportions
    where = {row.tobytes(): i for i, row in enumerate(pool)}
    rows = [where[np.asarray(x, dtype=float).tobytes()] for x in D]
    props = cands[blend_of[rows]]
    types = [ctypes[i] for i in blend_of[rows]]
    value = criterion_value(D, terms, crit, W)
    options = {"criterion": crit, "criterion_value": value, "model": model, "model_terms": p,
               "model_points": n_model, "replicates": n_rep, "lof_points": n_lof, "starts": starts,
               "candidates": int(len(pool)), "constraints": list(cs.texts),
               "bounds": {nm: (float(lo), float(hi)) for nm, lo, hi in zip(names, cs.lower, cs.upper)},
               "algorithm": "candidate exchange (Fedorov 1972) over the extreme-vertices candidate set",
               "notes": [f"{crit}-optimal for {what} ({p} terms); L-pseudo coding"]}
    if proc is not None:
        options["process"] = {f.name: (float(f.low), float(f.high)) for f in proc.factors if isinstance(f, Factor)}
    return finish_mixture("optimal", names, props, types, t, lows, seed=rng if used_seed is None else used_seed,
                          randomize=randomize, options=options, process=proc,
                          process_coded=D[:, q:] if k else None)


def _checked_candidates(cs: CandidateSet, k: int, terms: list[Term],
                        what: str) -> tuple[np.ndarray, np.ndarray, float, np.ndarray]:
    """``(pool, blend_of, r, Fc)``: the candidate points (L-pseudo blends x process levels -1,
    0, +1), the blend of each, the pseudo range ``r`` and the candidates' model matrix; a
    ``ParameterError`` when there are more than :data:`MAX_CANDIDATES` points or they cannot
    estimate every term."""
    r = cs.total - float(np.sum(cs.lows))
    zc = (cs.points - cs.lows[None, :]) / r
    levels = np.array(list(itertools.product([-1.0, 0.0, 1.0], repeat=k))) if k else np.zeros((1, 0))
    pool = np.hstack([np.repeat(zc, len(levels), axis=0), np.tile(levels, (len(zc), 1))])
    if len(pool) > MAX_CANDIDATES:
        raise ParameterError("bounds", f"the region gives {len(pool)} candidate points; at most {MAX_CANDIDATES} are "
                                       "searched (fewer components or process factors)")
    Fc = design_matrix(pool, terms)
    rank = np.linalg.matrix_rank(Fc)
    if rank < len(terms):
        raise ParameterError("model", f"the candidate blends of this region cannot support {what} "
                                      f"({rank} of {len(terms)} terms estimable)")
    return pool, np.repeat(np.arange(len(zc)), len(levels)), r, Fc


def _blocked(*, cs: CandidateSet, terms: list[Term], what: str, crit: str, runs: Any, lof_points: Any,
             replicates: Any, blocks: Any, block_size: Any, proc: FactorSpace | None, seed: Any, starts: Any,
             randomize: bool, model: str) -> MixtureDesign:
    """The D-optimal blocked mixture (or mixture-process) design (:func:`mixture_optimal` with ``blocks``)."""
    from .mixture_blocks import block_exchange, block_sizes

    if crit != "D":
        raise ParameterError("criterion", f"a blocked mixture design is D-optimal (criterion D), not {crit}")
    for name, given in (("lof_points", lof_points), ("replicates", replicates)):
        if given:
            what = "lack-of-fit points" if name == "lof_points" else "replicates"
            raise ParameterError(name, f"{what} are not set apart in a blocked design: every run is "
                                       "chosen by the D criterion (repeats where it gains)")
    if isinstance(blocks, (bool, np.bool_)) or not isinstance(blocks, (int, np.integer)) or blocks < 2:
        raise ParameterError("blocks", f"blocks must be a whole number >= 2 (got {blocks!r})")
    blocks = int(blocks)
    plural = "s" if blocks > 2 else ""
    p = len(terms)
    P = p + int(blocks) - 1
    if runs is None:
        runs = P + 10 if block_size is None else (
            int(block_size) * int(blocks) if isinstance(block_size, (int, np.integer)) else sum(block_size))
    run_budget(p, runs, None, None, starts)  # whole numbers
    runs = int(runs)
    if runs > MAX_RUNS:
        raise ParameterError("runs", f"at most {MAX_RUNS} runs (got {runs})")
    sizes = block_sizes(runs, blocks, block_size)
    if runs < P:
        raise ParameterError("runs", f"{runs} runs cannot support {what} ({p} terms) and {blocks - 1} block "
                                     f"effect{plural}: at least {P} are needed")
    k = 0 if proc is None else len(proc)
    pool, blend_of, r, Fc = _checked_candidates(cs, k, terms, what)
    rng, used_seed = resolve_seed(seed)
    if starts is None:
        starts = 20 if P <= 10 else (10 if P <= 30 else 5)
    starts = min(max(1, int(starts)), MAX_STARTS)
    idx, blk, logdet = block_exchange(Fc, sizes, rng, starts)
    if not math.isfinite(logdet):
        raise ParameterError("runs", f"no design of {runs} runs in blocks of {', '.join(map(str, sizes))} supports "
                                     f"{what} and the block effects (every search ended singular)")
    q = len(cs.names)
    D = pool[idx]
    value = float(math.exp(logdet / P) / runs)
    options = {"criterion": "D", "criterion_value": value, "model": model, "model_terms": p,
               "model_points": runs, "replicates": 0, "lof_points": 0, "starts": starts,
               "blocks": int(blocks), "block_sizes": sizes, "candidates": int(len(pool)),
               "constraints": list(cs.texts),
               "bounds": {nm: (float(lo), float(hi)) for nm, lo, hi in zip(cs.names, cs.lower, cs.upper)},
               "algorithm": "exchange and interchange over the extreme-vertices candidate set (Cook & Nachtsheim "
                            "1989), blocks as fixed effects",
               "notes": [f"D-optimal for {what} ({p} terms) beside {blocks - 1} block contrast"
                         f"{plural} (fixed block effects, as fit --block fits them); blocks of "
                         f"{', '.join(map(str, sizes))} runs; L-pseudo coding"]}
    if proc is not None:
        options["process"] = {f.name: (float(f.low), float(f.high)) for f in proc.factors if isinstance(f, Factor)}
    return finish_mixture("optimal", cs.names, cs.points[blend_of[idx]], [cs.types[i] for i in blend_of[idx]],
                          cs.total, cs.lows, seed=rng if used_seed is None else used_seed, randomize=randomize,
                          options=options, process=proc, process_coded=D[:, q:] if k else None, blocks=blk + 1)


def _greedy(prob: ExchangeProblem, F: np.ndarray, n: int) -> np.ndarray:
    """Indices of ``n`` candidates added one at a time, each the one that most improves the
    criterion of the runs so far (from a small ridge; Dykstra 1971)."""
    M = prob.ridge(n) * 1e3
    out: list[int] = []
    for _ in range(n):
        j = int(np.argmin(prob.batch(M, None, F)))
        out.append(j)
        M = M + np.outer(F[j], F[j])
    return np.array(out, dtype=int)


def _exact_score(prob: ExchangeProblem, D: np.ndarray) -> float:
    """The criterion to minimise on the scale of :meth:`ExchangeProblem.batch_pairs`
    (``-log det X'X`` for D, the trace for I and A; inf when singular), without the
    exchange's ridge: Scheffé terms in small pseudo components have small ``X'X`` entries,
    which a ridge of ``1e-9 n`` would bias."""
    X = design_matrix(D, prob.terms)
    M = X.T @ X
    if prob.crit == "D":
        sign, logdet = np.linalg.slogdet(M)
        return -float(logdet) if sign > 0 else math.inf
    try:
        inv = np.linalg.inv(M)
    except np.linalg.LinAlgError:
        return math.inf
    v = float(np.trace(inv @ prob.W) if prob.crit == "I" else np.trace(inv))
    return v if math.isfinite(v) and v > 0 else math.inf


def _fedorov(prob: ExchangeProblem, pool: np.ndarray, F: np.ndarray, idx: np.ndarray,
             exact: bool) -> tuple[np.ndarray, float]:
    """Fedorov's exchange on the candidate indices ``idx`` (see the module docstring):
    ``(indices, criterion to minimise)``; ``exact=False``: with the exchange's small ridge."""
    idx = np.array(idx, dtype=int)
    n, m = len(idx), len(pool)

    def score(i: np.ndarray) -> float:
        return _exact_score(prob, pool[i]) if exact else prob.score(pool[i])

    cur = score(idx)
    if not math.isfinite(cur):
        return idx, cur
    per = max(1, 200_000 // max(m, 1))  # runs per batch of pairs
    for _ in range(50 * n + 100):
        R = F[idx]
        M = R.T @ R + (0.0 if exact else prob.ridge(n))
        vals, runs, cands = [], [], []
        for lo in range(0, n, per):
            rr = np.arange(lo, min(n, lo + per))
            own = np.repeat(rr, m)
            cj = np.tile(np.arange(m), len(rr))
            vals.append(prob.batch_pairs(M, R, own, F[cj]))
            runs.append(own)
            cands.append(cj)
        v, own, cj = np.concatenate(vals), np.concatenate(runs), np.concatenate(cands)
        moved = False
        for b in np.argsort(v)[:3]:  # the ranking is by updates; the exact value decides
            if not v[b] < cur - 1e-10 * max(1.0, abs(cur)):
                break
            trial = idx.copy()
            trial[own[b]] = cj[b]
            s = score(trial)
            if s < cur - 1e-10 * max(1.0, abs(cur)):
                idx, cur, moved = trial, s, True
                break
        if not moved:
            break
    return idx, cur
