"""Benchmark the 3-D finite-volume thermal model against mesh size.

For each cell size: assembly, steady solve (SuperLU, symmetric mode; and Jacobi-PCG), and a
5-hour backward-Euler transient at dt = 60 s (300 steps) that factorises C/dt + K ONCE and
then only back-substitutes.  Prints a table and the fitted growth exponents
(time ~ n_cells ** p).  Usage::

    python benchmarks/bench_thermal.py [--sizes 0.004 0.002 0.0013 0.001 0.0007] [--full] [--json out.json]

``--full`` solves the whole guide instead of the symmetric quarter (4x the cells).
Times are wall-clock on this machine; nothing here is asserted.
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

from rsm_lrg.physics.thermal import FVSystem, GuideGeometry, voxelise

Q, HS, HF = 0.4150, 8.82, 22.45


def run(cell, symmetric=True, cg=True, steps=300):
    t0 = time.perf_counter()
    fv = FVSystem(voxelise(GuideGeometry(), HS, HF, cell_size_m=cell, symmetric=symmetric))
    t_asm = time.perf_counter() - t0
    t0 = time.perf_counter()
    st = fv.steady(Q)
    t_direct = time.perf_counter() - t0
    row = {"cell_size_m": cell, "n_cells": fv.n, "nnz": int(fv.K.nnz), "assemble_s": t_asm,
           "steady_direct_s": t_direct, "rise_k": st.mean_probe_rise_k,
           "energy_balance": st.energy_balance_error}
    if cg:
        t0 = time.perf_counter()
        sc = fv.steady(Q, method="cg", rtol=1e-8)
        row["steady_cg_s"] = time.perf_counter() - t0
        row["cg_iterations"] = sc.info["iterations"]
    if steps:
        tr = fv.transient(Q, duration_s=steps * 60.0, dt_s=60.0)
        row.update(transient_factorise_s=tr.info["factorise_s"], transient_step_s=tr.info["step_s"],
                   transient_total_s=tr.info["factorise_s"] + steps * tr.info["step_s"],
                   factorisations=tr.info["factorisations"])
    return row


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=float, nargs="+", default=[0.004, 0.002, 0.0013, 0.001, 0.0007])
    ap.add_argument("--full", action="store_true", help="whole guide, not the quarter")
    ap.add_argument("--no-cg", action="store_true")
    ap.add_argument("--json", help="write the rows as JSON")
    a = ap.parse_args(argv)
    rows = []
    hdr = (f"{'cell mm':>7} {'cells':>8} {'assemble s':>10} {'steady LU s':>11} {'steady CG s':>11} "
           f"{'CG it':>6} {'factor s':>9} {'step ms':>8} {'5 h s':>8} {'rise K':>7}")
    print(hdr)
    for c in a.sizes:
        r = run(c, symmetric=not a.full, cg=not a.no_cg)
        rows.append(r)
        print(f"{c * 1e3:7.2f} {r['n_cells']:8d} {r['assemble_s']:10.3f} {r['steady_direct_s']:11.3f} "
              f"{r.get('steady_cg_s', float('nan')):11.3f} {r.get('cg_iterations', 0):6d} "
              f"{r['transient_factorise_s']:9.3f} {1e3 * r['transient_step_s']:8.2f} "
              f"{r['transient_total_s']:8.2f} {r['rise_k']:7.4f}", flush=True)
    if len(rows) >= 3:
        n = np.log([r["n_cells"] for r in rows])
        for key in ("assemble_s", "steady_direct_s", "steady_cg_s", "transient_factorise_s", "transient_step_s"):
            if all(key in r for r in rows):
                p = np.polyfit(n[1:], np.log([r[key] for r in rows][1:]), 1)[0]
                print(f"growth exponent of {key:22s} (time ~ cells^p, excluding the smallest grid): p = {p:.2f}")
    if a.json:
        with open(a.json, "w") as fh:
            json.dump(rows, fh, indent=1)


if __name__ == "__main__":
    main()
