"""The simulator: N virtual runs drawn around one setting, through the fitted models.

For each run ``j`` (JMP's Simulator, with the model's own uncertainty added):

1. **Factor noise** (``factor_sd``, actual units): each numeric factor with an SD is drawn from
   a normal distribution about its setting **truncated to the design region** — a factor's
   range (``LOW:HIGH`` of ``--factor``, else its observed minimum and maximum); a mixture
   component's deviations are projected onto the blend plane (each gives up the mean deviation,
   so the blend keeps its total, as in :mod:`rsm_lrg.optimize.poe`) and a blend outside a
   component's bounds is drawn again. Truncation is exact (inverse CDF) for the box and by
   rejection for a mixture; a setting outside the region cannot be simulated with noise on the
   factor concerned. One factor draw per run is shared by every response (the same physical run).
2. **Model uncertainty** (``model_uncertainty=True``): the coefficients are drawn from their
   sampling distribution, a multivariate t with the fit's covariance ``C`` (σ̂²(X'X)⁻¹ for OLS,
   Kenward–Roger's Φ_A for REML) and ν degrees of freedom (residual df; REML: the KR df of the
   mean at the setting): ``b_j = b̂ + √w_j · C^{1/2} z_j`` with ``w_j = ν / χ²_ν``.
3. **Residual noise**: ``ε_j = √w_j · s · z'_j`` with ``s²`` the variance of a new run (the
   residual mean square; REML: both variance components). The same ``w_j`` scales the
   coefficients and the noise — the posterior predictive distribution of a normal linear model
   under the reference prior — so without factor noise a run is ``ŷ + t_ν √(se² + s²)``, whose
   central 95 % is exactly the prediction interval. Without model uncertainty ``w_j = 1``
   (the plug-in: coefficients and ``s`` taken as known).
4. The run's response is the back-transform of ``x_j' b_j + ε_j`` (response units).

Per response: mean, SD, the 0.1, 2.5, 50, 97.5 and 99.9 % quantiles, the defect rate (ppm)
below and above its spec, Cpk = min(USL - mean, mean - LSL) / (3 SD) of the simulated runs (one
side when the spec has one limit), and over all responses the rate of runs outside *any* spec.
Each rate has its Monte Carlo standard error √(p(1-p)/N).

Reproducible: the draws come in fixed blocks of :data:`BLOCK` runs, block ``b`` from the
generator of ``SeedSequence(seed).spawn`` child ``b``, so a seed gives bit-identical numbers
however the blocks are scheduled: in this process or on the workers of an ``executor`` (a
process pool: ``predict --workers N``; a Dask client's executor: ``predict --scheduler``).

**Streaming** (more than :data:`MAX_KEPT` runs, or ``stream=True``): the runs are not kept. The
blocks go out in tasks of :data:`TASK_BLOCKS`; pass 1 returns per block and response the count,
mean, sum of squared deviations, least and largest value and the counts outside the spec (and
per block the runs outside any spec), merged on the caller's side block by block *in block
order* (Chan, Golub and LeVeque's pairwise update), so the numbers do not depend on the worker
count or on the order in which tasks finish. The quantiles are **exact** — the order statistics
``numpy.quantile`` (method linear) would interpolate, found without sorting the runs: pass 2
counts the finite runs in :data:`HIST_BINS` equal bins over [least, largest] (integer counts,
and each bin's least and largest run); the bin that holds each wanted order statistic follows
from the cumulative counts; a bin with more than :data:`MAX_BIN_VALUES` runs is binned again
over its own range (another pass); a last pass collects the runs of those bins only, which are
sorted. Every pass redraws the same blocks from their seeds. Memory per task: a few histograms
(1.5 MiB each) and the collected bins' runs, whatever N. The mean and SD equal the kept runs'
to rounding (a different order of summation); everything else is equal bit for bit.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import ParameterError

__all__ = ["simulate", "simulate_runs", "simulate_blocks", "SimulationResult", "parse_specs", "MAX_DRAWS", "BLOCK", "QUANTILES"]

#: Runs per block of draws (the unit of reproducibility).
BLOCK = 1 << 16
#: The most runs one simulation may draw.
MAX_DRAWS = 10**9
#: Up to this many runs every run's response is kept (8 bytes each per response) and returned;
#: above it the statistics are streamed (exact all the same; module docstring).
MAX_KEPT = 10**7
#: Bins of the streamed quantiles' histogram.
HIST_BINS = 1 << 16
#: A bin holding more runs than this is split again before its values are collected.
MAX_BIN_VALUES = 1 << 20
#: Blocks per task of the streamed simulation (about a million runs).
TASK_BLOCKS = 16
#: The quantiles reported [-].
QUANTILES = (0.001, 0.025, 0.5, 0.975, 0.999)
#: A mixture's rejection sampling gives up after this many rounds of redraws.
MAX_REJECTION_ROUNDS = 200


def parse_specs(responses: Sequence[str], items: Mapping[str, Any] | Sequence[str] | None) -> dict:
    """``{response: (low or None, high or None)}`` from ``["Y=LOW:HIGH", "Y=:HIGH", ...]`` or
    a mapping of pairs; a ParameterError (parameter ``spec``) for an unknown response, a spec
    given twice, a bound that is not a finite number, or LOW >= HIGH."""
    if not items:
        return {}
    pairs: list[tuple[str, Any]]
    if isinstance(items, Mapping):
        pairs = list(items.items())
    else:
        pairs = []
        for s in items:
            name, sep, rest = str(s).partition("=")
            if not sep or ":" not in rest:
                raise ParameterError("spec", f"spec {s!r}: expected RESPONSE=LOW:HIGH (either side may be empty)")
            a, _, b = rest.partition(":")
            pairs.append((name.strip(), (a.strip() or None, b.strip() or None)))
    out: dict = {}
    for name, (a, b) in pairs:
        if name not in responses:
            raise ParameterError("spec", f"spec for {name!r}: not one of the responses ({', '.join(responses)})")
        if name in out:
            raise ParameterError("spec", f"spec for {name!r} is given more than once")
        lim: list[float | None] = []
        for v in (a, b):
            if v is None:
                lim.append(None)
                continue
            try:
                x = float(v)
            except (TypeError, ValueError):
                raise ParameterError("spec", f"spec for {name!r}: {v!r} is not a number") from None
            if not math.isfinite(x):
                raise ParameterError("spec", f"spec for {name!r}: the limits must be finite")
            lim.append(x)
        if lim[0] is None and lim[1] is None:
            raise ParameterError("spec", f"spec for {name!r}: give a lower limit, an upper limit or both")
        if lim[0] is not None and lim[1] is not None and not lim[0] < lim[1]:
            raise ParameterError("spec", f"spec for {name!r}: LOW must be below HIGH")
        out[name] = (lim[0], lim[1])
    return out


@dataclass(frozen=True)
class SimulationResult:
    """The simulated runs at one setting (frozen).

    Attributes
    ----------
    setting : dict
        The setting [actual units].
    draws, seed : int
    factor_sd : dict
        ``{factor: SD}`` [actual units].
    model_uncertainty : bool
    responses : dict
        Per response: ``mean``, ``sd``, ``quantiles`` (``{"0.1%": ..., ...}``), ``spec``
        (``[low, high]``, None for no limit), ``ppm_below``, ``ppm_above``, ``ppm`` (outside),
        ``ppm_se`` (its Monte Carlo standard error), ``cpk``, ``invalid`` (runs whose
        back-transform is undefined, left out) [response units, ppm].
    ppm_any, ppm_any_se : float or None
        Runs outside any spec [ppm] and its Monte Carlo SE (None without a spec).
    """

    setting: dict
    draws: int
    seed: int | None
    factor_sd: dict
    model_uncertainty: bool
    responses: dict
    ppm_any: float | None = None
    ppm_any_se: float | None = None
    notes: tuple = field(default=())

    def to_dict(self) -> dict:
        return {"setting": dict(self.setting), "draws": self.draws, "seed": self.seed,
                "factor_sd": dict(self.factor_sd), "model_uncertainty": self.model_uncertainty,
                "responses": {k: dict(v) for k, v in self.responses.items()},
                "ppm_outside_any_spec": self.ppm_any, "ppm_outside_any_spec_se": self.ppm_any_se,
                "notes": list(self.notes)}

    def summary(self) -> str:
        from ..present import format_g

        def g(v):
            return "-" if v is None or not math.isfinite(v) else format_g(v, 5, trim=True)

        head = (f"Simulation: {self.draws} runs (seed {self.seed}); factor noise "
                + (", ".join(f"{k} sd {g(v)}" for k, v in self.factor_sd.items()) or "none")
                + " (normal, truncated to the design region); model uncertainty "
                + ("drawn (multivariate t)" if self.model_uncertainty else "not drawn"))
        lines = [head]
        for name, r in self.responses.items():
            q = r["quantiles"]
            lines.append(f"  {name}: mean {g(r['mean'])}, sd {g(r['sd'])}; quantiles "
                         + ", ".join(f"{k} {g(v)}" for k, v in q.items()))
            if r["spec"] is not None:
                lo, hi = r["spec"]
                lines.append(f"    spec {g(lo)} .. {g(hi)}: {g(r['ppm'])} ppm outside (below {g(r['ppm_below'])}, "
                             f"above {g(r['ppm_above'])}; MC se {g(r['ppm_se'])}), Cpk {g(r['cpk'])}")
        if self.ppm_any is not None:
            lines.append(f"  outside any spec: {g(self.ppm_any)} ppm (MC se {g(self.ppm_any_se)})")
        lines += [f"  note: {n}" for n in self.notes]
        return "\n".join(lines) + "\n"


def _check_draws(draws: Any) -> int:
    try:
        n = int(draws)
        ok = n == draws
    except (TypeError, ValueError, OverflowError):
        ok = False
    if not ok or not 1 <= n <= MAX_DRAWS:
        raise ParameterError("draws", f"draws must be a whole number from 1 to {MAX_DRAWS:.0e}, not {draws!r}")
    return n


def _sqrt_cov(cov: np.ndarray) -> np.ndarray:
    """A square root ``L`` with ``L L' = cov`` (symmetric eigen-decomposition: also for a
    covariance that is only semi-definite)."""
    w, v = np.linalg.eigh((cov + cov.T) / 2.0)
    return v * np.sqrt(np.clip(w, 0.0, None))


class _Setting:
    """One setting's factor noise: the truncation bounds and the draw of a block of runs."""

    def __init__(self, space: Any, setting: Mapping[str, Any], sds: Mapping[str, float]) -> None:
        from .poe import mixture_components

        self.space = space
        self.names = list(space.names)
        self.base = {n: setting[n] for n in self.names}
        self.comps = mixture_components(space)
        comp_names = {self.names[j] for j in self.comps}
        self.free = []  # (name, mean, sd, low, high): box factors with noise
        for f in space.factors:
            sd = float(sds.get(f.name, 0.0))
            if sd <= 0 or f.name in comp_names:
                continue
            v = float(setting[f.name])
            if not f.low <= v <= f.high:
                raise ParameterError("setting", f"setting for {f.name!r}: {v:g} lies outside the design region "
                                                f"{f.low:g} .. {f.high:g}, to which the factor noise is truncated")
            self.free.append((f.name, v, sd, float(f.low), float(f.high)))
        self.mix_sd = np.array([float(sds.get(self.names[j], 0.0)) for j in self.comps])
        self.mixing = bool(self.comps) and bool(np.any(self.mix_sd > 0))
        if self.mixing:
            fs = [space.factors[j] for j in self.comps]
            self.mix_lo = np.array([float(f.lower) for f in fs])
            self.mix_hi = np.array([float(f.upper) for f in fs])
            self.mix_x = np.array([float(setting[f.name]) for f in fs])
            tol = 1e-9 * float(fs[0].total)
            bad = [f.name for f, x in zip(fs, self.mix_x) if not f.lower - tol <= x <= f.upper + tol]
            if bad:
                raise ParameterError("setting", f"setting for {bad[0]!r} lies outside the component's bounds, to "
                                                "which the blends drawn about it are held")

    @property
    def noisy(self) -> bool:
        return bool(self.free) or self.mixing

    def draw(self, rng: np.random.Generator, n: int) -> Any:
        """A frame of ``n`` settings (actual units) drawn about the setting."""
        import pandas as pd
        from scipy import special

        cols: dict[str, Any] = {}
        for f in self.space.factors:
            v = self.base[f.name]
            cols[f.name] = np.full(n, v, dtype=object) if f.kind == "categoric" else np.full(n, float(v))
        for name, mu, sd, lo, hi in self.free:
            a, b = special.ndtr((lo - mu) / sd), special.ndtr((hi - mu) / sd)
            u = a + rng.random(n) * (b - a)
            cols[name] = np.clip(mu + sd * special.ndtri(u), lo, hi)
        if self.mixing:
            q = len(self.comps)
            out = np.empty((n, q))
            todo = np.arange(n)
            for _ in range(MAX_REJECTION_ROUNDS):
                e = rng.standard_normal((todo.size, q)) * self.mix_sd
                e -= e.mean(axis=1, keepdims=True)
                x = self.mix_x + e
                ok = np.all((x >= self.mix_lo) & (x <= self.mix_hi), axis=1)
                out[todo[ok]] = x[ok]
                todo = todo[~ok]
                if not todo.size:
                    break
            else:
                raise ParameterError("factor_sd", "factor_sd: the component SDs are too large for the blend region "
                                                  "(most blends drawn fall outside the components' bounds)")
            for i, j in enumerate(self.comps):
                cols[self.names[j]] = out[:, i]
        return pd.DataFrame(cols)


