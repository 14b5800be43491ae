"""Optimal designs with two random strata: split-split-plot and strip-plot designs, chosen by
coordinate exchange on the generalised-least-squares information matrix.

Trinca, L. A. & Gilmour, S. G. (2001). Multistratum response surface designs.
*Technometrics* 43(1), 25-33.
Jones, B. & Goos, P. (2009). D-optimal design of split-split-plot experiments.
*Biometrika* 96(1), 67-82.
Arnouts, H., Goos, P. & Jones, B. (2010). Design and analysis of industrial strip-plot
experiments. *Quality and Reliability Engineering International* 26(2), 127-136.

**Split-split-plot.** ``W`` whole plots hold ``S`` sub-plots in all (nested: each sub-plot in
one whole plot), which hold the ``N`` runs. The *very-hard-to-change* factors take one setting
per whole plot, the *hard-to-change* ones one per sub-plot, the others one per run. The
responses have covariance ``σ² V`` with

``V = I + η_w Z_w Z_w' + η_s Z_s Z_s'``

(``Z_w``, ``Z_s`` the 0/1 incidence matrices of the whole plots and sub-plots,
``η_w = σ²_w / σ²`` and ``η_s = σ²_s / σ²`` the variance ratios).

**Strip-plot.** ``R`` row strips cross ``C`` column strips; each of the ``R C`` cells is one
run. The *row* factors take one setting per row strip, the *column* factors one per column
strip (the two processing stages), any other factor one per run;
``V = I + η_r Z_r Z_r' + η_c Z_c Z_c'``.

The GLS information is ``M = X' V⁻¹ X`` [1/σ²] (``V⁻¹`` by a Cholesky factorisation of the
dense ``V``); the criteria are those of :mod:`rsm_lrg.design.split_plot` with this ``M``
(D: ``det(M)^(1/p) / n``, I: ``trace(M⁻¹ W)`` [σ²], A: ``trace(M⁻¹)``).

Coordinate exchange (Jones & Goos 2009, Sec. 3): every factor has its stratum; from a random
start, each factor's setting in each of its groups (a whole plot, a sub-plot, a row or column
strip, or a run) is set, for the whole group at once, to the best of its levels (21 over
[-1, 1] for a numeric factor, every level of a categoric one, the -1/0/+1 grid in the coarse
starts), until a whole pass changes nothing. Changing the rows ``R`` of ``X`` by ``E`` changes
``M`` by ``E' (A X)_R + (A X)_R' E + E' A_RR E`` (``A = V⁻¹``), so a candidate costs
``O(n |R| p)``. The best of the starts (all drawn from ``seed``) is refined on the full grid.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from ..errors import ParameterError
from ..terms import Term, design_matrix, model_terms, n_columns
from .core import Design, as_factor_space, resolve_seed, seeded_options
from .exchange import (
    GRID,
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
from .split_plot import check_variance_ratio, plot_sizes

__all__ = ["split_split_plot", "strip_plot", "stratum_covariance", "stratum_information", "stratum_criteria",
           "MAX_STRATUM_RUNS"]

#: Most runs of a split-split-plot or strip-plot design (``V`` is held dense, n x n).
MAX_STRATUM_RUNS = 600

_COARSE = np.array([-1.0, 0.0, 1.0])


def _codes(labels: Any) -> np.ndarray:
    return np.unique(np.asarray(labels), return_inverse=True)[1].reshape(-1)


def stratum_covariance(groups: Mapping[str, Any], variance_ratios: Mapping[str, float], n: int) -> np.ndarray:
    """``V = I + Σ_k η_k Z_k Z_k'`` [σ²] of ``n`` runs (dense, n x n).

    Parameters
    ----------
    groups : mapping of str to array of shape (n,)
        Each random stratum's group label per run (``whole_plot``, ``subplot``, ...).
    variance_ratios : mapping of str to float
        ``η_k = σ²_k / σ²`` [-] of each stratum named in ``groups`` (finite, >= 0).
    n : int
        The number of runs.

    Returns
    -------
    numpy.ndarray, shape (n, n)
        ``V`` in units of the run variance σ².
    """
    V = np.eye(n)
    for name, labels in groups.items():
        eta = check_variance_ratio(variance_ratios[name])
        g = _codes(labels)
        if g.shape != (n,):
            raise ValueError(f"{name}: {len(g)} labels for {n} runs")
        V += eta * (g[:, None] == g[None, :])
    return V


def _inverse(V: np.ndarray) -> np.ndarray:
    from scipy.linalg import cho_factor, cho_solve

    A = cho_solve(cho_factor(V, lower=True), np.eye(len(V)))
    return (A + A.T) / 2.0


def stratum_information(X: np.ndarray, groups: Mapping[str, Any], variance_ratios: Mapping[str, float]) -> np.ndarray:
    """The GLS information ``X' V⁻¹ X`` [1/σ²] with ``V`` of :func:`stratum_covariance`.

    >>> X = np.array([[1.0, -1.0], [1.0, 1.0], [1.0, -1.0], [1.0, 1.0]])
    >>> stratum_information(X, {"whole_plot": [1, 1, 2, 2]}, {"whole_plot": 1.0}).round(6).tolist()
    [[1.333333, 0.0], [0.0, 4.0]]

    Parameters
    ----------
    X : numpy.ndarray, shape (n, p)
        The model matrix.
    groups : mapping of str to array of shape (n,)
        Each random stratum's group label per run.
    variance_ratios : mapping of str to float
        ``η`` [-] of each stratum.

    Returns
    -------
    numpy.ndarray, shape (p, p)
        ``X' V⁻¹ X`` [1/σ²].
    """
    X = np.asarray(X, dtype=float)
    A = _inverse(stratum_covariance(groups, variance_ratios, len(X)))
    return X.T @ A @ X


def _design_groups(design: Design) -> dict[str, np.ndarray]:
    out: dict[str, np.ndarray] = {}
    if design.whole_plots is not None:
        out["whole_plot"] = np.asarray(design.whole_plots)
    out.update({k: np.asarray(v) for k, v in design.strata.items()})
    return out


def _ratios(names: Sequence[str], variance_ratios: Any) -> dict[str, float]:
    """One ``η`` per stratum: a number for all, or a mapping by stratum (missing ones 1)."""
    if variance_ratios is None:
        return dict.fromkeys(names, 1.0)
    if isinstance(variance_ratios, Mapping):
        unknown = [k for k in variance_ratios if k not in names]
        if unknown:
            raise ParameterError("variance_ratios", f"{unknown[0]!r} is not a stratum of the design "
                                                   f"({', '.join(names)})")
        return {k: check_variance_ratio(variance_ratios.get(k, 1.0)) for k in names}
    eta = check_variance_ratio(variance_ratios)
    return dict.fromkeys(names, eta)


def stratum_criteria(design: Design, terms: list[Term] | None = None, model: str = "quadratic",
                     variance_ratios: Any = None) -> dict:
    """The GLS criteria of a design with random strata (whole plots, sub-plots, strips).

    Parameters
    ----------
    design : Design
        Its ``whole_plots`` and ``strata`` define ``V`` (:func:`stratum_covariance`).
    terms : list of Term or None
        The model's terms; None: :func:`rsm_lrg.terms.model_terms` of ``model``.
    model : str
        The model when ``terms`` is None.
    variance_ratios : float, mapping or None
        ``η`` [-] of every stratum (a number), or by stratum name (missing ones 1); None: 1.

    Returns
    -------
    dict
        ``variance_ratio`` (the first stratum's, as :func:`rsm_lrg.design.split_plot.gls_criteria`),
        ``variance_ratios`` and ``strata`` (per stratum: groups, min and max size),
        ``whole_plots`` and ``plot_sizes`` (of the first stratum), ``n``, ``p``,
        ``d_efficiency``, ``a_efficiency``, ``i_average`` [σ²] and ``estimable``.
    """
    groups = _design_groups(design)
    if not groups:
        raise ValueError("the design has no random strata (no whole_plot, subplot or strip columns)")
    etas = _ratios(list(groups), variance_ratios)
    space = design.factors
    if terms is None:
        terms = model_terms(space.letters, model, space.categoric or None)
    X = design_matrix(np.asarray(design.coded_runs, dtype=float), terms)
    n, p = X.shape
    M = stratum_information(X, groups, etas)
    d = reported_value(M, n, "D")
    ok = d > 0
    W = moment_matrix(space, terms)
    strata = {}
    for name, g in groups.items():
        counts = np.unique(g, return_counts=True)[1]
        strata[name] = {"groups": int(len(counts)), "sizes": [int(counts.min()), int(counts.max())],
                        "variance_ratio": etas[name]}
    first = next(iter(strata.values()))
    return {"variance_ratio": etas[next(iter(groups))], "variance_ratios": etas, "strata": strata,
            "whole_plots": first["groups"], "plot_sizes": first["sizes"], "n": int(n), "p": int(p),
            "estimable": bool(ok), "d_efficiency": d,
            "a_efficiency": float(p / (n * reported_value(M, n, "A"))) if ok else math.nan,
            "i_average": reported_value(M, n, "I", W) if ok else math.inf}


class _StrataSearch:
    """Coordinate exchange where factor ``j`` is set per group of ``groups_of[j]`` (lists of
    row indices), on the GLS information with ``A = V⁻¹``."""

    def __init__(self, prob: ExchangeProblem, A: np.ndarray, groups_of: list[list[np.ndarray]]):
        self.prob, self.A, self.groups_of = prob, A, groups_of
        self.n = len(A)

    def start(self, rng: np.random.Generator, coarse: bool) -> np.ndarray:
        """Each factor's setting per group drawn from the pool (categoric levels uniformly)."""
        D = np.empty((self.n, self.prob.k))
        for j, groups in enumerate(self.groups_of):
            draw = self.prob.random_start(len(groups), rng, grid=coarse)[:, j]
            for g, v in zip(groups, draw):
                D[g, j] = v
        return D

    def _levels(self, j: int, now: float, coarse: bool) -> np.ndarray:
        f = self.prob.space.factors[j]
        vals = np.arange(f.n_levels, dtype=float) if f.kind != "numeric" else (_COARSE if coarse else GRID)
        return vals[vals != now]

    def improve(self, D: np.ndarray, coarse: bool = False) -> tuple[np.ndarray, float]:
        """Coordinate exchange on ``D`` (n x k coded) until a pass changes nothing."""
        prob, A = self.prob, self.A
        D = D.copy()
        F = prob.rows(D)
        AF = A @ F
        ridge = prob.ridge(self.n)
        M = F.T @ AF
        cur = float(information_criterion(M + ridge, prob.crit, prob.W))
        for _ in range(100):
            changed = False
            for j, groups in enumerate(self.groups_of):
                for R in groups:
                    vals = self._levels(j, D[R[0], j], coarse)
                    if not len(vals):
                        continue
                    cand = np.repeat(D[R][None, :, :], len(vals), axis=0)
                    cand[:, :, j] = vals[:, None]
                    G = prob.rows(cand.reshape(-1, prob.k)).reshape(len(vals), len(R), -1)
                    E = G - F[R][None]
                    EtC = np.einsum("vrp,rq->vpq", E, AF[R])
                    Mnew = M + EtC + EtC.transpose(0, 2, 1) + np.einsum("vrp,rs,vsq->vpq", E, A[np.ix_(R, R)], E)
                    v = information_criterion(Mnew + ridge, prob.crit, prob.W)
                    i = int(np.argmin(v))
                    if gain := is_gain(float(v[i]), cur):
                        D[R, j] = vals[i]
                        F[R] = G[i]
                        AF += A[:, R] @ E[i]
                        M = (Mnew[i] + Mnew[i].T) / 2.0
                        cur = float(v[i])
                    changed |= gain
            if not changed:
                break
        M = F.T @ A @ F  # afresh: no drift of the updates in the value returned
        return D, float(information_criterion(M + ridge, prob.crit, prob.W))


def _names(names: Sequence[str], given: Any, option: str, taken: Sequence[int], need: bool = True) -> list[int]:
    """Positions of the factor names ``given`` (a name or a list) for ``option``; unknown,
    repeated or already placed names are a ParameterError naming the option."""
    items = [given] if isinstance(given, str) else list(given or [])
    if need and not items:
        raise ParameterError(option, "name at least one factor")
    out: list[int] = []
    for h in items:
        if h not in names:
            raise ParameterError(option, f"{h!r} is not among the factors ({', '.join(names)})")
        i = names.index(h)
        if i in out:
            raise ParameterError(option, f"{h!r} is given twice")
        if i in taken:
            raise ParameterError(option, f"{h!r} is already in another stratum (each factor is set in one)")
        out.append(i)
    return out


def _whole(value: Any, name: str) -> int:
    if isinstance(value, (bool, np.bool_)) or int(value) != value or value < 1:
        raise ParameterError(name, f"must be a whole number >= 1 (got {value!r})")
    return int(value)


def _stratum_terms(terms: list[Term], members: set[int]) -> int:
    """Columns of the terms (intercept left out) whose factors all lie in ``members``."""
    return n_columns([t for t in terms if t.order > 0 and all(i in members for i, e in enumerate(t.powers) if e)])


def _search(space: Any, terms: list[Term], crit: str, groups: dict[str, np.ndarray], etas: dict[str, float],
            groups_of: list[list[np.ndarray]], rng: np.random.Generator, starts: int | None,
            model: str) -> tuple[np.ndarray, float, Any]:
    n = len(next(iter(groups.values())))
    p = n_columns(terms)
    Wm = moment_matrix(space, terms) if crit == "I" else None
    pool = candidate_pool(space, None, seed=int(rng.integers(2 ** 31)))
    prob = ExchangeProblem(space, terms, crit, Wm, None, pool)
    A = _inverse(stratum_covariance(groups, etas, n))
    search = _StrataSearch(prob, A, groups_of)
    k = 20 if starts is None and p <= 21 else 6 if starts is None else min(max(1, int(starts)), MAX_STARTS)
    best: np.ndarray | None = None
    best_v = math.inf
    for how in ["coarse"] * k + ["continuous"] * max(1, k // 2):
        D, v = search.improve(search.start(rng, how == "coarse"), coarse=how == "coarse")
        if best is None or v < best_v:
            best, best_v = D, v
    assert best is not None
    best, best_v = search.improve(best)
    M = stratum_information(design_matrix(best, terms), groups, etas)
    if reported_value(M, n, "D") == 0.0:
        raise ParameterError("runs", f"no design of {n} runs in these strata was found that estimates the {model} "
                                     "model; add runs or groups")
    return best, reported_value(M, n, crit, Wm), k


def _check_size(n: int, p: int, model: str, k: int, option: str = "runs") -> None:
    if n > MAX_STRATUM_RUNS:
        raise ParameterError(option, f"at most {MAX_STRATUM_RUNS} runs (got {n})")
    if n < p:
        raise ParameterError(option, f"{n} runs cannot estimate the {p} coefficients of the {model} model in "
                                     f"{k} factors")


def split_split_plot(
    factors: Any,
    very_hard_to_change: Any,
    hard_to_change: Any,
    whole_plots: int,
    subplots: int,
    runs: int,
    model: str = "quadratic",
    criterion: str = "D",
    variance_ratios: Any = None,
    seed: Any = None,
    starts: int | None = None,
    randomize: bool = True,
) -> Design:
    """An optimal split-split-plot design by coordinate exchange on ``X' V⁻¹ X`` with
    ``V = I + η_w Z_w Z_w' + η_s Z_s Z_s'`` (Jones & Goos 2009; module docstring).

    Parameters
    ----------
    factors : FactorSpace, mapping or list
        Numeric (``"NAME=LOW:HIGH"``) and categoric (``"NAME=cat:L1,L2"``) factors.
    very_hard_to_change : str or list of str
        Factors held constant within each whole plot (at least one).
    hard_to_change : str or list of str
        Factors held constant within each sub-plot (at least one).
    whole_plots : int
        Number of whole plots ``W``: at least the whole-plot model columns plus one.
    subplots : int
        Number of sub-plots ``S`` in all (``S / W`` per whole plot, the first ``S mod W`` whole
        plots one more): at least the columns of the terms in the very-hard and hard factors
        plus one.
    runs : int
        Total runs ``N`` (``N / S`` per sub-plot, the first ``N mod S`` sub-plots one more).
    model : {"linear", "2fi", "quadratic", "cubic"}
        The model the design must support.
    criterion : {"D", "I", "A"}
        On the GLS information.
    variance_ratios : float, mapping or None
        ``η`` [-] of both strata (a number) or ``{"whole_plot": η_w, "subplot": η_s}``
        (missing ones 1); None: both 1.
    seed : int, numpy.random.Generator or None
        Seeds the starts and the run order (None: drawn and recorded).
    starts : int or None
        Random starts on the -1/0/+1 grid; half as many more in the continuous region
        (default 20 for up to 21 model columns, else 6).
    randomize : bool
        ``True``: whole plots in random order, sub-plots in random order within each and runs
        in random order within each sub-plot.

    Returns
    -------
    Design
        ``kind="split-split-plot"``, ``whole_plots`` 1..W and ``strata["subplot"]`` 1..S (numbered
        across the design, in run order); ``options`` holds the criterion and its GLS value,
        the variance ratios, both factor lists, the group sizes and the seed.

    Examples
    --------
    >>> d = split_split_plot(["T=100:200", "P=1:2", "x=0:1"], ["T"], ["P"], whole_plots=4, subplots=8,
    ...                      runs=16, model="linear", seed=1)
    >>> d.n_runs, int(d.whole_plots.max()), int(d.strata["subplot"].max())
    (16, 4, 8)
    """
    space = as_factor_space(factors)
    crit = check_criterion(criterion)
    names = space.names
    vh = _names(names, very_hard_to_change, "very_hard_to_change", [])
    h = _names(names, hard_to_change, "hard_to_change", vh)
    W_n, S_n, n = _whole(whole_plots, "whole_plots"), _whole(subplots, "subplots"), _whole(runs, "runs")
    if starts is not None:
        _whole(starts, "starts")
    terms = model_terms(space.letters, model, space.categoric or None)
    p = n_columns(terms)
    check_columns(p, model, len(space))
    _check_size(n, p, model, len(space))
    need_w = _stratum_terms(terms, set(vh)) + 1
    if W_n < need_w:
        raise ParameterError("whole_plots", f"{W_n} whole plots cannot estimate the intercept and the {need_w - 1} "
                                            f"whole-plot column(s) of the {model} model; need at least {need_w}")
    need_s = _stratum_terms(terms, set(vh) | set(h)) + 1
    if S_n < max(need_s, W_n):
        raise ParameterError("subplots", f"{S_n} sub-plots cannot fill {W_n} whole plots and estimate the "
                                         f"{need_s - 1} whole- and sub-plot column(s) of the {model} model; need at "
                                         f"least {max(need_s, W_n)}")
    if n < S_n:
        raise ParameterError("runs", f"{n} runs cannot fill {S_n} sub-plots (at least one run each)")
    etas = _ratios(["whole_plot", "subplot"], variance_ratios)
    sub_per_whole = plot_sizes(S_n, W_n)
    run_per_sub = plot_sizes(n, S_n)
    sub_of_run = np.repeat(np.arange(S_n), run_per_sub)
    whole_of_sub = np.repeat(np.arange(W_n), sub_per_whole)
    whole_of_run = whole_of_sub[sub_of_run]
    groups = {"whole_plot": whole_of_run, "subplot": sub_of_run}
    by_whole = [np.flatnonzero(whole_of_run == w) for w in range(W_n)]
    by_sub = [np.flatnonzero(sub_of_run == s) for s in range(S_n)]
    by_run = [np.array([r]) for r in range(n)]
    groups_of = [by_whole if j in vh else by_sub if j in h else by_run for j in range(len(space))]
    rng, used_seed = resolve_seed(seed)
    best, value, k = _search(space, terms, crit, groups, etas, groups_of, rng, starts, model)
    options: dict[str, Any] = {
        "criterion": crit, "criterion_value": value, "information": "GLS", "model": model, "model_terms": p,
        "variance_ratios": etas, "very_hard_to_change": [names[i] for i in vh],
        "hard_to_change": [names[i] for i in h], "whole_plots": W_n, "subplots": S_n,
        "subplots_per_whole_plot": sub_per_whole, "subplot_sizes": run_per_sub, "starts": k,
        "algorithm": "coordinate exchange on X'V^-1 X, V = I + eta_w Z_w Z_w' + eta_s Z_s Z_s' (Jones & Goos 2009)",
    }
    if len(set(sub_per_whole)) > 1 or len(set(run_per_sub)) > 1:
        options["note"] = (f"unequal groups: {min(sub_per_whole)} to {max(sub_per_whole)} sub-plots per whole plot, "
                           f"{min(run_per_sub)} to {max(run_per_sub)} runs per sub-plot")
    order_rng, opts = seeded_options(options, rng if used_seed is None else used_seed, randomize)
    perm: list[int] = []
    w_seq = np.arange(W_n) if order_rng is None else order_rng.permutation(W_n)
    for w in w_seq:
        subs = np.flatnonzero(whole_of_sub == w)
        for s in subs if order_rng is None else subs[order_rng.permutation(len(subs))]:
            members = by_sub[s]
            perm.extend((members if order_rng is None else members[order_rng.permutation(len(members))]).tolist())
    return _assemble(space, best, perm, "split-split-plot", opts,
                     whole_plots=whole_of_run, strata={"subplot": sub_of_run})


def _first_seen(labels: np.ndarray) -> np.ndarray:
    """Labels renumbered 1, 2, ... in order of first appearance."""
    codes: dict[int, int] = {}
    return np.array([codes.setdefault(int(v), len(codes) + 1) for v in labels], dtype=int)


def _assemble(space: Any, D: np.ndarray, perm: list[int], kind: str, opts: dict,
              whole_plots: np.ndarray | None, strata: dict[str, np.ndarray]) -> Design:
    """The design with runs made in the order ``perm`` (standard-order indices), its groups
    numbered 1, 2, ... in run order."""
    n = len(D)
    order = np.asarray(perm, dtype=int)
    run_order = np.empty(n, dtype=int)
    run_order[order] = np.arange(1, n + 1)
    renumber = (lambda g: _first_seen(np.asarray(g)[order])[np.argsort(order)])  # noqa: E731
    return Design(factors=space, kind=kind, coded_runs=D, std_order=np.arange(1, n + 1), run_order=run_order,
                  options=opts, whole_plots=None if whole_plots is None else renumber(whole_plots),
                  strata={k: renumber(v) for k, v in strata.items()})


def strip_plot(
    factors: Any,
    row_factors: Any,
    column_factors: Any,
    rows: int,
    columns: int,
    model: str = "quadratic",
    criterion: str = "D",
    variance_ratios: Any = None,
    seed: Any = None,
    starts: int | None = None,
    randomize: bool = True,
) -> Design:
    """An optimal strip-plot design by coordinate exchange on ``X' V⁻¹ X`` with
    ``V = I + η_r Z_r Z_r' + η_c Z_c Z_c'`` (Arnouts, Goos & Jones 2010; module docstring).

    Parameters
    ----------
    factors : FactorSpace, mapping or list
        Numeric and categoric factors.
    row_factors : str or list of str
        Factors set once per row strip (the first processing stage; at least one).
    column_factors : str or list of str
        Factors set once per column strip (the second stage; at least one).
    rows, columns : int
        Numbers ``R`` and ``C`` of row and column strips; the design has ``R C`` runs, one per
        cell. ``R`` must exceed the row-factor model columns and ``C`` the column-factor ones.
    model : {"linear", "2fi", "quadratic", "cubic"}
        The model the design must support.
    criterion : {"D", "I", "A"}
        On the GLS information.
    variance_ratios : float, mapping or None
        ``η`` [-] of both strata or ``{"strip_row": η_r, "strip_column": η_c}`` (missing
        ones 1); None: both 1.
    seed, starts, randomize
        As for :func:`split_split_plot`; the rows and the columns are processed in random
        order (runs listed row by row).

    Returns
    -------
    Design
        ``kind="strip-plot"`` with ``strata["strip_row"]`` (1..R) and ``strata["strip_column"]``
        (1..C); ``options`` as :func:`split_split_plot`'s.

    Examples
    --------
    >>> d = strip_plot(["A=0:1", "B=0:1", "C=0:1"], ["A"], ["B"], rows=4, columns=4, model="linear", seed=2)
    >>> d.n_runs, int(d.strata["strip_row"].max()), int(d.strata["strip_column"].max())
    (16, 4, 4)
    """
    space = as_factor_space(factors)
    crit = check_criterion(criterion)
    names = space.names
    rf = _names(names, row_factors, "row_factors", [])
    cf = _names(names, column_factors, "column_factors", rf)
    R, C = _whole(rows, "rows"), _whole(columns, "columns")
    if starts is not None:
        _whole(starts, "starts")
    n = R * C
    terms = model_terms(space.letters, model, space.categoric or None)
    p = n_columns(terms)
    check_columns(p, model, len(space))
    _check_size(n, p, model, len(space), "rows")
    for option, count, members in (("rows", R, rf), ("columns", C, cf)):
        need = _stratum_terms(terms, set(members)) + 1
        if count < need:
            raise ParameterError(option, f"{count} {option} cannot estimate the intercept and the {need - 1} "
                                         f"{option[:-1]}-factor column(s) of the {model} model; need at least {need}")
    etas = _ratios(["strip_row", "strip_column"], variance_ratios)
    row_of = np.repeat(np.arange(R), C)
    col_of = np.tile(np.arange(C), R)
    groups = {"strip_row": row_of, "strip_column": col_of}
    by_row = [np.flatnonzero(row_of == r) for r in range(R)]
    by_col = [np.flatnonzero(col_of == c) for c in range(C)]
    groups_of = [by_row if j in rf else by_col if j in cf else [np.array([i]) for i in range(n)]
                 for j in range(len(space))]
    rng, used_seed = resolve_seed(seed)
    best, value, k = _search(space, terms, crit, groups, etas, groups_of, rng, starts, model)
    options: dict[str, Any] = {
        "criterion": crit, "criterion_value": value, "information": "GLS", "model": model, "model_terms": p,
        "variance_ratios": etas, "row_factors": [names[i] for i in rf], "column_factors": [names[i] for i in cf],
        "rows": R, "columns": C, "starts": k,
        "algorithm": "coordinate exchange on X'V^-1 X, V = I + eta_r Z_r Z_r' + eta_c Z_c Z_c' "
                     "(Arnouts, Goos & Jones 2010)",
    }
    order_rng, opts = seeded_options(options, rng if used_seed is None else used_seed, randomize)
    r_seq = np.arange(R) if order_rng is None else order_rng.permutation(R)
    c_seq = np.arange(C) if order_rng is None else order_rng.permutation(C)
    perm = [int(r * C + c) for r in r_seq for c in c_seq]
    return _assemble(space, best, perm, "strip-plot", opts, whole_plots=None,
                     strata={"strip_row": row_of, "strip_column": col_of})
