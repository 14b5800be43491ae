"""Benchmark the closed loop (``rsm-lrg loop``: Latin hypercube, then Gaussian process ->
expected improvement -> evaluate, issue 33) against random search, a Latin hypercube with a
quadratic model, and R ``DiceOptim::EGO.nsteps`` started from the same initial designs, on
Branin, Hartmann-6 and the calibrated surrogate.

Usage::

    python benchmarks/bench_ego.py --seeds 20                       # the README's table
    python benchmarks/bench_ego.py --seeds 2 --problems branin      # a quick check
    python benchmarks/bench_ego.py --seeds 20 --no-r --json ego.json
    # in slices and parts (e.g. two processes, or over several sittings), then merged:
    python benchmarks/bench_ego.py --problems hartmann6 --seeds 10 --part ours --json h1.json
    python benchmarks/bench_ego.py --problems hartmann6 --seeds 10 --seed-start 11 --part ours --json h2.json
    python benchmarks/bench_ego.py --problems hartmann6 --seeds 20 --part r --json hr.json
    python benchmarks/bench_ego.py --merge h1.json h2.json hr.json --json hartmann6.json
    # other draws of the loop and of DiceOptim on the same initial designs, pooled:
    python benchmarks/bench_ego.py --problems branin --part ours --json b0.json
    python benchmarks/bench_ego.py --problems branin --part loop --loop-draw-offset 1000 --json b1.json
    python benchmarks/bench_ego.py --problems branin --part r --r-seed-offset 0 --json r0.json
    python benchmarks/bench_ego.py --problems branin --part r --r-seed-offset 1000 --json r1.json
    python benchmarks/bench_ego.py --merge b0.json b1.json r0.json r1.json --json branin_pooled.json

Protocol. Every sequential method starts from the same initial design per seed, as standard
Bayesian-optimisation benchmarks do: the loop's Latin hypercube of ``initial`` runs
(``latin_hypercube(space, initial, seed)``). Per problem and seed, every method spends the
same budget of evaluations:

* ``loop``: the loop's own steps, in process (what ``rsm-lrg loop --batch 1`` does round by
  round: the initial design, then ``fit(..., model="gp", seed, length_scale_bounds=LOOP_THETA_BOUNDS)`` and
  ``suggest(model, goal, 1, criterion="ei", seed=seed + round)`` on all runs so far);
* ``diceoptim``: ``km(~1, covtype="matern5_2")`` on the same initial design and
  ``EGO.nsteps`` for the rest of the budget (``benchmarks/r/ego_diceoptim.R``, DiceOptim's
  defaults);
* ``random``: the same initial design, then uniform random settings (seeded) for the rest of
  the budget;
* ``random_uniform`` (shown, not judged): uniform random settings from the first run, with no
  initial design (the protocol of earlier versions of this script; at the end of the initial
  design it differs from the others only by the luck of the draws);
* ``lhs_quadratic``: at budget ``b``, a Latin hypercube of ``b - 1`` runs, a full quadratic
  fitted to them and one run at its predicted optimum (``rsm_lrg.optimize``); with fewer runs
  than the quadratic's coefficients + 1, the hypercube's best alone. Each budget is a
  separate design (a one-shot strategy cannot reuse a smaller one), so it does not share the
  initial design.

The simple regret at budget ``b`` is the best of the first ``b`` evaluations minus the
optimum (Branin 0.397887, Hartmann-6 -3.32237; the surrogate's is the best value known: a
grid of 5⁴ settings, its best polished by L-BFGS-B, and every evaluation of every method).
Printed: the median regret over the seeds per method at each budget from the end of the
initial design. At that step the loop, DiceOptim and random search have evaluated the same
design and are equal by construction, so the verdicts ("below random", "below LHS +
quadratic", "at most DiceOptim") are taken over the steps after it, ``initial + 1 .. budget``.
Nothing here is asserted.

DiceOptim's own draws. With its defaults, ``km`` fits from one BFGS start and ``EGO.nsteps``
maximises EI by ``genoud`` with a small population, so its runs depend on R's random numbers
(``set.seed(seed + --r-seed-offset)``), not only on the initial design: ``--part r
--r-seed-offset 1000`` runs the same reference with other draws. On Branin (8 runs, 20 seeds)
its median regret at budget 12 was 1.81, 2.02, 3.13 and 2.64 with offsets 0, 1000, 2000, 3000.
The loop has random numbers of its own too (the GP's multistart, the EI optimiser's starts):
``--loop-draw-offset K`` seeds them by ``seed + K`` (the fit) and ``seed + K + round``
(suggest) on the same initial design (``latin_hypercube(space, initial, seed)``); 0, the
default, is the single-draw protocol above. ``--part loop`` runs the loop alone (random search
and LHS + quadratic do not depend on the draw). Each seed's traces record their
``loop_draw_offset`` / ``r_seed_offset``.

Pooled draws. ``--merge`` of files that hold the same seeds with other draws keeps every draw
(a file's offsets, 0 where a file predates them) and summarises the pool: per method the median
regret over all (seed, draw) traces (20 seeds x 4 draws: 80 per step), the verdicts on these
medians (steps ``initial + 1 .. budget`` as above), each draw's own median, and per step the
loop against DiceOptim seed by seed: each seed's regret averaged over its draws, the seeds
where each is ahead and the two-sided Wilcoxon signed-rank p (``scipy.stats.wilcoxon``; seeds
that tie left out), so that a difference of medians can be told from the draws' noise. Every
seed must hold the same draws of a method. The README's pooled table: 4 draws of each (loop
offsets 0, 1000, 2000, 3000; R offsets 0, 1000, 2000, 3000), 20 seeds, fixed before the runs.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import tempfile
import threading
import time
from pathlib import Path

import numpy as np
import pandas as pd

import rsm_lrg
from rsm_lrg.design.spacefill import latin_hypercube
from rsm_lrg.factors import FactorSpace
from rsm_lrg.model.pipelines.gp import LOOP_THETA_BOUNDS
from rsm_lrg.optimize.next_runs import suggest

HERE = Path(__file__).parent
TIE = 1e-12  # medians closer than this (relative, or absolute below 1) are equal
R_SCRIPT = HERE / "r" / "ego_diceoptim.R"

_A = np.array([[10, 3, 17, 3.5, 1.7, 8], [0.05, 10, 17, 0.1, 8, 14], [3, 3.5, 1.7, 10, 17, 8],
               [17, 8, 0.05, 10, 0.1, 14]])
_P = 1e-4 * np.array([[1312, 1696, 5569, 124, 8283, 5886], [2329, 4135, 8307, 3736, 1004, 9991],
                      [2348, 1451, 3522, 2883, 3047, 6650], [4047, 8828, 8732, 5743, 1091, 381]])
_ALPHA = np.array([1.0, 1.2, 3.0, 3.2])


def branin(x: np.ndarray) -> np.ndarray:
    """Branin–Hoo on [-5, 10] x [0, 15] (minimum 0.397887 at three points)."""
    x1, x2 = x[:, 0], x[:, 1]
    return (x2 - 5.1 / (4 * np.pi ** 2) * x1 ** 2 + 5 / np.pi * x1 - 6) ** 2 + 10 * (1 - 1 / (8 * np.pi)) * np.cos(x1) + 10


def hartmann6(x: np.ndarray) -> np.ndarray:
    """Hartmann-6 on [0, 1]⁶ (minimum -3.32237)."""
    return -np.sum(_ALPHA * np.exp(-np.sum(_A * (x[:, None, :] - _P) ** 2, axis=2)), axis=1)


SURROGATE_FACTORS = {"thickness_m": (1e-4, 5e-4), "stroke_m": (0.04, 0.06), "velocity_m_s": (0.4, 0.6),
                     "acceleration_m_s2": (20.0, 40.0)}  # the paper's Table 3 box


def surrogate(x: np.ndarray) -> np.ndarray:
    """κ [°C/min] of the calibrated surrogate, deterministic (what ``loop --surrogate`` runs)."""
    from rsm_lrg.surrogate.execute import simulate

    df = pd.DataFrame(np.atleast_2d(x), columns=list(SURROGATE_FACTORS))
    out = simulate(df, seed=0, noise_sd=0.0, calibration="default", progress=False)
    return out["tcr_c_per_min"].to_numpy(dtype=float)


PROBLEMS = {  # name: (factors {name: (low, high)}, function, optimum or None, initial runs, budget)
    "branin": ({"x1": (-5.0, 10.0), "x2": (0.0, 15.0)}, branin, 0.397887357729739, 8, 20),
    "hartmann6": ({f"x{i}": (0.0, 1.0) for i in range(1, 7)}, hartmann6, -3.32236801141551, 12, 36),
    "surrogate": (SURROGATE_FACTORS, surrogate, None, 10, 20),
}


def _space(factors: dict) -> FactorSpace:
    return FactorSpace.from_specs([f"{n}={lo!r}:{hi!r}" for n, (lo, hi) in factors.items()])


def initial_design(factors: dict, n: int, seed: int) -> np.ndarray:
    """The loop's initial design (actual units)."""
    d = latin_hypercube(_space(factors), n, seed=seed)
    return d.actual[list(factors)].to_numpy(dtype=float)


