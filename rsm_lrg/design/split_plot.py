"""Optimal split-plot designs: hard-to-change factors held constant within whole plots, chosen
by coordinate exchange on the generalised-least-squares information matrix.

Goos, P. & Vandebroek, M. (2003). D-optimal split-plot designs with given numbers and sizes
of whole plots. *Technometrics* 45(3), 235-245.
Goos, P. & Vandebroek, M. (2004). Outperforming completely randomized designs. *Journal of
Quality Technology* 36(1), 12-26.

The runs fall into ``W`` whole plots; the hard-to-change (whole-plot) factors take one setting
per whole plot, the easy-to-change (sub-plot) factors one per run. With a random whole-plot
effect of variance ``σ²_wp`` and a run error of variance ``σ²``, the responses of whole plot
``b`` (``m_b`` runs) have covariance ``σ² V_b`` with ``V_b = I + η J`` (``J`` all ones,
``η = σ²_wp / σ²`` the variance ratio), so the GLS estimator has covariance ``σ² M⁻¹`` with
the information matrix

``M = X' V⁻¹ X = Σ_b (X_b' X_b - c_b s_b s_b')``,  ``c_b = η / (1 + m_b η)``,  ``s_b = X_b' 1``

(``V_b⁻¹ = I - c_b J``: Goos & Vandebroek 2003, Eq. 4). At ``η = 0`` it is ``X'X``, the
completely randomised design's. The criteria are those of :mod:`rsm_lrg.design.optimal` with
``M`` in place of ``X'X``: D maximises ``det M`` (reported ``det(M)^(1/p) / n``), I minimises
the average prediction variance ``trace(M⁻¹ W)`` [σ²] over the region, A ``trace(M⁻¹)``.

Coordinate exchange (Goos & Vandebroek 2003, Sec. 4): from a random start, each whole-plot
factor of each whole plot is set, for the whole plot at once, to the best of its levels (21
over [-1, 1] for a numeric factor, every level of a categoric one, the -1/0/+1 grid in the
coarse starts), and each sub-plot factor of each run likewise, until a whole pass changes
nothing; every move keeps each run inside the constraints. The best of the starts (all drawn
from ``seed``) is refined on the full grid and polished by steps of 0.05 and 0.01 (a polishing
step is taken only for a relative gain of at least :data:`POLISH_GAIN`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..errors import ParameterError
from ..factors import FactorSpace
from ..terms import Term, design_matrix, model_terms, n_columns
from .core import Design, as_factor_space, resolve_seed, seeded_options
from .exchange import (
    GRID,
    MAX_RUNS,
    MAX_STARTS,
    ExchangeProblem,
    candidate_pool,
    check_columns,
    check_criterion,
    information_criterion,
    is_gain,
    moment_matrix,
    reported_value,
)

__all__ = ["split_plot", "split_plot_ccd", "equivalent_alpha", "gls_information", "gls_criteria", "whole_plot_terms", "plot_sizes", "plot_weights",
           "check_variance_ratio"]

_COARSE = np.array([-1.0, 0.0, 1.0])

#: Relative gain a polishing step (0.05, 0.01) must make to move a setting off the grid.
POLISH_GAIN = 1e-4


def check_variance_ratio(eta: Any) -> float:
    """``eta`` as a finite number >= 0 [-], or a ValueError starting ``variance_ratio:``."""
    try:
        v = float(eta)
    except (TypeError, ValueError):
        raise ParameterError("variance_ratio", f"expected a finite number >= 0, got {eta!r}") from None
    if isinstance(eta, (bool, np.bool_)) or not (math.isfinite(v) and v >= 0.0):
        raise ParameterError("variance_ratio", f"expected a finite number >= 0 (sigma^2 whole plot / sigma^2), got {eta!r}")
    return v


def plot_sizes(runs: int, whole_plots: int) -> list[int]:
    """Runs per whole plot: ``runs // whole_plots`` each, the first ``runs % whole_plots``
    whole plots one more."""
    m, r = divmod(int(runs), int(whole_plots))
    return [m + 1] * r + [m] * (int(whole_plots) - r)


def gls_information(X: np.ndarray, plots: np.ndarray, eta: float) -> np.ndarray:
    """The GLS information ``X' V⁻¹ X`` (p x p, in units of 1/σ²) of the model matrix ``X``
    (n x p) whose rows fall in the whole plots ``plots`` (n labels), ``V`` block diagonal
    with ``I + η J`` per whole plot (Goos & Vandebroek 2003, Eq. 4).

    >>> X = np.array([[1.0, -1.0], [1.0, 1.0], [1.0, -1.0], [1.0, 1.0]])
    >>> gls_information(X, np.array([1, 1, 2, 2]), 1.0).round(6).tolist()
    [[1.333333, 0.0], [0.0, 4.0]]

    Parameters
    ----------
    X : numpy.ndarray, shape (n, p)
        The model matrix.
    plots : numpy.ndarray, shape (n,)
        The whole plot of each run.
    eta : float
        The variance ratio η = σ²_whole-plot / σ² [-].

    Returns
    -------
    numpy.ndarray, shape (p, p)
        ``X' V⁻¹ X`` [1/σ²].
    """
    X = np.asarray(X, dtype=float)
    _, codes, counts = np.unique(np.asarray(plots), return_inverse=True, return_counts=True)
    S = np.zeros((len(counts), X.shape[1]))
    np.add.at(S, codes.reshape(-1), X)
    return X.T @ X - (S.T * plot_weights(counts, eta)) @ S


def plot_weights(sizes: Any, eta: float) -> np.ndarray:
    """``c_b = η / (1 + m_b η)`` for whole plots of ``m_b`` runs, written ``1 / (m_b + 1/η)``
    so that a large ``η`` does not overflow (0 at ``η = 0``)."""
    m = np.asarray(sizes, dtype=float)
    return np.zeros_like(m) if eta == 0 else 1.0 / (m + 1.0 / eta)


def whole_plot_terms(terms: list[Term], hard: list[int]) -> list[Term]:
    """The terms (intercept left out) whose factors are all hard to change (positions
    ``hard``): the effects estimated between whole plots."""
    h = set(hard)
    return [t for t in terms if t.order > 0 and all(i in h for i, e in enumerate(t.powers) if e)]


def gls_criteria(design: Design, terms: list[Term] | None = None, model: str = "quadratic",
                 variance_ratio: float = 1.0, whole_plots: Any = None) -> dict:
    """The GLS criteria of a split-plot design under the variance ratio ``η``.

    Parameters
    ----------
    design : Design
        Its ``whole_plots`` (or ``whole_plots`` given here: one label per run, in the
        design's row order) define ``V``.
    terms : list of Term or None
        The model's terms; None: :func:`rsm_lrg.terms.model_terms` of ``model``.
    variance_ratio : float
        ``η = σ²_wp / σ²`` [-], finite and >= 0.

    Returns
    -------
    dict
        ``variance_ratio``, ``whole_plots`` (number), ``plot_sizes`` (min, max), ``n``, ``p``,
        ``d_efficiency`` ``det(M)^(1/p) / n``, ``a_efficiency`` ``p / (n trace(M⁻¹))``,
        ``i_average`` ``trace(M⁻¹ W)`` [σ²] over the coded cube (categoric levels equally
        weighted) and ``estimable`` (``M`` of full rank); the criteria are 0 / inf / NaN when
        not estimable.
    """
    eta = check_variance_ratio(variance_ratio)
    plots = design.whole_plots if whole_plots is None else np.asarray(whole_plots)
    if plots is None:
        raise ValueError("the design has no whole plots")
    if len(plots) != design.n_runs:
        raise ValueError(f"{len(plots)} whole-plot labels for {design.n_runs} runs")
    space = design.factors
    if terms is None:
        terms = model_terms(space.letters, model, space.categoric or None)
    X = design_matrix(np.asarray(design.coded_runs, dtype=float), terms)
    n, p = X.shape
    M = gls_information(X, plots, eta)
    counts = np.unique(np.asarray(plots), return_counts=True)[1]
    d = reported_value(M, n, "D")
    ok = d > 0
    W = moment_matrix(space, terms)
    return {"variance_ratio": eta, "whole_plots": int(len(counts)),
            "plot_sizes": [int(counts.min()), int(counts.max())], "n": int(n), "p": int(p),
            "estimable": bool(ok), "d_efficiency": d,
            "a_efficiency": float(p / (n * reported_value(M, n, "A"))) if ok else math.nan,
            "i_average": reported_value(M, n, "I", W) if ok else math.inf}


class _Search:
    """Coordinate exchange over split-plot designs (whole plots contiguous: rows
    ``bounds[b]:bounds[b + 1]``), model rows and candidate levels from an
    :class:`~rsm_lrg.design.exchange.ExchangeProblem`."""

    def __init__(self, prob: ExchangeProblem, sizes: list[int], hard: list[int], eta: float):
        self.prob = prob
        self.sizes = np.asarray(sizes, dtype=int)
        self.bounds = np.r_[0, np.cumsum(self.sizes)]
        self.plot = np.repeat(np.arange(len(sizes)), self.sizes)
        self.c = plot_weights(self.sizes, eta)
        self.hard = list(hard)
        self.easy = [j for j in range(prob.k) if j not in set(hard)]
        self.n = int(self.sizes.sum())

    def value(self, M: np.ndarray) -> Any:
        return information_criterion(M, self.prob.crit, self.prob.W)

    def plot_info(self, Xb: np.ndarray, c: float) -> np.ndarray:
        """``Xb' Xb - c s s'`` of one whole plot's rows (..., m, p), batched."""
        s = Xb.sum(axis=-2)
        return np.einsum("...mp,...mq->...pq", Xb, Xb) - c * s[..., :, None] * s[..., None, :]

    def start(self, rng: np.random.Generator, coarse: bool) -> np.ndarray:
        """A random feasible start: each whole plot's hard-to-change settings from one pool
        point, each run's easy ones from another (the whole plot's own point where the
        combination breaks a constraint)."""
        prob = self.prob
        P0 = prob.random_start(len(self.sizes), rng, grid=coarse)[self.plot]
        D = prob.random_start(self.n, rng, grid=coarse)
        D[:, self.hard] = P0[:, self.hard]
        if prob.cons is not None and prob.cons:
            bad = ~prob.cons.feasible_coded(D)
            D[bad] = P0[bad]
        return D

    def _levels(self, j: int, now: float, phase: int, coarse: bool) -> np.ndarray:
        f = self.prob.space.factors[j]
        if f.kind != "numeric":
            vals = np.arange(f.n_levels, dtype=float) if phase == 0 else np.empty(0)
        elif phase == 0:
            vals = _COARSE if coarse else GRID
        else:
            step = 0.05 / (5 ** (phase - 1))
            vals = np.unique(np.clip(now + np.linspace(-step, step, 11), -1.0, 1.0))
        return vals[vals != now]

    def improve(self, D: np.ndarray, coarse: bool = False, polish: bool = False) -> tuple[np.ndarray, float]:
        """Coordinate exchange on ``D`` (n x k coded, whole plots contiguous) until a pass
        changes nothing; ``polish``: then steps of 0.05 and 0.01 on the numeric factors."""
        prob = self.prob
        D = D.copy()
        F = prob.rows(D)
        ridge = prob.ridge(self.n)
        Mb = np.stack([self.plot_info(F[a:b], c) for a, b, c in zip(self.bounds[:-1], self.bounds[1:], self.c)])
        M = Mb.sum(axis=0) + ridge
        cur = float(self.value(M))
        cons = prob.cons if prob.cons is not None and prob.cons else None
        for phase in (0, 1, 2) if polish else (0,):
            # a polished level must gain a relative 1e-4 (no settings moved off the grid for noise)
            gain = is_gain if phase == 0 else (lambda v, c: v < c - POLISH_GAIN * max(1.0, abs(c)))
            for _ in range(100):
                changed = False
                for b in range(len(self.sizes)):  # a whole-plot factor changes for the whole plot
                    a, e = int(self.bounds[b]), int(self.bounds[b + 1])
                    for j in self.hard:
                        vals = self._levels(j, D[a, j], phase, coarse)
                        if not len(vals):
                            continue
                        cand = np.repeat(D[a:e][None, :, :], len(vals), axis=0)
                        cand[:, :, j] = vals[:, None]
                        flat = cand.reshape(-1, prob.k)
                        ok = np.ones(len(vals), dtype=bool)
                        if cons is not None:
                            ok = cons.feasible_coded(flat).reshape(len(vals), e - a).all(axis=1)
                        if not ok.any():
                            continue
                        Xc = prob.rows(flat).reshape(len(vals), e - a, -1)
                        Mnew = self.plot_info(Xc, self.c[b])
                        v = np.where(ok, self.value(M - Mb[b] + Mnew), np.inf)
                        i = int(np.argmin(v))
                        if gain(float(v[i]), cur):
                            D[a:e, j] = vals[i]
                            F[a:e] = Xc[i]
                            Mb[b] = Mnew[i]
                            M = Mb.sum(axis=0) + ridge
                            cur = float(self.value(M))
                            changed = True
                for r in range(self.n):  # a sub-plot factor changes for one run
                    b = int(self.plot[r])
                    a, e = int(self.bounds[b]), int(self.bounds[b + 1])
                    for j in self.easy:
                        vals = self._levels(j, D[r, j], phase, coarse)
                        if not len(vals):
                            continue
                        pts = np.repeat(D[r][None, :], len(vals), axis=0)
                        pts[:, j] = vals
                        ok = np.ones(len(vals), dtype=bool) if cons is None else cons.feasible_coded(pts)
                        if not ok.any():
                            continue
                        G = prob.rows(pts)
                        Xc = np.repeat(F[a:e][None, :, :], len(vals), axis=0)
                        Xc[:, r - a, :] = G
                        Mnew = self.plot_info(Xc, self.c[b])
                        v = np.where(ok, self.value(M - Mb[b] + Mnew), np.inf)
                        i = int(np.argmin(v))
                        if gain(float(v[i]), cur):
                            D[r, j] = vals[i]
                            F[r] = G[i]
                            Mb[b] = Mnew[i]
                            M = Mb.sum(axis=0) + ridge
                            cur = float(self.value(M))
                            changed = True
                if not changed:
                    break
        return D, cur


def hard_to_change_indices(names: Sequence[str], hard_to_change: str | Sequence[str] | None) -> list[int]:
    """Positions in ``names`` of the hard-to-change factors (a name or a list of names), in the
    order given; none, an unknown name or a name given twice is a ``ValueError`` naming the
    option."""
    hard_names = [hard_to_change] if isinstance(hard_to_change, str) else list(hard_to_change or [])
    if not hard_names:
        raise ParameterError("hard_to_change", "name at least one hard-to-change factor")
    hard: list[int] = []
    for h in hard_names:
        if h not in names:
            raise ParameterError("hard_to_change", f"{h!r} is not among the factors ({', '.join(names)})")
        if names.index(h) in hard:
            raise ParameterError("hard_to_change", f"{h!r} is given twice")
        hard.append(names.index(h))
    return hard


def split_plot(
    factors: Any,
    hard_to_change: Any,
    whole_plots: int,
    runs: int,
    model: str = "quadratic",
    criterion: str = "D",
    variance_ratio: float = 1.0,
    constraints: Any = None,
    seed: Any = None,
    starts: int | None = None,
    randomize: bool = True,
) -> Design:
    """An optimal split-plot design by coordinate exchange on the GLS information matrix
    (Goos & Vandebroek 2003, 2004; module docstring).

    Parameters
    ----------
    factors : FactorSpace, mapping or list
        Numeric (``"NAME=LOW:HIGH"``) and categoric (``"NAME=cat:L1,L2"``) factors.
    hard_to_change : str or list of str
        The factors (names) held constant within each whole plot (at least one).
    whole_plots : int
        Number of whole plots ``W``; at least the whole-plot model columns plus one.
    runs : int
        Total runs ``N`` (at least the model's columns and ``W``); ``N / W`` runs per whole
        plot, and when ``W`` does not divide ``N`` the first ``N mod W`` whole plots hold one
        run more (said in ``options["note"]``).
    model : {"linear", "2fi", "quadratic", "cubic"}
        The model the design must support (:func:`rsm_lrg.terms.model_terms`).
    criterion : {"D", "I", "A"}, default "D"
        On the GLS information ``X' V⁻¹ X``.
    variance_ratio : float, default 1
        ``η = σ²_wp / σ²`` [-], finite and >= 0 (0: the runs independent).
    constraints : str, list of str or Constraints
        Inequalities in actual units every run satisfies.
    seed : int, numpy.random.Generator or None
        Seeds the random starts and the run order (``None``: drawn and recorded).
    starts : int or None
        Random starts on the -1/0/+1 grid; half as many more start in the continuous region
        (default 20 for up to 21 model columns, else 6).
    randomize : bool
        ``True``: the whole plots in random order and the runs in random order within each
        (whole plots stay together); ``False``: run order = standard order.

    Returns
    -------
    Design
        ``kind="split-plot"`` with ``whole_plots`` (1..W in run order); ``options`` holds the
        criterion and its GLS value (:func:`rsm_lrg.design.exchange.reported_value` of
        :func:`gls_information`), the model, the variance ratio, the hard-to-change factors,
        the whole-plot sizes, the constraints and the seed.

    Examples
    --------
    >>> d = split_plot(["T=100:200", "x=0:1"], ["T"], whole_plots=4, runs=12, model="2fi", seed=1)
    >>> d.n_runs, sorted(set(d.whole_plots.tolist()))
    (12, [1, 2, 3, 4])
    """
    from .constraints import Constraints

    space = as_factor_space(factors)
    crit = check_criterion(criterion)
    eta = check_variance_ratio(variance_ratio)
    names = space.names
    hard = hard_to_change_indices(names, hard_to_change)
    for name, given in (("whole_plots", whole_plots), ("runs", runs), ("starts", starts)):
        if given is not None and (isinstance(given, (bool, np.bool_)) or int(given) != given or given < 1):
            raise ParameterError(name, f"must be a whole number >= 1 (got {given!r})")
    W_plots, n = int(whole_plots), int(runs)
    terms = model_terms(space.letters, model, space.categoric or None)
    p = n_columns(terms)
    check_columns(p, model, len(space))
    wp_cols = n_columns(whole_plot_terms(terms, hard))
    hard_text = ", ".join(names[i] for i in sorted(hard))
    if W_plots < wp_cols + 1:
        raise ParameterError("whole_plots", f"{W_plots} whole plots cannot estimate the intercept and the {wp_cols} "
                         f"whole-plot column(s) of the {model} model in {hard_text}; need at least {wp_cols + 1}")
    if n > MAX_RUNS:
        raise ParameterError("runs", f"at most {MAX_RUNS} runs (got {n})")
    if n < p:
        raise ParameterError("runs", f"{n} runs cannot estimate the {p} coefficients of the {model} model in "
                         f"{len(space)} factors")
    if n < W_plots:
        raise ParameterError("runs", f"{n} runs cannot fill {W_plots} whole plots (at least one run each)")
    if constraints is not None and not isinstance(constraints, Constraints):
        constraints = Constraints.parse(constraints, space)
    sizes = plot_sizes(n, W_plots)
    rng, used_seed = resolve_seed(seed)
    Wm = moment_matrix(space, terms, constraints) if crit == "I" else None
    pool = candidate_pool(space, constraints, seed=int(rng.integers(2 ** 31)))
    search = _Search(ExchangeProblem(space, terms, crit, Wm, constraints, pool), sizes, hard, eta)
    if starts is None:
        starts = 20 if p <= 21 else 6
    starts = min(max(1, int(starts)), MAX_STARTS)
    best: np.ndarray | None = None
    best_v = math.inf
    for how in ["coarse"] * starts + ["continuous"] * max(1, starts // 2):
        D, v = search.improve(search.start(rng, how == "coarse"), coarse=how == "coarse")
        if best is None or v < best_v:
            best, best_v = D, v
    assert best is not None
    best, best_v = search.improve(best, polish=True)
    X = design_matrix(best, terms)
    M = gls_information(X, search.plot, eta)
    value = reported_value(M, n, crit, Wm)
    if reported_value(M, n, "D") == 0.0:
        raise ParameterError("runs", f"no split-plot design of {n} runs in {W_plots} whole plots was found that estimates "
                         f"the {model} model; add runs or whole plots")
    options: dict[str, Any] = {
        "criterion": crit,
        "criterion_value": value,
        "information": "GLS",
        "model": model,
        "model_terms": p,
        "variance_ratio": eta,
        "hard_to_change": [names[i] for i in hard],
        "whole_plots": W_plots,
        "whole_plot_sizes": sizes,
        "starts": starts,
        "constraints": [] if constraints is None else constraints.expressions,
        "algorithm": "coordinate exchange on X'V^-1 X (Goos & Vandebroek 2003)",
    }
    if len(set(sizes)) > 1:
        options["note"] = (f"{n} runs do not divide into {W_plots} whole plots: {sizes.count(max(sizes))} whole plots "
                           f"of {max(sizes)} runs and {sizes.count(min(sizes))} of {min(sizes)}")
    return _ordered(space, best, search.sizes, options, rng if used_seed is None else used_seed, randomize)


#: Most whole-plot and most sub-plot factors of :func:`split_plot_ccd` (full 2^k cubes).
_MAX_CCD_K = 5


def equivalent_alpha(k_wp: int, k_sp: int, alpha: float | None = None) -> tuple[float, float]:
    """Whole-plot and sub-plot star distances ``(α_w, α_s)`` [coded units] that give the
    split-plot CCD of :func:`split_plot_ccd` equivalent estimation (OLS = GLS for every η).

    The sums of each sub-plot square ``s_j²`` over a whole plot are ``2^k_sp`` in a whole-plot
    cube plot, 0 in a whole-plot star plot and ``2 α_s²`` in a centre plot; they lie in the
    column space of the quadratic model (``a + c Σ w_i²`` over the whole-plot points) only when

    ``2 α_s² (1 - k_wp / α_w²) = 2^k_sp``,  i.e.  ``α_s² = 2^(k_sp-1) α_w² / (α_w² - k_wp)``.

    ``alpha=None``: one common distance, ``α_w = α_s = sqrt(k_wp + 2^(k_sp-1))`` (1.414 for
    one whole-plot and one sub-plot factor, 1.732 for 1 + 2, 2 for 2 + 2, 2.236 for 1 + 3);
    else ``alpha`` is ``α_w`` (it must exceed ``sqrt(k_wp)``) and ``α_s`` follows.
    """
    if alpha is None:
        a = math.sqrt(k_wp + 2.0 ** (k_sp - 1))
        return a, a
    a_w = float(alpha)
    if not (math.isfinite(a_w) and a_w * a_w > k_wp):
        raise ParameterError("alpha", f"the whole-plot star distance must exceed sqrt({k_wp}) = {math.sqrt(k_wp):.4g} for "
                         f"equivalent estimation (got {alpha!r})")
    return a_w, math.sqrt(2.0 ** (k_sp - 1) * a_w * a_w / (a_w * a_w - k_wp))


def split_plot_ccd(
    factors: Any,
    hard_to_change: Any,
    alpha: float | None = None,
    center_whole_plots: int = 1,
    seed: Any = None,
    randomize: bool = True,
) -> Design:
    """The equivalent-estimation split-plot central composite design (after Vining, Kowalski &
    Montgomery 2005, *J. Quality Technology* 37(2), 115-129; conditions as in Parker,
    Kowalski & Vining 2007): OLS and GLS (REML) estimates of the quadratic model coincide
    for every variance ratio η.

    With ``k_w`` hard-to-change (whole-plot) and ``k_s`` easy (sub-plot) factors, every whole
    plot holds ``m = max(2^k_s, 2 k_s + 1)`` runs:

    * ``2^k_w`` whole-plot cube plots (``w = ±1``): the sub-plot 2^k_s cube and ``m - 2^k_s``
      sub-plot centre runs;
    * ``2 k_w`` whole-plot star plots (``w = ±α_w e_i``): ``m`` sub-plot centre runs;
    * ``center_whole_plots`` centre plots (``w = 0``): the ``2 k_s`` sub-plot star points
      (``±α_s``) and ``m - 2 k_s`` centre runs.

    ``N = m (2^k_w + 2 k_w + K)`` runs in ``2^k_w + 2 k_w + K`` whole plots. Equal whole-plot
    sizes, sub-plot sets symmetric about 0 and the star distances of
    :func:`equivalent_alpha` make ``Z Z' X`` (whole-plot sums) a linear combination of the
    columns of ``X``, so the column space of ``X`` is invariant under ``V = I + η Z Z'``
    (the equivalent-estimation condition; checked numerically in the tests).

    Parameters
    ----------
    factors : FactorSpace, mapping or list
        Numeric factors only; low/high [factor units] are coded ±1, star points lie beyond.
    hard_to_change : str or list of str
        The whole-plot factors (1 to 5); the other factors (1 to 5) are the sub-plot factors.
    alpha : float or None
        Whole-plot star distance ``α_w`` [coded units] (the sub-plot one follows); ``None``:
        the common distance of :func:`equivalent_alpha`.
    center_whole_plots : int
        Whole plots at the whole-plot centre, each holding the sub-plot star and centre runs.
    seed, randomize
        As for :func:`split_plot`: whole plots in random order, runs in random order within each.

    Returns
    -------
    Design
        ``kind="split-plot-ccd"`` with ``whole_plots``; ``options`` holds both star distances,
        the hard-to-change factors, the whole-plot size and count, and the seed.

    Examples
    --------
    >>> d = split_plot_ccd(["T=100:200", "x=0:1", "y=0:1"], ["T"], randomize=False)
    >>> d.n_runs, int(d.whole_plots.max()), round(d.options["alpha_whole_plot"], 4)
    (25, 5, 1.7321)
    """
    from pyDOE3 import ff2n

    space = as_factor_space(factors)
    names = space.names
    if space.categoric:
        raise ParameterError("factors", "a split-plot central composite design takes numeric factors only")
    hard = hard_to_change_indices(names, hard_to_change)
    easy = [i for i in range(len(names)) if i not in hard]
    kw, ks = len(hard), len(easy)
    if not 1 <= ks <= _MAX_CCD_K or kw > _MAX_CCD_K:
        raise ParameterError("hard_to_change", f"a split-plot central composite design needs 1 to {_MAX_CCD_K} hard-to-change "
                         f"and 1 to {_MAX_CCD_K} other factors (got {kw} and {ks})")
    K = center_whole_plots
    if isinstance(K, (bool, np.bool_)) or int(K) != K or K < 1:
        raise ParameterError("center_whole_plots", f"must be a whole number >= 1 (got {K!r})")
    K = int(K)
    a_w, a_s = equivalent_alpha(kw, ks, alpha)

    def cube(k: int) -> np.ndarray:
        c = np.asarray(ff2n(k), dtype=float)
        return c[np.lexsort(c.T)]  # Yates order, first factor fastest (as central_composite)

    def star(k: int, a: float) -> np.ndarray:
        st = np.zeros((2 * k, k))
        for i in range(k):
            st[2 * i, i], st[2 * i + 1, i] = -a, a
        return st

    m = max(2 ** ks, 2 * ks + 1)
    plots: list[tuple[np.ndarray, np.ndarray]] = []  # (whole-plot setting, sub-plot runs)
    for w in cube(kw):
        plots.append((w, np.vstack([cube(ks), np.zeros((m - 2 ** ks, ks))])))
    for w in star(kw, a_w):
        plots.append((w, np.zeros((m, ks))))
    for _ in range(K):
        plots.append((np.zeros(kw), np.vstack([star(ks, a_s), np.zeros((m - 2 * ks, ks))])))
    D = np.zeros((m * len(plots), len(names)))
    for b, (w, sub) in enumerate(plots):
        D[b * m:(b + 1) * m, hard] = w
        D[b * m:(b + 1) * m, easy] = sub
    options: dict[str, Any] = {
        "alpha_whole_plot": a_w,
        "alpha_sub_plot": a_s,
        "hard_to_change": [names[i] for i in hard],
        "whole_plots": len(plots),
        "whole_plot_size": m,
        "whole_plot_sizes": [m] * len(plots),
        "center_whole_plots": K,
        "construction": (f"{2 ** kw} whole-plot cube plots (sub-plot cube + {m - 2 ** ks} centre), {2 * kw} whole-plot "
                         f"star plots ({m} sub-plot centre runs), {K} centre plot(s) (sub-plot star + {m - 2 * ks} "
                         "centre): equivalent estimation, OLS = GLS for every variance ratio (Vining, Kowalski & "
                         "Montgomery 2005)"),
    }
    rng, used_seed = resolve_seed(seed)
    return _ordered(space, D, [m] * len(plots), options, rng if used_seed is None else used_seed, randomize,
                    kind="split-plot-ccd")


def _ordered(space: FactorSpace, D: np.ndarray, sizes: Any, options: dict, seed: Any,
             randomize: bool, kind: str = "split-plot") -> Design:
    """The design with the whole plots (consecutive blocks of ``sizes`` runs of ``D``, standard
    order) in random order and the runs in random order within each (``randomize``), whole
    plots numbered in run order."""
    order_rng, opts = seeded_options(options, seed, randomize)
    n_plots = len(sizes)
    bounds = np.concatenate([[0], np.cumsum(sizes)]).astype(int)
    plot = np.repeat(np.arange(n_plots), sizes)
    plot_seq = np.arange(n_plots) if order_rng is None else order_rng.permutation(n_plots)
    perm: list[int] = []
    for b in plot_seq:
        members = np.arange(bounds[b], bounds[b + 1])
        perm.extend((members if order_rng is None else members[order_rng.permutation(len(members))]).tolist())
    n = len(D)
    run_order = np.empty(n, dtype=int)
    run_order[np.asarray(perm)] = np.arange(1, n + 1)
    number = np.empty(n_plots, dtype=int)
    number[plot_seq] = np.arange(1, n_plots + 1)
    return Design(factors=space, kind=kind, coded_runs=D, std_order=np.arange(1, n + 1),
                  run_order=run_order, options=opts, whole_plots=number[plot])
