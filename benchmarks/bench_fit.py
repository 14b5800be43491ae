"""Cost of rsm_lrg.fit relative to one least-squares solve (not part of the test suite).

For n runs and k factors (full quadratic: 15 terms for k = 4, 66 for k = 10) it times
``numpy.linalg.lstsq`` on the coded design matrix (the baseline: one solve) and the whole
``rsm_lrg.fit`` (matrix build, statsmodels OLS, hat diagonal, Type III ANOVA from
(X'X)^-1, pure error, PRESS, VIF, canonical analysis), and prints the ratio.

    python benchmarks/bench_fit.py            # n = 27, 1e4, 1e5, 1e6; k = 4 and 10
    python benchmarks/bench_fit.py --max-n 100000
"""

from __future__ import annotations

import argparse
import time

import numpy as np
import pandas as pd


def make(n: int, k: int, seed: int = 0) -> pd.DataFrame:
    rng = np.random.default_rng(seed)
    x = rng.integers(-1, 2, size=(n, k)).astype(float)
    x[: max(n // 10, 1)] = rng.uniform(-1, 1, (max(n // 10, 1), k))
    df = pd.DataFrame(x, columns=[f"x{i}" for i in range(k)])
    df["y"] = 1 + x.sum(axis=1) + 0.5 * (x ** 2).sum(axis=1) + rng.normal(size=n)
    return df


def bench(n: int, k: int) -> dict:
    import rsm_lrg
    from rsm_lrg.model.terms import design_matrix, model_terms

    df = make(n, k)
    specs = [f"x{i}=-1:1" for i in range(k)]
    terms = model_terms([chr(65 + i) for i in range(k)], "quadratic")
    X = design_matrix(df[[f"x{i}" for i in range(k)]].to_numpy(), terms)
    y = df["y"].to_numpy()
    t0 = time.perf_counter()
    np.linalg.lstsq(X, y, rcond=None)
    t_solve = time.perf_counter() - t0
    t0 = time.perf_counter()
    r = rsm_lrg.fit(df, "y", factors=specs)
    t_fit = time.perf_counter() - t0
    return {"n": n, "k": k, "terms": len(terms), "lstsq_s": t_solve, "fit_s": t_fit,
            "ratio": t_fit / t_solve, "r2": r.statistics.r2}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max-n", type=float, default=1e6)
    args = ap.parse_args()
    import rsm_lrg

    rsm_lrg.fit(make(40, 2), "y")  # warm-up: imports statsmodels
    print(f"{'n':>8} {'k':>3} {'terms':>5} {'lstsq [s]':>10} {'fit [s]':>9} {'ratio':>6}")
    for n in (27, 10_000, 100_000, 1_000_000):
        if n > args.max_n:
            continue
        for k in (4, 10):
            if n < 1 + 2 * k + k * (k - 1) // 2 + 2:
                continue
            b = bench(n, k)
            print(f"{b['n']:>8} {b['k']:>3} {b['terms']:>5} {b['lstsq_s']:>10.4f} {b['fit_s']:>9.4f} {b['ratio']:>6.1f}")


if __name__ == "__main__":
    main()