def run_loop(factors: dict, fun, x0: np.ndarray, budget: int, seed: int, draw_offset: int = 0) -> np.ndarray:
    """The loop's steps in process (batch 1): the responses in order of evaluation. The loop's
    own random numbers (the GP's multistart, the EI optimiser's starts) are seeded by
    ``seed + draw_offset`` (the fit) and ``seed + draw_offset + round`` (suggest); the initial
    design ``x0`` is given."""
    names = list(factors)
    specs = [f"{n}={lo!r}:{hi!r}" for n, (lo, hi) in factors.items()]
    X = x0.copy()
    y = fun(X)
    r = 1
    while y.size < budget:
        data = pd.DataFrame(X, columns=names)
        data["y"] = y
        model = rsm_lrg.fit(data, "y", factors=specs, model="gp", seed=seed + draw_offset,
                            length_scale_bounds=LOOP_THETA_BOUNDS)
        s = suggest(model, "minimize", 1, criterion="ei", seed=seed + draw_offset + r)
        xn = s.design.actual[names].to_numpy(dtype=float)
        X = np.vstack([X, xn])
        y = np.r_[y, fun(xn)]
        r += 1
    return y


def run_random(factors: dict, fun, y0: np.ndarray, budget: int, seed: int) -> np.ndarray:
    """The initial design's responses ``y0``, then uniform random settings to the budget."""
    lo, hi = (np.array(v) for v in zip(*factors.values()))
    u = np.random.default_rng(10_000 + seed).random((budget - y0.size, len(factors)))
    return np.r_[y0, fun(lo + u * (hi - lo))]


