"""Write mixture_ssp.csv for tests/model/engines/test_mixture_reml.py (checked against R by
mixture_vinyl.R): a simulated mixture-process experiment with two random effects, 4 days (random
blocks), 3 batches a day (whole plots: one blend each, a simplex-centroid blend of three
components in turn) and the 2^2 factorial in two process factors inside every batch; the
response from a stated model (day sd 1.2, batch sd 0.9, run sd 0.5). Run from this folder:
python make_mixture_ssp.py
"""

import itertools

import numpy as np
import pandas as pd


def main() -> None:
    rng = np.random.default_rng(35)
    blends = [(1, 0, 0), (0, 1, 0), (0, 0, 1), (0.5, 0.5, 0), (0.5, 0, 0.5), (0, 0.5, 0.5), (1 / 3, 1 / 3, 1 / 3)]
    rows = []
    batch = 0
    for day in range(1, 5):
        u_day = rng.normal(0, 1.2)
        for _ in range(3):
            x = blends[batch % len(blends)]
            batch += 1
            u_batch = rng.normal(0, 0.9)
            for z1, z2 in itertools.product([-1, 1], repeat=2):
                y = (14 * x[0] + 9 * x[1] + 11 * x[2] + 6 * x[0] * x[1] + z1 * (1.5 * x[0] - 0.5 * x[2])
                     + 0.8 * z2 * x[1] + u_day + u_batch + rng.normal(0, 0.5))
                rows.append({"day": f"d{day}", "batch": f"b{batch}", "x1": round(x[0], 6), "x2": round(x[1], 6),
                             "x3": round(1 - round(x[0], 6) - round(x[1], 6), 6), "z1": z1, "z2": z2,
                             "y": round(y, 3)})
    pd.DataFrame(rows).to_csv("mixture_ssp.csv", index=False)


if __name__ == "__main__":
    main()
