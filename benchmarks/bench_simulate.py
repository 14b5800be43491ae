"""Virtual runs per second of ``rsm_lrg.simulate`` (the physics surrogate).

    python benchmarks/bench_simulate.py [--rows 1 27 1000 100000] [--single 40] [--workers 2]
                                        [--noise-sd 0.03] [--compare 2000] [--network 2000] [--json PATH]

Workload: every row a different setting, drawn uniformly from the paper's Table 3 box
(thickness 0.1-0.5 mm, stroke 0.04-0.06 m, velocity 0.4-0.6 m/s, acceleration 20-40 m/s^2),
RFCMS, calibrated surrogate, reading noise on. For each size: wall time and runs per second
(the first call, which builds the thermal network, is warmed up beforehand).

Also:
- ``row-at-a-time``: ``--single`` rows, each through its own ``simulate`` call (what one
  Python call per row would cost), against the batched cost per run at the largest size:
  the speed-up factor (issue 4 asks >= 100x);
- scaling: cost of the largest size over the cost of 1,000 rows (issue 4: close to 100x for
  100,000 vs 1,000);
- ``--workers N``: the largest size again on a ``ProcessPoolExecutor`` of N processes.

- ``old vs new``: ``--compare`` rows (default 2,000; :func:`compare_rows`: the box, 1/4 RMS,
  1/2 S-curve strokes) through ``simulate`` with the integrator of before issue 24
  (``integrator="compiled"``: DOP853's tableau in equal steps, ω·Δt = 0.6, cycles until two
  agree to 1e-5, at most 12), the same criterion with the error-controlled steps
  (``"adaptive"``), and the default now (adaptive, cycles to 1e-8, at most 40), alternated in
  this one process: rows per CPU-second of the whole ``simulate`` and of the dynamics alone
  (``time.process_time``, one BLAS thread), and the relative difference of every column
  simulate writes, between the integrators and against the converged reference
  (:data:`CONVERGED`: the periodic state to 1e-10; issue 24 asks >= 8,900 rows per CPU-second,
  the pre-membrane surrogate, and 1e-6).
- ``two-carriage network``: ``--network`` rows (default 2,000, :func:`network_compare`) through
  ``simulate`` with the default calibration (both carriages on one rail), the network solved per row
  by its own object (``runs.NETWORK_ROUTE = "dense"``, before issue 34's item 5) and all rows in one
  compiled loop (the default), alternated in this one process: rows per CPU-second, the network's
  CPU time per row alone, and the largest relative difference of the columns.

Figures go in the report, not in tests (wall-clock times depend on the machine).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # before numpy: one BLAS thread, CPU-seconds comparable

import numpy as np
import pandas as pd

from rsm_lrg.surrogate import simulate


def box(n, seed=0):
    rng = np.random.default_rng(seed)
    return pd.DataFrame({"thickness_m": rng.uniform(1e-4, 5e-4, n), "stroke_m": rng.uniform(0.04, 0.06, n),
                         "velocity_m_s": rng.uniform(0.4, 0.6, n), "acceleration_m_s2": rng.uniform(20, 40, n)})


def timed(fn, repeat=1):
    best = np.inf
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t)
    return best


#: The converged reference of ``--compare``: the reference integrator at a 3x finer step, run until
#: two successive cycles agree to 1e-10 (at most 40 cycles): the periodic state itself, which the
#: criterion of before issue 24 (1e-5, at most 12 cycles) reaches only to about 3e-3 on some rows.
CONVERGED = {"integrator": "compiled", "h_rk": 0.2, "rtol": 1e-10, "max_cycles": 40}


def compare_rows(n, seed=11):
    """n rows of the box for ``--compare``: every fourth row the rigid stage (RMS), every other
    row S-curve strokes (jerk time 2-20 ms), the rest trapezoids."""
    d = box(n, seed=seed)
    rng = np.random.default_rng(seed + 1)
    d["stage"] = np.where(np.arange(n) % 4 == 3, "rms", "rfcms")
    d["jerk_time_s"] = np.where(np.arange(n) % 2 == 1, rng.uniform(0.002, 0.02, n), 0.0)
    return d


def compare(n, noise_sd, repeat=2):
    """Rows per CPU-second of simulate() with the integrator of before issue 24 (equal steps,
    cycles to 1e-5, at most 12), the error-controlled one at that criterion, and the default now
    (error-controlled, cycles to 1e-8, at most 40; :func:`rsm_lrg.physics.dynamics.cycle_metrics`)
    on the same n rows (:func:`compare_rows`), alternated in this one process (best of ``repeat``
    each), and the largest relative difference of every numeric column simulate writes between
    them and against the converged reference (:data:`CONVERGED`, timed once)."""
    import functools

    from rsm_lrg.physics import dynamics
    from rsm_lrg.surrogate.design_input import EXTRA_OUTPUT_COLUMNS, OUTPUT_COLUMNS

    d = compare_rows(n)
    original = dynamics.cycle_metrics
    old_rule = {"rtol": 1e-5, "max_cycles": 12}
    names = {"old: compiled, 1e-5": {"integrator": "compiled", **old_rule},
             "adaptive, 1e-5": {"integrator": "adaptive", **old_rule},
             "new default": {},
             "converged reference": CONVERGED}
    cpu = {k: np.inf for k in names}
    dyn = {k: np.inf for k in names}
    frames = {}
    spent = [0.0]

    def timed_dynamics(*args, **kw):
        t0 = time.process_time()
        try:
            return original(*args, **kw)
        finally:
            spent[0] += time.process_time() - t0

    try:
        for rep in range(repeat):
            for name, kw in names.items():
                if rep and name == "converged reference":
                    continue
                dynamics.cycle_metrics = functools.partial(timed_dynamics, **kw)
                spent[0] = 0.0
                t = time.process_time()
                frames[name] = simulate(d, seed=1, noise_sd=noise_sd, progress=False)
                cpu[name] = min(cpu[name], time.process_time() - t)
                dyn[name] = min(dyn[name], spent[0])
    finally:
        dynamics.cycle_metrics = original
    print(f"integrators side by side, {n} random rows of the Table 3 box through simulate (1/4 RMS, 1/2 S-curve; "
          f"one BLAS thread, CPU time, best of {repeat}; the converged reference once); 'dynamics' is the CPU time "
          f"inside cycle_metrics alone:")
    print(f"{'integrator':>20} {'CPU s':>8} {'rows/CPU-s':>11} {'dynamics s':>11} {'rows/CPU-s':>11}")
    res = {}
    for name in names:
        res[name] = {"rows": n, "cpu_seconds": cpu[name], "rows_per_cpu_s": n / cpu[name],
                     "dynamics_cpu_seconds": dyn[name], "dynamics_rows_per_cpu_s": n / dyn[name]}
        print(f"{name:>20} {cpu[name]:>8.3f} {n / cpu[name]:>11.0f} {dyn[name]:>11.3f} {n / dyn[name]:>11.0f}")
    speedup = cpu["old: compiled, 1e-5"] / cpu["new default"]
    print(f"new default over old: {speedup:.2f}x (simulate), "
          f"{dyn['old: compiled, 1e-5'] / dyn['new default']:.2f}x (dynamics); adaptive over compiled at the "
          f"same criterion: {cpu['old: compiled, 1e-5'] / cpu['adaptive, 1e-5']:.2f}x (simulate), "
          f"{dyn['old: compiled, 1e-5'] / dyn['adaptive, 1e-5']:.2f}x (dynamics)")
    diffs = {}
    for pair in (("old: compiled, 1e-5", "adaptive, 1e-5"), ("converged reference", "old: compiled, 1e-5"),
                 ("converged reference", "adaptive, 1e-5"), ("converged reference", "new default")):
        label = f"{pair[1]} vs {pair[0]}"
        print(label + ":")
        old, new = frames[pair[0]], frames[pair[1]]
        diffs[label] = {}
        for col in OUTPUT_COLUMNS + EXTRA_OUTPUT_COLUMNS:
            a, b = old[col].to_numpy(), new[col].to_numpy()
            if a.dtype == bool:
                diffs[label][col] = {"rows_differing": int(np.sum(a != b))}
                print(f"  {col}: {diffs[label][col]['rows_differing']} rows differ")
                continue
            with np.errstate(divide="ignore", invalid="ignore"):
                r = np.where(a == b, 0.0, np.abs(b / a - 1.0))
            q = {"median": float(np.median(r)), "p99": float(np.percentile(r, 99)), "max": float(np.max(r)),
                 "rows_over_1e-6": int(np.sum(r > 1e-6))}
            diffs[label][col] = q
            print(f"  {col}: relative difference median {q['median']:.1e}, 99th percentile {q['p99']:.1e}, "
                  f"max {q['max']:.1e}; {q['rows_over_1e-6']} rows over 1e-6")
    return res | {"speedup": speedup, "relative_differences": diffs}


def network_compare(n, noise_sd, repeat=2):
    """Rows per CPU-second of simulate() with the default calibration (model v6-alone: both carriages on
    one rail) on n rows (:func:`compare_rows`), the two-carriage network solved by each route of
    ``rsm_lrg.surrogate.runs.NETWORK_ROUTE`` -- ``"dense"`` (each row its own network object, before issue
    34's item 5) and ``"compiled"`` (the default: every row in one compiled loop) -- alternated in this one
    process, the caches cleared before every run (best of ``repeat`` each); the CPU time of the network
    alone per row on the same settings (each route called directly); and the largest relative difference
    of every numeric column simulate writes between the two routes."""
    from rsm_lrg.physics import motion
    from rsm_lrg.physics.params import LRGParams
    from rsm_lrg.physics.thermal import two_carriage as tc
    from rsm_lrg.surrogate import runs
    from rsm_lrg.surrogate.design_input import EXTRA_OUTPUT_COLUMNS, OUTPUT_COLUMNS

    d = compare_rows(n)
    cpu = {"dense": np.inf, "compiled": np.inf}
    frames = {}
    try:
        for _ in range(repeat):
            for route in cpu:
                runs.NETWORK_ROUTE = route
                runs.clear_row_caches()
                t = time.process_time()
                frames[route] = simulate(d, seed=1, noise_sd=noise_sd, progress=False)
                cpu[route] = min(cpu[route], time.process_time() - t)
    finally:
        runs.NETWORK_ROUTE = "compiled"
        runs.clear_row_caches()
    # the network alone, on the rows' own settings (the default calibration's parameters)
    from rsm_lrg.surrogate.calibrate import resolve_calibration

    v = LRGParams().with_overrides(**{k: x for k, x in resolve_calibration("default").parameter_values().items()
                                      if k in LRGParams().to_dict()}).to_dict()
    y = d["thickness_m"].to_numpy()
    s = d["stroke_m"].to_numpy()
    msq = np.asarray(motion.mean_square_speed(s, d["velocity_m_s"].to_numpy(), d["acceleration_m_s2"].to_numpy(),
                                              0.0, d["jerk_time_s"].to_numpy()), float)
    rms = (d["stage"] == "rms").to_numpy()
    times = np.tile([49 * 60.0, 50 * 60.0], (n, 1))
    m = min(n, 300)
    tc.clear_network_cache()
    t = time.process_time()
    for i in range(m):
        run = tc.CarriageSetting(float(y[i]), float(s[i]), float(msq[i]))
        net = tc.cached_network(v, run, run)
        node = "rms.carriage" if rms[i] else "rfcms.carriage"
        for src in tc.STAGES:
            net.response(times[i], node, src)
            net.steady_rise(src)
    dense_row = (time.process_time() - t) / m
    tc.two_carriage_rows(v, y[:2], s[:2], msq[:2], rms[:2], times[:2])  # the template, once per rig
    t = time.process_time()
    tc.two_carriage_rows(v, y, s, msq, rms, times)
    compiled_row = (time.process_time() - t) / n
    print(f"two-carriage network (default calibration, model v6-alone), {n} random rows of the Table 3 box through "
          f"simulate, each route alternated in one process (CPU time, best of {repeat}, caches cleared):")
    print(f"{'route':>20} {'CPU s':>8} {'rows/CPU-s':>11} {'network ms/row':>15}")
    res = {}
    for route, per in (("dense", dense_row), ("compiled", compiled_row)):
        res[route] = {"rows": n, "cpu_seconds": cpu[route], "rows_per_cpu_s": n / cpu[route],
                      "network_ms_per_row": 1e3 * per}
        print(f"{route:>20} {cpu[route]:>8.3f} {n / cpu[route]:>11.0f} {1e3 * per:>15.3f}")
    worst = {}
    for col in OUTPUT_COLUMNS + EXTRA_OUTPUT_COLUMNS:
        a, b = frames["dense"][col].to_numpy(), frames["compiled"][col].to_numpy()
        if a.dtype == bool:
            worst[col] = float(np.sum(a != b))
            continue
        with np.errstate(divide="ignore", invalid="ignore"):
            worst[col] = float(np.max(np.where(a == b, 0.0, np.abs(b / a - 1.0))))
    print(f"compiled over dense: {cpu['dense'] / cpu['compiled']:.2f}x (simulate), "
          f"{dense_row / compiled_row:.1f}x (network alone); largest relative difference of any column: "
          f"{max(worst.values()):.1e}")
    return res | {"speedup": cpu["dense"] / cpu["compiled"], "max_relative_difference": worst}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rows", type=int, nargs="*", default=[1, 27, 1000, 100_000])
    ap.add_argument("--single", type=int, default=40, help="rows run one simulate() call each")
    ap.add_argument("--workers", type=int, default=0, help="also run the largest size on N processes")
    ap.add_argument("--noise-sd", type=float, default=0.03)
    ap.add_argument("--json", default=None)
    ap.add_argument("--compare", type=int, default=2000, help="rows for the old-vs-new integrator comparison (0: skip)")
    ap.add_argument("--network", type=int, default=2000,
                    help="rows for the two-carriage network's dense-vs-compiled comparison (0: skip)")
    a = ap.parse_args(argv)

    simulate(box(3), seed=0, noise_sd=a.noise_sd)  # warm-up: imports, thermal network, compiled stepper
    out = {"machine": {"cpus": os.cpu_count(), "python": platform.python_version(),
                       "processor": platform.processor() or platform.machine()}, "sizes": []}
    if a.network > 0:
        out["network_dense_vs_compiled"] = network_compare(a.network, a.noise_sd)
    if a.compare > 0:
        out["old_vs_new"] = compare(a.compare, a.noise_sd)
    print(f"{'rows':>8} {'seconds':>10} {'runs/s':>12} {'ms/run':>10}")
    for n in a.rows:
        d = box(n, seed=n)
        sec = timed(lambda d=d: simulate(d, seed=1, noise_sd=a.noise_sd, progress=False), repeat=3 if n <= 1000 else 1)
        out["sizes"].append({"rows": n, "seconds": sec, "runs_per_s": n / sec})
        print(f"{n:>8} {sec:>10.3f} {n / sec:>12.1f} {1e3 * sec / n:>10.4f}")

    if a.single > 0 and out["sizes"]:
        d = box(a.single, seed=7)
        t = time.perf_counter()
        for i in range(a.single):
            simulate(d.iloc[[i]], seed=1, noise_sd=a.noise_sd, progress=False)
        single = (time.perf_counter() - t) / a.single
        big = out["sizes"][-1]
        batched = big["seconds"] / big["rows"]
        out["row_at_a_time"] = {"rows": a.single, "seconds_per_run": single,
                                "batched_seconds_per_run": batched, "speedup": single / batched}
        print(f"row at a time: {1e3 * single:.2f} ms/run; batched ({big['rows']} rows): "
              f"{1e3 * batched:.4f} ms/run; speed-up {single / batched:.0f}x")
    sizes = {s["rows"]: s["seconds"] for s in out["sizes"]}
    if 1000 in sizes and max(sizes) > 1000:
        n = max(sizes)
        ratio = sizes[n] / sizes[1000]
        out["scaling"] = {"rows": n, "over_1000": ratio, "ideal": n / 1000}
        print(f"scaling: {n} rows cost {ratio:.1f}x of 1,000 rows (ideal {n / 1000:.0f}x)")
    if a.workers > 1 and a.rows:
        from concurrent.futures import ProcessPoolExecutor

        n = max(a.rows)
        d = box(n, seed=n)
        with ProcessPoolExecutor(a.workers) as ex:
            simulate(box(3), executor=ex)  # start the workers
            sec = timed(lambda d=d: simulate(d, seed=1, noise_sd=a.noise_sd, executor=ex, progress=False))
        out["workers"] = {"workers": a.workers, "rows": n, "seconds": sec, "runs_per_s": n / sec}
        print(f"{a.workers} processes, {n} rows: {sec:.2f} s, {n / sec:.0f} runs/s")
    if a.json:
        with open(a.json, "w") as fh:
            json.dump(out, fh, indent=2)


if __name__ == "__main__":
    main()
