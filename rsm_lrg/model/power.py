"""Power by simulation (Monte Carlo power, as R skpr's ``eval_design_mc`` and JMP's
simulated power): the probability that the analysis a user will run declares each model
coefficient significant, estimated by simulating responses at a design and refitting.

The simulated truth, in the units of :func:`rsm_lrg.model.evaluate.evaluate_design`'s
parametric power: every model coefficient but the intercept (and the block contrasts, which
are 0) is ``effect_sd / 2`` — a change of ``effect_sd`` over the coded range -1..+1 — and

* **gaussian** (``family="gaussian"``): noise ``sigma = 1``; the responses are refitted by
  ordinary least squares and each coefficient is declared significant when its two-sided
  ``t`` test (the coefficient table of :func:`rsm_lrg.fit`; equal to the one-df partial ``F``
  test) has ``p < alpha``. All draws are one matrix computation: the model matrix is
  factorised once (``X = QR``), the coefficients of a block of draws are
  ``R^-1 Q'Y`` and their residual sums of squares ``|Y - QQ'Y|^2``. Beside it, the exact power
  of the same test, ``P(F'(1, nu, lambda) > F(1 - alpha; 1, nu))`` with
  ``lambda = (effect_sd / 2)^2 / C_jj`` (:func:`rsm_lrg.model.evaluate.ols_power`);
* **split plot** (a design with whole plots): a random intercept per whole plot with variance
  ``variance_ratio * sigma^2`` (``eta``, default 1) is added to every draw, and each draw is
  refitted by REML with Kenward–Roger tests (:func:`rsm_lrg.model.engines.mixed.fit_reml`,
  the analysis of ``fit --whole-plot``; R's ``lmer`` with ``pbkrtest``): the coefficient's
  KR ``F`` test, ``p < alpha``. No formula gives this power, so there is no parametric column;
* **binomial** (``family="binomial"``): one 0/1 outcome per run from a logit model whose
  intercept is ``logit(baseline)`` and whose other coefficients are ``effect_sd / 2`` on the
  logit scale (skpr's convention: the change of the log-odds over the coded range, so a factor
  at +1 against -1 multiplies the odds by ``exp(effect_sd)``); each draw is refitted by maximum
  likelihood (:func:`rsm_lrg.model.pipelines.glm.irls`, the engine of ``fit --family
  binomial``) and each coefficient is tested by the **likelihood-ratio** test of the model
  without its column (the analysis of deviance, R's ``drop1(fit, test = "LRT")``), ``p <
  alpha``. A draw whose outcomes are separated (:func:`~rsm_lrg.model.pipelines.glm.check_separation`)
  has no finite fit — ``fit`` refuses it — so it declares nothing significant; the number
  of such draws is reported.

One test per model column, the rows of ``evaluate``'s power table (a categoric factor's
effect-coded columns one by one).

**Reproducibility.** Draw ``i`` takes its random numbers from the ``i``-th child of
``numpy.random.SeedSequence(seed).spawn(draws)`` alone, so the result is bit-identical for a
seed whatever the number of worker processes (``workers``) or how the draws are split among
them.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import ParameterError
from .evaluate import design_model, ols_power

__all__ = ["simulate_power", "PowerSimulation", "FAMILIES", "MAX_DRAWS", "OLS_CHUNK", "REFIT_CHUNK"]

#: The response families simulated.
FAMILIES = ("gaussian", "binomial")
#: Most draws of one simulation.
MAX_DRAWS = 10_000_000
#: Draws computed together by the least-squares route (fixed, so every split of the draws
#: among workers computes the same blocks).
OLS_CHUNK = 4096
#: Draws per task of the refitting routes (REML, GLM).
REFIT_CHUNK = 25


@dataclass(frozen=True)
class PowerSimulation:
    """Monte Carlo power of a design (frozen; :func:`simulate_power`).

    Attributes
    ----------
    model : str
        The model (``"linear"``, ..., or ``"terms"`` for a list of terms).
    family : {"gaussian", "binomial"}
    analysis : str
        The analysis refitted per draw, in words.
    n : int
        Runs of the design.
    draws, seed, workers : int
        Simulated responses, the seed of their ``SeedSequence`` and the worker processes used.
    alpha : float
        Level of the tests.
    effect_sd : float
        Effect over the coded range -1..+1 (coefficient ``effect_sd / 2``): in σ (gaussian) or
        on the logit scale (binomial).
    variance_ratio : float or None
        ``η = σ²_wp / σ²`` of a split-plot design (None without whole plots).
    baseline : float or None
        Probability at the centre of the design (binomial).
    whole_plots : int or None
        Number of whole plots (None without).
    terms : pandas.DataFrame
        Index the model columns (intercept left out); columns ``coefficient`` (the simulated
        value), ``power`` (fraction of draws with ``p < alpha``), ``mc_se`` (its Monte Carlo
        standard error ``sqrt(power (1 - power) / draws)``) and ``parametric`` (the exact
        noncentral-F power of the OLS test; NaN where no formula applies).
    separated : int
        Draws whose outcomes were separated (binomial): no finite fit, nothing declared.
    failed : int
        Draws whose refit failed otherwise (REML with no residual variance, IRLS not
        converging): nothing declared.
    seconds : float
        Wall time of the simulation [s] (not part of :meth:`to_dict`, which is identical for a seed).
    """

    model: str
    family: str
    analysis: str
    n: int
    draws: int
    seed: int
    alpha: float
    effect_sd: float
    terms: Any = field(repr=False)
    variance_ratio: float | None = None
    baseline: float | None = None
    whole_plots: int | None = None
    separated: int = 0
    failed: int = 0
    workers: int = 1
    seconds: float = math.nan

    def to_dict(self) -> dict:
        """The simulation as JSON-ready data (no non-finite number: NaN is ``None``).

        Returns
        -------
        dict
            ``{"power_simulation": {...}}`` with the settings, the counts and one entry per
            model column (``coefficient``, ``power``, ``mc_se``, ``parametric``).
        """
        def f(v: Any) -> float | None:
            return float(v) if v is not None and math.isfinite(float(v)) else None

        return {"power_simulation": {
            "model": self.model, "family": self.family, "analysis": self.analysis, "n": self.n,
            "draws": self.draws, "seed": self.seed, "alpha": self.alpha, "effect_sd": self.effect_sd,
            "variance_ratio": f(self.variance_ratio), "baseline": f(self.baseline), "whole_plots": self.whole_plots,
            "separated": self.separated, "failed": self.failed,
            "terms": {str(t): {"coefficient": f(r.coefficient), "power": f(r.power), "mc_se": f(r.mc_se),
                               "parametric": f(r.parametric)} for t, r in self.terms.iterrows()}}}

    def summary(self) -> str:
        """The simulation for people: the settings, then one row per model column.

        Returns
        -------
        str
        """
        from ..present import format_g, text_table

        truth = (f"coefficients {format_g(self.effect_sd / 2)} on the logit scale (effect {format_g(self.effect_sd)} "
                 f"over the coded range), baseline probability {format_g(self.baseline)}"
                 if self.family == "binomial" else
                 f"coefficients {format_g(self.effect_sd / 2)} σ (effect {format_g(self.effect_sd)} σ over the coded "
                 "range), σ = 1" + ("" if self.variance_ratio is None else
                                    f", whole-plot variance η σ² with η = {format_g(self.variance_ratio)}"))
        out = [f"Power by simulation for a {self.model} model: {self.n} runs"
               + ("" if self.whole_plots is None else f" in {self.whole_plots} whole plots")
               + f", {self.draws} draws (seed {self.seed}), α {self.alpha:g}",
               f"Simulated: {truth}.", f"Analysis per draw: {self.analysis}."]
        pct = lambda v: "" if not math.isfinite(v) else f"{100 * v:.1f} %"  # noqa: E731
        has_par = bool(np.isfinite(self.terms["parametric"].to_numpy(dtype=float)).any())
        heads = ["Term", "Coefficient", "Power (simulated)", "MC SE"] + (["Power (exact, noncentral F)"] if has_par else [])
        rows = [[str(t), format_g(r.coefficient), pct(r.power), pct(r.mc_se)] + ([pct(r.parametric)] if has_par else [])
                for t, r in self.terms.iterrows()]
        out += ["", text_table(heads, rows)]
        if self.separated:
            out.append(f"{self.separated} of {self.draws} draws had separated outcomes (no finite fit): counted as "
                       "declaring nothing significant.")
        if self.failed:
            out.append(f"{self.failed} of {self.draws} draws could not be refitted: counted as declaring nothing "
                       "significant.")
        return "\n".join(out) + "\n"

    def __str__(self) -> str:
        return self.summary()


@dataclass(frozen=True)
class _Setup:
    """What every draw needs (sent to the worker processes)."""

    kind: str  # "ols", "reml" or "glm"
    X: np.ndarray
    beta: np.ndarray
    tested: np.ndarray
    names: tuple
    alpha: float
    codes: np.ndarray | None = None
    eta: float = 0.0


def _seeds(seed: int, start: int, stop: int) -> list:
    """The children ``start..stop-1`` of ``SeedSequence(seed).spawn(draws)`` (made directly: child
    ``i`` is ``SeedSequence(seed, spawn_key=(i,))``)."""
    return [np.random.SeedSequence(seed, spawn_key=(i,)) for i in range(start, stop)]


def _chunk(setup: _Setup, seed: int, start: int, stop: int) -> tuple[np.ndarray, int, int]:
    """``(significant (draws, tested) bool, separated, failed)`` of the draws ``start..stop-1``."""
    seeds = _seeds(seed, start, stop)
    if setup.kind == "ols":
        return _ols_chunk(setup, seeds), 0, 0
    sig = np.zeros((len(seeds), setup.tested.size), dtype=bool)
    sep = bad = 0
    for i, s in enumerate(seeds):
        status, row = (_reml_draw if setup.kind == "reml" else _glm_draw)(setup, np.random.default_rng(s))
        sig[i] = row
        sep += status == 1
        bad += status == 2
    return sig, sep, bad


def _ols_chunk(setup: _Setup, seeds: list) -> np.ndarray:
    """The t tests of a block of draws in one matrix computation (``X = QR`` once)."""
    from scipy.linalg import solve_triangular
    from scipy.special import stdtrit

    X = setup.X
    n, p = X.shape
    Q, R = np.linalg.qr(X)
    Rinv = solve_triangular(R, np.eye(p))
    cjj = np.sum(Rinv * Rinv, axis=1)[setup.tested]  # diag((X'X)^-1)
    mean = X @ setup.beta
    E = np.empty((n, len(seeds)))
    for i, s in enumerate(seeds):
        E[:, i] = np.random.default_rng(s).standard_normal(n)
    Y = mean[:, None] + E
    Z = Q.T @ Y
    B = solve_triangular(R, Z)
    res = Y - Q @ Z
    df = n - p
    s2 = np.sum(res * res, axis=0) / df
    tcrit = float(stdtrit(df, 1.0 - setup.alpha / 2.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        t = B[setup.tested] / np.sqrt(cjj[:, None] * s2[None, :])
    return np.asarray((np.abs(t) > tcrit).T)


def _reml_draw(setup: _Setup, rng: np.random.Generator) -> tuple[int, np.ndarray]:
    """One split-plot draw refitted by REML; Kenward–Roger ``p < alpha`` per tested column."""
    from .engines.mixed import fit_reml

    X, codes = setup.X, setup.codes
    assert codes is not None
    n, p = X.shape
    e = rng.standard_normal(n)
    u = rng.standard_normal(int(codes.max()) + 1) * math.sqrt(setup.eta)
    y = X @ setup.beta + e + u[codes]
    try:
        mm, _ = fit_reml(X, y, codes, tuple(range(int(codes.max()) + 1)), list(setup.names), column="whole_plot")
    except (ValueError, np.linalg.LinAlgError):
        return 2, np.zeros(setup.tested.size, dtype=bool)
    row = np.zeros(setup.tested.size, dtype=bool)
    for i, j in enumerate(setup.tested):
        L = np.zeros((1, p))
        L[0, j] = 1.0
        _, _, pv, _ = mm.test(L)
        row[i] = bool(pv < setup.alpha)  # a NaN p (den df not positive) declares nothing
    return 0, row


def _glm_draw(setup: _Setup, rng: np.random.Generator) -> tuple[int, np.ndarray]:
    """One binomial draw refitted by maximum likelihood; the likelihood-ratio test of each
    tested column (the model without it refitted), ``p < alpha``."""
    from scipy.special import chdtrc, expit

    from .engines.glm_family import family
    from .pipelines.glm import SeparationError, check_separation, irls

    X = setup.X
    n, p = X.shape
    prob = expit(X @ setup.beta)
    y = (rng.random(n) < prob).astype(float)
    m = np.ones(n)
    fam = family("binomial")
    row = np.zeros(setup.tested.size, dtype=bool)
    try:
        check_separation(X, y, m, fam, list(setup.names))
    except SeparationError:
        return 1, row
    try:
        full = irls(X, y, m, fam)
        for i, j in enumerate(setup.tested):
            keep = np.delete(np.arange(p), j)
            sub = irls(X[:, keep], y, m, fam, start=full.params[keep])
            chi = max(sub.deviance - full.deviance, 0.0)
            row[i] = bool(float(chdtrc(1, chi)) < setup.alpha)
    except (ValueError, np.linalg.LinAlgError):
        return 2, np.zeros(setup.tested.size, dtype=bool)
    return 0, row


def _whole(value: Any, name: str, lo: int, hi: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not lo <= int(value) <= hi:
        raise ParameterError(name, f"{name} must be a whole number from {lo} to {hi}, not {value!r}")
    return int(value)


def simulate_power(design: Any, model: str = "quadratic", *, effect_sd: float = 2.0, alpha: float = 0.05,
                   draws: int = 1000, seed: int = 1, family: str = "gaussian", baseline: float | None = None,
                   variance_ratio: float | None = None, whole_plots: Any = None, workers: int = 1,
                   terms: Any = None, intercept: bool = True, executor: Any = None) -> PowerSimulation:
    """Monte Carlo power of each model coefficient of a design (see the module docstring).

    Parameters
    ----------
    design : Design or (n, k) array of coded settings
        A :class:`~rsm_lrg.design.Design` (blocks are fitted, with no block effect simulated;
        whole plots make the split-plot simulation) or coded runs.
    model : {"linear", "2fi", "quadratic", "cubic"}
    effect_sd : float
        Effect to detect over the coded range -1..+1 (coefficient ``effect_sd / 2``): in σ, or
        on the logit scale for ``family="binomial"``.
    alpha : float
        Level of the tests.
    draws : int
        Simulated responses, 1 to :data:`MAX_DRAWS`.
    seed : int
        Seed of the draws' ``SeedSequence`` (>= 0).
    family : {"gaussian", "binomial"}
    baseline : float, optional
        Probability at the design centre (binomial only; default 0.5), strictly between 0 and 1.
    variance_ratio : float, optional
        ``η = σ²_wp / σ²`` of a split-plot design (default 1); refused without whole plots.
    whole_plots : array_like, optional
        The whole plot of each run (any labels) when ``design`` is an array; a
        :class:`~rsm_lrg.design.Design` brings its own.
    workers : int
        Worker processes for the draws (1 to 64); the result does not depend on it.
    terms, intercept
        A list of terms instead of ``model``, as :func:`~rsm_lrg.model.evaluate.evaluate_design`.
    executor : concurrent.futures.Executor, optional
        Where the blocks of draws run instead of ``workers`` local processes: a
        ``ProcessPoolExecutor`` or a Dask ``Client.get_executor()`` (a cluster); the blocks and
        their seeds are the same, so the result does not depend on it.

    Returns
    -------
    PowerSimulation
        ``ValueError`` when the design cannot estimate the model or leaves no residual degrees
        of freedom; :class:`~rsm_lrg.errors.ParameterError` naming a bad argument.
    """
    import pandas as pd

    if family not in FAMILIES:
        raise ParameterError("family", f"family must be one of {', '.join(FAMILIES)}, not {family!r}")
    if not 0 < alpha < 1:
        raise ParameterError("alpha", f"alpha must lie between 0 and 1, not {alpha!r}")
    if not (isinstance(effect_sd, (int, float)) and effect_sd > 0 and math.isfinite(effect_sd)):
        raise ParameterError("effect_sd", f"effect_sd must be a positive number, not {effect_sd!r}")
    draws = _whole(draws, "draws", 1, MAX_DRAWS)
    seed = _whole(seed, "seed", 0, 2 ** 63 - 1)
    workers = _whole(workers, "workers", 1, 64)
    if family == "binomial":
        p0 = 0.5 if baseline is None else baseline
        if not (isinstance(p0, (int, float)) and 0.0 < p0 < 1.0):
            raise ParameterError("baseline", f"baseline must be a probability strictly between 0 and 1, not {p0!r}")
        baseline = float(p0)
    elif baseline is not None:
        raise ParameterError("baseline", "baseline is the probability of a binomial response: give family "
                                         "'binomial' too")
    dm = design_model(design, model, terms=terms, intercept=intercept)
    plots = dm.whole_plots
    if whole_plots is not None:
        if plots is not None:
            raise ParameterError("whole_plots", "the design has whole plots of its own")
        plots = list(np.asarray(whole_plots).tolist())
        if len(plots) != dm.X.shape[0]:
            raise ParameterError("whole_plots", f"{len(plots)} whole-plot labels for {dm.X.shape[0]} runs")
    if plots is None and variance_ratio is not None:
        raise ParameterError("variance_ratio", "the design has no whole plots (no whole_plot column; name the "
                                               "whole-plot column with --whole-plot COL)")
    if plots is not None:
        if family == "binomial":
            raise ParameterError("family", "a binomial response with whole plots needs a generalised linear mixed "
                                           "model, which is not simulated here; drop the whole plots or use the "
                                           "gaussian family")
        if dm.n_blocks > 1:
            raise ValueError("a design with both blocks and whole plots is not simulated here; drop the block "
                             "column or the whole-plot column")
        eta = 1.0 if variance_ratio is None else variance_ratio
        if not (isinstance(eta, (int, float)) and 0.0 <= eta <= 1e6 and math.isfinite(eta)):
            raise ParameterError("variance_ratio", f"variance_ratio must be a number from 0 to 1e6, not {eta!r}")
        variance_ratio = float(eta)
    X = dm.X
    n, p = X.shape
    if np.linalg.matrix_rank(X) < p:
        from .engines.least_squares import least_squares

        ls = least_squares(X, np.zeros(n), ["Intercept"] + [f"Block{j + 1}" for j in range(dm.n_blocks - 1)]
                           + list(dm.names[1:]))
        raise ValueError(f"the {model} model is not estimable from this design (rank {ls.rank} < {p} parameters): "
                         f"aliased {', '.join(ls.aliased[:12]) or '(unidentified)'}; use a smaller --model or add runs")
    if n - p < 1:
        raise ValueError(f"the {model} model leaves no residual degrees of freedom ({n} runs, {p} parameters): "
                         "nothing to test the coefficients against; add runs or use a smaller --model")
    cols = dm.term_columns
    has_intercept = any(t.order == 0 for t in dm.terms)
    tested = cols[1:] if has_intercept else cols
    names = list(dm.names[1:]) if has_intercept else list(dm.names)
    beta = np.zeros(p)
    beta[tested] = effect_sd / 2.0
    if family == "binomial" and has_intercept:
        assert baseline is not None
        beta[0] = math.log(baseline / (1.0 - baseline))
    col_names = tuple(["Intercept"] + [f"Block{j + 1}" for j in range(dm.n_blocks - 1)] + list(dm.names[1:])) \
        if has_intercept else tuple(dm.names)
    codes = None
    if plots is not None:
        from .engines.mixed import group_codes

        codes = group_codes(np.asarray(plots).tolist())[0]
        kind, analysis = "reml", ("REML with a random intercept per whole plot, Kenward–Roger F test of each "
                                  "coefficient (fit --whole-plot; R lmer + pbkrtest)")
    elif family == "binomial":
        kind, analysis = "glm", ("binomial GLM (logit link) by maximum likelihood, likelihood-ratio test of each "
                                 "coefficient (fit --family binomial's analysis of deviance; R glm + drop1 LRT)")
    else:
        kind, analysis = "ols", "ordinary least squares, t test of each coefficient (fit's coefficient table)"
    setup = _Setup(kind=kind, X=X, beta=beta, tested=np.asarray(tested), names=col_names, alpha=float(alpha),
                   codes=codes, eta=float(variance_ratio or 0.0))
    size = OLS_CHUNK if kind == "ols" else REFIT_CHUNK
    starts = list(range(0, draws, size))
    stops = [min(s + size, draws) for s in starts]
    t0 = time.perf_counter()
    if executor is not None:
        parts = list(executor.map(_chunk, [setup] * len(starts), [seed] * len(starts), starts, stops))
    elif workers > 1 and len(starts) > 1:
        from concurrent.futures import ProcessPoolExecutor

        with ProcessPoolExecutor(max_workers=min(workers, len(starts))) as ex:
            parts = list(ex.map(_chunk, [setup] * len(starts), [seed] * len(starts), starts, stops))
    else:
        parts = [_chunk(setup, seed, a, b) for a, b in zip(starts, stops)]
    seconds = time.perf_counter() - t0
    sig = np.concatenate([q[0] for q in parts], axis=0)
    separated = int(sum(q[1] for q in parts))
    failed = int(sum(q[2] for q in parts))
    power = sig.sum(axis=0) / draws
    mc_se = np.sqrt(power * (1.0 - power) / draws)
    parametric = np.full(len(tested), np.nan)
    if kind == "ols":
        Rinv = np.linalg.inv(np.linalg.qr(X, mode="r"))
        parametric = ols_power(np.sum(Rinv * Rinv, axis=1)[tested], n - p, alpha, effect_sd)
    frame = pd.DataFrame({"coefficient": beta[tested], "power": power, "mc_se": mc_se, "parametric": parametric},
                         index=pd.Index(names, name="term"))
    return PowerSimulation(model=model if terms is None else "terms", family=family, analysis=analysis, n=n,
                           draws=draws, seed=seed, alpha=float(alpha), effect_sd=float(effect_sd), terms=frame,
                           variance_ratio=variance_ratio, baseline=baseline if family == "binomial" else None,
                           whole_plots=None if codes is None else int(codes.max()) + 1, separated=separated,
                           failed=failed, workers=workers, seconds=seconds)
