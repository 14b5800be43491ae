"""Cost of the per-cycle stage dynamics for virtual runs (``rsm_lrg.physics.dynamics``).

    python benchmarks/bench_dynamics.py [--rows 1000 10000] [--full]

Three workloads over the paper's Table 3 box (thickness 0.1-0.5 mm, stroke 0.04-0.06 m,
velocity 0.4-0.6 m/s, acceleration 20-40 m/s^2):

- ``distinct``: every row different (uniform random) -> every RFCMS row is integrated;
- ``bbd``: the 27 Box-Behnken settings repeated to n rows (rows are de-duplicated first);
- ``quasi_static``: the analytic path on the same distinct rows.

Prints seconds and rows per second. ``--full`` adds 100 000 distinct rows.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from rsm_lrg.physics.dynamics import cycle_metrics


def box(n, rng):
    return (rng.uniform(1e-4, 5e-4, n), rng.uniform(0.04, 0.06, n), rng.uniform(0.4, 0.6, n),
            rng.uniform(20.0, 40.0, n))


def bbd(n):
    from rsm_lrg.datasets import load_table4

    t = load_table4()
    idx = np.arange(n) % len(t)
    return (t.thickness_m.to_numpy()[idx], t.stroke_m.to_numpy()[idx], t.velocity_m_s.to_numpy()[idx],
            t.acceleration_m_s2.to_numpy()[idx])


def bench(label, cols, **kw):
    y, s, v, a = cols
    t0 = time.perf_counter()
    m = cycle_metrics(s, v, a, hinge_thickness_m=y, **kw)
    dt = time.perf_counter() - t0
    n = len(y)
    print(f"{label:<14} rows={n:>7}  {dt:8.2f} s  {n / dt:10.0f} rows/s  "
          f"max periodicity error {np.max(m.periodicity_error_m):.2e} m")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rows", type=int, nargs="*", default=[1000, 10000])
    ap.add_argument("--full", action="store_true")
    args = ap.parse_args()
    rows = list(args.rows) + ([100_000] if args.full else [])
    rng = np.random.default_rng(1)
    for n in rows:
        cols = box(n, rng)
        bench("distinct", cols, method="integrate")
        bench("quasi_static", cols, method="quasi_static")
        bench("bbd", bbd(n), method="integrate")


if __name__ == "__main__":
    main()