class _Response:
    """One response's model: what a block of runs needs."""

    def __init__(self, fit: Any, setting_frame: Any, model_uncertainty: bool) -> None:
        from ..model.contract.tolerance import coefficient_covariance, new_run_variance

        self.fit = fit
        self.beta = fit.coefficients["coded"].to_numpy(dtype=float)
        self.s = math.sqrt(new_run_variance(fit))
        if not math.isfinite(self.s):
            raise ValueError(f"response {fit.response!r}: the model has no residual degrees of freedom, so the "
                             "run-to-run noise is unknown; nothing to simulate")
        self.model_uncertainty = model_uncertainty
        if model_uncertainty:
            form = fit.interval_form  # the prediction contract: one df, or Kenward-Roger's per point
            df = float(fit.kr_mean(setting_frame)[1][0]) if form.kenward_roger else float(form.df)
            if not (math.isfinite(df) and df > 0):
                raise ValueError(f"response {fit.response!r}: no degrees of freedom for the model's uncertainty")
            self.df = df
            self.root = _sqrt_cov(coefficient_covariance(fit))

    def draw(self, rng: np.random.Generator, frame: Any, x_row: np.ndarray | None) -> np.ndarray:
        """Responses (response units) of the runs ``frame``; ``x_row`` is the one model row when
        the factors do not vary."""
        from ..model.build.terms import design_matrix

        n = len(frame)
        if x_row is None:
            X = design_matrix(self.fit.space.encode(frame).to_numpy(dtype=float), self.fit.terms)
            eta = X @ self.beta
        else:
            X = x_row[None, :]
            eta = np.full(n, float(x_row @ self.beta))
        scale = np.ones(n)
        if self.model_uncertainty:
            scale = np.sqrt(self.df / rng.chisquare(self.df, n))
            z = rng.standard_normal((n, self.beta.size))
            eta = eta + scale * np.einsum("ij,ij->i", np.broadcast_to(X @ self.root, (n, self.beta.size)), z)
        eta = eta + scale * self.s * rng.standard_normal(n)
        with np.errstate(invalid="ignore", over="ignore"):
            return np.asarray(self.fit.transform.inverse(eta), dtype=float)


