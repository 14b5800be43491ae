"""Make the synthetic split-plot data sets of tests/model/r/mixed.R (run once; the CSVs are kept).

    python tests/model/r/make_mixed.py

* ``mixed_sp_bal.csv``: 8 whole plots x 4 runs; hard-to-change temp_c, preload_kn (whole-plot
  settings: the 3x3 grid less its centre), easy speed_m_s, lube_ml (4 settings of the 3x3 grid
  per whole plot, drawn at random); a quadratic response with a whole-plot effect sd 1.5 and
  a within-plot error sd 1.0.
* ``mixed_sp_unbal.csv``: 10 whole plots of 2 to 5 runs (35 runs); temp_c, preload_kn
  whole-plot factors, speed_m_s easy, lube a 3-level categoric easy factor.
* ``mixed_sp_zero.csv``: as the balanced one with no whole-plot variation (seed chosen so that
  REML puts the whole-plot variance at zero).
* ``mixed_sp_small.csv``: as the balanced one with a small whole-plot effect (sd 0.5; the first
  seed at which REML puts the whole-plot variance at zero): the boundary with a true component.
"""

from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).parent
GRID = [(a, b) for a in (-1, 0, 1) for b in (-1, 0, 1)]


def _decode(v, lo, hi):
    return (lo + hi) / 2 + v * (hi - lo) / 2


def balanced(seed: int, sd_wp: float) -> pd.DataFrame:
    rng = np.random.default_rng(seed)
    wps = [g for g in GRID if g != (0, 0)]
    rows = []
    for w, (a, b) in enumerate(wps, start=1):
        u = rng.normal(0.0, sd_wp) if sd_wp > 0 else 0.0
        for k in rng.choice(9, size=4, replace=False):
            c, d = GRID[k]
            mu = 50 + 3 * a - 2 * b + 4 * c + 1.5 * d + 1.2 * a * c - 0.8 * b * d - 2.5 * a * a + 1.5 * c * c - d * d
            rows.append({"whole_plot": f"W{w}", "temp_c": _decode(a, 150, 250), "preload_kn": _decode(b, 2, 6),
                         "speed_m_s": _decode(c, 0.2, 0.6), "lube_ml": _decode(d, 1, 3),
                         "wear_um": round(mu + u + rng.normal(0.0, 1.0), 3)})
    return pd.DataFrame(rows)


def unbalanced(seed: int) -> pd.DataFrame:
    rng = np.random.default_rng(seed)
    sizes = [2, 3, 4, 5, 3, 4, 2, 5, 3, 4]
    wps = GRID + [(0, 0)]
    lubes = ["mineral", "synthetic", "grease"]
    shift = {"mineral": 0.0, "synthetic": -1.5, "grease": 1.0}
    rows = []
    for w, ((a, b), m) in enumerate(zip(wps, sizes), start=1):
        u = rng.normal(0.0, 1.2)
        for _ in range(m):
            c = int(rng.integers(-1, 2))
            lube = lubes[int(rng.integers(0, 3))]
            mu = 20 + 2 * a + b - 3 * c + shift[lube] + 0.8 * a * c + (0.7 * c if lube == "grease" else 0.0) - 1.5 * a * a + c * c
            rows.append({"whole_plot": w, "temp_c": _decode(a, 150, 250), "preload_kn": _decode(b, 2, 6),
                         "speed_m_s": _decode(c, 0.2, 0.6), "lube": lube, "wear_um": round(mu + u + rng.normal(0, 0.8), 3)})
    return pd.DataFrame(rows)


if __name__ == "__main__":
    balanced(20261127, 1.5).to_csv(HERE / "mixed_sp_bal.csv", index=False)
    unbalanced(7).to_csv(HERE / "mixed_sp_unbal.csv", index=False)
    balanced(4, 0.0).to_csv(HERE / "mixed_sp_zero.csv", index=False)
    balanced(4, 0.5).to_csv(HERE / "mixed_sp_small.csv", index=False)
