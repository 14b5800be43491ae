"""Cost of the double-double actual-units solve relative to the coded least-squares core (not a test).

For n runs of a full quadratic in k factors (actual values around 1e3 +- 1, a continuous
response) it times, in one process and alternating:

* the anchor: :func:`rsm_lrg.model.engines.least_squares.least_squares` of the coded model matrix
  (both passes, in chunks of 32768 rows; the matrix built beforehand, not timed);
* :func:`rsm_lrg.model.readings.actual_units.solve_actual` on the actual values (its own two passes,
  building the double-double model matrix chunk by chunk), with and without
  ``decimal_inputs``.

It prints the median ratio of each to the anchor.

    python benchmarks/bench_actual_units.py                 # n = 1e5, k = 4 and 10
    python benchmarks/bench_actual_units.py --n 1e6 --k 10 --repeat 3
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

from rsm_lrg.model.engines.least_squares import least_squares
from rsm_lrg.model.readings.actual_units import solve_actual
from rsm_lrg.terms import design_matrix, model_terms


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=float, default=1e5)
    ap.add_argument("--k", type=int, nargs="+", default=[4, 10])
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    n = int(a.n)
    rng = np.random.default_rng(0)
    for k in a.k:
        letters = "ABCDEFGHIJ"[:k]
        terms = model_terms(letters, "quadratic")
        coded = rng.uniform(-1, 1, (n, k))
        x = 1e3 + coded
        y = 1.0 + coded.sum(axis=1) + (coded ** 2).sum(axis=1) + rng.normal(0, 0.1, n)
        X = design_matrix(coded, terms)
        ratios: dict[str, list[float]] = {"decimal": [], "doubles": []}
        for _ in range(a.repeat):
            t0 = time.perf_counter()
            least_squares(X, y)
            base = time.perf_counter() - t0
            for label, dec in (("decimal", True), ("doubles", False)):
                t0 = time.perf_counter()
                solve_actual(x, y, terms, intercept=True, decimal_inputs=dec)
                ratios[label].append((time.perf_counter() - t0) / base)
        print(f"n={n} k={k} p={len(terms)}: solve_actual / least_squares = "
              f"{statistics.median(ratios['doubles']):.1f} (doubles as given), "
              f"{statistics.median(ratios['decimal']):.1f} (decimal inputs)")


if __name__ == "__main__":
    main()