def _stats(y: np.ndarray, spec: tuple | None) -> dict:
    ok = np.isfinite(y)
    v = y[ok]
    n = v.size
    mean = float(v.mean()) if n else math.nan
    sd = float(v.std(ddof=1)) if n > 1 else math.nan
    qs = np.quantile(v, QUANTILES) if n else np.full(len(QUANTILES), math.nan)
    below = int(np.count_nonzero(v < spec[0])) if spec is not None and spec[0] is not None else 0
    above = int(np.count_nonzero(v > spec[1])) if spec is not None and spec[1] is not None else 0
    return _summary_stats(int(y.size), n, mean, sd, [float(x) for x in qs], below, above, spec)


def _summary_stats(size: int, n: int, mean: float, sd: float, qs: Sequence[float], below: int, above: int,
                   spec: tuple | None) -> dict:
    """One response's statistics from ``size`` runs of which ``n`` finite (their mean, SD and
    :data:`QUANTILES`; ``below``/``above`` of them outside the spec)."""
    out: dict[str, Any] = {"mean": mean, "sd": sd,
                           "quantiles": {f"{100 * p:g}%": float(x) for p, x in zip(QUANTILES, qs)},
                           "spec": None, "ppm_below": None, "ppm_above": None, "ppm": None, "ppm_se": None,
                           "cpk": None, "invalid": int(size - n)}
    if spec is not None:
        lo, hi = spec
        fb = float(below) / size if lo is not None else 0.0
        fa = float(above) / size if hi is not None else 0.0
        p = fb + fa + (size - n) / size
        caps = [(hi - mean) / (3 * sd)] if hi is not None else []
        caps += [(mean - lo) / (3 * sd)] if lo is not None else []
        out.update(spec=[lo, hi], ppm_below=1e6 * fb if lo is not None else None,
                   ppm_above=1e6 * fa if hi is not None else None, ppm=1e6 * p,
                   ppm_se=1e6 * math.sqrt(p * (1 - p) / size), cpk=float(min(caps)) if sd > 0 else None)
    return out


