"""Benchmark the simulator (:mod:`rsm_lrg.optimize.simulator`): runs per second at the paper's
fit (Table 4, quadratic in four factors), with and without factor noise and model uncertainty,
and the interval optimiser (:mod:`rsm_lrg.optimize.robust`) on the CI, TI and POE.

Usage::

    python benchmarks/bench_simulator.py                 # 1e5 and 1e6 runs
    python benchmarks/bench_simulator.py --draws 1e6 1e7 --json out.json
    python benchmarks/bench_simulator.py --draws --dask 1e8 --workers 2   # streamed, on a local Dask cluster

``--dask N`` times N runs (more than 10⁷: the statistics streamed, nothing kept) on a local Dask
cluster of ``--workers`` single-threaded worker processes, with model uncertainty and no factor
noise (the ``predict --draws N --scheduler`` path), and checks that its numbers equal those of
``--check-against`` workers (default: none).

Times are wall-clock on this machine (shared cores: expect noise of tens of per cent); nothing
here is asserted.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import pandas as pd

import rsm_lrg
from rsm_lrg.optimize.robust import optimize_robust, parse_robust_goal
from rsm_lrg.optimize.simulator import simulate

Y = "tcr_c_per_min"
SETTING = {"thickness_m": 0.0003, "stroke_m": 0.05, "velocity_m_s": 0.5, "acceleration_m_s2": 25.0}
SDS = {"velocity_m_s": 0.02, "acceleration_m_s2": 1.0}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--draws", type=float, nargs="*", default=[1e5, 1e6])
    ap.add_argument("--dask", type=float, nargs="*", default=[], metavar="N")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--check-against", type=int, default=None, metavar="K",
                    help="also run --dask N on K workers and check the numbers are the same")
    ap.add_argument("--json", default=None)
    a = ap.parse_args()
    fit = rsm_lrg.fit(pd.read_csv(Path(__file__).parents[1] / "data" / "table4.csv"), Y)
    rows = []
    for n in (int(v) for v in a.dask):
        results = {}
        for k in [a.workers] + ([a.check_against] if a.check_against else []):
            from distributed import Client, LocalCluster

            with LocalCluster(processes=True, n_workers=k, threads_per_worker=1, host="127.0.0.1",
                              dashboard_address=None) as cluster, Client(cluster) as client:
                t0 = time.perf_counter()
                r = simulate(fit, SETTING, draws=n, seed=1, spec={Y: (None, 0.035)}, executor=client.get_executor(),
                             progress=False)
                dt = time.perf_counter() - t0
            results[k] = r.to_dict()
            rows.append({"what": "simulate streamed on dask", "draws": n, "workers": k, "seconds": dt,
                         "runs_per_s": n / dt, "quantiles": r.responses[Y]["quantiles"]})
            print(f"simulate N={n:,} streamed on {k} Dask workers: {dt:7.1f} s ({n / dt:,.0f} runs/s); "
                  f"quantiles {r.responses[Y]['quantiles']}")
        if len(results) > 1:
            same = len({json.dumps(v, sort_keys=True) for v in results.values()}) == 1
            print(f"same numbers on {' and '.join(map(str, results))} workers: {same}")
            rows.append({"what": "same numbers", "draws": n, "same": same})
    if not a.draws:
        if a.json:
            Path(a.json).write_text(json.dumps(rows, indent=2) + "\n")
        return
    for n in (int(v) for v in a.draws):
        for noise, model in ((False, False), (True, False), (False, True), (True, True)):
            t0 = time.perf_counter()
            simulate(fit, SETTING, draws=n, seed=1, factor_sd=SDS if noise else None, spec={Y: (None, 0.035)},
                     model_uncertainty=model)
            dt = time.perf_counter() - t0
            rows.append({"what": "simulate", "draws": n, "factor_noise": noise, "model_uncertainty": model,
                         "seconds": dt, "runs_per_s": n / dt})
            print(f"simulate N={n:>9d} factor noise={noise!s:5} model uncertainty={model!s:5}: {dt:7.3f} s "
                  f"({n / dt:,.0f} runs/s)")
    g, _ = parse_robust_goal(Y, "minimize")
    for iv in ("ci", "ti"):
        t0 = time.perf_counter()
        optimize_robust({Y: fit}, [g], intervals={Y: iv})
        dt = time.perf_counter() - t0
        rows.append({"what": f"optimize --interval {iv}", "seconds": dt})
        print(f"optimize --interval {iv}: {dt:.2f} s")
    t0 = time.perf_counter()
    optimize_robust({Y: fit}, [g], poe=[Y], factor_sd=SDS)
    dt = time.perf_counter() - t0
    rows.append({"what": "optimize --goal poe", "seconds": dt})
    print(f"optimize --goal poe: {dt:.2f} s")
    if a.json:
        Path(a.json).write_text(json.dumps(rows, indent=2) + "\n")


if __name__ == "__main__":
    main()
