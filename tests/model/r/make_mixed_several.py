"""Make the synthetic data sets of tests/model/r/mixed_several.R (run once; the CSVs are kept).

    python tests/model/r/make_mixed_several.py

* ``mixed_ssp.csv``: a split-split-plot: 8 whole plots (very-hard-to-change ``temp_c``, two
  whole plots at each of 4 levels), each split into 2 subplots (hard-to-change
  ``preload_kn`` at its low and high setting), each of 4 runs (easy ``speed_m_s`` x
  ``lube_ml``, the 2^2 factorial); whole-plot sd 1.2, subplot sd 0.8, run sd 0.5; three runs
  removed (unbalanced). Subplot labels are unique (``wp3-s2``), so ``subplot`` is nested in
  ``whole_plot`` as given. A ``block`` column pairs the whole plots (b1 = wp1, wp2, ...; no block
  effect was simulated) for a three-effect fit.
* ``mixed_strip.csv``: a strip-plot: 8 rows (``wash_min``, 4 levels twice) crossed with 6
  columns (``dry_c``, 3 levels twice), one run per cell with an easy ``rpm`` at +-1
  (alternating); row sd 1.0, column sd 0.7, run sd 0.6.
"""

from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).parent


def split_split_plot(seed: int = 351) -> pd.DataFrame:
    rng = np.random.default_rng(seed)
    rows = []
    temps = [150.0, 170.0, 190.0, 210.0, 150.0, 170.0, 190.0, 210.0]
    for w, t in enumerate(temps, start=1):
        uw = rng.normal(0.0, 1.2)
        for s, pre in enumerate(rng.permutation([2.0, 6.0]), start=1):
            us = rng.normal(0.0, 0.8)
            for sp in (1.0, 3.0):
                for lube in (5.0, 15.0):
                    a, b, c, d = (t - 180) / 30, (pre - 4) / 2, sp - 2, (lube - 10) / 5
                    y = 20 + 1.5 * a + 0.8 * b - 1.1 * c + 0.6 * d + 0.5 * a * c - 0.4 * b * d + uw + us \
                        + rng.normal(0.0, 0.5)
                    rows.append({"block": f"b{(w + 1) // 2}", "whole_plot": f"wp{w}", "subplot": f"wp{w}-s{s}", "temp_c": t, "preload_kn": pre,
                                 "speed_m_s": sp, "lube_ml": lube, "wear_um": round(y, 4)})
    df = pd.DataFrame(rows)
    return df.drop(index=[5, 30, 47]).reset_index(drop=True)


def strip_plot(seed: int = 352) -> pd.DataFrame:
    rng = np.random.default_rng(seed)
    wash = [10.0, 20.0, 30.0, 40.0, 10.0, 20.0, 30.0, 40.0]
    dry = [60.0, 80.0, 100.0, 60.0, 80.0, 100.0]
    ur = rng.normal(0.0, 1.0, len(wash))
    uc = rng.normal(0.0, 0.7, len(dry))
    rows = []
    for i, w in enumerate(wash):
        for j, d in enumerate(dry):
            rpm = 1.0 if (i + j) % 2 == 0 else -1.0
            a, b = (w - 25) / 15, (d - 80) / 20
            y = 50 + 2.0 * a - 1.2 * b + 0.7 * rpm + 0.8 * a * b - 0.9 * b * b + ur[i] + uc[j] + rng.normal(0.0, 0.6)
            rows.append({"row": f"r{i + 1}", "col": f"c{j + 1}", "wash_min": w, "dry_c": d, "rpm": 1000 + 200 * rpm,
                         "gloss": round(y, 4)})
    return pd.DataFrame(rows)


if __name__ == "__main__":
    split_split_plot().to_csv(HERE / "mixed_ssp.csv", index=False)
    strip_plot().to_csv(HERE / "mixed_strip.csv", index=False)