def simulate(fits: Any, setting: Mapping[str, Any], *, draws: int, seed: Any = None,
             factor_sd: Mapping[str, Any] | Sequence[str] | None = None,
             spec: Mapping[str, Any] | Sequence[str] | None = None,
             model_uncertainty: bool = True, executor: Any = None, progress: bool | None = None,
             stream: bool | None = None) -> SimulationResult:
    """Simulate ``draws`` runs at ``setting`` through one or several fitted models (see the
    module docstring).

    Parameters
    ----------
    fits : FitResult or mapping of response -> FitResult
        The models (one factor space: the same factors in the same order).
    setting : mapping
        ``{factor name: value}`` [actual units]; a categoric factor at a level.
    draws : int
        N, from 1 to :data:`MAX_DRAWS`.
    seed : int, SeedSequence or None
        The seed (None: fresh entropy, stated as ``seed=None``).
    factor_sd : mapping or list of str, optional
        ``{name: SD}`` or ``["NAME=SD", ...]`` [actual units].
    spec : mapping or list of str, optional
        ``{response: (low, high)}`` or ``["Y=LOW:HIGH", ...]`` (either side may be None / empty).
    model_uncertainty : bool
        Draw the coefficients from their sampling distribution (default) or take them as known.
    executor : concurrent.futures.Executor, optional
        Where the blocks of runs are drawn (a process pool, a Dask client's executor); the
        numbers are the same as without (each block has its own child of the seed).
    progress : bool, optional
        A progress bar on stderr (tqdm) while streaming; default: for more than
        :data:`MAX_KEPT` runs.
    stream : bool, optional
        Stream the statistics instead of keeping the runs (default: above :data:`MAX_KEPT`
        runs); the numbers are the kept runs' (the mean and SD to rounding).

    Returns
    -------
    SimulationResult
    """
    return simulate_runs(fits, setting, draws=draws, seed=seed, factor_sd=factor_sd, spec=spec,
                         model_uncertainty=model_uncertainty, executor=executor, progress=progress,
                         stream=stream)[0]