def run_random_uniform(factors: dict, fun, budget: int, seed: int) -> np.ndarray:
    """Uniform random settings from the first run (no shared initial design)."""
    lo, hi = (np.array(v) for v in zip(*factors.values()))
    u = np.random.default_rng(10_000 + seed).random((budget, len(factors)))
    return fun(lo + u * (hi - lo))


def run_lhs_quadratic(factors: dict, fun, budget: int, initial: int, seed: int) -> np.ndarray:
    """Best value per budget ``b = initial .. budget`` (index ``b - 1``; NaN before ``initial``)."""
    names = list(factors)
    specs = [f"{n}={lo!r}:{hi!r}" for n, (lo, hi) in factors.items()]
    k = len(names)
    p = (k + 1) * (k + 2) // 2
    best = np.full(budget, np.nan)
    for b in range(initial, budget + 1):
        if b - 1 < p + 1:
            x = initial_design(factors, b, 20_000 + 97 * seed + b)
            best[b - 1] = float(np.min(fun(x)))
            continue
        x = initial_design(factors, b - 1, 20_000 + 97 * seed + b)
        y = fun(x)
        data = pd.DataFrame(x, columns=names)
        data["y"] = y
        fit = rsm_lrg.fit(data, "y", factors=specs, model="quadratic")
        opt = rsm_lrg.optimize(fit, "minimize")
        xo = np.array([[opt.actual[n] for n in names]])
        best[b - 1] = float(min(np.min(y), fun(xo)[0]))
    return best


