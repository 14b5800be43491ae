"""Benchmark the Gaussian process (issue 33) on thousands of runs: the fit with its multistart,
and predictions at 10⁵ new settings with and without the kriging variance, against an anchor
run in the same process — one Cholesky factorisation of an SPD matrix of the runs' size, which
every likelihood evaluation needs at least.

Usage::

    python benchmarks/bench_gp.py                            # 2,000 runs of Hartmann-6, 10⁵ points
    python benchmarks/bench_gp.py --runs 500 2000 --points 100000 --json out.json

The runs are a seeded Latin hypercube on [0, 1]⁶ with the Hartmann-6 function as response
(Dixon & Szegő 1978); the fit is ``rsm_lrg.fit(..., model="gp")`` with its defaults (Matérn
5/2, constant trend, 10 seeded starts; above ``MULTISTART_RUNS`` runs the starts are searched on
a seeded subsample and the best polished on every run). Printed per size: the anchor, the fit's
wall and CPU time, the search (the likelihood evaluations on the subsample and on all runs,
``fit.search``), the mean-only
prediction (``predict_coded``) and the prediction with the kriging sd (``mean_sd``) of
``--points`` settings, each with its ratio to the anchor, and the peak memory (tracemalloc
of the fit and of the predictions; NumPy reports its arrays to it) with the process's peak
resident size, the threads of the compiled passes and of the kriging sd's chunks
(``rsm_lrg.model.engines.gp_compiled.threads``: the usable cores, at most 8; set
``RSM_LRG_GP_THREADS`` to change) and the BLAS threads asked for (``OPENBLAS_NUM_THREADS``).
With ``--sklearn`` (when scikit-learn is installed; it is not a dependency) the same runs, in
coded units, are also fitted by scikit-learn's ``GaussianProcessRegressor`` with one start
(``n_restarts_optimizer=0``): a Matérn 5/2 kernel with one length-scale per factor (bounds
0.001–20) times a constant, ``normalize_y=True`` in place of the constant trend, ``alpha=1e-10``
(the maintained library the issue names; its model differs from ours in the trend, taken out
by ``normalize_y``, and in the length-scales' bounds, so its log-likelihood is not comparable,
its time is).
Times are wall-clock on a shared machine (expect noise of tens of per cent); nothing here is
asserted.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import time
import tracemalloc
from pathlib import Path

import numpy as np
import pandas as pd

import rsm_lrg
from rsm_lrg.model.engines import gp_compiled
from rsm_lrg.model.pipelines import gp as gp_pipeline

_A = np.array([[10, 3, 17, 3.5, 1.7, 8], [0.05, 10, 17, 0.1, 8, 14], [3, 3.5, 1.7, 10, 17, 8],
               [17, 8, 0.05, 10, 0.1, 14]])
_P = 1e-4 * np.array([[1312, 1696, 5569, 124, 8283, 5886], [2329, 4135, 8307, 3736, 1004, 9991],
                      [2348, 1451, 3522, 2883, 3047, 6650], [4047, 8828, 8732, 5743, 1091, 381]])
_ALPHA = np.array([1.0, 1.2, 3.0, 3.2])


def hartmann6(u: np.ndarray) -> np.ndarray:
    """Hartmann-6 on [0, 1]⁶ (minimum -3.32237 at (0.20169, 0.150011, 0.476874, 0.275332,
    0.311652, 0.6573))."""
    return -np.sum(_ALPHA * np.exp(-np.sum(_A * (u[:, None, :] - _P) ** 2, axis=2)), axis=1)


def latin_hypercube(rng: np.random.Generator, n: int, k: int) -> np.ndarray:
    return (np.argsort(rng.random((n, k)), axis=0) + rng.random((n, k))) / n


def _median_time(fn, repeat: int) -> tuple[float, float]:
    """Median wall and CPU (this process, all threads) seconds of ``fn()``."""
    walls, cpus = [], []
    for _ in range(repeat):
        c0, t0 = time.process_time(), time.perf_counter()
        fn()
        walls.append(time.perf_counter() - t0)
        cpus.append(time.process_time() - c0)
    return statistics.median(walls), statistics.median(cpus)


def _sklearn_one_start(x: np.ndarray, y: np.ndarray) -> dict:
    """Wall and CPU seconds of scikit-learn's ``GaussianProcessRegressor`` with one start on
    coded runs ``x`` (Matérn 5/2, one length-scale per factor, times a constant)."""
    from sklearn import __version__
    from sklearn.gaussian_process import GaussianProcessRegressor
    from sklearn.gaussian_process.kernels import ConstantKernel, Matern

    kernel = ConstantKernel(1.0, (1e-5, 1e5)) * Matern(length_scale=np.ones(x.shape[1]),
                                                       length_scale_bounds=(1e-3, 20.0), nu=2.5)
    gpr = GaussianProcessRegressor(kernel, alpha=1e-10, normalize_y=True, n_restarts_optimizer=0, random_state=1)
    c0, t0 = time.process_time(), time.perf_counter()
    gpr.fit(x, y)
    return {"sklearn_version": __version__, "sklearn_one_start_wall_s": time.perf_counter() - t0,
            "sklearn_one_start_cpu_s": time.process_time() - c0, "sklearn_kernel": str(gpr.kernel_)}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--runs", type=int, nargs="+", default=[2000])
    ap.add_argument("--points", type=int, default=100_000)
    ap.add_argument("--repeat", type=int, default=3, help="repeats of the anchor and the predictions")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--json", default=None)
    ap.add_argument("--sklearn", action="store_true",
                    help="also time scikit-learn's GaussianProcessRegressor (one start) on the same runs")
    args = ap.parse_args(argv)

    names = list("abcdef")
    factors = [f"{c}=0:1" for c in names]
    warm = pd.DataFrame(latin_hypercube(np.random.default_rng(0), 400, 6), columns=names)
    warm["y"] = hartmann6(warm[names].to_numpy())
    g = gp_pipeline.fit_gp(warm, "y", factors, starts=1)  # compiles / loads the kernels
    g.predict_coded(np.zeros((200, 6)))
    rows = []
    for n in args.runs:
        rng = np.random.default_rng(args.seed)
        df = pd.DataFrame(latin_hypercube(rng, n, 6), columns=names)
        df["y"] = hartmann6(df[names].to_numpy())
        a = rng.standard_normal((n, n))
        spd = a @ a.T + n * np.eye(n)
        anchor, anchor_cpu = _median_time(lambda spd=spd: np.linalg.cholesky(spd), args.repeat)
        del a, spd
        tracemalloc.start()
        c0, t0 = time.process_time(), time.perf_counter()
        fit = rsm_lrg.fit(df, "y", factors=factors, model="gp", seed=args.seed)
        fit_wall, fit_cpu = time.perf_counter() - t0, time.process_time() - c0
        fit_peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        pts = 2.0 * np.random.default_rng(args.seed + 1).random((args.points, 6)) - 1.0  # coded
        mean_only, mean_cpu = _median_time(lambda pts=pts, fit=fit: fit.predict_coded(pts), args.repeat)
        with_sd, sd_cpu = _median_time(lambda pts=pts, fit=fit: fit.mean_sd(pts), 1)
        tracemalloc.start()
        fit.mean_sd(pts)
        pred_peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        rows.append({"runs": n, "factors": 6, "points": args.points, "anchor_cholesky_s": anchor,
                     "anchor_cholesky_cpu_s": anchor_cpu, "fit_wall_s": fit_wall, "fit_cpu_s": fit_cpu,
                     "fit_per_anchor": fit_wall / anchor, "fit_cpu_per_anchor_cpu": fit_cpu / anchor_cpu,
                     "predict_mean_cpu_s": mean_cpu, "predict_mean_sd_cpu_s": sd_cpu,
                     "search": fit.search,
                     "log_likelihood": fit.log_likelihood,
                     "predict_mean_s": mean_only, "predict_mean_per_anchor": mean_only / anchor,
                     "predict_mean_sd_s": with_sd, "predict_mean_sd_per_anchor": with_sd / anchor,
                     "fit_peak_mib": fit_peak / 2 ** 20, "predict_peak_mib": pred_peak / 2 ** 20,
                     "max_rss_mib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
                     "load": os.getloadavg()[0], "gp_threads": gp_compiled.threads(args.points * n),
                     "blas_threads": os.environ.get("OPENBLAS_NUM_THREADS", "(OpenBLAS default)")})
        r = rows[-1]
        if args.sklearn:
            r.update(_sklearn_one_start(2.0 * df[names].to_numpy() - 1.0, df["y"].to_numpy()))
            r["sklearn_one_start_per_fit"] = r["sklearn_one_start_wall_s"] / fit_wall
            print(f"{n} runs: scikit-learn, one start: {r['sklearn_one_start_wall_s']:.1f} s wall, "
                  f"{r['sklearn_one_start_cpu_s']:.1f} s CPU ({r['sklearn_one_start_per_fit']:.1f}x our fit "
                  f"with {fit.starts} starts)")
        print(f"{n} runs x 6 factors (load {r['load']:.1f}, {r['gp_threads']} GP threads, BLAS threads "
              f"{r['blas_threads']}): anchor (one Cholesky) {anchor:.3f} s wall, "
              f"{anchor_cpu:.3f} s CPU; fit {fit_wall:.2f} s wall ({r['fit_per_anchor']:.0f}x), {fit_cpu:.2f} s CPU "
              f"({r['fit_cpu_per_anchor_cpu']:.0f}x the anchor's CPU), search {r['search']}; {args.points} points: "
              f"mean {mean_only:.3f} s wall, {mean_cpu:.3f} s CPU ({r['predict_mean_per_anchor']:.1f}x), mean + sd "
              f"{with_sd:.2f} s wall, {sd_cpu:.2f} s CPU ({r['predict_mean_sd_per_anchor']:.1f}x); peak {r['fit_peak_mib']:.0f} MiB (fit), "
              f"{r['predict_peak_mib']:.0f} MiB (prediction), resident {r['max_rss_mib']:.0f} MiB")
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