def _iter_blocks(fits: Mapping[str, Any], setting: Mapping[str, Any], sds: Mapping[str, float],
                 model_uncertainty: bool, seeds: Sequence[np.random.SeedSequence],
                 sizes: Sequence[int]) -> Iterator[dict[str, np.ndarray]]:
    """The runs of consecutive blocks, one ``{response: ndarray}`` per block, block ``i`` of
    ``sizes[i]`` runs drawn from ``seeds[i]``."""
    import pandas as pd

    from ..model.build.terms import design_matrix

    first = next(iter(fits.values()))
    space = first.space
    base = pd.DataFrame({k: [setting[k]] for k in space.names})
    plan = _Setting(space, setting, sds)
    models = {r: _Response(f, base, model_uncertainty) for r, f in fits.items()}
    rows = None if plan.noisy else {r: design_matrix(f.space.encode(base).to_numpy(dtype=float), f.terms)[0]
                                    for r, f in fits.items()}
    for child, size in zip(seeds, sizes):
        rng = np.random.Generator(np.random.PCG64(child))
        frame = plan.draw(rng, size) if plan.noisy else base
        block: dict[str, np.ndarray] = {}
        for r, m in models.items():
            if rows is None:
                block[r] = m.draw(rng, frame, None)
            else:
                block[r] = m.draw(rng, pd.DataFrame(index=range(size)), rows[r])
        yield block


def simulate_blocks(fits: Mapping[str, Any], setting: Mapping[str, Any], sds: Mapping[str, float],
                    model_uncertainty: bool, seeds: Sequence[np.random.SeedSequence],
                    sizes: Sequence[int]) -> dict[str, np.ndarray]:
    """The runs of consecutive blocks, block ``i`` of ``sizes[i]`` runs drawn from ``seeds[i]``
    (the unit of work of :func:`simulate_runs`, in this process or a worker).

    Parameters
    ----------
    fits : mapping
        ``{response: FitResult}``.
    setting : mapping
        ``{factor: value}`` [actual units].
    sds : mapping
        ``{factor: SD}`` [actual units].
    model_uncertainty : bool
        Draw the coefficients from their sampling distribution.
    seeds : sequence of SeedSequence
        One per block.
    sizes : sequence of int
        Runs per block.

    Returns
    -------
    dict
        ``{response: ndarray}`` [response units], the blocks' runs in order.
    """
    out: dict[str, list] = {r: [] for r in fits}
    for block in _iter_blocks(fits, setting, sds, model_uncertainty, seeds, sizes):
        for r, v in block.items():
            out[r].append(v)
    return {r: np.concatenate(v) if v else np.empty(0) for r, v in out.items()}


def _executor_width(executor: Any) -> int:
    """The number of workers of a process pool (or a guess of 2 for another executor)."""
    return int(getattr(executor, "_max_workers", 0) or 2)


