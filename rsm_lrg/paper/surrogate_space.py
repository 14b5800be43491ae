"""The design space through the physics: the probability that the rig meets its
specifications, computed by running the calibrated surrogate itself with its parameters drawn
from their uncertainty, and which source of variation dominates where.

At each node of a grid over the chosen factors (``grid`` levels each; the other design factors
held at the centre of Table 3's box) the surrogate (:func:`rsm_lrg.surrogate.simulate`) runs
``draws`` times, draw ``j`` with

* **the calibrated parameters** drawn from their uncertainty as the calibration file states it:
  a parameter with a profile-likelihood interval ``[ci_low, ci_high]`` (95 %) from a two-piece
  normal with its value as the median, each half with SD ``σ_low = (value - ci_low) / 1.96``
  below and ``σ_high = (ci_high - value) / 1.96`` above, so that 2.5 % lies beyond each end of
  the interval as stated, truncated to the parameter's bounds (a draw outside them is drawn
  again); a parameter at a bound, or without an interval, is known
  only to lie within its plausible range and is drawn **uniformly** over ``[lower, upper]``
  (the notes name it); one with a standard error and no interval from a normal with that SD,
  truncated likewise;
* **the rig's tolerances** (``param_sd``): a design factor (``thickness_m`` — the leaf
  thickness —, ``stroke_m``, ...) or a physical parameter of
  :class:`~rsm_lrg.physics.params.LRGParams` (``preload_n``, ...) varied by a normal deviation
  with that SD about its nominal value (the factor's setting; the parameter's value), not
  truncated;
* **the run noise**: the thermocouple reading noise of the simulator (``noise_sd`` per reading;
  keyed by the seed and the row, so the numbers do not depend on the worker count).

The same draws are used at every node (common random numbers), so the map is smooth and the
window's comparisons are paired. ``p`` is the fraction of the draws in which every response is
inside its specification (its Monte Carlo standard error ``sqrt(p (1 - p) / draws)`` is
reported); the window is searched as in :mod:`rsm_lrg.optimize.design_space` on the grid of
``p``.

**Attribution** (first-order Sobol indices of groups of inputs; Saltelli et al. 2010, Comput.
Phys. Commun. 181, 259, estimator (b), centred): with two independent sets of draws A and B of
the parameters and tolerances, and A_B^g the set A with the group g taken from B, the
noise-free surrogate ``f`` gives ``V_g = mean((f(B) - mean f(B)) (f(A_B^g) - f(A)))``, the
variance of the response explained by group g alone (parameters; tolerances): ``f(A_B^g) -
f(A)`` changes group g only, so a group that matters little gives a small, quiet estimate;
the run noise adds ``V_noise =
var(f_noisy(A) - f(A))`` (it is independent of the rest); the shares are ``V_g / V`` with ``V
= var(f(A), f(B)) + V_noise``, and ``1 - Σ shares`` is the interaction of parameters and
tolerances. The estimates carry Monte Carlo error (a share may come out slightly negative).
The attribution costs four runs per draw beyond the probability's one (two when there are no
tolerances).
"""

from __future__ import annotations

import itertools
import math
import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import ParameterError

__all__ = ["SurrogateDesignSpace", "surrogate_design_space", "parameter_draws", "first_order_shares", "draw_values",
           "MAX_SURROGATE_RUNS"]

#: The most surrogate runs one call makes (nodes x draws x runs per draw).
MAX_SURROGATE_RUNS = 2_000_000
Z975 = 1.959963984540054