def _fifo_server(fun, fifo_in: str, fifo_out: str, stop: threading.Event) -> None:
    while not stop.is_set():
        with open(fifo_in) as f:
            line = f.readline().strip()
        if not line:
            continue
        v = float(fun(np.array([[float(s) for s in line.split(",")]]))[0])
        with open(fifo_out, "w") as f:
            f.write(f"{v!r}\n")


def run_diceoptim(name: str, factors: dict, fun, designs: dict, budget: int, r_seed_offset: int = 0) -> dict:
    """``{seed: responses}`` from R DiceOptim (``benchmarks/r/ego_diceoptim.R``; R's random
    numbers seeded by ``seed + r_seed_offset``)."""
    with tempfile.TemporaryDirectory() as tmp:
        rows = []
        for seed, (x0, y0) in designs.items():
            for xi, yi in zip(x0, y0):
                rows.append({"seed": seed, **{f"x{j + 1}": v for j, v in enumerate(xi)}, "y": yi})
        init = Path(tmp) / "initial.csv"
        pd.DataFrame(rows).to_csv(init, index=False, float_format="%.17g")
        lo, hi = zip(*factors.values())
        pd.DataFrame({"low": lo, "high": hi}).to_csv(Path(tmp) / "initial_bounds.csv", index=False,
                                                     float_format="%.17g")
        out = Path(tmp) / "out.csv"
        nsteps = budget - len(next(iter(designs.values()))[1])
        cmd = ["Rscript", str(R_SCRIPT), name, str(init), str(nsteps), str(out)]
        stop = threading.Event()
        if name == "surrogate":
            fin, fout = str(Path(tmp) / "in.fifo"), str(Path(tmp) / "out.fifo")
            os.mkfifo(fin)
            os.mkfifo(fout)
            th = threading.Thread(target=_fifo_server, args=(fun, fin, fout, stop), daemon=True)
            th.start()
            cmd += [fin, fout]
        proc = subprocess.run(cmd, capture_output=True, text=True,
                              env={**os.environ, "EGO_R_SEED_OFFSET": str(int(r_seed_offset))})
        stop.set()
        if proc.returncode != 0:
            raise RuntimeError(f"Rscript failed: {proc.stderr[-2000:]}")
        for line in proc.stdout.splitlines() + proc.stderr.splitlines():
            if line.startswith("seed "):
                print(f"DiceOptim {name} {line}", flush=True)
        res = pd.read_csv(out)
    return {int(s): g.sort_values("evaluation")["y"].to_numpy(dtype=float) for s, g in res.groupby("seed")}


def best_so_far(y: np.ndarray, budget: int) -> np.ndarray:
    out = np.full(budget, np.nan)
    m = np.minimum.accumulate(y[:budget])
    out[:m.size] = m
    if m.size < budget:  # a run that stopped early keeps its best
        out[m.size:] = m[-1]
    return out


def surrogate_optimum(extra: list) -> float:
    """Best value known of the surrogate: a 5⁴ grid, its best polished, and ``extra`` values."""
    from scipy.optimize import minimize

    lo, hi = (np.array(v) for v in zip(*SURROGATE_FACTORS.values()))
    g = np.linspace(0.0, 1.0, 5)
    U = np.array(np.meshgrid(*[g] * 4, indexing="ij")).reshape(4, -1).T
    X = lo + U * (hi - lo)
    y = surrogate(X)
    r = minimize(lambda u: float(surrogate((lo + u * (hi - lo))[None, :])[0]), U[int(np.argmin(y))],
                 method="L-BFGS-B", bounds=[(0.0, 1.0)] * 4)
    return float(min(np.min(y), r.fun, *extra))


