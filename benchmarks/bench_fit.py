"""Cost of rsm_lrg.fit relative to one QR factorisation of its model matrix (not a test).

For n runs and k factors (full quadratic: 66 terms for k = 10) it measures, each in a
fresh subprocess so that one measurement's memory does not colour the next:

* the baseline: ``scipy.linalg.qr(X, mode="r")`` of the n x p model matrix ``X``
  (time; the size of ``X`` is the memory yardstick);
* the whole ``rsm_lrg.fit`` (model matrix built and factorised in chunks, hat diagonal
  in a second pass, ANOVA with Type III SS, lack of fit / pure error, PRESS, VIF,
  canonical analysis): wall time, and the peak of memory allocated during the fit
  (``tracemalloc``, in a second run; the input DataFrame, made before, is not counted)
  and the peak resident memory above that at the start of the fit (sampled; it also sees
  LAPACK work arrays, which tracemalloc does not).

It prints ``fit / QR`` time and ``peak / size of X`` ratios (issue 11 targets: at most 3
and 1.5 for 10^6 runs x 10 factors). With ``--repeat`` the QR and the fit alternate and
the median of the per-round ratios is printed with their range.

    python benchmarks/bench_fit.py                 # n = 1e6, k = 10
    python benchmarks/bench_fit.py --threads 1 --repeat 3
    python benchmarks/bench_fit.py --n 3e5 --k 10 4
    python benchmarks/bench_fit.py --dask 1e7 --partitions 64 --workers 2 --memory-limit 1GB

BLAS threads: on an idle machine the ratio is about 1 with one or two OpenBLAS threads. On
a machine whose cores are busy with other work (load above the core count) two threads make
the fit slower than the QR (measured 2x at load 3.8 on 2 cores, 0.97x at load 1.9): LAPACK's
``dgeqrf`` factorises matrices of at most 128 columns column by column with level-2 BLAS
calls that OpenBLAS splits over its threads, and each call waits until every thread has had
a core; the fit makes those calls once per chunk of 32768 rows, the one QR once in all.
Larger chunks (``--chunk-rows``) make fewer such calls but lose the cache (about 1.5x slower
with one thread), so the default stays.

With ``--dask N`` it fits N runs made partition by partition on a ``distributed.LocalCluster``
(the runs are never in one process; needs ``dask[dataframe]``) and prints the time and the
peak resident memory of each worker and of the client.
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


class _PeakRSS:
    """Peak resident memory [bytes] of this process while the ``with`` block runs, above
    its resident memory at entry (sampled every 2 ms from /proc/self/statm; it sees what
    ``tracemalloc`` does not: LAPACK work arrays that NumPy allocates with ``malloc``)."""

    def __enter__(self):
        import os
        import threading

        self._page = os.sysconf("SC_PAGE_SIZE")
        self.base = self._rss()
        self.peak = self.base
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._poll, daemon=True)
        self._thread.start()
        return self

    def _rss(self) -> int:
        with open("/proc/self/statm") as fh:
            return int(fh.read().split()[1]) * self._page

    def _poll(self):
        while not self._stop.wait(0.002):
            self.peak = max(self.peak, self._rss())

    def __exit__(self, *exc):
        self._stop.set()
        self._thread.join()
        self.peak = max(self.peak, self._rss())
        self.above = self.peak - self.base
        return False


def _terms_api():
    try:
        from rsm_lrg.terms import design_matrix, model_terms
    except ImportError:  # before the terms moved to the base layer
        from rsm_lrg.model.build.terms import design_matrix, model_terms
    return design_matrix, model_terms


def _child(what: str, n: int, k: int, chunk_rows: int | None = None) -> dict:
    import tracemalloc

    import rsm_lrg

    design_matrix, model_terms = _terms_api()

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
    kw = {"chunk_rows": chunk_rows} if chunk_rows else {}
    rsm_lrg.fit(make(200, 3), "y")  # warm-up: imports
    with _PeakRSS() as rss:
        t0, c0 = time.perf_counter(), time.process_time()
        r = rsm_lrg.fit(df, "y", factors=specs, **kw)
        t_fit, c_fit = time.perf_counter() - t0, time.process_time() - c0
    assert np.isfinite(r.statistics.press) and r.pure_error is not None
    del r
    tracemalloc.start()
    r = rsm_lrg.fit(df, "y", factors=specs, **kw)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return {"fit_s": t_fit, "fit_cpu": c_fit, "peak_bytes": peak, "rss_bytes": rss.above, "x_bytes": nbytes,
            "r2": r.statistics.r2}


def _run(what: str, n: int, k: int, threads: int | None = None, chunk_rows: int | None = None) -> dict:
    import os

    env = dict(os.environ)
    if threads:
        for var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
            env[var] = str(threads)
    extra = ["--chunk-rows", str(chunk_rows)] if chunk_rows else []
    out = subprocess.run([sys.executable, __file__, "--child", what, "--n", str(n), "--k", str(k), *extra],
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
    import os
    import resource

    def peak_rss() -> int:  # peak resident memory of the calling process [bytes] (Linux: ru_maxrss in KiB)
        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024

    with distributed.LocalCluster(n_workers=workers, threads_per_worker=1, memory_limit=memory_limit,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        ddf = dd.from_delayed(parts, meta=meta)
        t0 = time.perf_counter()
        r = rsm_lrg.fit(ddf, "y", factors=specs)
        t = time.perf_counter() - t0
        worker_peaks = sorted(client.run(peak_rss).values())
    p = (k + 1) * (k + 2) // 2
    x_mb = n * p * 8 / 1e6
    print(f"dask fit: n {n}, k {k} ({p} terms; the n x p model matrix would be {x_mb:.0f} MB), {len(parts)} partitions "
          f"(each made on its worker), {workers} workers x 1 thread, memory limit {memory_limit} each, "
          f"{os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.2f}: {t:.1f} s (includes making the runs, three "
          f"times: one per pass); peak resident memory per worker {', '.join(f'{b / 1e6:.0f}' for b in worker_peaks)} MB, "
          f"client {peak_rss() / 1e6:.0f} MB; R2 {r.statistics.r2:.4f}, PRESS {r.statistics.press:.6g}, "
          f"pure error df {r.pure_error.df}", flush=True)


def main() -> None:
    import statistics

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=float, nargs="+", default=[1e6])
    ap.add_argument("--k", type=int, nargs="+", default=[10])
    ap.add_argument("--repeat", type=int, default=1,
                    help="rounds, QR and fit alternating; medians and the median of per-round ratios are printed")
    ap.add_argument("--chunk-rows", type=int, default=None, help="rows per chunk of the fit (default: the core's)")
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
        print(json.dumps(_child(args.child, int(args.n[0]), args.k[0], args.chunk_rows)))
        return
    import os

    print(f"wall and CPU (process, all threads) seconds, BLAS threads {args.threads or 'default'}, "
          f"{os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.2f}; {args.repeat} round(s), medians. "
          "peak: tracemalloc (Python/NumPy allocations); rss: resident memory above the start of the fit")
    print(f"{'n':>9} {'k':>3} {'terms':>5} {'X [MB]':>8} {'QR [s]':>8} {'fit [s]':>8} {'fit/QR':>7} "
          f"{'QR cpu':>7} {'fit cpu':>7} {'cpu/cpu':>7} {'peak [MB]':>10} {'peak/X':>7} {'rss/X':>6}")
    med = statistics.median
    for n in (int(v) for v in args.n):
        for k in args.k:
            qs, fs = [], []
            for _ in range(args.repeat):
                qs.append(_run("qr", n, k, args.threads))
                fs.append(_run("fit", n, k, args.threads, args.chunk_rows))
            p = (k + 1) * (k + 2) // 2
            xb = qs[0]["x_bytes"]
            wall = med(f["fit_s"] / q["qr_s"] for q, f in zip(qs, fs))
            cpu = med(f["fit_cpu"] / q["qr_cpu"] for q, f in zip(qs, fs))
            spread = (f" (per-round fit/QR {min(f['fit_s'] / q['qr_s'] for q, f in zip(qs, fs)):.2f}"
                      f"-{max(f['fit_s'] / q['qr_s'] for q, f in zip(qs, fs)):.2f})") if args.repeat > 1 else ""
            print(f"{n:>9} {k:>3} {p:>5} {xb / 1e6:>8.1f} {med(q['qr_s'] for q in qs):>8.2f} "
                  f"{med(f['fit_s'] for f in fs):>8.2f} {wall:>7.2f} {med(q['qr_cpu'] for q in qs):>7.2f} "
                  f"{med(f['fit_cpu'] for f in fs):>7.2f} {cpu:>7.2f} {med(f['peak_bytes'] for f in fs) / 1e6:>10.1f} "
                  f"{med(f['peak_bytes'] for f in fs) / xb:>7.2f} {med(f['rss_bytes'] for f in fs) / xb:>6.2f}{spread}",
                  flush=True)


if __name__ == "__main__":
    main()