@dataclass(frozen=True)
class SurrogateDesignSpace:
    """The surrogate's design space (frozen).

    Attributes
    ----------
    space : DesignSpace
        Map, window and probabilities (:class:`rsm_lrg.optimize.design_space.DesignSpace`).
    nodes : list of dict
        Per grid node: the setting, ``p``, ``p_se`` and, with the attribution, per response
        ``{"variance", "parameters", "tolerances", "noise", "interaction", "dominant"}``, and
        ``limits``: per response the ``upper`` limit that the setting's runs stay at or below
        with the target probability (at least that fraction of its draws; the ``probability``
        quantile, inverted CDF) and the ``lower`` one they stay at or above (None where a
        run's response is not finite).
    parameters : list of dict
        How each varied input was drawn (``name``, ``kind``, ``distribution`` and its numbers).
    draws : int
    seed : int
    workers : int
    seconds : float
        Wall time of the surrogate runs [s].
    runs : int
        Surrogate runs made.
    """

    space: Any
    nodes: list
    parameters: list
    draws: int
    seed: int
    workers: int
    seconds: float
    runs: int
    held: dict = field(default_factory=dict)
    notes: tuple = ()

    def to_dict(self) -> dict:
        d = self.space.to_dict()
        d["notes"] = list(self.space.notes) + list(self.notes)
        d["surrogate"] = {"draws": self.draws, "seed": self.seed, "workers": self.workers, "runs": self.runs,
                          "seconds": self.seconds, "held": dict(self.held), "parameters": self.parameters,
                          "nodes": self.nodes}
        return d

    def summary(self) -> str:
        from ..present import format_g

        out = [self.space.summary().rstrip("\n")]
        out.append(f"Surrogate: {self.draws} draws per setting, seed {self.seed}, {self.runs} runs on "
                   f"{self.workers} worker(s) in {self.seconds:.1f} s")
        if self.held:
            out.append("Held at Table 3's centre: " + ", ".join(f"{k} = {format_g(v)}" for k, v in self.held.items()))
        for p in self.parameters:
            out.append(f"  {p['name']}: {p['description']}")
        if self.nodes and self.nodes[0].get("limits"):
            names_ = list(self.space.factors)
            for resp_, (_lo_s, hi_s) in self.space.specs.items():
                side = "upper" if hi_s is not None else "lower"
                vals = [(nd["limits"][resp_][side], nd) for nd in self.nodes if nd["limits"][resp_][side] is not None]
                if not vals:
                    continue
                v_, nd_ = (min if side == "upper" else max)(vals, key=lambda t: t[0])
                where_ = ", ".join(f"{f}={format_g(nd_['setting'][f])}" for f in names_)
                out.append(f"{'Lowest upper' if side == 'upper' else 'Highest lower'} limit of {resp_} met with "
                           f"probability {self.space.probability:g}: {format_g(v_)} at {where_}")
        if self.nodes and "attribution" in self.nodes[0]:
            resp = next(iter(self.nodes[0]["attribution"]))
            out.append(f"Variance attribution of {resp} (first-order shares: parameters / tolerances / run noise; "
                       "interaction):")
            names = list(self.space.factors)
            for nd in self.nodes:
                a = nd["attribution"][resp]
                where = ", ".join(f"{n}={format_g(nd['setting'][n])}" for n in names)
                out.append(f"  {where}: p = {nd['p']:.3f} ± {nd['p_se']:.3f}; {a['parameters']:.2f} / "
                           f"{a['tolerances']:.2f} / {a['noise']:.2f}; {a['interaction']:.2f} -> {a['dominant']}")
        out += [f"Note: {n}" for n in self.notes]
        return "\n".join(out) + "\n"

    def __str__(self) -> str:
        return self.summary()


def _truncated(rng: np.random.Generator, n: int, draw: Any, lo: float, hi: float) -> np.ndarray:
    """``n`` draws of ``draw(rng, m)`` inside ``[lo, hi]`` (those outside drawn again)."""
    out = draw(rng, n)
    for _ in range(1000):
        bad = (out < lo) | (out > hi)
        if not bad.any():
            return out
        out[bad] = draw(rng, int(bad.sum()))
    return np.clip(out, lo, hi)


