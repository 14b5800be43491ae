"""Optimal designs by coordinate exchange (Meyer & Nachtsheim 1995), D, I or A.

Meyer, R. K. & Nachtsheim, C. J. (1995). The coordinate-exchange algorithm for
constructing exact optimal experimental designs. *Technometrics* 37(1), 60-69.

The model matrix ``X`` (n x p) of a standard model (:func:`rsm_lrg.terms.model_terms`:
linear, 2FI, quadratic, cubic; categoric factors effect-coded) gives the information
matrix ``M = X'X``. The criteria, as Design-Expert and JMP define them:

``D``  maximise ``det(M)``; reported as ``det(M)**(1/p) / n`` (per run);
``A``  minimise ``trace(M^-1)`` (the sum of the coefficient variances / sigma^2);
``I``  minimise the average prediction variance over the region,
       ``trace(M^-1 W)`` with the moment matrix ``W = mean over the region of f(x) f(x)'``
       (exact moments of the uniform measure on the coded cube [-1, 1]^k and uniform weight
       on the levels of categoric factors; on a constrained region the mean over about
       16 000 feasible quasi-random points).

Coordinate exchange: from a random feasible start, each coordinate of each run is set in
turn to the best of a grid of values (21 levels over [-1, 1] for a numeric factor, every
level of a categoric one) among those that keep the run inside the constraints, until a
whole pass changes nothing; a finer local grid then polishes the numeric settings. The
best of ``starts`` random starts is kept; every start comes from ``seed``, so the same seed
gives the same design. A start on the -1/0/+1 grid is first improved by Fedorov's exchange
of runs for candidate points (Fedorov 1972, as AlgDesign's ``optFederov``), a continuous start
by coordinate exchange first; the two alternate until neither gains. The updates are
evaluated in batches (``M - f f' + g g'`` for every candidate ``g``) from ``M^-1`` carried by
rank-two updates, with a tiny ridge so a singular start can still climb.

Design-Expert's extras: ``lof_points`` runs spread by distance (each the feasible
candidate farthest from every run so far: lack-of-fit points) and ``replicates`` runs that
repeat model points (each the repeat that best improves the criterion). By default, as
Design-Expert: ``p`` model points, 5 lack-of-fit points and 5 replicates; with ``runs=N``
every run is chosen by the criterion unless ``lof_points``/``replicates`` ask for some.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..errors import ParameterError
from ..terms import model_terms, n_columns
from .core import Design, as_factor_space, resolve_seed

# the exchange step lives in .exchange (augment uses it too); its public names stay importable here
from .exchange import (
    CRITERIA,
    GRID,  # noqa: F401 - kept importable from here (old imports)
    MAX_COLUMNS,  # noqa: F401 - kept importable from here (old imports)
    MAX_RUNS,
    MAX_STARTS,
    ExchangeProblem,
    at_every_level,
    candidate_pool,
    check_columns,
    check_criterion,
    criterion_value,
    information,
    moment_matrix,
)

__all__ = ["optimal", "criterion_value", "moment_matrix", "CRITERIA", "information", "farthest_candidates", "run_budget"]


def farthest_candidates(D: np.ndarray, pool: np.ndarray, space, count: int) -> np.ndarray:
    """``count`` candidates each farthest (coded distance; a categoric mismatch counts 2)
    from every run so far: Design-Expert's lack-of-fit points, spread by distance."""
    num = space.numeric_index
    cat = [i for i in range(len(space)) if i not in num]
    cands = at_every_level(pool, space)
    out = []
    cur = D.copy()
    for _ in range(count):
        d = np.sqrt(((cands[:, None, num] - cur[None, :, num]) ** 2).sum(-1))
        if cat:
            d = d + 2.0 * (cands[:, None, cat] != cur[None, :, cat]).sum(-1)
        best = int(np.argmax(d.min(axis=1)))
        out.append(cands[best])
        cur = np.vstack([cur, cands[best]])
    return np.array(out).reshape(count, len(space))


def run_budget(p: int, runs: Any, lof_points: Any, replicates: Any, starts: Any = None) -> tuple[int, int, int]:
    """Runs, lack-of-fit points and replicates of an optimal design with ``p`` model columns:
    each given count a whole number >= 0 (``starts`` is only checked); without ``runs``, p
    model points plus 5 lack-of-fit points and 5 replicates (as Design-Expert proposes),
    with ``runs`` none of either unless asked for."""
    for name, given in (("runs", runs), ("lof_points", lof_points), ("replicates", replicates), ("starts", starts)):
        if given is not None and (isinstance(given, (bool, np.bool_)) or int(given) != given or given < 0):
            raise ParameterError(name, f"{name} must be a whole number >= 0 (got {given!r})")
    if runs is None:
        n_lof = 5 if lof_points is None else int(lof_points)
        n_rep = 5 if replicates is None else int(replicates)
        return p + n_lof + n_rep, n_lof, n_rep
    return int(runs), 0 if lof_points is None else int(lof_points), 0 if replicates is None else int(replicates)


