"""Write the blocked mixture data of tests/model/test_mixture_fit_blocks.py (checked against R by
mixture_blocks.R): D-optimal blocked designs from rsm_lrg's own ``mixture_optimal(blocks=...)``
with a response simulated from a stated model (the numbers are not fitted to anything). Run
from this folder: PYTHONPATH=../../.. python make_mixture_blocks.py
"""

import numpy as np

from rsm_lrg.design.mixture_optimal import mixture_optimal


def main() -> None:
    rng = np.random.default_rng(20261128)
    # three components on a constrained region, 3 blocks of 7 (batches of raw material)
    d = mixture_optimal({"a": (0.1, 0.8), "b": (0.1, 0.8), "c": (0.0, 0.5)}, model="mixture-quadratic",
                        criterion="D", constraints=["a + b <= 0.85"], blocks=3, block_size=7, seed=3, starts=5)
    f = d.to_frame()[["block", "a", "b", "c"]]
    shift = np.array([0.0, 1.2, -0.7])[f.block.to_numpy() - 1]
    f["y"] = (10 * f.a + 12 * f.b + 8 * f.c + 5 * f.a * f.b - 3 * f.b * f.c + shift
              + rng.normal(0, 0.3, len(f))).round(3)
    f.to_csv("mixture_blocks_quad3.csv", index=False)
    # a mixture-process design: 3 components, one process factor, 2 blocks of 12 (days)
    d = mixture_optimal({"a": (0.0, 1.0), "b": (0.0, 1.0), "c": (0.2, 1.0)}, model="mixture-quadratic",
                        criterion="D", process=["t=20:40"], blocks=2, block_size=12, seed=4, starts=5)
    f = d.to_frame()[["block", "a", "b", "c", "t"]]
    z = (f.t - 30) / 10
    shift = np.array([-0.8, 0.8])[f.block.to_numpy() - 1]
    f["y"] = (20 * f.a + 15 * f.b + 25 * f.c + 10 * f.a * f.b + z * (2 * f.a - 1 * f.c) + shift
              + rng.normal(0, 0.5, len(f))).round(3)
    f.to_csv("mixture_blocks_proc3.csv", index=False)


if __name__ == "__main__":
    main()