def parameter_draws(calibration: Any) -> list[dict]:
    """How each calibrated parameter is drawn (module docstring): a list of ``{"name",
    "kind": "calibrated", "distribution": "split-normal"|"uniform"|"normal", ...}``."""
    out = []
    for p in getattr(calibration, "parameters", ()):
        if isinstance(p.value, bool):  # a switch of the physics, not a number
            continue
        lo, hi = float(p.lower), float(p.upper)
        ci_lo, ci_hi = float(p.ci_low), float(p.ci_high)
        if not p.at_bound and math.isfinite(ci_lo) and math.isfinite(ci_hi) and ci_lo < p.value < ci_hi:
            s_lo, s_hi = (p.value - ci_lo) / Z975, (ci_hi - p.value) / Z975
            out.append({"name": p.name, "kind": "calibrated", "distribution": "split-normal", "value": p.value,
                        "sd_low": s_lo, "sd_high": s_hi, "lower": lo, "upper": hi,
                        "description": f"two-piece normal, median {p.value:.4g}, from its {p.ci_method or 'profile'} interval "
                                       f"{ci_lo:.4g}..{ci_hi:.4g} (SDs {s_lo:.3g} below, {s_hi:.3g} above), "
                                       f"truncated to [{lo:.4g}, {hi:.4g}] {p.unit}".rstrip()})
        elif p.at_bound or not (math.isfinite(p.std_error) and p.std_error > 0):
            why = "at a bound of its range" if p.at_bound else "without an interval or standard error"
            out.append({"name": p.name, "kind": "calibrated", "distribution": "uniform", "lower": lo, "upper": hi,
                        "description": f"uniform over its plausible range [{lo:.4g}, {hi:.4g}] {p.unit} (the "
                                       f"calibration leaves it {why}: known only by a bound)"})
        else:
            out.append({"name": p.name, "kind": "calibrated", "distribution": "normal", "value": p.value,
                        "sd": float(p.std_error), "lower": lo, "upper": hi,
                        "description": f"normal {p.value:.4g} ± {p.std_error:.3g} (its standard error), truncated to "
                                       f"[{lo:.4g}, {hi:.4g}] {p.unit}".rstrip()})
    return out


def draw_values(spec: dict, rng: np.random.Generator, n: int) -> np.ndarray:
    """``n`` draws of one input by its ``spec`` (:func:`parameter_draws`; tolerances)."""
    kind = spec["distribution"]
    if kind == "uniform":
        return rng.uniform(spec["lower"], spec["upper"], n)
    if kind == "split-normal":
        v, a, b = spec["value"], spec["sd_low"], spec["sd_high"]

        def split(r: np.random.Generator, m: int) -> np.ndarray:
            z = r.standard_normal(m)
            # half the probability on each side (the value is the median), so that 2.5 % lies beyond each
            # end of the 95 % interval as stated (the density jumps at the value where the SDs differ)
            left = r.uniform(size=m) < 0.5
            return np.where(left, v - a * np.abs(z), v + b * np.abs(z))

        return _truncated(rng, n, split, spec["lower"], spec["upper"])
    if kind == "normal":
        return _truncated(rng, n, lambda r, m: spec["value"] + spec["sd"] * r.standard_normal(m),
                          spec["lower"], spec["upper"])
    return spec["value"] + spec["sd"] * rng.standard_normal(n)  # a tolerance: untruncated


def first_order_shares(fa: np.ndarray, eps: np.ndarray, fb: np.ndarray | None = None,
                       fab: Mapping[str, np.ndarray] | None = None,
                       only: str | None = None) -> tuple[float, dict[str, float]]:
    """The variance of a response and the first-order shares of the parameters, the tolerances
    and the run noise (module docstring).

    Parameters
    ----------
    fa, fb : ndarray
        The noise-free response at the draws A and B (``fb`` None: nothing but noise varies).
    eps : ndarray
        The run noise at A: the noisy response minus ``fa``.
    fab : mapping, optional
        ``{"parameters": f(A_B^par), "tolerances": f(A_B^tol)}``; None when one group only
        varies (``only`` names it; it then explains all of the noise-free variance).
    only : {"parameters", "tolerances"}, optional

    Returns
    -------
    (float, dict)
        ``V`` [response units²] and ``{"parameters", "tolerances", "noise"}`` shares of it.
    """
    v_noise = float(np.var(eps, ddof=1))
    v0 = float(np.var(np.concatenate([fa, fb]), ddof=1)) if fb is not None else 0.0
    v = {"parameters": 0.0, "tolerances": 0.0}
    if fab is not None and fb is not None:  # Saltelli (b), centred: V_g = mean((f(B) - mean f(B)) (f(A_B^g) - f(A)))
        for g_, f in fab.items():
            v[g_] = float(np.mean((fb - fb.mean()) * (f - fa)))
    elif only is not None:
        v[only] = v0
    total = v0 + v_noise
    if not total > 0:
        return 0.0, {"parameters": 0.0, "tolerances": 0.0, "noise": 0.0}
    return total, {"parameters": v["parameters"] / total, "tolerances": v["tolerances"] / total,
                   "noise": v_noise / total}


