"""Choosing the model's terms: forward, backward, stepwise and all hierarchical subsets, by
p-value, AICc or BIC (:func:`choose_terms`; Design-Expert's "Auto Select").

The starting model (an order or a term list) is factorised once
(:mod:`rsm_lrg.model.engines.least_squares`); every model compared is a sub-model of that factor (a QR
of a p x p matrix), never a refit of the runs.

* ``backward``: remove a term while the largest p-value of the removable terms exceeds
  ``alpha_out`` (``criterion="p"``), or while a removal lowers the criterion. Backward by p or
  AICc with hierarchy is :func:`rsm_lrg.model.choice.reduce.reduce_inputs`, unchanged.
* ``forward``: from the intercept, add the term whose partial-F p-value (in the model with it)
  is smallest while it is below ``alpha_in``, or the addition that lowers the criterion most
  while one does.
* ``stepwise``: by p, forward steps each followed by the backward removals (p > ``alpha_out``)
  they make possible (Design-Expert, Minitab; ``alpha_in <= alpha_out``); by AICc or BIC, at
  each step the best single addition or removal while one lowers the criterion (R's
  ``step(direction = "both")`` from the intercept-only model).
* ``all-subsets``: every hierarchical sub-model of the starting model (the intercept always
  in; a term only with every term of the starting model it contains), the best by AICc or
  BIC, and the next best listed (``subsets``). At most :data:`MAX_SUBSETS` models.

Hierarchy (``hierarchy=True``, the default): a term may enter only when every term of the
starting model that it contains is in (``A`` before ``AB`` and ``A^2``), and may leave only
when no remaining term contains it (:func:`rsm_lrg.model.choice.reduce.removable`).

Criteria (Gaussian likelihood with the variance estimated, ``K = p + 1`` parameters):
``AICc = n ln(SS_res/n) + n ln(2 pi) + n + 2K + 2K(K+1)/(n-K-1)`` (Burnham & Anderson 2002,
Eq. 2.14; :func:`rsm_lrg.model.choice.reduce.aicc`) and ``BIC = n ln(SS_res/n) + n ln(2 pi) + n + K ln n``
(Schwarz 1978); BIC differs from R's ``extractAIC(fit, k = log(n))`` by a constant, so both
choose the same model.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np

from ..build.spec import ReduceSpec, SpecError
from .dsd import TwoStage
from .reduce import Reduction, aicc, reduce_inputs, removable

__all__ = ["choose_terms", "search", "Scorer", "LeastSquaresScorer", "Selection", "bic", "MAX_SUBSETS", "TOP_SUBSETS",
           "contains"]

#: Most sub-models that ``all-subsets`` compares (beyond: use stepwise).
MAX_SUBSETS = 200_000
#: Sub-models listed by ``all-subsets`` (the best first).
TOP_SUBSETS = 5
#: Columns of :attr:`Selection.steps`.
STEP_COLUMNS = ["step", "action", "term", "p", "criterion_before", "criterion_after"]


def bic(ss_res: float, n: int, p: int) -> float:
    """Schwarz's criterion of a Gaussian linear model with ``p`` coefficients (see the
    module docstring) [-]."""
    K = p + 1
    if ss_res <= 0:
        return -math.inf
    return n * math.log(ss_res / n) + n * math.log(2 * math.pi) + n + K * math.log(n)


def contains(s: Any, t: Any) -> bool:
    """Whether term ``s`` is contained in term ``t`` (``s`` != ``t``; every exponent of ``s``
    at most that of ``t``), the relation hierarchy is about."""
    return (s.key != t.key and all(a <= b for a, b in zip(s.powers, t.powers))
            and (not s.diff or s.diff == t.diff))


@dataclass(frozen=True)
class Selection:
    """The terms chosen by forward, backward, stepwise or all-subsets selection (frozen).

    Attributes
    ----------
    kept : tuple of str
        Term names kept, in model order (intercept first).
    removed : tuple of str
        Terms of the starting model left out.
    steps : pandas.DataFrame
        One row per step: ``step, action ("add"|"remove"), term, p, criterion_before,
        criterion_after`` (empty for all-subsets).
    criterion : str
        ``"p"``, ``"aicc"`` or ``"bic"``.
    alpha_out, alpha_in : float
    method : str
        ``"backward"``, ``"forward"``, ``"stepwise"`` or ``"all-subsets"``.
    hierarchy : bool
    start_model : str
    subsets : pandas.DataFrame or None
        All-subsets: the best :data:`TOP_SUBSETS` models, ``rank, terms, aicc, bic`` and the
        scorer's numbers (least squares: ``n_coefficients``, counting the intercept and the
        blocks, and ``adj_r2``; a GLM: ``n_coefficients`` and ``deviance``), best first.
    n_compared : int
        Models whose criterion was computed.
    """

    kept: tuple
    removed: tuple
    steps: Any = field(repr=False)
    criterion: str = "p"
    alpha_out: float = 0.1
    alpha_in: float = 0.1
    method: str = "forward"
    hierarchy: bool = True
    start_model: str = "quadratic"
    subsets: Any = field(default=None, repr=False)
    n_compared: int = 0

    def to_dict(self) -> dict:
        """The keys of :meth:`rsm_lrg.model.choice.reduce.Reduction.to_dict` plus ``method``,
        ``alpha_in``, ``hierarchy``, ``n_compared`` and (all-subsets) ``subsets``."""
        def clean(rows: list[dict]) -> list[dict]:
            return [{k: (None if isinstance(v, float) and not math.isfinite(v) else v) for k, v in r.items()}
                    for r in rows]

        out = {"method": self.method, "criterion": self.criterion, "alpha_out": self.alpha_out,
               "alpha_in": self.alpha_in, "hierarchy": self.hierarchy, "start_model": self.start_model,
               "kept": list(self.kept), "removed": list(self.removed),
               "steps": clean(self.steps.to_dict(orient="records")), "n_compared": self.n_compared}
        if self.subsets is not None:
            out["subsets"] = clean(self.subsets.to_dict(orient="records"))
        return out

    def describe(self) -> str:
        """One line: the method, criterion, hierarchy, what was kept (and the runner-up subsets)."""
        crit = {"p": (f"p < {self.alpha_in:g} in" if self.method == "forward" else
                      f"p < {self.alpha_in:g} in, p > {self.alpha_out:g} out" if self.method == "stepwise" else
                      f"p > {self.alpha_out:g}"),
                "aicc": "AICc", "bic": "BIC"}[self.criterion]
        hier = "hierarchy kept" if self.hierarchy else "hierarchy not enforced"
        kept = [k for k in self.kept if k != "Intercept"]
        line = (f"{self.method.capitalize()} selection ({crit}, {hier}): kept {' '.join(kept) or 'no term'}; "
                f"left out {' '.join(self.removed) or 'nothing'}")
        if self.subsets is not None:
            line += f" ({self.n_compared} hierarchical models compared)"
        return line


def choose_terms(inp: Any, reduce: ReduceSpec, *, model: str = "quadratic", terms: Any = None, intercept: bool = True,
                 mixture: bool = False) -> Reduction | Selection | TwoStage:
    """The terms chosen from the starting model (``model`` or ``terms``) over checked inputs
    (:func:`rsm_lrg.model.build.inputs.model_inputs`) as ``reduce`` says (see the module docstring).

    Returns
    -------
    Reduction, Selection or TwoStage
        Backward elimination by p or AICc with hierarchy gives
        :func:`rsm_lrg.model.choice.reduce.reduce_inputs`'s Reduction; ``"dsd"`` the
        :class:`~rsm_lrg.model.choice.dsd.TwoStage` analysis; every other choice a Selection.

    Raises
    ------
    SpecError
        A method other than backward for a mixture model; forward, stepwise or all-subsets
        without an intercept; all-subsets over more than :data:`MAX_SUBSETS` models.
    ValueError
        No term kept (nothing explains the response), and what the fit refuses.
    """

    from ..build.inputs import chosen_terms
    from ..build.terms import check_model_size, model_terms, n_columns, term_columns
    from ..engines.least_squares import factorise

    if reduce.method == "dsd":
        from .dsd import two_stage_inputs

        if mixture or not intercept:
            raise SpecError("model", "the definitive screening analysis fits a model with an intercept in process "
                                      "factors (not a mixture or a model without intercept)")
        if terms is not None or model != "quadratic":
            raise SpecError("terms" if terms is not None else "model",
                            "the definitive screening analysis chooses among the quadratic model's terms; give no "
                            "other model or terms")
        return two_stage_inputs(inp, reduce.alpha_in)
    if reduce.method == "backward" and reduce.criterion in ("p", "aicc") and reduce.hierarchy:
        return reduce_inputs(inp, model=model, terms=terms, intercept=intercept, alpha_out=reduce.alpha_out,
                             criterion=str(reduce.criterion), mixture=mixture)
    if mixture:
        raise SpecError("reduce", "a mixture model is reduced by backward elimination with hierarchy, by p or AICc "
                                  f"(not {reduce.method} by {reduce.criterion})")
    method = reduce.method
    if not intercept and method != "backward":
        raise SpecError("reduce", f"{method} selection starts from (or keeps) the intercept: the model needs one")
    letters, cats = inp.space.letters, inp.space.categoric
    n, nb = inp.n, inp.nb - 1
    if terms is None:
        check_model_size(n, len(letters), model, nb, categoric=cats)
        start = list(model_terms(letters, model, cats))
    else:
        start = list(chosen_terms(list(terms), letters, cats, intercept=intercept))
    p_start = n_columns(start) + nb
    if n <= p_start:
        raise ValueError(f"{n} runs cannot fit {p_start} coefficients; start from a smaller model")
    full = factorise(inp.chunks(start), p_start, inp.column_names(start), shift=None if intercept else 0.0)
    full.require_full_rank("model to reduce")
    lead = 1 if intercept else 0
    pool = [t for t in start if t.order > 0]
    col = {id(t): list(g) for t, g in zip(pool, term_columns(pool, lead + nb))}
    y = np.asarray(inp.y, dtype=float)
    scorer = LeastSquaresScorer(full, col, lead + nb, n, float(np.sum((y - y.mean()) ** 2)))
    return search(pool, reduce, scorer, intercept=intercept, start_model=model if terms is None else "custom")


class Scorer(Protocol):
    """What a search asks of a family of fits (least squares, a GLM): each model is a list
    of terms of the starting model (the intercept and blocks always in)."""

    def criteria(self, ts: Sequence) -> tuple[float, float] | None:
        """``(AICc, BIC)`` of the model, or None when it cannot be judged (too few runs)."""

    def p_value(self, ts: Sequence, t: Any) -> float:
        """The p-value of term ``t`` in the model ``ts`` (``t`` among them)."""

    def extra(self, ts: Sequence) -> dict[str, float]:
        """Further numbers of a model for the all-subsets list (and ``n_coefficients``)."""


class LeastSquaresScorer:
    """Least-squares sub-models of one factorisation (partial-F p-values, Gaussian AICc/BIC)."""

    def __init__(self, full: Any, col: dict, fixed: int, n: int, ss_total: float) -> None:
        self.full, self.col, self.fixed, self.n, self.ss_total = full, col, fixed, n, ss_total

    def columns(self, ts: Sequence) -> list[int]:
        return sorted([*range(self.fixed), *(c for t in ts for c in self.col[id(t)])])

    def fitted(self, ts: Sequence) -> Any:
        return self.full.submodel(self.columns(ts))

    def criteria(self, ts: Sequence) -> tuple[float, float] | None:
        ls = self.fitted(ts)
        if self.n - ls.p - 2 <= 0:
            return None
        return aicc(ls.ss_res, self.n, ls.p), bic(ls.ss_res, self.n, ls.p)

    def p_value(self, ts: Sequence, t: Any) -> float:
        from ..contract import statistics as special

        ls = self.fitted(ts)
        if ls.df_resid <= 0:
            return math.nan
        where = {c: i for i, c in enumerate(self.columns(ts))}
        g = [where[c] for c in self.col[id(t)]]
        with np.errstate(divide="ignore", invalid="ignore"):
            f = ls.partial_ss(g) / len(g) / ls.sigma2
        return float(special.fdtrc(len(g), ls.df_resid, f))

    def extra(self, ts: Sequence) -> dict[str, float]:
        ls = self.fitted(ts)
        n = self.n
        adj = 1.0 - (ls.ss_res / (n - ls.p)) / (self.ss_total / (n - 1)) if self.ss_total > 0 else math.nan
        return {"n_coefficients": int(ls.p), "adj_r2": adj}


def search(pool: list, reduce: ReduceSpec, scorer: Scorer, *, intercept: bool = True,
           start_model: str = "quadratic") -> Selection:
    """Forward, backward, stepwise or all-subsets over the terms ``pool`` of the starting
    model (see the module docstring), the models judged by ``scorer``."""
    import pandas as pd

    method, crit = reduce.method, str(reduce.criterion)
    order = {id(t): i for i, t in enumerate(pool)}

    def value(ts: Sequence) -> float:
        c = scorer.criteria(ts)
        return math.inf if c is None else (c[0] if crit == "aicc" else c[1])

    def addable(current: list) -> list:
        out = [t for t in pool if all(t is not s for s in current)]
        if reduce.hierarchy:
            out = [t for t in out if all(any(s is c for c in current) for s in pool if contains(s, t))]
        return out

    def droppable(current: list) -> list:
        return list(removable(current)) if reduce.hierarchy else list(current)

    def sort(ts: Sequence) -> list:
        return sorted(ts, key=lambda t: order[id(t)])

    steps: list[dict[str, Any]] = []
    compared = 0
    subsets = None

    def step(action: str, t: Any, p: float, before: float, after: float) -> None:
        steps.append({"step": len(steps) + 1, "action": action, "term": t.name, "p": p, "criterion_before": before,
                      "criterion_after": after})

    if method == "all-subsets":
        current, subsets, compared = _all_subsets(pool, reduce.hierarchy, scorer, crit)
    elif crit == "p":
        current = [] if method in ("forward", "stepwise") else list(pool)
        seen = {frozenset(id(t) for t in current)}
        while True:
            changed = False
            if method in ("forward", "stepwise"):
                cand = [(scorer.p_value(sort([*current, t]), t), t) for t in addable(current)]
                cand = [c for c in cand if math.isfinite(c[0])]
                compared += len(cand)
                if cand:
                    best_p, best = min(cand, key=lambda z: z[0])
                    if best_p < reduce.alpha_in:
                        current = sort([*current, best])
                        step("add", best, best_p, math.nan, math.nan)
                        changed = True
            if method in ("backward", "stepwise"):
                while True:
                    cand = [(scorer.p_value(current, t), t) for t in droppable(current)]
                    cand = [c for c in cand if math.isfinite(c[0])]
                    compared += len(cand)
                    if not cand:
                        break
                    worst_p, worst = max(cand, key=lambda z: z[0])
                    if not worst_p > reduce.alpha_out:
                        break
                    current = [t for t in current if t is not worst]
                    step("remove", worst, worst_p, math.nan, math.nan)
                    changed = True
                    if method == "backward":
                        break
            key = frozenset(id(t) for t in current)
            if not changed or key in seen:  # nothing moved, or a stepwise cycle
                break
            seen.add(key)
    else:  # AICc or BIC: the best single move while one lowers the criterion
        current = [] if method in ("forward", "stepwise") else list(pool)
        now = value(current)
        compared = 1
        while True:
            moves = []
            if method in ("forward", "stepwise"):
                moves += [("add", t, sort([*current, t])) for t in addable(current)]
            if method in ("backward", "stepwise"):
                moves += [("remove", t, [s for s in current if s is not t]) for t in droppable(current)]
            best = None
            for action, t, ts in moves:
                v = value(ts)
                compared += 1
                if math.isfinite(v) and (best is None or v < best[0]):
                    best = (v, action, t, ts)
            if best is None or not best[0] < now:
                break
            v, action, t, ts = best
            step(action, t, math.nan, now, v)
            current, now = ts, v
    current = sort(current)
    if not current:
        raise ValueError(f"{method} selection ({crit}) kept no term: no factor explains the response")
    kept = (("Intercept",) if intercept else ()) + tuple(t.name for t in current)
    removed = tuple(t.name for t in pool if all(t is not s for s in current))
    return Selection(kept=kept, removed=removed, steps=pd.DataFrame(steps, columns=STEP_COLUMNS), criterion=crit,
                     alpha_out=float(reduce.alpha_out), alpha_in=float(reduce.alpha_in), method=method,
                     hierarchy=reduce.hierarchy, start_model=start_model, subsets=subsets, n_compared=compared)


def _all_subsets(pool: list, hierarchy: bool, scorer: Scorer, crit: str) -> tuple[list, Any, int]:
    """The best hierarchical sub-model of ``pool`` by ``crit`` (``aicc``/``bic``), the best
    :data:`TOP_SUBSETS` as a frame, and the count compared."""
    import pandas as pd

    ranked = sorted(pool, key=lambda t: t.order)  # a contained term has a lower order: it comes first
    inside = {id(t): [s for s in ranked if contains(s, t)] if hierarchy else [] for t in ranked}
    found: list[tuple[float, float, float, list]] = []
    count = 0

    def visit(i: int, chosen: list) -> None:
        nonlocal count
        if i == len(ranked):
            count += 1
            if count > MAX_SUBSETS:
                raise SpecError("reduce", f"all-subsets would compare more than {MAX_SUBSETS} models of the "
                                          f"{len(pool)} terms; start from a smaller model or use stepwise")
            c = scorer.criteria(chosen)
            if c is not None:
                found.append((c[0] if crit == "aicc" else c[1], c[0], c[1], list(chosen)))
            return
        t = ranked[i]
        visit(i + 1, chosen)
        if all(any(s is c for c in chosen) for s in inside[id(t)]):
            visit(i + 1, [*chosen, t])

    visit(0, [])
    found.sort(key=lambda z: z[0])
    position = {id(t): j for j, t in enumerate(pool)}
    rows = []
    for r, (_, a, b, ts) in enumerate(found[:TOP_SUBSETS], 1):
        names = [t.name for t in sorted(ts, key=lambda t: position[id(t)])]
        rows.append({"rank": r, "terms": " ".join(names), "aicc": a, "bic": b, **scorer.extra(ts)})
    best = found[0][3] if found else []
    return best, pd.DataFrame(rows), count
