"""The two-stage analysis of a definitive screening design (``fit --reduce dsd``).

Jones, B. & Nachtsheim, C. J. (2017). Effective design-based model selection for definitive
screening designs. *Technometrics* 59(3), 319-329.

A definitive screening design (DSD, :func:`rsm_lrg.design.definitive_screening`) is a fold-over
design: its runs are ``P`` mirror pairs ``(x, -x)`` and ``c`` centre runs. Every main effect
(an odd function of the settings) lies in the *odd* space spanned by the pair differences, and
the intercept, the two-factor interactions and the squares (even functions) in the *even*
space, orthogonal to it. The response splits accordingly, ``Y = Y_ME + Y_2nd``, and the two
parts are analysed apart. In the orthonormal coordinates used here,

* odd: ``z_k = (y_i - y_j) / √2`` for the pair ``(i, j)``, the main-effect rows ``√2 x_i``;
* even: ``w_k = (y_i + y_j) / √2`` with term rows ``√2 t(x_i)``, and, with centre runs,
  ``w_0 = √c ȳ_centre`` with term rows ``√c t(0)``; the ``c - 1`` contrasts among the centre
  runs are pure error.

**Stage 1** (main effects) regresses ``z`` on the main effects. Its ``P - m`` residual degrees
of freedom (the *fake factors*: the conference matrix's columns left unused) and the ``c - 1``
pure-error ones give an error variance free of any second-order effect (third-order effects
assumed absent). When there are such degrees of freedom, each main effect is tested against
it (t test) and those with ``p < alpha`` are *active*. When there are none (a DSD of an
even number of factors whose conference matrix is used whole, with one centre run), the
paper tests subsets of main effects against the smaller ones; here instead the standardised
main effects ``b_j / sqrt(C_jj)`` (orthogonal, of equal variance in a DSD) are judged by
Lenth's (1989) pseudo standard error, ``t = |b_j| / PSE`` on ``m/3`` df, a rule calibrated for
exactly this case (at least one main effect must stay inactive). Either way the inactive main
effects are then pooled into the error: ``σ̂² = (RSS_odd(active) + SS_pe) / (P - |A| + c - 1)``.

**Stage 2** (second-order effects) regresses ``w`` on the intercept and the second-order terms
of the active factors only (strong heredity: ``AB`` with ``A`` and ``B`` both active, ``A²``
with ``A``). For ``k = 0, 1, 2, ...`` terms the best subset (least residual sum of squares) is
found, and its residual mean square ``RSS_k / (D - 1 - k)`` (``D`` the even coordinates) is
compared with the stage-1 ``σ̂²`` by ``F`` on ``(D - 1 - k, df_1)`` degrees of freedom; the first
``k`` whose mean square is not significantly larger (``p >= alpha``) is the model. All subsets
of each size are compared while there are at most :data:`MAX_STAGE2_SUBSETS`; beyond, forward
selection (said in the result).

The model is then the intercept, the active main effects and the chosen second-order terms,
fitted by least squares to all the runs as any other model.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...errors import ParameterError

__all__ = ["TwoStage", "two_stage", "fold_over_pairs", "MAX_STAGE2_SUBSETS", "PAIR_TOL"]

#: Most subsets of one size that stage 2 compares exhaustively (beyond: forward selection).
MAX_STAGE2_SUBSETS = 20_000
#: Coded settings within this of each other (or of 0) are the same.
PAIR_TOL = 1e-9


def fold_over_pairs(x: np.ndarray) -> tuple[list[tuple[int, int]], list[int]]:
    """The mirror pairs ``(i, j)`` (``x_j = -x_i``) and the centre runs (``x = 0``) of coded
    settings ``x`` (n x m), or a ValueError naming the first run without a mirror.

    Parameters
    ----------
    x : numpy.ndarray, shape (n, m)
        Coded settings [-].

    Returns
    -------
    tuple
        ``(pairs, centres)``: index pairs (first in row order) and centre-run indices.
    """
    x = np.asarray(x, dtype=float)
    centre = np.all(np.abs(x) <= PAIR_TOL, axis=1)
    free = [i for i in range(len(x)) if not centre[i]]
    taken: set[int] = set()
    pairs: list[tuple[int, int]] = []
    for i in free:
        if i in taken:
            continue
        mate = next((j for j in free if j != i and j not in taken and np.all(np.abs(x[j] + x[i]) <= PAIR_TOL)), None)
        if mate is None:
            raise ValueError(f"run {i + 1} has no mirror run (all its coded settings negated): a definitive screening "
                             "design is made of fold-over pairs and centre runs")
        taken.update((i, mate))
        pairs.append((i, mate))
    return pairs, [int(i) for i in np.flatnonzero(centre)]


def _rss(y: np.ndarray, X: np.ndarray) -> tuple[float, int, np.ndarray]:
    """Residual sum of squares, rank and coefficients of ``y`` on ``X`` (QR, no intercept)."""
    if X.shape[1] == 0:
        return float(y @ y), 0, np.empty(0)
    b, _, rank, _ = np.linalg.lstsq(X, y, rcond=None)
    r = y - X @ b
    return float(r @ r), int(rank), b


def _t_table(z: np.ndarray, Xo: np.ndarray, cols: list[int], sigma2: float, df: int) -> list[dict]:
    from ..contract.statistics import stdtr

    _, _, b = _rss(z, Xo[:, cols])
    C = np.linalg.inv(Xo[:, cols].T @ Xo[:, cols])
    rows = []
    for i, j in enumerate(cols):
        se = math.sqrt(sigma2 * C[i, i]) if sigma2 > 0 else math.nan
        t = b[i] / se if se > 0 else math.inf
        rows.append({"column": j, "estimate": float(b[i]), "se": se, "t": float(t),
                     "p": float(2 * stdtr(df, -abs(t))) if df > 0 and math.isfinite(t) else (0.0 if df > 0 else math.nan)})
    return rows


def _fdist_p(d1: int, d2: int, f: float) -> float:
    from ..contract.statistics import fdtrc

    return float(fdtrc(d1, d2, f)) if d1 > 0 and d2 > 0 else math.nan


@dataclass(frozen=True)
class TwoStage:
    """The two-stage analysis of a definitive screening design (frozen; :func:`two_stage`).

    Attributes
    ----------
    kept : tuple of str
        ``Intercept``, the active main effects and the chosen second-order terms.
    removed : tuple of str
        The other terms of the quadratic model.
    stage1 : list of dict
        Per main effect: ``term, estimate`` (coded coefficient), ``se, t, p`` (against the
        pooled stage-1 error, ``stage1_df`` df), ``active`` (as the stage-1 procedure decided).
    stage1_rmse : float
        ``σ̂`` after pooling the inactive main effects [response units].
    stage1_df : int
        Its degrees of freedom.
    stage1_method : str
        ``"fake factors and centre runs"`` (an error independent of the model) or
        ``"Lenth's PSE (no error df)"`` (none: Lenth's pseudo standard error of the
        standardised main effects).
    stage2 : list of dict
        Per size ``k``: ``size, terms, rss, df, mean_square, f, p``.
    stage2_search : str
        ``"all subsets"`` or ``"forward"``.
    pairs, centre_runs, fake_df, pure_error_df : int
        The fold-over pairs, centre runs, odd-space residual and pure-error degrees of freedom.
    alpha : float
        The threshold of both stages.
    """

    kept: tuple
    removed: tuple
    stage1: list = field(repr=False)
    stage1_rmse: float
    stage1_df: int
    stage1_method: str
    stage2: list = field(repr=False)
    stage2_search: str
    pairs: int
    centre_runs: int
    fake_df: int
    pure_error_df: int
    alpha: float
    method: str = "dsd"
    criterion: str = "p"
    start_model: str = "quadratic"
    hierarchy: bool = True

    @property
    def alpha_out(self) -> float:
        """The threshold (as :class:`~rsm_lrg.model.choice.reduce.Reduction` names it)."""
        return self.alpha

    def to_dict(self) -> dict:
        """The analysis as plain data (non-finite numbers as None).

        Returns
        -------
        dict
            ``method, alpha, kept, removed, stage1 {method, rmse, df, effects}, stage2 {search,
            steps}, pairs, centre_runs, fake_df, pure_error_df``.
        """
        def clean(rows: list[dict]) -> list[dict]:
            return [{k: (None if isinstance(v, float) and not math.isfinite(v) else v) for k, v in r.items()}
                    for r in rows]

        return {"method": "dsd", "criterion": "p", "alpha": self.alpha, "start_model": self.start_model,
                "kept": list(self.kept), "removed": list(self.removed),
                "stage1": {"method": self.stage1_method, "rmse": self.stage1_rmse, "df": self.stage1_df,
                           "effects": clean(self.stage1)},
                "stage2": {"search": self.stage2_search, "steps": clean(self.stage2)},
                "pairs": self.pairs, "centre_runs": self.centre_runs, "fake_df": self.fake_df,
                "pure_error_df": self.pure_error_df}

    def describe(self) -> str:
        """The two stages for people: the main effects found and how, the second-order sizes
        tried, the model chosen.

        Returns
        -------
        str
            Several lines.
        """
        from ...present import format_g

        active = [r["term"] for r in self.stage1 if r["active"]]
        lines = [f"Definitive screening two-stage analysis (Jones & Nachtsheim 2017), alpha {self.alpha:g}: "
                 f"{self.pairs} fold-over pairs, {self.centre_runs} centre run(s); error from "
                 f"{self.fake_df} fake-factor and {self.pure_error_df} pure-error df"
                 + (" (none: the main effects judged by Lenth's pseudo standard error)"
                    if self.stage1_method.startswith("Lenth") else ""),
                 "Stage 1, main effects (odd space):"]
        for r in self.stage1:
            lines.append(f"  {r['term']:<4} estimate {format_g(r['estimate']):>10}  t {format_g(r['t']):>9}  "
                         f"p {format_g(r['p']):>9}  {'active' if r['active'] else ''}")
        lines.append(f"  active: {' '.join(active) or 'none'}; RMSE {format_g(self.stage1_rmse)} on "
                     f"{self.stage1_df} df (inactive main effects pooled)")
        lines.append(f"Stage 2, second-order terms of the active factors (even space, {self.stage2_search}):")
        for s in self.stage2:
            lines.append(f"  {s['size']} term(s) {s['terms'] or '(intercept only)'}: mean square "
                         f"{format_g(s['mean_square'])} on {s['df']} df, F {format_g(s['f'])}, p {format_g(s['p'])}")
        second = [k for k in self.kept if k != "Intercept" and k not in active]
        lines.append(f"Model: {' '.join(k for k in self.kept if k != 'Intercept') or 'intercept only'}"
                     + (f" (second order: {' '.join(second)})" if second else " (no second-order term)"))
        return "\n".join(lines)


def two_stage(x: np.ndarray, y: np.ndarray, letters: list[str], alpha: float = 0.1) -> TwoStage:
    """The two-stage analysis (module docstring) of coded settings ``x`` and responses ``y``.

    Parameters
    ----------
    x : numpy.ndarray, shape (n, m)
        Coded settings of a fold-over design (mirror pairs and centre runs) [-].
    y : numpy.ndarray, shape (n,)
        The responses [response units].
    letters : list of str
        The factors' letters (term names ``A``, ``AB``, ``A^2``).
    alpha : float
        Threshold of both stages, between 0 and 1.

    Returns
    -------
    TwoStage
        The main effects found, the second-order terms chosen and the figures of both stages.

    Raises
    ------
    ValueError
        Not a fold-over design, too few pairs, or no main effect active.
    """
    if not (isinstance(alpha, (int, float)) and not isinstance(alpha, bool) and 0.0 < alpha < 1.0):
        raise ParameterError("alpha_in", f"the threshold must lie between 0 and 1, not {alpha!r}")
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    n, m = x.shape
    pairs, centres = fold_over_pairs(x)
    P, c = len(pairs), len(centres)
    if P < m:
        raise ValueError(f"{P} fold-over pairs cannot estimate {m} main effects")
    i_, j_ = np.array([p[0] for p in pairs]), np.array([p[1] for p in pairs])
    r2 = math.sqrt(2.0)
    z = (y[i_] - y[j_]) / r2
    Xo = r2 * x[i_]
    rss_full, rank, _ = _rss(z, Xo)
    if rank < m:
        raise ValueError("the main effects are not estimable from the fold-over pairs (the design's columns are "
                         "linearly dependent)")
    fake_df = P - m
    yc = y[centres] if c else np.empty(0)
    ss_pe = float(np.sum((yc - yc.mean()) ** 2)) if c > 1 else 0.0
    pe_df = max(c - 1, 0)
    err_df = fake_df + pe_df
    if err_df > 0:
        method = "fake factors and centre runs"
        rows = _t_table(z, Xo, list(range(m)), (rss_full + ss_pe) / err_df, err_df)
        active = [j for j in range(m) if rows[j]["p"] < alpha]
    else:
        # no error df: Lenth's pseudo standard error of the standardised main effects
        # b_j / sqrt(C_jj) (orthogonal, equal variance sigma^2 in a DSD), t on m/3 df
        from ..contract.statistics import stdtr
        from ..readings.effects import lenth_pse

        method = "Lenth's PSE (no error df)"
        _, _, b = _rss(z, Xo)
        C = np.linalg.inv(Xo.T @ Xo)
        std = b / np.sqrt(np.diag(C))
        pse = lenth_pse(std)
        with np.errstate(divide="ignore", invalid="ignore"):
            tl = np.abs(std) / pse if pse > 0 else np.full(m, math.inf)
        p_lenth = [float(2 * stdtr(m / 3.0, -t)) if math.isfinite(t) else 0.0 for t in tl]
        active = [j for j in range(m) if p_lenth[j] < alpha]
        if len(active) == m:
            raise ValueError("every main effect is active by Lenth's PSE and there is no error df: the design needs "
                             "fake factors (extra runs) or replicated centre runs")
    if not active:
        raise ValueError(f"stage 1 of the definitive screening analysis found no active main effect at alpha "
                         f"{alpha:g}; nothing explains the response")
    df1 = P - len(active) + pe_df
    sigma2_1 = (_rss(z, Xo[:, active])[0] + ss_pe) / df1
    final = _t_table(z, Xo, list(range(m)), sigma2_1, df1)
    stage1 = [{"term": letters[j], "estimate": final[j]["estimate"], "se": final[j]["se"], "t": final[j]["t"],
               "p": final[j]["p"], "active": j in active} for j in range(m)]
    # stage 2: the even coordinates (pure error left out)
    w = list((y[i_] + y[j_]) / r2)
    settings = [x[i_]]
    scale = [np.full(P, r2)]
    if c:
        w.append(math.sqrt(c) * float(yc.mean()))
        settings.append(np.zeros((1, m)))
        scale.append(np.array([math.sqrt(c)]))
    W = np.asarray(w, dtype=float)
    Xe = np.vstack(settings)  # the settings behind each even coordinate
    s = np.concatenate(scale)
    D = len(W)
    names, cols = [], []
    for a, j in enumerate(active):
        for k in active[a + 1:]:
            names.append(letters[j] + letters[k])
            cols.append(s * Xe[:, j] * Xe[:, k])
    for j in active:
        names.append(letters[j] + "^2")
        cols.append(s * Xe[:, j] ** 2)
    cand = np.column_stack(cols) if cols else np.empty((D, 0))
    one = s[:, None]
    q = len(names)
    biggest = min(q, D - 2)
    exhaustive = all(math.comb(q, k) <= MAX_STAGE2_SUBSETS for k in range(biggest + 1))
    steps: list[dict] = []
    chosen: list[int] = []
    current: list[int] = []
    for k in range(0, biggest + 1):
        best: tuple[float, list[int]] | None = None
        if k == 0:
            best = (_rss(W, one)[0], [])
        elif exhaustive:
            for combo in itertools.combinations(range(q), k):
                rss, rank, _ = _rss(W, np.hstack([one, cand[:, list(combo)]]))
                if rank == k + 1 and (best is None or rss < best[0] - 1e-12 * max(1.0, best[0])):
                    best = (rss, list(combo))
        else:
            for t in range(q):
                if t in current:
                    continue
                sub = sorted([*current, t])
                rss, rank, _ = _rss(W, np.hstack([one, cand[:, sub]]))
                if rank == k + 1 and (best is None or rss < best[0]):
                    best = (rss, sub)
        if best is None:
            break
        rss, sub = best
        current = sub
        df = D - 1 - k
        ms = rss / df
        f = ms / sigma2_1 if sigma2_1 > 0 else math.inf
        p = _fdist_p(df, df1, f)
        steps.append({"size": k, "terms": " ".join(names[t] for t in sub), "rss": rss, "df": df, "mean_square": ms,
                      "f": f, "p": p})
        chosen = sub
        if not p < alpha:
            break
    second = {names[t] for t in chosen}
    from ..build.terms import model_terms

    pool = [t for t in model_terms(letters, "quadratic") if t.order > 0]
    keep = {letters[j] for j in active} | second
    kept = ("Intercept",) + tuple(t.name for t in pool if t.name in keep)
    removed = tuple(t.name for t in pool if t.name not in keep)
    return TwoStage(kept=kept, removed=removed, stage1=stage1, stage1_rmse=math.sqrt(sigma2_1), stage1_df=df1,
                    stage1_method=method, stage2=steps, stage2_search="all subsets" if exhaustive else "forward",
                    pairs=P, centre_runs=c, fake_df=fake_df, pure_error_df=pe_df, alpha=float(alpha))


def two_stage_inputs(inp: Any, alpha: float) -> TwoStage:
    """:func:`two_stage` of checked fit inputs (:func:`rsm_lrg.model.build.inputs.model_inputs`):
    numeric factors only, no blocks, no transform of the settings.

    Parameters
    ----------
    inp : ModelInputs
        The fit's inputs.
    alpha : float
        The threshold of both stages.

    Returns
    -------
    TwoStage
        As :func:`two_stage`.
    """
    if inp.space.categoric:
        raise ParameterError("factors", "the definitive screening analysis takes numeric factors only")
    if inp.nb > 1:
        raise ParameterError("block", "the definitive screening analysis does not take blocks")
    return two_stage(np.asarray(inp.x, dtype=float), np.asarray(inp.y, dtype=float), list(inp.space.letters), alpha)
