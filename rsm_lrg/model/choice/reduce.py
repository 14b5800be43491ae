"""Model reduction by backward elimination, keeping the model hierarchical.

Starting from a full model, one term at a time is removed:

* ``criterion="p"`` (Design-Expert's "backward, alpha out"): among the terms that may be
  removed, the one with the largest partial-F p-value goes, while that p-value exceeds
  ``alpha_out`` (default 0.1). The p-values are those of the current model's ANOVA
  (Type III, ``SS_j = b_j² / C_jj`` as in :mod:`rsm_lrg.model.readings.anova`; a categoric term with
  L levels leaves as a whole, its L - 1 columns tested jointly).

The starting model is factorised once (:mod:`rsm_lrg.model.engines.least_squares`); every smaller
model is a sub-model of that factor (a QR of a p x p matrix), never a refit of the runs.
* ``criterion="aicc"``: the removal that lowers the corrected Akaike criterion most,
  while any removal lowers it. ``AICc = n ln(SS_res/n) + n ln(2π) + n + 2K + 2K(K+1)/(n-K-1)``
  with ``K = p + 1`` (p coefficients including intercept and blocks, plus the variance;
  Burnham & Anderson, *Model Selection and Multimodel Inference*, 2nd ed., Eq. 2.14).

**Hierarchy**: a term may only be removed when no remaining term contains it — ``s`` is
contained in ``t`` when every exponent of ``s`` is at most that of ``t`` (so ``A`` stays
while ``AC`` or ``A^2`` stays; in a cubic model ``AB`` stays while ``A^2B`` stays).
The intercept and blocks are never removed.

On the paper's Table 4 at ``alpha_out = 0.1`` the p-value route keeps A, B, C, D, AC, C²,
D² (issue 6).

>>> import rsm_lrg
>>> r = reduce_terms(rsm_lrg.load_table4(), "tcr_c_per_min")
>>> r.kept
('Intercept', 'A', 'B', 'C', 'D', 'AC', 'C^2', 'D^2')
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...errors import ParameterError

__all__ = ["reduce_terms", "reduce_inputs", "Reduction", "removable", "CRITERIA", "aicc"]

#: Accepted values of ``criterion``.
CRITERIA = ("p", "aicc")


def removable(terms: Sequence) -> list:
    """Terms that no other remaining term contains (hierarchy), intercept excluded.

    >>> from rsm_lrg.model.build.terms import model_terms
    >>> [t.name for t in removable(model_terms("AB", "quadratic"))]
    ['AB', 'A^2', 'B^2']
    """
    out = []
    for s in terms:
        if s.order == 0:
            continue
        inside = any(t is not s and t.key != s.key and all(a <= b for a, b in zip(s.powers, t.powers))
                     and (not s.diff or s.diff == t.diff) for t in terms)
        if not inside:
            out.append(s)
    return out


def aicc(ss_res: float, n: int, p: int) -> float:
    """Corrected AIC of a Gaussian linear model (see the module docstring) [-]."""
    K = p + 1
    if n - K - 1 <= 0 or ss_res <= 0:
        return math.inf if ss_res > 0 else -math.inf
    return n * math.log(ss_res / n) + n * math.log(2 * math.pi) + n + 2 * K + 2 * K * (K + 1) / (n - K - 1)


def _term_p_values(ls, groups: Sequence[Sequence[int]]) -> list[float]:
    """Partial-F p-value of each group of columns of a fit (a term: its columns jointly,
    ``F = (SS_S / |S|) / MS_res`` with ``SS_S = b_S' (C_SS)^-1 b_S`` as in the ANOVA;
    ``fdtrc``)."""
    from ..contract.statistics import fdtrc  # the t and F tails without importing SciPy

    df = ls.df_resid
    if df <= 0:
        return [math.nan] * len(groups)
    out = []
    for g in groups:
        with np.errstate(divide="ignore", invalid="ignore"):
            f = ls.partial_ss(list(g)) / len(g) / ls.sigma2
        out.append(float(fdtrc(len(g), df, f)))
    return out


@dataclass(frozen=True)
class Reduction:
    """Outcome of backward elimination (frozen).

    Attributes
    ----------
    kept : tuple of str
        Term names kept, in model order (intercept first).
    removed : tuple of str
        Term names removed, in the order they went.
    steps : pandas.DataFrame
        One row per removal: ``step, term, p, aicc_before, aicc_after``.
    criterion : str
    alpha_out : float
    start_model : str
    """

    kept: tuple
    removed: tuple
    steps: Any = field(repr=False)
    criterion: str = "p"
    alpha_out: float = 0.1
    start_model: str = "quadratic"

    def describe(self) -> str:
        """One line: ``Backward elimination (p > 0.1, hierarchy kept): removed AB, A^2``."""
        crit = f"p > {self.alpha_out:g}" if self.criterion == "p" else "AICc"
        return f"Backward elimination ({crit}, hierarchy kept): removed {', '.join(self.removed) or 'nothing'}"

    def to_dict(self) -> dict:
        """``{"criterion", "alpha_out", "start_model", "kept", "removed", "steps"}``."""
        steps = [{k: (None if isinstance(v, float) and not math.isfinite(v) else v) for k, v in r.items()}
                 for r in self.steps.to_dict(orient="records")]
        return {"criterion": self.criterion, "alpha_out": self.alpha_out, "start_model": self.start_model,
                "kept": list(self.kept), "removed": list(self.removed), "steps": steps}


def reduce_terms(data: Any, response: str, factors: Any = None, block: str | None = None, model: str = "quadratic", *,
                 alpha_out: float = 0.1, criterion: str = "p", terms: Any = None, intercept: bool = True,
                 transform: Any = None) -> Reduction:
    """Backward elimination keeping hierarchy (see the module docstring).

    Parameters
    ----------
    data, response, factors, block, model
        As for :func:`rsm_lrg.fit`; ``model`` is the starting model.
    alpha_out : float
        Remove while the largest removable p-value exceeds this (criterion ``"p"``).
    criterion : {"p", "aicc"}
    terms : sequence of str, optional
        Start from these terms instead of ``model`` (the intercept, when there is one, is
        always kept).
    intercept : bool
        Whether the model has an intercept.
    transform : str or Transform, optional
        Reduce the model of the transformed response (as :func:`rsm_lrg.fit` fits it).

    Returns
    -------
    Reduction
    """
    from ..build.inputs import model_inputs
    from ..build.transform import parse_transform

    inp = model_inputs(data, response, factors, block, transform=parse_transform(transform), origin=not intercept)
    return reduce_inputs(inp, model=model, terms=terms, intercept=intercept, alpha_out=alpha_out, criterion=criterion)


def reduce_inputs(inp: Any, *, model: str = "quadratic", terms: Any = None, intercept: bool = True,
                  alpha_out: float = 0.1, criterion: str = "p", mixture: bool = False) -> Reduction:
    """:func:`reduce_terms` on checked inputs (:func:`rsm_lrg.model.build.inputs.model_inputs`).

    ``mixture=True``: a Scheffé model (``model`` a mixture order, no intercept column;
    :mod:`rsm_lrg.model.build.mixture`) whose linear blending terms always stay (they hold the
    mean); the other terms leave as for any model, hierarchy kept (``AB`` stays while
    ``ABC`` or ``ABD`` stays)."""
    import pandas as pd

    from ..build.inputs import chosen_terms
    from ..build.terms import check_model_size, model_terms, n_columns, term_columns
    from ..engines.least_squares import factorise

    crit = str(criterion).strip().lower()
    if crit not in CRITERIA:
        raise ParameterError("criterion", f"criterion must be 'p' or 'aicc', not {criterion!r}")
    if not (isinstance(alpha_out, (int, float)) and 0.0 < alpha_out < 1.0):
        raise ParameterError("alpha_out", f"alpha_out must lie between 0 and 1, not {alpha_out!r}")
    letters, cats = inp.space.letters, inp.space.categoric
    n, nb = inp.n, inp.nb - 1
    check_model_size(n, len(letters), "linear", nb, categoric=cats)
    if mixture:
        from ...factors import MixtureComponent
        from ..build.mixture import check_mixture_terms, scheffe_names

        q = sum(isinstance(f, MixtureComponent) for f in inp.space.factors)
        names = scheffe_names(letters[:q], model, letters[q:]) if terms is None else list(terms)
        current = list(chosen_terms(names, letters, None, intercept=False))
        check_mixture_terms(current, q)
        intercept = False
    elif terms is None:
        check_model_size(n, len(letters), model, nb, categoric=cats)  # counted before any term is built
        current = list(model_terms(letters, model, cats))
    else:
        current = list(chosen_terms(list(terms), letters, cats, intercept=intercept))
    p_start = n_columns(current) + nb
    if n <= p_start:
        raise ValueError(f"{n} runs cannot fit {p_start} coefficients; start from a smaller model")
    # one factorisation of the starting model; every smaller model is a sub-model of its
    # factor (no pass over the runs again)
    start = list(current)
    full = factorise(inp.chunks(start), p_start, inp.column_names(start), shift=None if intercept else 0.0)
    full.require_full_rank("model to reduce")
    lead = 1 if intercept else 0  # the intercept's column (and the block columns after it) always stay
    col = {id(t): list(g) for t, g in zip(start[lead:], term_columns(start[lead:], lead + nb))}

    def columns(ts: list) -> list[int]:
        return sorted([*range(lead + nb), *(c for t in ts if t.order > 0 for c in col[id(t)])])

    def fitted(ts: list) -> Any:
        return full.submodel(columns(ts))

    def p_values(ls: Any, ts: list) -> dict:
        where = {c: i for i, c in enumerate(columns(ts))}
        mt = [t for t in ts if t.order > 0]
        pv = _term_p_values(ls, [[where[c] for c in col[id(t)]] for t in mt])
        return {id(t): v for t, v in zip(mt, pv)}

    steps: list[dict[str, Any]] = []
    removed = []
    while True:
        ls = fitted(current)
        p = p_values(ls, current)
        ss = ls.ss_res
        cand = removable(current)
        if mixture:  # the linear blending terms always stay
            cand = [t for t in cand if t.order > 1]
        if not intercept and len(cand) == len([t for t in current if t.order > 0]) == 1:
            cand = []  # the last term of a model without an intercept stays
        if not cand:
            break
        a_now = aicc(ss, n, ls.p)
        if crit == "p":
            pv = [(p[id(t)], t) for t in cand]
            worst_p, worst = max(pv, key=lambda z: z[0])
            if not (worst_p > alpha_out):
                break
            ss2 = fitted([t for t in current if t is not worst]).ss_res
            steps.append({"step": len(steps) + 1, "term": worst.name, "p": worst_p,
                          "aicc_before": a_now, "aicc_after": aicc(ss2, n, ls.p - worst.df)})
        else:
            best = None
            for t in cand:
                a2 = aicc(fitted([s for s in current if s is not t]).ss_res, n, ls.p - t.df)
                if best is None or a2 < best[0]:
                    best = (a2, t)
            if best is None or not best[0] < a_now:
                break
            worst = best[1]
            steps.append({"step": len(steps) + 1, "term": worst.name, "p": p[id(worst)],
                          "aicc_before": a_now, "aicc_after": best[0]})
        current = [t for t in current if t is not worst]
        removed.append(worst.name)
    frame = pd.DataFrame(steps, columns=["step", "term", "p", "aicc_before", "aicc_after"])
    return Reduction(kept=tuple(t.name for t in current), removed=tuple(removed), steps=frame,
                     criterion=crit, alpha_out=float(alpha_out), start_model=model if terms is None else "custom")
