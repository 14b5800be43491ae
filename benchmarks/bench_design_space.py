"""Benchmark the design space (:func:`rsm_lrg.optimize.design_space.design_space`): the probability
map over a grid of the four Table 4 factors and the search for the largest operating window,
against an anchor run in the same process — the fit's own ``predictive`` at every grid node (one
model-matrix product with the interval form), which every design-space evaluation needs at least.

Usage::

    python benchmarks/bench_design_space.py                  # grids 7, 11 and 15 (2,401 .. 50,625 nodes)
    python benchmarks/bench_design_space.py --grid 11 21 --repeat 5 --json out.json

Printed per grid: nodes, the median wall time of the anchor, of the whole design space (map and
window) and of the window search alone (``largest_window`` on the map already computed), and the
ratios to the anchor. Times are wall-clock on this machine (shared cores: expect noise of tens of
per cent); nothing here is asserted.
"""

from __future__ import annotations

import argparse
import itertools
import json
import statistics
import time
from pathlib import Path

import numpy as np

import rsm_lrg
from rsm_lrg.optimize.design_space import design_space, largest_window

Y = "tcr_c_per_min"
SPEC = {Y: (None, 0.030)}  # κ at most 0.030 °C/min


def _median_time(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--grid", type=int, nargs="+", default=[7, 11, 15])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--probability", type=float, default=0.9)
    ap.add_argument("--json", default=None)
    args = ap.parse_args(argv)

    fit = rsm_lrg.fit(rsm_lrg.load_table4(), Y)
    k = len(fit.space)
    fit.predictive(np.zeros((1, k)))  # warm-up: the interval form and its caches
    design_space({Y: fit}, SPEC, probability=args.probability, grid=3)
    rows = []
    for g in args.grid:
        levels = np.linspace(-1.0, 1.0, g)
        nodes = np.array(list(itertools.product(levels, repeat=k)))
        anchor = _median_time(lambda nodes=nodes: fit.predictive(nodes), args.repeat)
        ds = design_space({Y: fit}, SPEC, probability=args.probability, grid=g)
        whole = _median_time(lambda g=g: design_space({Y: fit}, SPEC, probability=args.probability, grid=g),
                             args.repeat)
        p = np.asarray(ds.grid_probability)
        ok = p >= args.probability
        window = _median_time(lambda ok=ok, p=p: largest_window(ok, p), args.repeat)
        rows.append({"grid": g, "nodes": int(g ** k), "anchor_s": anchor, "design_space_s": whole,
                     "window_s": window, "design_space_per_anchor": whole / anchor,
                     "window_per_anchor": window / anchor, "window_found": bool(ds.window)})
        r = rows[-1]
        print(f"grid {g:3d} ({r['nodes']:6d} nodes): anchor {anchor * 1e3:8.2f} ms, design space "
              f"{whole * 1e3:8.2f} ms ({r['design_space_per_anchor']:.1f}x), window search "
              f"{window * 1e3:8.2f} ms ({r['window_per_anchor']:.1f}x)")
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