def one_seed(name: str, seed: int, draw_offset: int = 0, loop_only: bool = False) -> dict:
    """The initial design and the traces of ``loop`` (its random numbers drawn with
    ``draw_offset``, see :func:`run_loop`), ``random``, ``random_uniform`` and ``lhs_quadratic``
    (``loop_only``: the loop's alone)."""
    factors, fun, _, initial, budget = PROBLEMS[name]
    x0 = initial_design(factors, initial, seed)
    t0 = time.perf_counter()
    loop = run_loop(factors, fun, x0, budget, seed, draw_offset)
    t_loop = time.perf_counter() - t0
    if loop_only:
        return {"x0": x0.tolist(), "y0": loop[:initial].tolist(), "loop": loop.tolist(), "loop_s": t_loop,
                "loop_draw_offset": draw_offset}
    return {"x0": x0.tolist(), "y0": loop[:initial].tolist(), "loop": loop.tolist(), "loop_draw_offset": draw_offset,
            "random": run_random(factors, fun, loop[:initial], budget, seed).tolist(),
            "random_uniform": run_random_uniform(factors, fun, budget, seed).tolist(),
            "lhs_quadratic": run_lhs_quadratic(factors, fun, budget, initial, seed).tolist(), "loop_s": t_loop}


def initial_runs(name: str, seed: int) -> dict:
    """The initial design of ``seed`` and its responses (all that DiceOptim needs)."""
    factors, fun, _, initial, _ = PROBLEMS[name]
    x0 = initial_design(factors, initial, seed)
    return {"x0": x0.tolist(), "y0": fun(x0).tolist()}


#: the methods whose runs depend on their own random numbers beyond the initial design, and the
#: key of a seed's traces that names the draw (``--loop-draw-offset``, ``--r-seed-offset``)
DRAWN = {"loop": "loop_draw_offset", "diceoptim": "r_seed_offset"}
METHODS = ("loop", "diceoptim", "random", "lhs_quadratic", "random_uniform")


def seed_draws(run: dict, method: str) -> dict:
    """``{draw offset: trace}`` of ``method`` in one seed's traces: the draws ``--merge``
    gathered (``run["draws"]``), else the one trace there is (offset as recorded, 0 in files
    written before the offsets were)."""
    if method in run.get("draws", {}):
        return {int(k): v for k, v in run["draws"][method].items()}
    return {int(run.get(DRAWN.get(method, ""), 0) or 0): run[method]}


def regret_per_seed(runs: dict, method: str, budget: int, fstar: float) -> tuple[list, np.ndarray]:
    """The draw offsets of ``method`` and its simple regret per seed, draw and budget step, an
    array (seeds, draws, budget) (``lhs_quadratic``'s traces are already best-per-budget). Every
    seed must hold the same draws."""
    seeds = sorted(runs)
    per = [seed_draws(runs[s], method) for s in seeds]
    offsets = sorted(per[0])
    for s, d in zip(seeds, per):
        if sorted(d) != offsets:
            raise SystemExit(f"{method}: seed {s} has draws {sorted(d)}, seed {seeds[0]} {offsets}: "
                             "pool the same draws for every seed")
    out = np.empty((len(seeds), len(offsets), budget))
    for i, d in enumerate(per):
        for j, k in enumerate(offsets):
            y = np.asarray(d[k], dtype=float)
            out[i, j] = (y[:budget] if method == "lhs_quadratic" else best_so_far(y, budget)) - fstar
    return offsets, out


def pooled_median(regret: np.ndarray) -> np.ndarray:
    """Median regret per budget step over all (seed, draw) traces of ``regret`` (seeds, draws,
    budget): 20 seeds x 4 draws are 80 traces per step."""
    return np.median(regret.reshape(-1, regret.shape[-1]), axis=0)


def paired_wilcoxon(a: np.ndarray, b: np.ndarray, tie: float = TIE) -> dict:
    """Seed-by-seed comparison of two methods per budget step: each seed's regret averaged over
    its draws (``a``, ``b``: (seeds, draws, budget), the same seeds in the same order), then the
    Wilcoxon signed-rank test (two-sided, ``scipy.stats.wilcoxon``; seeds with equal means, to
    ``tie`` relative, are left out). ``p`` is None at a step where every seed ties."""
    from scipy.stats import wilcoxon

    ma, mb = a.mean(axis=1), b.mean(axis=1)
    res: dict = {"a_ahead": [], "b_ahead": [], "p": []}
    for t in range(ma.shape[1]):
        d = ma[:, t] - mb[:, t]
        nz = np.abs(d) > tie * np.maximum(1.0, np.maximum(np.abs(ma[:, t]), np.abs(mb[:, t])))
        res["a_ahead"].append(int(np.sum(nz & (d < 0))))
        res["b_ahead"].append(int(np.sum(nz & (d > 0))))
        res["p"].append(float(wilcoxon(d[nz]).pvalue) if nz.any() else None)
    return res


