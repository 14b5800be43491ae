"""Augmenting a design: runs added to the runs already made, which stay as they are.

Three ways, as in Design-Expert's and JMP's *Augment Design*:

``method="optimal"``
    Add ``runs`` runs chosen D-, I- or A-optimally **given** the existing runs (coordinate
    exchange on the new runs only; :mod:`rsm_lrg.design.optimal`) so that a bigger model
    (linear -> 2FI -> quadratic -> cubic) becomes estimable; constraints respected.
``method="ccd"``
    Star points at ±alpha on every numeric factor's axis and centre points: a two-level
    factorial (with or without centre points) becomes a central composite design (Box &
    Wilson 1951); with categoric factors at every combination of their levels.
    ``alpha="rotatable"`` by default (F^(1/4), F the factorial runs), or
    ``"face"``, ``"orthogonal"``, ``"practical"`` or a number (see
    :func:`~rsm_lrg.design.ccd_alpha`).
``method="foldover"``
    The fold-over of a two-level screening design: every run with the signs of the chosen
    factors reversed (all factors by default, the full fold-over, which frees the main
    effects from their two-factor-interaction aliases; Box, Hunter & Hunter 2005,
    section 6.8). Centre runs are not repeated.

The original runs keep their settings, their ``std_order`` (1..n0) and their run order
(they come first); the added runs follow (``std_order`` n0+1..), their run order
randomised from the seed. With ``new_block=True`` the added runs form a new block (the
original runs are block 1 when the design was not blocked).

Blocks in the optimal criterion. When the augmented design has two or more blocks (a new
block, or a blocked design added to), the block effects are nuisance parameters of the fit
and the criterion accounts for them: each run's row of the information matrix is the model
row ``f(x)`` followed by its block contrasts, coded exactly as the fit codes a block column
(:func:`rsm_lrg.terms.block_contrasts`, sum-to-zero; blocks numbered in sorted order, the
added runs' block last), ``M = [X B]'[X B]``. Then

``D``  maximises ``det(M)`` of the full matrix. This equals
       ``det(B'B) det(X'(I - P_B)X)``, and ``B'B`` is fixed by the block sizes, so it is the
       same as maximising the determinant of the model part adjusted for blocks.
``A``  minimises ``trace`` of the model-term block of ``M^-1`` (the coefficient variances
       after the blocks are estimated; block effects not counted).
``I``  minimises ``trace(M^-1 W_b)`` with ``W_b`` the region moment matrix ``W`` padded
       with zeros for the block columns: the average prediction variance over the region
       of the average block (the intercept is the mean over blocks, as in the fit).

A block shift absorbs the mean of the added runs, so only their spread about their own mean
informs the model: a run set that is best ignoring the block can be poor with it (e.g. the
added runs' intercept information is lost). ``options["block_aware"]`` says whether the
criterion included the blocks.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import ParameterError
from .core import Design, resolve_seed

__all__ = ["augment", "METHODS"]

#: Augmentation methods.
METHODS = ("optimal", "ccd", "foldover")


def augment(
    design: Design,
    method: str = "optimal",
    *,
    model: str = "quadratic",
    criterion: str = "D",
    runs: int | None = None,
    alpha: Any = "rotatable",
    center: int = 2,
    fold: list | None = None,
    new_block: bool = False,
    constraints: Any = None,
    seed: Any = None,
    starts: int | None = None,
    randomize: bool = True,
) -> Design:
    """Add runs to ``design``; the original runs are kept untouched and first.

    Parameters
    ----------
    design : Design
        The runs already made (e.g. from :func:`~rsm_lrg.design.read_design`).
    method : {"optimal", "ccd", "foldover"}
    model : str
        ``optimal``: the model the augmented design must support.
    criterion : {"D", "I", "A"}
        ``optimal``: the criterion of the added runs given the existing ones.
    runs : int or None
        ``optimal``: runs to add (default: enough for the model, ``p - n0`` but at least
        ``max(4, p // 2)``).
    alpha : str or float
        ``ccd``: star distance [coded units].
    center : int
        ``ccd``: centre points added with the star points.
    fold : list of str or None
        ``foldover``: names or letters of the factors whose signs are reversed (default all).
    new_block : bool
        Put the added runs in a new block. ``optimal``: whenever the result has two or more
        blocks the criterion includes the block effects as nuisance parameters (module
        docstring); ``options["block_aware"]`` records it.
    constraints : str, list or Constraints
        ``optimal``: every added run satisfies them.
    seed, starts, randomize
        Search starts and run order of the added runs.

    Returns
    -------
    Design
        The original runs first and untouched, then the added runs (a new block with
        ``new_block=True``).
    """
    if not isinstance(design, Design):
        raise TypeError("design must be a Design (read one with rsm_lrg.design.read_design)")
    if method not in METHODS:
        raise ParameterError("method", f"method must be one of {', '.join(METHODS)} (got {method!r})")
    space = design.factors
    n0 = design.n_runs
    order0 = np.argsort(design.run_order, kind="stable")
    old = design.coded_runs[order0]  # run order
    num = space.numeric_index
    rng, used = resolve_seed(seed)
    options: dict = {"original_runs": n0, "method": method}
    if method == "optimal":
        from ..terms import model_terms, n_columns
        from .constraints import Constraints
        from .exchange import (
            MAX_RUNS,
            ExchangeProblem,
            candidate_pool,
            check_columns,
            check_criterion,
            criterion_value,
            moment_matrix,
        )

        crit = check_criterion(criterion)
        terms = model_terms(space.letters, model, space.categoric or None)
        p = n_columns(terms)
        check_columns(p, model, len(space))
        if runs is None:
            runs = max(p - n0, 4, p // 2)
        if isinstance(runs, (bool, np.bool_)) or int(runs) != runs or runs < 1:
            raise ParameterError("runs", f"runs to add must be a whole number >= 1 (got {runs!r})")
        runs = int(runs)
        if n0 + runs > MAX_RUNS:
            raise ParameterError("runs", f"at most {MAX_RUNS} runs in all (got {n0} + {runs} to add)")
        if n0 + runs < p:
            raise ParameterError("runs", f"{n0} runs + {runs} added cannot fit the {model} model's {p} terms; add at least "
                             f"{p - n0} runs")
        if constraints is not None and not isinstance(constraints, Constraints):
            constraints = Constraints.parse(constraints, space)
        W = moment_matrix(space, terms, constraints) if crit == "I" else None
        pool = candidate_pool(space, constraints, seed=int(rng.integers(2 ** 31)))
        b_old, b_new = _block_labels(design, order0, new_block)
        labels = np.unique(np.concatenate([b_old, [b_new]]))
        block_aware = len(labels) > 1
        old_p, search_crit = p, crit
        if block_aware and n0 + runs < p + len(labels) - 1:
            raise ParameterError("runs", f"{n0} runs + {runs} added cannot fit the {model} model's {p} terms and "
                             f"{len(labels) - 1} block effects; add at least {p + len(labels) - 1 - n0} runs")
        if block_aware:  # the block contrasts as one more (held) coordinate and term
            codes = np.searchsorted(labels, b_old).astype(float)
            new_code = float(np.searchsorted(labels, b_new))
            if crit == "A":  # trace of the model-term block of M^-1 = trace(M^-1 W) with W = I padded
                W = np.eye(p)
            xspace, terms, W, cons_x = _with_block(space, terms, W, constraints, len(labels))
            old = np.column_stack([old, codes])
            pool = np.column_stack([pool, np.full(len(pool), new_code)])
            search_crit = "I" if crit == "A" else crit  # A on the model part: trace(M^-1 [I 0; 0 0])
            prob = _blocked_problem_class()(xspace, terms, search_crit, W, cons_x, pool)
            prob.hold_block(new_code)
        else:
            prob = ExchangeProblem(space, terms, crit, W, constraints, pool)
        nstarts = starts or (8 if p <= 21 else 3)
        best, best_v = None, np.inf
        plan = ["greedy"] + ["coarse"] * nstarts + ["continuous"] * nstarts
        for how in plan:
            if how == "greedy":
                new0 = prob.greedy_start(runs, fixed=old)
            else:
                new0 = prob.random_start(runs, rng, grid=how == "coarse")
            D, v = prob.improve(np.vstack([old, new0]), fixed=n0, coarse=how != "continuous")
            if best is None or v < best_v:
                best, best_v = D, v
        best, _ = prob.improve(best, fixed=n0, polish=True)
        value = criterion_value(best, terms, search_crit, W)
        new = best[n0:, :len(space)]
        old = old[:, :len(space)]
        options.update(criterion=crit, model=model, model_terms=old_p, criterion_value=value,
                       block_aware=bool(block_aware),
                       constraints=[] if constraints is None else constraints.expressions)
    elif method == "ccd":
        from .composite import ccd_alpha

        kn = len(num)
        if kn < 2:
            raise ValueError("a central composite design needs at least two numeric factors")
        c = old[:, num]
        fact = np.all(np.isin(c, (-1.0, 1.0)), axis=1)
        if not np.all(fact | np.all(c == 0.0, axis=1)):
            raise ValueError("the design is not a two-level factorial with centre points (a run has a numeric "
                             "setting other than -1, 0 or +1); use method='optimal'")
        if isinstance(center, (bool, np.bool_)) or int(center) != center or center < 0:
            raise ParameterError("center", f"center must be a whole number >= 0 (got {center!r})")
        n_combos = 1
        for f in space.factors:
            if f.kind == "categoric":  # the positions not in num
                n_combos *= f.n_levels
        F = max(1, int(fact.sum()) // n_combos)  # factorial runs per level combination
        a = float(alpha) if isinstance(alpha, (int, float)) else None
        if a is None:
            if str(alpha).lower() in ("rotatable", "r"):
                a = F ** 0.25
            else:
                a = ccd_alpha(kn, alpha, (int(np.sum(~fact)), int(center)), new_block)
        if not (np.isfinite(a) and a > 0):
            raise ParameterError("alpha", f"alpha must be a finite number > 0 (got {alpha!r})")
        star = []  # star and centre points, repeated at every level combination (the crossed layout)
        for j in num:
            for sgn in (-1.0, 1.0):
                r = np.zeros(len(space))
                r[j] = sgn * a
                star.append(r)
        star += [np.zeros(len(space)) for _ in range(int(center))]
        from .exchange import at_every_level

        new = at_every_level(np.array(star), space)
        options.update(alpha=a, center_added=int(center), factorial_runs=F)
    else:
        cols = list(num)
        if fold:
            cols = []
            for name in fold:
                try:
                    f = space[name]
                except KeyError:
                    raise ParameterError("fold", f"{name!r} is not a factor of the design") from None
                if f.kind != "numeric":
                    raise ParameterError("fold", f"{name!r} is categoric; only numeric factors are folded")
                cols.append(space.factors.index(f))
        keep = ~np.all(old[:, num] == 0.0, axis=1)
        new = old[keep].copy()
        new[:, cols] = -new[:, cols]
        new = new + 0.0
        options.update(fold=[space.factors[j].letter for j in cols])
    if not len(new):
        raise ValueError("nothing to add")
    n_new = len(new)
    coded = np.vstack([old, new])
    std = np.concatenate([design.std_order[order0], np.arange(n0 + 1, n0 + n_new + 1)])
    perm = rng.permutation(n_new) if randomize else np.arange(n_new)
    run_new = np.empty(n_new, dtype=int)
    run_new[perm] = np.arange(n0 + 1, n0 + n_new + 1)
    run = np.concatenate([np.arange(1, n0 + 1), run_new])
    blocks = None
    if new_block or design.blocks is not None:
        b0, bn = _block_labels(design, order0, new_block)
        blocks = np.concatenate([b0, np.full(n_new, bn)])
    options.update(seed=used, randomize=bool(randomize), new_block=bool(new_block))
    return Design(space, "augmented", coded, std, run, blocks, options)


def _block_labels(design: Design, order0: np.ndarray, new_block: bool) -> tuple[np.ndarray, int]:
    """Block of each original run (run order; all 1 when not blocked) and of the added runs."""
    n0 = design.n_runs
    b0 = design.blocks[order0] if design.blocks is not None else np.ones(n0, dtype=int)
    bn = int(b0.max()) + 1 if new_block else int(b0.max())
    return b0, bn


class _HeldColumns:
    """Constraints seen through the factor columns only (the block coordinate dropped)."""

    def __init__(self, constraints, k: int):
        self.c, self.k = constraints, k

    def __bool__(self) -> bool:
        return bool(self.c)

    def feasible_coded(self, coded, tol: float = 1e-9) -> np.ndarray:
        return self.c.feasible_coded(np.asarray(coded)[:, :self.k], tol)


def _with_block(space, terms, W, constraints, n_blocks: int):
    """The factor space and terms with the block as one more categoric coordinate (level
    index = block code 0..b-1) and one more term whose columns are the fit's block
    contrasts; ``W`` padded with zeros for them; constraints on the factor columns only.

    The block term's columns are :func:`rsm_lrg.terms.effect_codes` of the code, which is
    what :func:`rsm_lrg.terms.block_contrasts` (the fit's block coding, through
    :func:`rsm_lrg.terms.model_matrix`) returns: the same routine, not a second one.
    """
    from ..factors import CategoricFactor, FactorSpace, letters_for
    from ..terms import Term, n_columns

    k = len(space)
    names = {f.name for f in space.factors}
    name = "augment_block"
    while name in names:
        name += "_"
    used = {f.letter for f in space.factors}
    letter = next(L for L in letters_for(k + 27) if L not in used)
    levels = tuple(str(i + 1) for i in range(n_blocks))
    xspace = FactorSpace(tuple(space.factors) + (CategoricFactor(name, levels, letter),))
    bterm = Term(powers=(0,) * k + (1,), name="Block", cat=((k, levels),), cat_letters=(letter,))
    xterms = list(terms) + [bterm]
    Wx = None
    if W is not None:
        Wx = np.zeros((n_columns(xterms),) * 2)
        Wx[:W.shape[0], :W.shape[1]] = W
    cons = None if constraints is None else _HeldColumns(constraints, k)
    return xspace, xterms, Wx, cons


def _blocked_problem_class():
    from .exchange import ExchangeProblem

    class _Blocked(ExchangeProblem):
        """Exchange with the block coordinate held at the added runs' block."""

        def hold_block(self, code: float) -> None:
            j = len(self.space) - 1
            self.code = code
            self.values[j] = np.array([code])
            keep = self.candidates[:, j] == code
            self.candidates, self.cand_rows = self.candidates[keep], self.cand_rows[keep]

        def random_start(self, n: int, rng, grid: bool = False) -> np.ndarray:
            D = super().random_start(n, rng, grid)
            D[:, -1] = self.code
            return D

    return _Blocked

