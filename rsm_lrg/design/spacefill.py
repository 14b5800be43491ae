"""Space-filling designs for virtual runs: Latin hypercube and Sobol' points (scipy.stats.qmc).

For ``simulate`` studies the response is deterministic: no replicates are needed and a
design that spreads its runs over the whole region serves a surrogate or a flexible model
better than a response-surface design.

``latin_hypercube``
    scipy's ``LatinHypercube`` with ``optimization="random-cd"`` (centred discrepancy
    lowered by column permutations) or, with ``criterion="maximin"``, the best of several
    seeded hypercubes by the smallest distance between runs. On a constrained region the
    hypercube is drawn on the box and its infeasible runs replaced, one at a time, by the
    feasible point of a Sobol' candidate set farthest from every run kept (the Latin
    property then holds only for the runs kept; the design says so).
``sobol``
    scrambled Sobol' points (the first N points of the sequence; N a power of 2 keeps the
    balance properties); on a constrained region the first N feasible points of the
    sequence.

Categoric factors take their levels in turn (run i at level i mod L, then shuffled from
the seed), so every level gets its share of the runs.
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np

from ..errors import ParameterError
from .core import Design, as_factor_space, resolve_seed

__all__ = ["latin_hypercube", "sobol"]

#: Largest space-filling design built [runs].
MAX_RUNS = 100_000
#: Largest maximin Latin hypercube (pairwise distances) [runs].
MAX_MAXIMIN = 5000
#: Largest Latin hypercube whose discrepancy is optimised (beyond: a plain one) [runs].
MAX_DISCREPANCY = 1000


def _prepare(factors, runs, constraints):
    from .constraints import Constraints

    space = as_factor_space(factors)
    if isinstance(runs, (bool, np.bool_)) or int(runs) != runs or not 2 <= runs <= MAX_RUNS:
        raise ParameterError("runs", f"runs must be a whole number from 2 to {MAX_RUNS} (got {runs!r})")
    if not space.numeric_index:
        raise ValueError("a space-filling design needs at least one numeric factor")
    if constraints is not None and not isinstance(constraints, Constraints):
        constraints = Constraints.parse(constraints, space)
    return space, int(runs), constraints


def _full(space, U: np.ndarray, rng) -> np.ndarray:
    """Unit-cube points (n x numeric) to coded runs with categoric levels in turn."""
    n = U.shape[0]
    out = np.zeros((n, len(space)))
    out[:, space.numeric_index] = 2.0 * U - 1.0
    for j, f in enumerate(space.factors):
        if f.kind == "categoric":
            out[:, j] = rng.permutation(np.arange(n) % f.n_levels)
    return out


def _sobol_unit(d: int, n: int, seed) -> np.ndarray:
    from scipy.stats import qmc

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # balance warning for n not a power of 2
        return qmc.Sobol(d, scramble=True, seed=seed).random(n)


def latin_hypercube(factors: Any, runs: int, criterion: str = "discrepancy", constraints: Any = None,
                    seed: Any = None, randomize: bool = True, tries: int = 20) -> Design:
    """Latin hypercube design of ``runs`` runs (McKay, Beckman & Conover 1979).

    Parameters
    ----------
    criterion : {"discrepancy", "maximin"}
        ``"discrepancy"``: scipy's ``random-cd`` optimisation; ``"maximin"``: the best of
        ``tries`` hypercubes by their smallest pairwise distance (coded units).
    constraints : str, list or Constraints
        Every run satisfies them (see the module docstring).

    Returns
    -------
    Design
        The runs in coded and actual units, in run order (:meth:`~rsm_lrg.design.Design.to_frame`
        gives the design CSV layout).
    """
    from scipy.spatial.distance import pdist
    from scipy.stats import qmc

    space, n, cons = _prepare(factors, runs, constraints)
    if criterion not in ("discrepancy", "maximin"):
        raise ParameterError("criterion", f"criterion must be 'discrepancy' or 'maximin' (got {criterion!r})")
    if criterion == "maximin" and n > MAX_MAXIMIN:
        raise ParameterError("runs", f"the maximin criterion compares every pair of runs; at most {MAX_MAXIMIN} runs "
                         f"(got {n}); use criterion='discrepancy'")
    rng, used = resolve_seed(seed)
    d = len(space.numeric_index)
    if criterion == "discrepancy":
        opt = "random-cd" if n <= MAX_DISCREPANCY else None
        U = qmc.LatinHypercube(d, optimization=opt, seed=rng).random(n)
    else:
        best, best_d = None, -1.0
        for _ in range(max(1, int(tries))):
            cand = qmc.LatinHypercube(d, seed=rng).random(n)
            dist = pdist(cand).min() if n > 1 else 0.0
            if dist > best_d:
                best, best_d = cand, dist
        U = best
    coded = _full(space, U, rng)
    replaced = 0
    if cons is not None and cons:
        ok = cons.feasible_coded(coded)
        replaced = int((~ok).sum())
        if replaced:
            pool = _full(space, _sobol_unit(d, 8192, rng), rng)
            pool = pool[cons.feasible_coded(pool)]
            if not len(pool):
                from .exchange import thin_region_error

                raise thin_region_error(cons)
            keep = coded[ok]
            num = space.numeric_index
            for i in np.flatnonzero(~ok):
                dd = np.sqrt(((pool[:, None, num] - (keep[None, :, num] if len(keep) else pool[None, :1, num])) ** 2)
                             .sum(-1)).min(axis=1)
                j = int(np.argmax(dd))
                pt = pool[j].copy()
                pt[[c for c in range(len(space)) if c not in num]] = coded[i, [c for c in range(len(space))
                                                                              if c not in num]]
                coded[i] = pt
                keep = np.vstack([keep, pt])
                pool = np.delete(pool, j, axis=0)
    if criterion == "discrepancy" and n > MAX_DISCREPANCY:
        criterion = "none (plain Latin hypercube: more runs than the discrepancy optimisation takes)"
    options = {"criterion": criterion, "replaced_for_constraints": replaced,
               "constraints": [] if cons is None else cons.expressions,
               "note": (f"{replaced} runs moved inside the constraints (the Latin property holds for the others)"
                        if replaced else None)}
    return Design.from_standard(space, "latin-hypercube", coded, seed=used if used is not None else rng,
                                randomize=randomize, options=options)


def sobol(factors: Any, runs: int, constraints: Any = None, seed: Any = None, randomize: bool = True) -> Design:
    """Scrambled Sobol' points (Sobol' 1967; scipy.stats.qmc.Sobol); with constraints the first
    ``runs`` feasible points of the sequence.

    Parameters
    ----------
    factors : FactorSpace, mapping or list
        As for :func:`~rsm_lrg.design.box_behnken`.
    runs : int
        The number of runs.
    constraints : str or list of str, optional
        Inequalities in actual units (``"v**2/a <= s"``); only feasible points are kept.
    seed, randomize
        As for :func:`~rsm_lrg.design.box_behnken`.

    Returns
    -------
    Design
        The runs in coded and actual units, in run order (:meth:`~rsm_lrg.design.Design.to_frame`
        gives the design CSV layout).
    """
    space, n, cons = _prepare(factors, runs, constraints)
    rng, used = resolve_seed(seed)
    d = len(space.numeric_index)
    from scipy.stats import qmc

    eng = qmc.Sobol(d, scramble=True, seed=rng)
    pts: list = []
    drawn = 0
    while sum(len(p) for p in pts) < n:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)
            U = eng.random(max(n, 256))
        drawn += len(U)
        c = _full(space, U, rng)
        if cons is not None and cons:
            c = c[cons.feasible_coded(c)]
        pts.append(c)
        if drawn > 200 * n + 65536 and not sum(len(p) for p in pts):
            from .exchange import thin_region_error

            raise thin_region_error(cons)
    coded = np.vstack(pts)[:n]
    for j, f in enumerate(space.factors):  # levels in turn over the runs kept
        if f.kind == "categoric":
            coded[:, j] = rng.permutation(np.arange(n) % f.n_levels)
    options = {"power_of_two": bool(n & (n - 1) == 0), "constraints": [] if cons is None else cons.expressions,
               "note": None if n & (n - 1) == 0 or cons else "runs not a power of 2: Sobol' balance is partial"}
    return Design.from_standard(space, "sobol", coded, seed=used if used is not None else rng,
                                randomize=randomize, options=options)