def rank_sum(a: np.ndarray, b: np.ndarray) -> dict:
    """Comparison of two methods per budget step whose runs are not paired by seed (LHS +
    quadratic draws a fresh design per budget; the loop starts from the seed's initial design):
    each seed's regret averaged over its draws (``a``, ``b``: (seeds, draws, budget)), then the
    two-sided Mann–Whitney U test of the two samples of seeds (``scipy.stats.mannwhitneyu``,
    exact where it can be). ``p`` is None at a step where the two samples are one constant or a
    trace holds no value yet (before the initial design is complete)."""
    from scipy.stats import mannwhitneyu

    ma, mb = a.mean(axis=1), b.mean(axis=1)
    res: dict = {"p": []}
    for t in range(ma.shape[1]):
        both = np.concatenate([ma[:, t], mb[:, t]])
        if not np.all(np.isfinite(both)) or np.ptp(both) == 0.0:
            res["p"].append(None)
        else:
            res["p"].append(float(mannwhitneyu(ma[:, t], mb[:, t], alternative="two-sided").pvalue))
    return res


def summarise(name: str, runs: dict, fstar: float | None) -> dict:
    """Median simple regret per method and budget over all (seed, draw) traces, the verdicts on
    them, and, when the loop or DiceOptim holds several draws, each draw's median and the
    seed-by-seed comparison of the two (mean over draws, Wilcoxon)."""
    factors, _, _, initial, budget = PROBLEMS[name]
    seeds = sorted(runs)
    methods = [m for m in METHODS if all(m in runs[s] or m in runs[s].get("draws", {}) for s in seeds)]
    if fstar is None:
        fstar = surrogate_optimum([float(np.nanmin(t)) for s in seeds for m in methods
                                   for t in seed_draws(runs[s], m).values()])
    curves, regret, draws = {}, {}, {}
    for m in methods:
        draws[m], regret[m] = regret_per_seed(runs, m, budget, fstar)
        curves[m] = pooled_median(regret[m])
    steps = list(range(initial + 1, budget + 1))
    loop = curves["loop"]
    # medians that differ by rounding alone (the same runs' values averaged in another order) are
    # equal: "below" needs more than TIE, "at most" allows it
    verdict: dict = {"steps": [steps[0], steps[-1]], "tie_tolerance": TIE}

    def tie(a: float, b: float) -> float:
        return TIE * max(1.0, abs(a), abs(b))

    for m, key, better in (("random", "below_random", lambda a, b: a < b - tie(a, b)),
                           ("lhs_quadratic", "below_lhs_quadratic", lambda a, b: a < b - tie(a, b)),
                           ("diceoptim", "at_most_diceoptim", lambda a, b: a <= b + tie(a, b))):
        if m not in curves:
            continue
        failed = [b for b in steps if not better(loop[b - 1], curves[m][b - 1])]
        verdict[key] = not failed
        verdict[key + "_failed_at"] = failed
    if "diceoptim" in curves:
        a, b = loop[budget - 1], curves["diceoptim"][budget - 1]
        verdict["at_most_diceoptim_at_budget"] = bool(a <= b + tie(a, b))
    ndraws = {m: len(draws[m]) for m in methods if m in DRAWN}
    pooled = any(n > 1 for n in ndraws.values())
    print(f"\n{name}: {len(factors)} factors, initial {initial}, budget {budget}, {len(seeds)} seeds"
          + "".join(f", {m} {n} draw{'s' * (n > 1)} {draws[m]}" for m, n in ndraws.items())
          + f"; median simple regret{' over all (seed, draw) traces' * pooled} (optimum {fstar:.6g})")
    print("budget " + " ".join(f"{m:>14}" for m in methods))
    for b in range(initial, budget + 1):
        print(f"{b:6d} " + " ".join(f"{curves[m][b - 1]:14.4g}" for m in methods))
    out = {"initial": initial, "budget": budget, "seeds": len(seeds), "optimum": fstar,
           "draws": {m: draws[m] for m in ndraws},
           "median_regret": {m: [float(v) for v in c] for m, c in curves.items()}, "verdict": verdict}
    if pooled:
        cols = [(m, j, k) for m in ndraws for j, k in enumerate(draws[m])]
        print("median per draw: budget " + " ".join(f"{m + '@' + str(k):>14}" for m, _, k in cols))
        for b in range(initial, budget + 1):
            print(f"{b:23d} " + " ".join(f"{np.median(regret[m][:, j, b - 1]):14.4g}" for m, j, _ in cols))
        out["median_regret_per_draw"] = {m: {str(k): [float(v) for v in np.median(regret[m][:, j], axis=0)]
                                             for j, k in enumerate(draws[m])} for m in ndraws}
    if "diceoptim" in regret:
        pw = paired_wilcoxon(regret["loop"], regret["diceoptim"])
        print("loop vs DiceOptim, seed by seed (each seed's regret averaged over its draws): "
              "seeds where each is ahead, Wilcoxon signed-rank p (two-sided)")
        print("budget   loop ahead  DiceOptim ahead          p")
        for b in steps:
            p = pw["p"][b - 1]
            print(f"{b:6d} {pw['a_ahead'][b - 1]:12d} {pw['b_ahead'][b - 1]:16d} "
                  + (f"{p:10.3g}" if p is not None else f"{'(all tie)':>10}"))
        out["loop_vs_diceoptim"] = {"loop_ahead": pw["a_ahead"], "diceoptim_ahead": pw["b_ahead"],
                                    "wilcoxon_p": pw["p"]}
    if "lhs_quadratic" in regret:
        rs = rank_sum(regret["loop"], regret["lhs_quadratic"])
        behind = verdict.get("below_lhs_quadratic_failed_at", [])
        print("loop vs LHS + quadratic (not paired: each seed's regret averaged over its draws), "
              "two-sided Mann-Whitney p at the steps where the loop is not below: "
              + (", ".join(f"{b}: {rs['p'][b - 1]:.3g}" if rs["p"][b - 1] is not None else f"{b}: (all tie)"
                           for b in behind) or "none"))
        out["loop_vs_lhs_quadratic"] = {"mann_whitney_p": rs["p"]}
    print(f"verdict: {verdict}", flush=True)
    return out


