"""Benchmark the 3-D finite-volume thermal model against mesh size: direct vs AMG paths.

For each cell size (quarter guide, paper inputs Q = 0.4150 W, h = 8.82 / 22.45 W/(m^2 K)):

* assembly of K, C, b;
* steady state ``K theta = b Q``: sparse direct (SuperLU factorisation + solve) and
  AMG-preconditioned CG (hierarchy set-up and solve reported separately; rtol 1e-10);
* a 5-hour backward-Euler transient, 300 steps of 60 s, by both paths: the direct path
  factorises ``C/dt + K`` ONCE and back-substitutes every step; the AMG path builds the
  hierarchy of ``C/dt + K`` ONCE and runs warm-started PCG every step. The one-off set-up
  and the per-step cost are reported separately, and both paths are compared (max
  |difference| of the final field / max rise).

Prints a table and the fitted growth exponents (log-log least-squares slope, time ~ cells^p)
over the grids with at least ``--fit-min`` cells (small grids are dominated by fixed Python
overhead). Usage::

    python benchmarks/bench_thermal.py                       # ~1e3 .. ~1e6 cells
    python benchmarks/bench_thermal.py --sizes 0.004 0.002 --steps 30 --json out.json

The direct path is skipped above ``--direct-max-cells`` (its LU fill grows ~cells^2 in time
and memory). ``--cg`` adds the Jacobi-PCG steady solve. Times are wall-clock on this machine
(shared cores: expect noise of tens of per cent); nothing here is asserted.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import time

import numpy as np

from rsm_lrg.physics.thermal import FVSystem, GuideGeometry, voxelise
from rsm_lrg.physics.thermal.fv import AUTO_AMG_CELLS

Q, HS, HF = 0.4150, 8.82, 22.45
DEFAULT_SIZES = [0.004, 0.002, 0.0013, 0.001, 0.0007, 0.0005, 0.00035, 0.00025]


def run(cell, *, symmetric=True, steps=300, direct_max_cells=130_000, cg=False, rtol=1e-10):
    t0 = time.perf_counter()
    fv = FVSystem(voxelise(GuideGeometry(), HS, HF, cell_size_m=cell, symmetric=symmetric))
    row = {"cell_size_m": cell, "n_cells": fv.n, "nnz": int(fv.K.nnz),
           "assemble_s": time.perf_counter() - t0}
    direct = fv.n <= direct_max_cells

    sa = fv.steady(Q, method="amg", rtol=rtol)
    row.update(steady_amg_setup_s=sa.info["setup_s"], steady_amg_solve_s=sa.info["solve_s"],
               steady_amg_s=sa.info["setup_s"] + sa.info["solve_s"],
               steady_amg_iterations=sa.info["iterations"], amg_levels=sa.info["levels"],
               amg_operator_complexity=sa.info["operator_complexity"],
               rise_k=sa.mean_probe_rise_k, energy_balance_amg=sa.energy_balance_error)
    if direct:
        t0 = time.perf_counter()
        sd = fv.steady(Q, method="direct")
        row.update(steady_direct_s=time.perf_counter() - t0,
                   steady_diff_rel=float(np.abs(sd.theta_k - sa.theta_k).max() / sd.max_rise_k))
        fv._lu = None  # free the steady factors before the transient one
    if cg:
        t0 = time.perf_counter()
        sc = fv.steady(Q, method="cg", rtol=1e-8)
        row.update(steady_cg_s=time.perf_counter() - t0, cg_iterations=sc.info["iterations"])
    fv._amg = None

    if steps:
        ta = fv.transient(Q, duration_s=steps * 60.0, dt_s=60.0, solver="amg", rtol=rtol)
        row.update(tr_amg_setup_s=ta.info["setup_s"], tr_amg_step_s=ta.info["step_s"],
                   tr_amg_total_s=ta.info["setup_s"] + steps * ta.info["step_s"],
                   tr_amg_iter_per_step=ta.info["iterations_total"] / steps,
                   tr_amg_hierarchies=ta.info["hierarchies"])
        if direct:
            td = fv.transient(Q, duration_s=steps * 60.0, dt_s=60.0, solver="direct")
            row.update(tr_direct_factor_s=td.info["factorise_s"], tr_direct_step_s=td.info["step_s"],
                       tr_direct_total_s=td.info["factorise_s"] + steps * td.info["step_s"],
                       tr_direct_factorisations=td.info["factorisations"],
                       tr_diff_rel=float(np.abs(td.theta_final_k - ta.theta_final_k).max()
                                         / td.theta_final_k.max()))
    return row


def _f(v, fmt):
    return format(v, fmt) if v is not None else "-".rjust(len(format(0.0, fmt)))


def growth_exponents(rows, keys, min_cells):
    """Least-squares slope of log(time) on log(cells) for every key with >= 3 usable grids."""
    out = {}
    for key in keys:
        pts = [(r["n_cells"], r[key]) for r in rows if key in r and r["n_cells"] >= min_cells and r[key] > 0]
        if len(pts) >= 3:
            n, t = np.log(np.array(pts)).T
            out[key] = (float(np.polyfit(n, t, 1)[0]), len(pts), int(min(p[0] for p in pts)),
                        int(max(p[0] for p in pts)))
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=float, nargs="+", default=DEFAULT_SIZES, help="cell sizes [m]")
    ap.add_argument("--full", action="store_true", help="whole guide, not the quarter")
    ap.add_argument("--steps", type=int, default=300, help="60 s steps of the transient (300 = 5 h)")
    ap.add_argument("--direct-max-cells", type=int, default=130_000)
    ap.add_argument("--fit-min", type=int, default=10_000, help="smallest grid in the exponent fit")
    ap.add_argument("--cg", action="store_true", help="also time the Jacobi-PCG steady solve")
    ap.add_argument("--json", help="write the rows and exponents as JSON")
    a = ap.parse_args(argv)
    print(f"# {platform.processor() or platform.machine()}, {os.cpu_count()} logical cores, "
          f"load {os.getloadavg()[0]:.1f}; transient {a.steps} x 60 s backward Euler; "
          f"AUTO_AMG_CELLS = {AUTO_AMG_CELLS}")
    hdr = (f"{'cell mm':>7} {'cells':>8} {'asm s':>6} | {'LU st s':>8} {'AMG set':>7} {'AMG sol':>7} {'it':>3} | "
           f"{'LU fac s':>8} {'LU ms/st':>8} {'LU 5h s':>8} | {'AMG set':>7} {'AMG ms/st':>9} {'it/st':>5} "
           f"{'AMG 5h s':>8} | {'diff/rise':>9} {'rise K':>7}")
    print(hdr)
    rows = []
    for c in a.sizes:
        r = run(c, symmetric=not a.full, steps=a.steps, direct_max_cells=a.direct_max_cells, cg=a.cg)
        rows.append(r)
        g = r.get

        def ms(k, r=r):
            return 1e3 * r[k] if k in r else None

        diff = max(g("steady_diff_rel", 0.0), g("tr_diff_rel", 0.0)) if "steady_diff_rel" in r else None
        print(f"{c * 1e3:7.2f} {r['n_cells']:8d} {r['assemble_s']:6.2f} | {_f(g('steady_direct_s'), '8.3f')} "
              f"{r['steady_amg_setup_s']:7.3f} {r['steady_amg_solve_s']:7.3f} {r['steady_amg_iterations']:3d} | "
              f"{_f(g('tr_direct_factor_s'), '8.3f')} {_f(ms('tr_direct_step_s'), '8.2f')} "
              f"{_f(g('tr_direct_total_s'), '8.2f')} | {_f(g('tr_amg_setup_s'), '7.3f')} "
              f"{_f(ms('tr_amg_step_s'), '9.2f')} {_f(g('tr_amg_iter_per_step'), '5.2f')} "
              f"{_f(g('tr_amg_total_s'), '8.2f')} | {_f(diff, '9.1e')} {r['rise_k']:7.4f}", flush=True)
    keys = ["assemble_s", "steady_direct_s", "steady_amg_setup_s", "steady_amg_solve_s", "steady_amg_s",
            "steady_cg_s", "tr_direct_factor_s", "tr_direct_step_s", "tr_direct_total_s",
            "tr_amg_setup_s", "tr_amg_step_s", "tr_amg_total_s"]
    exps = growth_exponents(rows, keys, a.fit_min)
    print(f"\ngrowth exponents p (time ~ cells^p, least squares on grids with >= {a.fit_min} cells):")
    for key, (p, k, lo, hi) in exps.items():
        print(f"  {key:22s} p = {p:5.2f}   ({k} grids, {lo}..{hi} cells)")
    if a.json:
        with open(a.json, "w") as fh:
            json.dump({"rows": rows, "exponents": {k: v[0] for k, v in exps.items()}}, fh, indent=1)


if __name__ == "__main__":
    main()
