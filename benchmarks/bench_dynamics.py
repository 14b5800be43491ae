"""Cost of the per-cycle stage dynamics for virtual runs (``rsm_lrg.physics.dynamics``).

    python benchmarks/bench_dynamics.py [--rows 1000 10000] [--full] [--convergence 2000]

Three workloads over the paper's Table 3 box (thickness 0.1-0.5 mm, stroke 0.04-0.06 m,
velocity 0.4-0.6 m/s, acceleration 20-40 m/s^2):

- ``distinct``: every row different (uniform random) -> every RFCMS row is integrated;
- ``bbd``: the 27 Box-Behnken settings repeated to n rows (rows are de-duplicated first);
- ``quasi_static``: the analytic path on the same distinct rows.

Prints seconds and rows per second. ``--full`` adds 100 000 distinct rows.

``--convergence N``: how far the integrators' cycle criterion leaves a row from its periodic
state. N random rows of the box (every other one with S-curve strokes, jerk time 2-20 ms; the
shipped calibration's viscous friction), every row integrated, through ``cycle_metrics`` with
each integrator and cycle criterion ``rtol`` (successive cycles' sliding, at most
``max_cycles``): CPU seconds (``time.process_time``, best of two), mean cycles taken, and the
largest relative difference in sliding, viscous work and peak deflection from the converged
reference (the equal steps at ω·Δt = 0.2, cycles within 1e-10, at most 40) on the rows that
reference settles, with the number of rows beyond 1e-6.
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


def convergence(n):
    """The table of ``--convergence`` (module docstring)."""
    from rsm_lrg.physics.params import LRGParams
    from rsm_lrg.surrogate.calibrate import resolve_calibration

    cal = resolve_calibration("default")
    cv = 0.0 if cal is None else float({**cal.fixed_values(), **cal.parameter_values()}.get(
        "viscous_friction_n_s_m", 0.0))
    rng = np.random.default_rng(11)
    y, s, v, a = box(n, rng)
    tj = np.where(np.arange(n) % 2 == 1, rng.uniform(0.002, 0.02, n), 0.0)
    kw = dict(params=LRGParams(viscous_friction_n_s_m=cv), method="integrate", hinge_thickness_m=y, jerk_time_s=tj)

    def run(**more):
        best, m = np.inf, None
        for _ in range(2 if more.get("h_rk", 0.6) >= 0.6 else 1):
            t = time.process_time()
            m = cycle_metrics(s, v, a, **kw, **more)
            best = min(best, time.process_time() - t)
        return m, best

    ref, _ = run(integrator="compiled", h_rk=0.2, rtol=1e-10, max_cycles=40)
    ok = ref.periodicity_error_m <= 1e-10 * ref.sliding_distance_m
    print(f"convergence to the periodic state, {n} rows of the box (half S-curve), c_v = {cv:.3f} N s/m; "
          f"{int(ok.sum())} rows settle to 1e-10 within 40 cycles:")
    cols = (("sliding", "sliding_distance_m"), ("viscous work", "viscous_work_j"), ("peak", "peak_deflection_m"))
    for integ, rtol, mc in (("compiled", 1e-5, 12), ("adaptive", 1e-5, 12), ("adaptive", 1e-6, 12),
                            ("adaptive", 1e-7, 12), ("adaptive", 1e-8, 12), ("adaptive", 1e-8, 40),
                            ("compiled", 1e-8, 40)):
        m, sec = run(integrator=integ, rtol=rtol, max_cycles=mc)
        cyc = _cycles(integ, rtol, mc, s, v, a, kw)
        txt = []
        for label, f in cols:
            r = np.abs(getattr(m, f)[ok] / getattr(ref, f)[ok] - 1.0)
            txt.append(f"{label} {r.max():.1e} ({int(np.sum(r > 1e-6))} rows > 1e-6)")
        print(f"  {integ:>8} rtol {rtol:.0e}, <= {mc:2d} cycles: {sec:6.3f} CPU-s, {n / sec:6.0f} rows/CPU-s, "
              f"{cyc:5.2f} cycles; max relative difference: " + ", ".join(txt))


def _cycles(integ, rtol, mc, s, v, a, kw):
    # mean cycles a row takes (the compiled stepper reports them; cycle_metrics does not)
    from rsm_lrg.physics import dynamics, stepper

    seen = {}
    original = stepper.integrate_rows

    def spy(*args, **kwargs):
        info = {}
        res = original(*args, **kwargs, info=info)
        seen["c"] = float(np.mean(info["cycles"]))
        return res

    dynamics.integrate_rows = spy
    try:
        cycle_metrics(s, v, a, **kw, integrator=integ, rtol=rtol, max_cycles=mc)
    finally:
        dynamics.integrate_rows = original
    return seen["c"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rows", type=int, nargs="*", default=[1000, 10000])
    ap.add_argument("--full", action="store_true")
    ap.add_argument("--convergence", type=int, default=0, help="rows for the convergence table (0: skip)")
    args = ap.parse_args()
    if args.convergence > 0:
        convergence(args.convergence)
    rows = list(args.rows) + ([100_000] if args.full else [])
    rng = np.random.default_rng(1)
    for n in rows:
        cols = box(n, rng)
        bench("distinct", cols, method="integrate")
        bench("quasi_static", cols, method="quasi_static")
        bench("bbd", bbd(n), method="integrate")


if __name__ == "__main__":
    main()