def surrogate_design_space(factors: Mapping[str, tuple[float, float]], specs: Mapping[str, tuple[float | None, float | None]],
                           *, probability: float = 0.9, grid: int = 5, draws: int = 200, seed: int = 0,
                           calibration: Any = "default", param_sd: Mapping[str, float] | None = None,
                           noise_sd: float | None = None, workers: int = 1, attribution: bool = True,
                           duration_min: float = 50.0) -> SurrogateDesignSpace:
    """The probability map and window of the calibrated surrogate, and the variance attribution
    per setting (module docstring).

    Parameters
    ----------
    factors : mapping
        ``{design factor: (low, high)}`` [actual units] among ``thickness_m``, ``stroke_m``,
        ``velocity_m_s``, ``acceleration_m_s2``; those not named are held at the centre of
        Table 3's box.
    specs : mapping
        ``{surrogate output: (low, high)}`` (``tcr_c_per_min``, ``wear_volume_m3_per_h``, ...;
        None an open side) [the output's units].
    probability : float
        The target probability (0 < p < 1).
    grid : int
        Levels per factor (2 to 21).
    draws : int
        Draws per setting (4 to 100000).
    seed : int
        Seed of every draw and of the run noise.
    calibration : "default", None, path or Calibration
        As for :func:`rsm_lrg.simulate` (``None``: the raw physics, nothing drawn but the
        tolerances and the noise).
    param_sd : mapping, optional
        ``{factor or LRGParams parameter: SD}`` [its units]: the rig's tolerances.
    noise_sd : float, optional
        The reading noise [°C] (default :data:`rsm_lrg.surrogate.DEFAULT_NOISE_SD`).
    workers : int
        Local worker processes for the runs (1: this process); the numbers do not depend on it.
    attribution : bool
        Also estimate the first-order variance shares per setting.
    duration_min : float
        The test duration [min].

    Returns
    -------
    SurrogateDesignSpace
    """
    import pandas as pd

    from ..optimize.design_space import DesignSpace, largest_window
    from ..physics.chain import TABLE3_BOX
    from ..physics.params import LRGParams, param_names
    from ..surrogate import DEFAULT_NOISE_SD, simulate
    from ..surrogate.calibrate import resolve_calibration

    if not factors:
        raise ParameterError("factors", "name at least one factor NAME=LOW:HIGH of " + ", ".join(TABLE3_BOX))
    for name, (lo, hi) in factors.items():
        if name not in TABLE3_BOX:
            raise ParameterError("factors", f"{name!r} is not a design factor of the surrogate ({', '.join(TABLE3_BOX)})")
        if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi):
            raise ParameterError("factors", f"{name}: expected 0 < LOW < HIGH, got {lo:g}:{hi:g}")
    if not specs:
        raise ParameterError("spec", "give a specification Y=LOW:HIGH for at least one surrogate output")
    from ..surrogate.design_input import OUTPUT_COLUMNS

    for r in specs:
        if r not in OUTPUT_COLUMNS:
            raise ParameterError("spec", f"{r!r} is not an output of the surrogate ({', '.join(OUTPUT_COLUMNS)})")
    if not (isinstance(probability, (int, float)) and 0.0 < float(probability) < 1.0):
        raise ParameterError("probability", f"probability must lie between 0 and 1, not {probability!r}")
    if isinstance(grid, bool) or not isinstance(grid, (int, np.integer)) or not 2 <= int(grid) <= 21:
        raise ParameterError("grid", f"grid must be a whole number from 2 to 21 with --surrogate, not {grid!r}")
    if isinstance(draws, bool) or not isinstance(draws, (int, np.integer)) or not 4 <= int(draws) <= 100_000:
        raise ParameterError("draws", f"draws must be a whole number from 4 to 100000, not {draws!r}")
    if isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or not 1 <= int(workers) <= 64:
        raise ParameterError("workers", f"workers must be a whole number from 1 to 64, not {workers!r}")
    cal = resolve_calibration(calibration)
    notes: list[str] = []
    base = LRGParams()
    calibrated = {p.name for p in getattr(cal, "parameters", ())}
    tol_specs: list[dict[str, Any]] = []
    for name, sd in (param_sd or {}).items():
        if not (isinstance(sd, (int, float)) and math.isfinite(sd) and sd > 0):
            raise ParameterError("param_sd", f"{name}: the SD must be a positive number")
        if name in TABLE3_BOX:
            tol_specs.append({"name": name, "kind": "factor tolerance", "distribution": "deviation", "value": 0.0,
                              "sd": float(sd), "description": f"the setting ± a normal deviation of SD {sd:g} (a "
                                                              "tolerance; not truncated)"})
        elif name in calibrated:
            raise ParameterError("param_sd", f"{name} is calibrated: it is drawn from its calibration interval already")
        elif name in param_names():
            value = float(getattr(base, name))
            tol_specs.append({"name": name, "kind": "parameter tolerance", "distribution": "tolerance", "value": value,
                              "sd": float(sd), "description": f"normal about its value {value:g} with SD {sd:g} (a "
                                                              "tolerance; not truncated)"})
        else:
            raise ParameterError("param_sd", f"{name!r} is neither a design factor nor a parameter of the physics")
    cal_specs: list[dict[str, Any]] = parameter_draws(cal) if cal is not None else []
    if cal is None:
        notes.append("uncalibrated: the raw physics, no parameter drawn")
    names = list(factors)
    k = len(names)
    g = int(grid)
    n_nodes = g ** k
    n = int(draws)
    groups = int(bool(cal_specs)) + int(bool(tol_specs))
    per_draw = 1 + ((2 if groups else 1) + (2 if groups == 2 else 0) if attribution else 0)
    if n_nodes * n * per_draw > MAX_SURROGATE_RUNS:
        raise ParameterError("draws", f"{n_nodes} settings x {n} draws x {per_draw} runs is more than "
                                      f"{MAX_SURROGATE_RUNS:,} surrogate runs (fewer draws or a smaller grid)")
    held = {f: 0.5 * (lo + hi) for f, (lo, hi) in TABLE3_BOX.items() if f not in factors}
    levels = tuple(np.linspace(factors[f][0], factors[f][1], g) for f in names)
    mesh = np.stack(np.meshgrid(*levels, indexing="ij"), axis=-1).reshape(-1, k)
    rng = np.random.default_rng([int(seed), 32])

    def draw_set(r: np.random.Generator) -> dict[str, np.ndarray]:
        return {s["name"]: draw_values(s, r, n) for s in cal_specs + tol_specs}

    set_a = draw_set(rng)
    set_b = draw_set(rng)
    cal_names = [str(s["name"]) for s in cal_specs]
    tol_names = [str(s["name"]) for s in tol_specs]

    def design(values: dict[str, np.ndarray]) -> pd.DataFrame:
        """Every node x every draw (node-major)."""
        cols: dict[str, np.ndarray] = {}
        for j, f in enumerate(names):
            cols[f] = np.repeat(mesh[:, j], n)
        for f, v in held.items():
            cols[f] = np.full(n_nodes * n, v)
        for s in tol_specs:
            dev = np.tile(values[s["name"]], n_nodes)
            if s["kind"] == "factor tolerance":
                cols[s["name"]] = cols[s["name"]] + dev
            else:
                cols[s["name"]] = dev
        for name_ in cal_names:
            cols[name_] = np.tile(values[name_], n_nodes)
        return pd.DataFrame(cols)

    sd_noise = DEFAULT_NOISE_SD if noise_sd is None else float(noise_sd)
    executor = None
    t0 = time.perf_counter()
    runs = 0
    import warnings
    from concurrent.futures import ProcessPoolExecutor

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        if int(workers) > 1:
            executor = ProcessPoolExecutor(max_workers=int(workers))
        try:
            def run(values: dict[str, np.ndarray], noisy: bool) -> pd.DataFrame:
                nonlocal runs
                d = design(values)
                runs += len(d)
                return simulate(d, seed=int(seed), noise_sd=sd_noise if noisy else 0.0, duration_min=duration_min,
                                executor=executor, calibration=cal if cal is not None else None, progress=False)

            noisy_a = run(set_a, True)
            free: dict[str, pd.DataFrame] = {}
            if attribution:
                free["a"] = run(set_a, False)
                if cal_specs or tol_specs:
                    free["b"] = run(set_b, False)
                if cal_specs and tol_specs:
                    free["a_b_par"] = run({**set_a, **{m: set_b[m] for m in cal_names}}, False)
                    free["a_b_tol"] = run({**set_a, **{m: set_b[m] for m in tol_names}}, False)
        finally:
            if executor is not None:
                executor.shutdown()
    seconds = time.perf_counter() - t0
    yields = [str(w.message) for w in caught if "yield" in str(w.message)]
    if yields:
        notes.append("some runs are outside the physics' validity (a hinge leaf would yield; counted as they come): "
                     + yields[0][:200])
    inside = np.ones(n_nodes * n, dtype=bool)
    for r, (lo_s, hi_s) in specs.items():
        v = noisy_a[r].to_numpy(dtype=float)
        ok = np.isfinite(v)
        if lo_s is not None:
            ok &= v >= lo_s
        if hi_s is not None:
            ok &= v <= hi_s
        inside &= ok
    p = inside.reshape(n_nodes, n).mean(axis=1)
    p_se = np.sqrt(p * (1 - p) / n)
    nodes = []
    for i in range(n_nodes):
        nd: dict[str, Any] = {"setting": {f: float(mesh[i, j]) for j, f in enumerate(names)}, "p": float(p[i]),
                              "p_se": float(p_se[i]), "limits": {}}
        for r in specs:  # the limits this setting meets with the target probability, one side at a time
            v = noisy_a[r].to_numpy(dtype=float)[i * n:(i + 1) * n]
            v = np.where(np.isnan(v), np.inf, v)
            lo_q, hi_q = np.quantile(v, [1.0 - float(probability), float(probability)], method="inverted_cdf")
            nd["limits"][r] = {"upper": float(hi_q) if math.isfinite(hi_q) else None,
                               "lower": float(lo_q) if math.isfinite(lo_q) else None}
        if attribution:
            nd["attribution"] = {}
            for r in specs:
                sl = slice(i * n, (i + 1) * n)
                fa = free["a"][r].to_numpy(dtype=float)[sl]
                eps = noisy_a[r].to_numpy(dtype=float)[sl] - fa
                fb = free["b"][r].to_numpy(dtype=float)[sl] if "b" in free else None
                fab = ({g_: free[key][r].to_numpy(dtype=float)[sl] for g_, key in
                        (("parameters", "a_b_par"), ("tolerances", "a_b_tol"))} if "a_b_par" in free else None)
                only = "parameters" if cal_specs else ("tolerances" if tol_specs else None)
                total, share = first_order_shares(fa, eps, fb, fab, only)
                nd["attribution"][r] = dict(variance=total, **share,
                                            interaction=1.0 - sum(share.values()),
                                            dominant=max(share, key=share.__getitem__))
        nodes.append(nd)
    pgrid = p.reshape((g,) * k)
    okgrid = pgrid >= float(probability)
    ib = np.unravel_index(int(np.argmax(pgrid)), pgrid.shape)
    best = {f: float(levels[j][ib[j]]) for j, f in enumerate(names)}
    window, wmin, wnodes = None, math.nan, 0
    centre_idx: list[int] = [int(i_) for i_ in ib]
    if okgrid.any():
        box = largest_window(okgrid, pgrid)
        sl_box = tuple(slice(a, b + 1) for a, b in box)
        window = {f: (float(levels[j][box[j][0]]), float(levels[j][box[j][1]])) for j, f in enumerate(names)}
        wmin = float(pgrid[sl_box].min())
        wnodes = int(np.prod([b - a + 1 for a, b in box]))
        centre_idx = [(a + b) // 2 for a, b in box]
    maps = []
    for a, b in itertools.combinations(range(k), 2):
        idx: list[Any] = list(centre_idx)
        idx[a], idx[b] = slice(None), slice(None)
        maps.append({"x": names[a], "y": names[b], "x_levels": levels[a], "y_levels": levels[b],
                     "p": np.asarray(pgrid[tuple(idx)]).T})
    ds_notes = [f"probability: the fraction of {n} surrogate runs per setting inside every specification (Monte "
                f"Carlo SE at most {0.5 / math.sqrt(n):.3f}); the same draws at every setting (seed {seed})"]
    if k > 2:
        ds_notes.append("maps: each pair of factors through the window's centre node (the others at their grid "
                        "level nearest the centre)")
    space = DesignSpace(specs=dict(specs), probability=float(probability), factors=tuple(names), levels=levels,
                        grid_probability=pgrid, window=window, window_min_probability=wmin, window_nodes=wnodes,
                        best=best, best_probability=float(pgrid[ib]), maps=maps, notes=tuple(ds_notes),
                        factor_sd={s["name"]: s["sd"] for s in tol_specs}, draws=n)
    return SurrogateDesignSpace(space=space, nodes=nodes, parameters=cal_specs + tol_specs, draws=n, seed=int(seed),
                                workers=int(workers), seconds=seconds, runs=runs, held=held, notes=tuple(notes))
