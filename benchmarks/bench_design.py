"""Whole-process cost of ``rsm-lrg design`` against R (issue 25, item 5; not a test).

Two comparisons, each run alternately ``--repeat`` times after one uncounted warm-up round:

* **D-optimal quadratic designs**, k = 4, 5, 6 factors, N = p + 4 runs (p = (k+1)(k+2)/2):
  ``python -m rsm_lrg design optimal --criterion D --model quadratic --runs N`` against
  ``Rscript benchmarks/r/optfederov.R`` (AlgDesign's ``optFederov(~quad(.))`` on the 3^k grid,
  its default 5 repeats). Both designs are scored by the same formula, the D-efficiency
  ``det(X'X / N)^(1/p)`` of the quadratic model in coded units (higher is better).
* **Box-Behnken**, k = 4: ``python -m rsm_lrg design box-behnken`` against
  ``Rscript benchmarks/r/bbd.R`` (R ``rsm``'s ``bbd()``).

CPU time is user + system of the child process tree (``resource.getrusage(RUSAGE_CHILDREN)``
deltas); every child runs with one BLAS/OpenMP thread (``OPENBLAS_NUM_THREADS=1`` etc.: R's
reference BLAS is single-threaded). The script prints the medians and the median ratios
Python / R; the seeds differ per round (``--seed`` + round) so that neither side is timed on
one lucky start.

R libraries: AlgDesign and rsm (``R_LIBS``; e.g. ``R CMD INSTALL -l /tmp/rlib`` from the CRAN
sources). Targets (issue 25): D-optimal CPU at most 2x R's at a D-efficiency at least R's;
``design box-behnken`` at most 2x ``bbd()``.

    R_LIBS=/tmp/rlib python benchmarks/bench_design.py              # 5 rounds
    R_LIBS=/tmp/rlib python benchmarks/bench_design.py --repeat 9 --json out.json
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
from itertools import combinations
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
THREADS = {v: "1" for v in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS")}


def quadratic(X: np.ndarray) -> np.ndarray:
    """The full quadratic model matrix of coded runs ``X`` (intercept, linear, 2FI, squares)."""
    n, k = X.shape
    cols = [np.ones(n)] + [X[:, i] for i in range(k)]
    cols += [X[:, i] * X[:, j] for i, j in combinations(range(k), 2)]
    cols += [X[:, i] ** 2 for i in range(k)]
    return np.column_stack(cols)


def d_efficiency(X: np.ndarray) -> float:
    """``det(F'F / N)^(1/p)`` of the quadratic model (0 for a singular design)."""
    F = quadratic(X)
    sign, logdet = np.linalg.slogdet(F.T @ F / len(X))
    return float(np.exp(logdet / F.shape[1])) if sign > 0 else 0.0


def timed(cmd: list[str], env: dict) -> tuple[float, float]:
    """``(cpu, wall)`` seconds of one child process (its whole tree)."""
    import time

    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    out = subprocess.run(cmd, env=env, capture_output=True, text=True, cwd=ROOT)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if out.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed:\n{out.stderr[-2000:]}")
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), wall


def coded_runs(path: Path, k: int) -> np.ndarray:
    import pandas as pd

    df = pd.read_csv(path)
    cols = [c for c in df.columns if c.startswith("coded_")] or [f"x{i + 1}" for i in range(k)]
    return df[cols[:k]].to_numpy(dtype=float)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--ks", default="4,5,6")
    ap.add_argument("--json", default=None)
    a = ap.parse_args()
    env = dict(os.environ, **THREADS)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    rows = {}
    with tempfile.TemporaryDirectory() as tmp:
        tmpd = Path(tmp)
        for k in [int(x) for x in a.ks.split(",")]:
            p = (k + 1) * (k + 2) // 2
            n = p + 4
            facs = [f"--factor=x{i + 1}=-1:1" for i in range(k)]
            res = {"py_cpu": [], "r_cpu": [], "py_wall": [], "r_wall": [], "py_d": [], "r_d": []}
            for r in range(a.repeat + 1):
                seed = a.seed + r
                py_out, r_out = tmpd / f"py{k}_{r}.csv", tmpd / f"r{k}_{r}.csv"
                py = [sys.executable, "-m", "rsm_lrg", "design", "optimal", "--criterion", "D", "--model",
                      "quadratic", "--runs", str(n), *facs, "--seed", str(seed), "-o", str(py_out)]
                rr = ["Rscript", str(HERE / "r" / "optfederov.R"), str(k), str(n), str(seed), str(r_out)]
                cpu_p, wall_p = timed(py, env)
                cpu_r, wall_r = timed(rr, env)
                if r == 0:
                    continue  # warm-up: byte-code caches, file system
                res["py_cpu"].append(cpu_p)
                res["r_cpu"].append(cpu_r)
                res["py_wall"].append(wall_p)
                res["r_wall"].append(wall_r)
                res["py_d"].append(d_efficiency(coded_runs(py_out, k)))
                res["r_d"].append(d_efficiency(coded_runs(r_out, k)))
            med = {key: statistics.median(v) for key, v in res.items()}
            med["cpu_ratio"] = med["py_cpu"] / med["r_cpu"]
            med["d_ratio"] = med["py_d"] / med["r_d"]
            rows[f"optimal k={k} N={n}"] = med
            print(f"D-optimal quadratic k={k} N={n}: CPU python {med['py_cpu']:.2f} s, R optFederov "
                  f"{med['r_cpu']:.2f} s, ratio {med['cpu_ratio']:.2f}; D-eff python {med['py_d']:.4f}, "
                  f"R {med['r_d']:.4f} (ratio {med['d_ratio']:.3f}; min python {min(res['py_d']):.4f})", flush=True)
        res = {"py_cpu": [], "r_cpu": []}
        for r in range(a.repeat + 1):
            py = [sys.executable, "-m", "rsm_lrg", "design", "box-behnken", *[f"--factor=x{i + 1}=-1:1" for i in range(4)],
                  "--seed", "1", "-o", str(tmpd / f"bb{r}.csv")]
            rr = ["Rscript", str(HERE / "r" / "bbd.R"), "4", "3", str(tmpd / f"rbb{r}.csv")]
            cpu_p, _ = timed(py, env)
            cpu_r, _ = timed(rr, env)
            if r:
                res["py_cpu"].append(cpu_p)
                res["r_cpu"].append(cpu_r)
        med = {key: statistics.median(v) for key, v in res.items()}
        med["cpu_ratio"] = med["py_cpu"] / med["r_cpu"]
        rows["box-behnken k=4"] = med
        print(f"box-behnken k=4: CPU python {med['py_cpu']:.2f} s, R bbd() {med['r_cpu']:.2f} s, "
              f"ratio {med['cpu_ratio']:.2f}", flush=True)
    if a.json:
        Path(a.json).write_text(json.dumps(rows, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
