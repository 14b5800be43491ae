"""Cost of rsm_lrg.fit relative to one QR factorisation of its model matrix (not a test).

For n runs and k factors (full quadratic: 66 terms for k = 10) it measures, each in a
fresh subprocess so that one measurement's memory does not colour the next:

* the baseline: ``scipy.linalg.qr(X, mode="r")`` of the n x p model matrix ``X``
  (time; the size of ``X`` is the memory yardstick);
* the whole ``rsm_lrg.fit`` (model matrix built and factorised in chunks, hat diagonal
  in a second pass, ANOVA with Type III SS, lack of fit / pure error, PRESS, VIF,
  canonical analysis): wall time, and the peak of memory allocated during the fit
  (``tracemalloc``, in a second run; the input DataFrame, made before, is not counted).

It prints ``fit / QR`` time and ``peak / size of X`` ratios (issue 11 targets: at most 3
and 1.5 for 10^6 runs x 10 factors).

    python benchmarks/bench_fit.py                 # n = 1e6, k = 10
    python benchmarks/bench_fit.py --n 3e5 --k 10 4
    python benchmarks/bench_fit.py --dask 1e6 --partitions 16 --workers 2 --memory-limit 1GB

With ``--dask N`` it fits N runs made partition by partition on a ``distributed.LocalCluster``
(the runs are never in one process; needs ``dask[dataframe]``) and prints the time.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time

import numpy as np


def make(n: int, k: int, seed: int = 0):
    """n runs of k factors on three levels (a tenth of them anywhere in [-1, 1]) and a
    quadratic response with unit noise."""
    import pandas as pd

    rng = np.random.default_rng(seed)
    x = rng.integers(-1, 2, size=(n, k)).astype(float)
    x[: max(n // 10, 1)] = rng.uniform(-1, 1, (max(n // 10, 1), k))
    df = pd.DataFrame(x, columns=[f"x{i}" for i in range(k)])
    df["y"] = 1 + x.sum(axis=1) + 0.5 * (x ** 2).sum(axis=1) + rng.normal(size=n)
    return df


def _child(what: str, n: int, k: int) -> dict:
    import tracemalloc

    import rsm_lrg
    from rsm_lrg.model.terms import design_matrix, model_terms

    df = make(n, k)
    specs = [f"x{i}=-1:1" for i in range(k)]
    terms = model_terms([chr(65 + i) for i in range(k)], "quadratic")
    nbytes = n * len(terms) * 8
    if what == "qr":
        from scipy.linalg import qr

        X = design_matrix(df[[f"x{i}" for i in range(k)]].to_numpy(), terms)
        t0, c0 = time.perf_counter(), time.process_time()
        qr(X, mode="r")
        return {"qr_s": time.perf_counter() - t0, "qr_cpu": time.process_time() - c0, "x_bytes": nbytes}
    rsm_lrg.fit(make(200, 3), "y")  # warm-up: imports
    t0, c0 = time.perf_counter(), time.process_time()
    r = rsm_lrg.fit(df, "y", factors=specs)
    t_fit, c_fit = time.perf_counter() - t0, time.process_time() - c0
    assert np.isfinite(r.statistics.press) and r.pure_error is not None
    del r
    tracemalloc.start()
    r = rsm_lrg.fit(df, "y", factors=specs)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return {"fit_s": t_fit, "fit_cpu": c_fit, "peak_bytes": peak, "x_bytes": nbytes, "r2": r.statistics.r2}


def _run(what: str, n: int, k: int, threads: int | None = None) -> dict:
    import os

    env = dict(os.environ)
    if threads:
        for var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
            env[var] = str(threads)
    out = subprocess.run([sys.executable, __file__, "--child", what, "--n", str(n), "--k", str(k)],
                         capture_output=True, text=True, check=True, env=env)
    return json.loads(out.stdout.strip().splitlines()[-1])


def _dask(n: int, k: int, partitions: int, workers: int, memory_limit: str) -> None:
    import dask
    import dask.dataframe as dd
    import distributed

    import rsm_lrg

    rows = -(-n // partitions)
    parts = [dask.delayed(make)(min(rows, n - i * rows), k, i) for i in range(partitions) if n - i * rows > 0]
    meta = make(2, k).iloc[:0]
    specs = [f"x{i}=-1:1" for i in range(k)]
    with distributed.LocalCluster(n_workers=workers, threads_per_worker=1, memory_limit=memory_limit,
                                  dashboard_address=None) as cluster, distributed.Client(cluster):
        ddf = dd.from_delayed(parts, meta=meta)
        t0 = time.perf_counter()
        r = rsm_lrg.fit(ddf, "y", factors=specs)
        t = time.perf_counter() - t0
    p = (k + 1) * (k + 2) // 2
    print(f"dask fit: n {n}, k {k} ({p} terms), {len(parts)} partitions (each made on its worker), {workers} workers "
          f"x 1 thread, memory limit {memory_limit} each: {t:.1f} s (includes making the runs); R2 {r.statistics.r2:.4f}, "
          f"PRESS {r.statistics.press:.6g}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=float, nargs="+", default=[1e6])
    ap.add_argument("--k", type=int, nargs="+", default=[10])
    ap.add_argument("--dask", type=float, default=None, metavar="N", help="fit N runs on a LocalCluster instead")
    ap.add_argument("--partitions", type=int, default=16)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--memory-limit", default="1GB")
    ap.add_argument("--threads", type=int, default=None,
                    help="BLAS threads in both measurements (1 gives steady ratios on a shared machine)")
    ap.add_argument("--child", choices=["qr", "fit"], help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.dask:
        _dask(int(args.dask), args.k[0], args.partitions, args.workers, args.memory_limit)
        return
    if args.child:
        print(json.dumps(_child(args.child, int(args.n[0]), args.k[0])))
        return
    print("wall and CPU (process, all threads) seconds; the CPU ratio is the steadier one on a shared machine")
    print(f"{'n':>9} {'k':>3} {'terms':>5} {'X [MB]':>8} {'QR [s]':>8} {'fit [s]':>8} {'fit/QR':>7} "
          f"{'QR cpu':>7} {'fit cpu':>7} {'cpu/cpu':>7} {'peak [MB]':>10} {'peak/X':>7}")
    for n in (int(v) for v in args.n):
        for k in args.k:
            q = _run("qr", n, k, args.threads)
            f = _run("fit", n, k, args.threads)
            p = (k + 1) * (k + 2) // 2
            print(f"{n:>9} {k:>3} {p:>5} {q['x_bytes'] / 1e6:>8.1f} {q['qr_s']:>8.2f} {f['fit_s']:>8.2f} "
                  f"{f['fit_s'] / q['qr_s']:>7.2f} {q['qr_cpu']:>7.2f} {f['fit_cpu']:>7.2f} "
                  f"{f['fit_cpu'] / q['qr_cpu']:>7.2f} {f['peak_bytes'] / 1e6:>10.1f} {f['peak_bytes'] / q['x_bytes']:>7.2f}",
                  flush=True)


if __name__ == "__main__":
    main()