def simulate_runs(fits: Any, setting: Mapping[str, Any], *, draws: int, seed: Any = None,
                  factor_sd: Mapping[str, Any] | Sequence[str] | None = None,
                  spec: Mapping[str, Any] | Sequence[str] | None = None,
                  model_uncertainty: bool = True, executor: Any = None, progress: bool | None = None,
                  stream: bool | None = None) -> tuple[SimulationResult, dict[str, np.ndarray]]:
    """:func:`simulate`, also returning the simulated runs ``{response: ndarray}`` [response units]
    (empty when the statistics were streamed: more than :data:`MAX_KEPT` runs, or ``stream``).

    Parameters
    ----------
    fits, setting, draws, seed, factor_sd, spec, model_uncertainty, executor, progress, stream
        As for :func:`simulate`.

    Returns
    -------
    (SimulationResult, dict)
        The result and the runs.
    """
    from .poe import parse_factor_sd

    n = _check_draws(draws)
    fits = dict(fits) if isinstance(fits, Mapping) else {fits.response: fits}
    first = next(iter(fits.values()))
    space = first.space
    for r, f in fits.items():
        if list(f.space.names) != list(space.names):
            raise ValueError(f"response {r!r}: the models must share their factors")
    sds = parse_factor_sd(space, factor_sd)
    specs = parse_specs(list(fits), spec)
    if isinstance(seed, (bool, np.bool_)) or not (seed is None or isinstance(seed, (int, np.integer, np.random.SeedSequence))):
        raise ParameterError("seed", f"seed must be a whole number, not {seed!r}")
    if isinstance(seed, (int, np.integer)) and seed < 0:
        raise ParameterError("seed", f"seed must be a whole number >= 0, not {seed}")
    ss = seed if isinstance(seed, np.random.SeedSequence) else np.random.SeedSequence(seed)
    import pandas as pd

    base = pd.DataFrame({k: [setting[k]] for k in space.names})
    first.predict(base)  # a setting the models cannot predict at is refused here
    _Setting(space, setting, sds)  # a setting outside the region is refused here, not in a worker
    for f in fits.values():  # so is a model without residual df
        _Response(f, base, model_uncertainty)
    children = ss.spawn(-(-n // BLOCK))
    sizes = [min(BLOCK, n - b * BLOCK) for b in range(len(children))]
    streamed = n > MAX_KEPT if stream is None else bool(stream)
    runs: dict[str, np.ndarray] = {}
    if streamed:
        stats, outside = _streamed(fits, setting, sds, model_uncertainty, children, sizes, specs, executor,
                                   n > MAX_KEPT if progress is None else bool(progress))
    else:
        runs, stats, outside = _kept(fits, setting, sds, model_uncertainty, children, sizes, specs, executor, n)
    ppm_any = ppm_any_se = None
    if specs:
        p = float(outside) / n
        ppm_any, ppm_any_se = 1e6 * p, 1e6 * math.sqrt(p * (1 - p) / n)
    notes = tuple(f"{r}: {s['invalid']} of {n} runs fall outside the back-transform's range (left out of the "
                  "statistics, counted outside the spec)" for r, s in stats.items() if s["invalid"])
    if streamed:
        notes += ("the runs were not kept: mean and SD merged block by block, the quantiles exact (found by "
                  "histogram passes over the same seeded blocks)",)
    res = SimulationResult(setting={k: (v if isinstance(v, str) else float(v)) for k, v in setting.items()},
                           draws=n, seed=None if isinstance(seed, np.random.SeedSequence) or seed is None else int(seed),
                           factor_sd=sds, model_uncertainty=bool(model_uncertainty), responses=stats,
                           ppm_any=ppm_any, ppm_any_se=ppm_any_se, notes=notes)
    return res, runs


def _kept(fits: Mapping[str, Any], setting: Mapping[str, Any], sds: Mapping[str, float], model_uncertainty: bool,
          children: Sequence[Any], sizes: Sequence[int], specs: Mapping[str, tuple], executor: Any,
          n: int) -> tuple[dict[str, np.ndarray], dict, int]:
    """Every run drawn and kept: the runs, the statistics per response, the runs outside any spec."""
    if executor is None:
        parts = [simulate_blocks(fits, setting, sds, model_uncertainty, children, sizes)]
    else:  # contiguous groups of blocks, each block from its own child seed: the same runs
        n_tasks = max(1, min(len(children), 4 * _executor_width(executor)))
        cuts = np.linspace(0, len(children), n_tasks + 1).round().astype(int)
        futures = [executor.submit(simulate_blocks, fits, setting, sds, model_uncertainty, children[a:b], sizes[a:b])
                   for a, b in zip(cuts[:-1], cuts[1:]) if b > a]
        parts = [f.result() for f in futures]
    runs = {r: np.concatenate([p[r] for p in parts]) for r in fits}
    stats = {r: _stats(runs[r], specs.get(r)) for r in fits}
    out = np.zeros(n, dtype=bool)
    for r, (lo, hi) in specs.items():
        y = runs[r]
        bad = ~np.isfinite(y)
        if lo is not None:
            bad |= y < lo
        if hi is not None:
            bad |= y > hi
        out |= bad
    return runs, stats, int(np.count_nonzero(out))


# --- streaming: more runs than are kept ------------------------------------------------------------------------

def _bin_index(v: np.ndarray, lo: float, scale: float) -> np.ndarray:
    """The histogram bin of each value of ``v`` (all at least ``lo``): ``floor((v/2 - lo/2)
    scale)`` held to the last bin. Rounding is monotone, so a bin's values all lie below the
    next bin's; halves keep ``v - lo`` finite whatever the range."""
    t = (v * 0.5 - lo * 0.5) * scale
    return np.minimum(t.astype(np.int64), HIST_BINS - 1)


def _passes(v: np.ndarray, chain: Sequence[tuple[float, float, int]]) -> np.ndarray:
    """The values of ``v`` (finite) inside the nested bins ``chain`` ((lo, scale, bin) per level)."""
    for lo, scale, b in chain:
        if not v.size:
            break
        v = v[(v >= lo) & (_bin_index(np.maximum(v, lo), lo, scale) == b)]
    return v


def stream_task(stage: str, fits: Mapping[str, Any], setting: Mapping[str, Any], sds: Mapping[str, float],
                model_uncertainty: bool, seeds: Sequence[np.random.SeedSequence], sizes: Sequence[int],
                specs: Mapping[str, tuple], work: Sequence[tuple] = ()) -> Any:
    """One task of the streamed simulation (:func:`simulate_runs` above :data:`MAX_KEPT` runs):
    a group of consecutive blocks drawn as in :func:`simulate_blocks`, summarised.

    Parameters
    ----------
    stage : {"moments", "histogram", "values"}
        ``moments``: per block and response ``(runs, finite, mean, M2, min, max, below, above)``
        and the runs outside any spec; ``histogram``: per item of ``work`` the counts, minima
        and maxima of :data:`HIST_BINS` bins; ``values``: per item the values themselves.
    fits, setting, sds, model_uncertainty, seeds, sizes
        As for :func:`simulate_blocks`.
    specs : mapping
        ``{response: (low, high)}`` (None an open side) [response units].
    work : sequence of tuple
        ``(response, chain, lo, scale)`` (``histogram``) or ``(response, chain)`` (``values``):
        the finite runs inside the nested bins ``chain`` (:func:`_passes`), binned from ``lo``
        with ``scale`` bins per half unit.

    Returns
    -------
    list or dict
        ``moments``: a list, one ``(records, outside_any)`` per block; ``histogram``: a list of
        ``(counts, minima, maxima)`` per item; ``values``: a list of arrays per item.
    """
    blocks = _iter_blocks(fits, setting, sds, model_uncertainty, seeds, sizes)
    if stage == "moments":
        out = []
        for block in blocks:
            recs = {}
            bad_any = np.zeros(next(iter(block.values())).size, dtype=bool) if specs else None
            for r, y in block.items():
                ok = np.isfinite(y)
                v = y[ok]
                m = int(v.size)
                mean = float(v.mean()) if m else 0.0
                d = v - mean  # summed by numpy's pairwise sum, not BLAS (whose threads would change the bits)
                lo, hi = specs.get(r, (None, None))
                recs[r] = (int(y.size), m, mean, float(np.sum(d * d)), float(v.min()) if m else math.inf,
                           float(v.max()) if m else -math.inf,
                           int(np.count_nonzero(v < lo)) if lo is not None else 0,
                           int(np.count_nonzero(v > hi)) if hi is not None else 0)
                if bad_any is not None and r in specs:
                    bad = ~ok
                    if lo is not None:
                        bad |= y < lo
                    if hi is not None:
                        bad |= y > hi
                    bad_any |= bad
            out.append((recs, int(np.count_nonzero(bad_any)) if bad_any is not None else 0))
        return out
    if stage == "histogram":
        counts = [np.zeros(HIST_BINS, dtype=np.int64) for _ in work]
        mins = [np.full(HIST_BINS, math.inf) for _ in work]
        maxs = [np.full(HIST_BINS, -math.inf) for _ in work]
        for block in blocks:
            for i, (r, chain, lo, scale) in enumerate(work):
                y = block[r]
                v = _passes(y[np.isfinite(y)], chain)
                idx = _bin_index(v, lo, scale)
                counts[i] += np.bincount(idx, minlength=HIST_BINS)
                np.minimum.at(mins[i], idx, v)
                np.maximum.at(maxs[i], idx, v)
        return list(zip(counts, mins, maxs))
    if stage == "values":
        vals: list[list[np.ndarray]] = [[] for _ in work]
        for block in blocks:
            for i, (r, chain) in enumerate(work):
                y = block[r]
                vals[i].append(_passes(y[np.isfinite(y)], chain))
        return [np.concatenate(v) if v else np.empty(0) for v in vals]
    raise ValueError(f"unknown stage {stage!r}")


def _run_tasks(stage: str, args: tuple[Any, Any, Any, bool], specs: Mapping[str, tuple], work: Sequence[tuple], children: Sequence[Any],
               sizes: Sequence[int], executor: Any, bar: Any) -> list:
    """``stream_task(stage, ...)`` over groups of :data:`TASK_BLOCKS` blocks, here or on the
    ``executor``; the results in block order (whatever order they finish in)."""
    from concurrent.futures import as_completed

    cuts = list(range(0, len(children), TASK_BLOCKS)) + [len(children)]
    groups = [(a, b) for a, b in zip(cuts[:-1], cuts[1:]) if b > a]
    results: list[Any] = [None] * len(groups)
    if executor is None:
        for i, (a, b) in enumerate(groups):
            fits, setting, sds, model_uncertainty = args
            results[i] = stream_task(stage, fits, setting, sds, model_uncertainty, children[a:b], sizes[a:b], specs,
                                     work)
            bar.update(int(sum(sizes[a:b])))
        return results
    futures = {executor.submit(stream_task, stage, *args, children[a:b], sizes[a:b], specs, work): i
               for i, (a, b) in enumerate(groups)}
    for fut in as_completed(futures):
        i = futures[fut]
        results[i] = fut.result()
        a, b = groups[i]
        bar.update(int(sum(sizes[a:b])))
    return results


class _NoBar:
    def update(self, n: int) -> None:
        pass

    def close(self) -> None:
        pass


def _progress_bar(total: int, show: bool, desc: str) -> Any:
    """A tqdm bar on stderr (the ``parallel`` extra), or one that shows nothing."""
    if not show:
        return _NoBar()
    try:
        from tqdm import tqdm
    except ImportError:
        return _NoBar()
    import sys

    return tqdm(total=total, unit="run", unit_scale=True, desc=desc, file=sys.stderr, dynamic_ncols=True)


def _lerp(a: float, b: float, t: float) -> float:
    """NumPy's linear interpolation of its quantiles (``numpy.quantile``, method linear), so
    that the streamed quantiles equal those of the kept runs bit for bit."""
    d = b - a
    return float(b - d * (1.0 - t)) if t >= 0.5 else float(a + d * t)


def _streamed(fits: Mapping[str, Any], setting: Mapping[str, Any], sds: Mapping[str, float], model_uncertainty: bool,
              children: Sequence[Any], sizes: Sequence[int], specs: Mapping[str, tuple], executor: Any,
              progress: bool) -> tuple[dict, int]:
    """Per response the statistics of :func:`_stats`, and the runs outside any spec, without
    keeping the runs: pass 1 the moments and ranges, merged block by block in block order
    (Chan's pairwise update: the same numbers however the blocks were scheduled); then the
    exact quantiles: a histogram of :data:`HIST_BINS` bins over the range (counts, and each
    bin's least and largest value), the bin that holds each wanted order statistic found from
    the counts, narrowed again inside that bin while it holds more than
    :data:`MAX_BIN_VALUES` distinct runs, and its values finally collected and sorted."""
    n = int(sum(sizes))
    task_args = (fits, setting, sds, model_uncertainty)

    def run(stage: str, work: Sequence[tuple], what: str) -> list:
        bar = _progress_bar(n, progress, f"simulated runs ({what})")
        try:
            return _run_tasks(stage, task_args, dict(specs), work, children, sizes, executor, bar)
        finally:
            bar.close()

    blocks = [rec for part in run("moments", (), "moments") for rec in part]
    outside_any = sum(b[1] for b in blocks)
    acc: dict[str, list] = {}
    for recs, _ in blocks:
        for r, (size, m, mean, m2, mn, mx, below, above) in recs.items():
            if r not in acc:
                acc[r] = [size, m, mean, m2, mn, mx, below, above]
                continue
            a = acc[r]
            tot = a[1] + m
            if m:
                delta = mean - a[2]
                a[2] = a[2] + delta * (m / tot)
                a[3] = a[3] + m2 + delta * delta * (a[1] * m / tot)
            a[0] += size
            a[1] = tot
            a[4], a[5] = min(a[4], mn), max(a[5], mx)
            a[6] += below
            a[7] += above
    # the order statistics wanted: numpy's linear method, positions (m - 1) q
    targets: dict[tuple[str, int], float | None] = {}
    for r, a in acc.items():
        m = a[1]
        for q in QUANTILES:
            h = (m - 1) * q
            k = int(math.floor(h))
            for kk in (k, min(k + 1, m - 1)):
                if m:
                    targets[(r, kk)] = a[4] if a[4] == a[5] else None
    # state per unresolved target: (chain, lo, scale, rank below the chain)
    state: dict[tuple[str, int], tuple[tuple, float, float, int]] = {}
    for (r, kk), v in targets.items():
        if v is None:
            lo, hi = acc[r][4], acc[r][5]
            state[(r, kk)] = ((), lo, HIST_BINS / (hi * 0.5 - lo * 0.5), 0)
    level = 0
    finals: dict[tuple[str, int], tuple[tuple, int]] = {}
    while state:
        level += 1
        items = sorted({(r, st[0], st[1], st[2]) for (r, _), st in state.items()}, key=repr)
        parts = run("histogram", items, f"quantiles, histogram {level}")
        hist = {}
        for i, it in enumerate(items):
            c = sum((p[i][0] for p in parts), np.zeros(HIST_BINS, dtype=np.int64))
            mn = np.minimum.reduce([p[i][1] for p in parts])
            mx = np.maximum.reduce([p[i][2] for p in parts])
            hist[it] = (np.cumsum(c), c, mn, mx)
        nxt: dict[tuple[str, int], tuple[tuple, float, float, int]] = {}
        for (r, kk), (chain, lo, scale, below) in state.items():
            cum, c, mn, mx = hist[(r, chain, lo, scale)]
            b = int(np.searchsorted(cum, kk - below, side="right"))
            before = below + (int(cum[b - 1]) if b else 0)
            sub = chain + ((lo, scale, b),)
            if mn[b] == mx[b]:
                targets[(r, kk)] = float(mn[b])
            elif c[b] <= MAX_BIN_VALUES or level >= 8:
                finals[(r, kk)] = (sub, before)
            else:
                nxt[(r, kk)] = (sub, float(mn[b]), HIST_BINS / (mx[b] * 0.5 - mn[b] * 0.5), before)
        state = nxt
    if finals:
        items_v = sorted({(r, sub) for (r, _), (sub, _) in finals.items()}, key=repr)
        parts = run("values", items_v, "quantiles, values")
        vals = {it: np.sort(np.concatenate([p[i] for p in parts])) for i, it in enumerate(items_v)}
        for (r, kk), (sub, before) in finals.items():
            targets[(r, kk)] = float(vals[(r, sub)][kk - before])
    stats = {}
    for r, a in acc.items():
        size, m, mean, m2 = a[0], a[1], a[2], a[3]
        qs = []
        for q in QUANTILES:
            if not m:
                qs.append(math.nan)
                continue
            h = (m - 1) * q
            k = int(math.floor(h))
            lo_v, hi_v = targets[(r, k)], targets[(r, min(k + 1, m - 1))]
            assert lo_v is not None and hi_v is not None
            qs.append(_lerp(lo_v, hi_v, h - k))
        stats[r] = _summary_stats(size, m, mean if m else math.nan, math.sqrt(m2 / (m - 1)) if m > 1 else math.nan,
                                  qs, a[6], a[7], specs.get(r))
    return stats, outside_any
