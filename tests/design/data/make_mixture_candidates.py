"""Write the candidate sets of tests/design/test_design_mixture_optimal.py for R (mixture_optimal.R).

Each case's candidates (rsm_lrg.design.mixture.candidate_blends, L-pseudo components, crossed
with the process levels -1, 0, +1) go to mixture_cand_<case>.csv. Run from this folder:
PYTHONPATH=../../.. python make_mixture_candidates.py
"""

import itertools

import numpy as np
import pandas as pd

from rsm_lrg.design.mixture import candidate_blends

#: case: (bounds, constraints, process factors)
CASES = {
    "quad3": ({"a": (0.1, 0.8), "b": (0.1, 0.8), "c": (0.0, 0.5)}, ["a + b <= 0.85"], 0),
    "flare4": ({"Mg": (0.4, 0.6), "NaNO3": (0.1, 0.5), "SrNO3": (0.1, 0.5), "binder": (0.03, 0.08)}, None, 0),
    "cubic3": ({"a": (0.0, 1.0), "b": (0.0, 1.0), "c": (0.0, 1.0)}, None, 0),
    "proc3": ({"a": (0.0, 1.0), "b": (0.0, 1.0), "c": (0.2, 1.0)}, None, 1),
}


def candidates(case: str) -> pd.DataFrame:
    bounds, cons, k = CASES[case]
    cs = candidate_blends(bounds, cons)
    r = cs.total - float(np.sum(cs.lows))
    z = (cs.points - cs.lows[None, :]) / r
    levels = np.array(list(itertools.product([-1.0, 0.0, 1.0], repeat=k))) if k else np.zeros((1, 0))
    pool = np.hstack([np.repeat(z, len(levels), axis=0), np.tile(levels, (len(z), 1))])
    return pd.DataFrame(pool, columns=list("ABCDEFGH"[:pool.shape[1]]))


if __name__ == "__main__":
    for case in CASES:
        candidates(case).to_csv(f"mixture_cand_{case}.csv", index=False, float_format="%.17g")
