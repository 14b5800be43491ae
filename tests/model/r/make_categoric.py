"""Data for the categoric-factor checks against R (tests/model/test_categoric_r.py).

Three response-surface data sets with categoric factors, made once with a fixed seed and
stored as CSV (so R and the tests read the same numbers):

* ``cat_bbd3x2``: a three-factor Box–Behnken design (12 edge runs + 3 centre points) crossed
  with a 2-level categoric factor ``supplier`` (Design-Expert's layout), 30 runs;
* ``cat_ccd2x3``: a two-factor face-centred CCD (4 + 4 + 3 centre runs) crossed with a 3-level
  ``lubricant``, 33 runs, one run left without a response;
* ``cat_f2x2x3``: a 3x3 factorial in two numeric factors crossed with a 2-level and a 3-level
  categoric factor (categoric x categoric interactions), 54 runs + 6 replicates.

    python tests/model/r/make_categoric.py
"""

import itertools
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).parent
rng = np.random.default_rng(20261123)


def bbd3():
    pts = []
    for i, j in itertools.combinations(range(3), 2):
        for a, b in itertools.product((-1, 1), repeat=2):
            p = [0, 0, 0]
            p[i], p[j] = a, b
            pts.append(p)
    return pts + [[0, 0, 0]] * 3


def main():
    rows = []
    for sup in ("north", "south"):
        for x in bbd3():
            a, b, c = x
            s = 1.0 if sup == "north" else -1.0
            y = 50 + 4 * a - 2 * b + 3 * c + 1.5 * a * b - 2 * a * a + 1.2 * c * c + 2.5 * s + 1.1 * s * a \
                + rng.normal(0, 0.8)
            rows.append({"temp_c": 150 + 20 * a, "time_min": 30 + 10 * b, "conc_pct": 5 + 2 * c,
                         "supplier": sup, "yield_pct": round(y, 4)})
    pd.DataFrame(rows).to_csv(HERE / "cat_bbd3x2.csv", index=False)

    rows = []
    ccd = [[a, b] for a in (-1, 1) for b in (-1, 1)] + [[-1, 0], [1, 0], [0, -1], [0, 1]] + [[0, 0]] * 3
    eff = {"mineral": -0.6, "synthetic": 0.9, "grease": -0.3}
    for lub in ("mineral", "synthetic", "grease"):
        for a, b in ccd:
            y = 2.0 + 0.7 * a + 0.4 * b - 0.5 * a * b + 0.6 * b * b + eff[lub] + 0.4 * a * (lub == "grease") \
                + rng.normal(0, 0.15)
            rows.append({"speed_m_s": 0.5 + 0.1 * a, "load_n": 800 + 200 * b, "lubricant": lub,
                         "wear_um": round(y, 5)})
    rows[7]["wear_um"] = None  # a run not made
    pd.DataFrame(rows).to_csv(HERE / "cat_ccd2x3.csv", index=False)

    rows = []
    for st, mat in itertools.product(("rfcms", "rms"), ("steel", "bronze", "polymer")):
        for a, b in itertools.product((-1, 0, 1), repeat=2):
            reps = 2 if (a == 0 and b == 0) else 1
            for _ in range(reps):
                s = 1.0 if st == "rms" else 0.0
                m = {"steel": 0.0, "bronze": 0.5, "polymer": -0.4}[mat]
                y = 10 + a - 0.5 * b + 0.3 * a * b + 0.8 * a * a + 1.5 * s + m + 0.7 * s * m + 0.3 * b * s \
                    + rng.normal(0, 0.2)
                rows.append({"x1": 2 + a, "x2": 40 + 5 * b, "stage": st, "material": mat, "y": round(y, 5)})
    pd.DataFrame(rows).to_csv(HERE / "cat_f2x2x3.csv", index=False)


if __name__ == "__main__":
    main()