def _merge(paths: list) -> dict:
    """The traces of several ``--json`` files, per problem and seed (later files add methods, and
    the same method from a later file replaces it). The loop's and DiceOptim's traces are also
    kept per draw (their ``loop_draw_offset``, ``r_seed_offset``; 0 in files that predate them)
    under ``"draws"``, which :func:`summarise` pools; files with the same seeds and other draws
    are pooled, not replaced."""
    traces: dict = {}
    for path in paths:
        data = json.loads(Path(path).read_text())
        for name, d in data["traces"].items():
            for s, v in d.items():
                seed = traces.setdefault(name, {}).setdefault(int(s), {})
                if "y0" in seed and "y0" in v and not np.array_equal(seed["y0"], v["y0"]):
                    raise SystemExit(f"{path}: {name} seed {s} has another initial design")
                for m, key in DRAWN.items():
                    if m in v:
                        seed.setdefault("draws", {}).setdefault(m, {})[str(int(v.get(key, 0) or 0))] = v[m]
                seed.update({k: x for k, x in v.items() if k != "draws"})
                for m, dd in v.get("draws", {}).items():  # a file that was merged itself
                    seed.setdefault("draws", {}).setdefault(m, {}).update(dd)
    return traces


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seeds", type=int, default=20, help="how many seeds")
    ap.add_argument("--seed-start", type=int, default=1, help="the first seed (a slice of seeds)")
    ap.add_argument("--problems", nargs="+", default=list(PROBLEMS), choices=list(PROBLEMS))
    ap.add_argument("--part", choices=["all", "ours", "loop", "r"], default="all",
                    help="ours: loop, random and LHS + quadratic; loop: the loop alone (another draw of it, "
                         "see --loop-draw-offset); r: R DiceOptim only; all: ours and r")
    ap.add_argument("--no-r", action="store_true", help="leave out R DiceOptim (same as --part ours)")
    ap.add_argument("--r-only", metavar="TRACES", default=None,
                    help="add R DiceOptim to the traces of an earlier --json (its initial designs) and summarise")
    ap.add_argument("--merge", nargs="+", metavar="JSON", default=None,
                    help="merge the traces of earlier --json files (slices, parts) and summarise")
    ap.add_argument("--r-seed-offset", type=int, default=0,
                    help="seed R's random numbers (km's start, genoud) by seed + this (default 0): the "
                         "same DiceOptim reference with other draws")
    ap.add_argument("--loop-draw-offset", type=int, default=0,
                    help="seed the loop's own random numbers (the GP's multistart, EI's starts) by seed + "
                         "this (fit) and seed + this + round (suggest) (default 0): the same loop on the same "
                         "initial designs with other draws; the other methods are unaffected")
    ap.add_argument("--jobs", type=int, default=1, help="seeds run in parallel processes")
    ap.add_argument("--json", default=None, help="write the traces and the summary here")
    args = ap.parse_args(argv)
    part = "ours" if args.no_r else args.part
    seeds = range(args.seed_start, args.seed_start + args.seeds)
    # the draws this run made (per seed too, in its traces, where --merge reads them)
    offsets = {"loop_draw_offset": args.loop_draw_offset if part in ("all", "ours", "loop") else None,
               "r_seed_offset": args.r_seed_offset if part in ("all", "r") else None}

    if args.merge:
        traces = _merge(args.merge)
        part = "ours"  # nothing new to run
        offsets = {"loop_draw_offset": None, "r_seed_offset": None}  # the summary lists the draws
    elif args.r_only:
        traces = _merge([args.r_only])
        part = "r"
    elif part == "r":
        traces = {name: {s: initial_runs(name, s) for s in seeds} for name in args.problems}
    else:
        from concurrent.futures import ProcessPoolExecutor

        traces = {name: {} for name in args.problems}
        tasks = [(name, s, args.loop_draw_offset, part == "loop") for name in args.problems for s in seeds]
        t0 = time.perf_counter()
        with ProcessPoolExecutor(max_workers=max(1, args.jobs)) as pool:
            for (name, s, _, _), res in zip(tasks, pool.map(one_seed, *zip(*tasks))):
                traces[name][s] = res
                if args.json:  # what is done so far, should the run be cut short
                    Path(args.json).write_text(json.dumps({**offsets, "traces": traces}))
                print(f"{name} seed {s}: loop best {min(res['loop']):.6g}, loop {res['loop_s']:.1f} s "
                      f"({time.perf_counter() - t0:.0f} s)", flush=True)
    summary = {}
    for name, runs in traces.items():
        factors, fun, fstar, initial, budget = PROBLEMS[name]
        if part in ("all", "r"):
            designs = {s: (np.array(r["x0"]), np.asarray(r.get("y0", r.get("loop", [])[:initial])))
                       for s, r in runs.items()}
            for s, y in run_diceoptim(name, factors, fun, designs, budget,
                                         args.r_seed_offset).items():
                runs[s].get("draws", {}).pop("diceoptim", None)  # this draw replaces the file's
                runs[s]["diceoptim"] = y.tolist()
                runs[s]["r_seed_offset"] = args.r_seed_offset
            if args.json:
                Path(args.json).write_text(json.dumps({**offsets, "traces": traces}))
        if any("loop" in r for r in runs.values()):
            summary[name] = summarise(name, runs, fstar)
    if args.json:
        Path(args.json).write_text(json.dumps({**offsets, "summary": summary, "traces": traces}, indent=1))
    return 0

if __name__ == "__main__":
    raise SystemExit(main())