def optimal(
    factors: Any,
    model: str = "quadratic",
    criterion: str = "I",
    runs: int | None = None,
    lof_points: int | None = None,
    replicates: int | None = None,
    constraints: Any = None,
    seed: Any = None,
    starts: int | None = None,
    randomize: bool = True,
) -> Design:
    """An exact D-, I- or A-optimal design by coordinate exchange (Meyer & Nachtsheim 1995).

    Parameters
    ----------
    factors : FactorSpace, mapping or list
        Numeric (``"NAME=LOW:HIGH"``) and categoric (``"NAME=cat:L1,L2"``) factors.
    model : {"linear", "2fi", "quadratic", "cubic"}
        The model the design must support (:func:`rsm_lrg.terms.model_terms`).
    criterion : {"D", "I", "A"}, default "I"
        Design-Expert's default for response surfaces is I.
    runs : int or None
        Total runs. ``None``: Design-Expert's default, ``p + lof + replicates`` with
        5 lack-of-fit points and 5 replicates unless given.
    lof_points, replicates : int or None
        Lack-of-fit points (spread by distance) and replicates of model points. With
        ``runs`` given both default to 0; without, to 5.
    constraints : str, list of str or Constraints
        Inequalities in actual units (:mod:`rsm_lrg.design.constraints`); every run
        satisfies every one.
    seed : int, numpy.random.Generator or None
        Seeds the random starts and the run order (``None``: drawn and recorded).
    starts : int or None
        Random starts in the continuous region; twice as many start on the -1/0/+1 grid
        and one more is a sequential build (default 6 for up to 10 model columns, 4 up
        to 21, 2 beyond: with these the median D-efficiency is above R AlgDesign's
        ``optFederov`` on the quadratic benchmarks, ``benchmarks/bench_design.py``).
    randomize : bool
        ``False``: run order = standard order (model points, replicates, lof points).

    Returns
    -------
    Design
        ``kind="optimal"``; ``options`` holds the criterion, its value
        (:func:`criterion_value`), the model, the numbers of model points, replicates and
        lack-of-fit points, the constraints and the seed.

    Examples
    --------
    >>> d = optimal(["x=0:1", "y=0:1"], model="quadratic", criterion="D", runs=9, seed=1)
    >>> d.n_runs, round(d.options["criterion_value"], 4)
    (9, 0.4622)
    """
    from .constraints import Constraints

    space = as_factor_space(factors)
    crit = check_criterion(criterion)
    terms = model_terms(space.letters, model, space.categoric or None)
    p = n_columns(terms)
    check_columns(p, model, len(space))
    if constraints is not None and not isinstance(constraints, Constraints):
        constraints = Constraints.parse(constraints, space)
    runs, L, R = run_budget(p, runs, lof_points, replicates, starts)
    n_model = runs - L - R
    if n_model < 0:
        raise ParameterError("runs", f"{L} lack-of-fit points and {R} replicates are more than the {runs} runs; the {model} "
                         f"model in {len(space)} factors needs at least {p} model points besides them")
    if n_model < p:
        raise ParameterError("runs", f"{runs} runs leave {n_model} model points after {L} lack-of-fit points and {R} replicates; "
                         f"the {model} model in {len(space)} factors needs at least {p} (one per coefficient)")
    if runs > MAX_RUNS:
        raise ParameterError("runs", f"at most {MAX_RUNS} runs (got {runs})")
    rng, used_seed = resolve_seed(seed)
    W = moment_matrix(space, terms, constraints) if crit == "I" else None
    pool = candidate_pool(space, constraints, seed=int(rng.integers(2 ** 31)))
    prob = ExchangeProblem(space, terms, crit, W, constraints, pool)
    if starts is None:
        starts = 6 if p <= 10 else (4 if p <= 21 else 2)
    starts = min(max(1, int(starts)), MAX_STARTS)
    best: Any = None
    best_v: float = math.inf
    # starts on the -1/0/+1 grid (cheap, discrete: the levels of the classical designs), then
    # continuous random starts; the sequential (greedy) build is one more start
    plan = ["greedy"] + ["coarse"] * (2 * starts) + ["continuous"] * starts
    for how in plan:
        if how == "greedy":
            D0 = prob.greedy_start(n_model)
        else:
            D0 = prob.random_start(n_model, rng, grid=how == "coarse")
        D, v = prob.improve(D0, coarse=how != "continuous")
        if v < best_v or best is None:
            best, best_v = D, v
    best, best_v = prob.improve(best, polish=True)
    # replicates: the repeat of a model point that best improves the criterion
    D = best
    for _ in range(R):
        uniq = np.unique(D, axis=0)
        scores = [prob.score(np.vstack([D, u])) for u in uniq]
        D = np.vstack([D, uniq[int(np.argmin(scores))]])
    if L:
        D = np.vstack([D, farthest_candidates(D, pool, space, L)])
    value = criterion_value(D, terms, crit, W)
    options = {
        "criterion": crit,
        "criterion_value": value,
        "model": model,
        "model_terms": p,
        "model_points": n_model,
        "replicates": R,
        "lof_points": L,
        "starts": starts,
        "constraints": [] if constraints is None else constraints.expressions,
        "algorithm": "coordinate exchange (Meyer & Nachtsheim 1995)",
    }
    return Design.from_standard(space, "optimal", D, seed=rng if used_seed is None else used_seed,
                                randomize=randomize, options=options)
