"""Writes the designs that ``gp.R`` fits with DiceKriging (run once; the CSVs are committed).

    python tests/model/r/make_gp.py && Rscript tests/model/r/gp.R

Three test functions on designs chosen once, before any fit (seeds below; not tuned):
Branin on a 20-run Latin hypercube, the 8-input borehole function on a 60-run Latin
hypercube, Hartmann-3 with N(0, 0.1²) noise on a 40-run Latin hypercube; and 200 virtual
runs of the physics surrogate (``rsm_lrg.simulate``, no noise) on a Latin hypercube of the
paper's Table 3 box (the same as ``rsm-lrg design latin-hypercube --factor
thickness_m=0.0001:0.0005 --factor stroke_m=0.04:0.06 --factor velocity_m_s=0.4:0.6 --factor
acceleration_m_s2=20:40 --runs 200 --seed 20261128 --no-randomize`` then ``rsm-lrg simulate
--noise-sd 0``), response ``tcr_c_per_min``. For each, 100 new points drawn uniformly over the
box. The functions as in Surjanovic & Bingham's Virtual
Library of Simulation Experiments (sfu.ca/~ssurjano). Floats are written with 17
significant digits, so R reads exactly the numbers Python holds.
"""

from pathlib import Path

import numpy as np
import pandas as pd
from scipy.stats import qmc

HERE = Path(__file__).parent

BOXES = {
    "branin": {"x1": (-5.0, 10.0), "x2": (0.0, 15.0)},
    "borehole": {"rw": (0.05, 0.15), "r": (100.0, 50000.0), "Tu": (63070.0, 115600.0), "Hu": (990.0, 1110.0),
                 "Tl": (63.1, 116.0), "Hl": (700.0, 820.0), "L": (1120.0, 1680.0), "Kw": (9855.0, 12045.0)},
    "hartmann3": {"x1": (0.0, 1.0), "x2": (0.0, 1.0), "x3": (0.0, 1.0)},
    "surrogate": {"thickness_m": (0.0001, 0.0005), "stroke_m": (0.04, 0.06), "velocity_m_s": (0.4, 0.6),
                  "acceleration_m_s2": (20.0, 40.0)},
}
RUNS = {"branin": 20, "borehole": 60, "hartmann3": 40}


def branin(d: pd.DataFrame) -> np.ndarray:
    x1, x2 = d["x1"].to_numpy(), d["x2"].to_numpy()
    return ((x2 - 5.1 / (4 * np.pi ** 2) * x1 ** 2 + 5 / np.pi * x1 - 6) ** 2
            + 10 * (1 - 1 / (8 * np.pi)) * np.cos(x1) + 10)


def borehole(d: pd.DataFrame) -> np.ndarray:
    lr = np.log(d["r"] / d["rw"])
    return (2 * np.pi * d["Tu"] * (d["Hu"] - d["Hl"])
            / (lr * (1 + 2 * d["L"] * d["Tu"] / (lr * d["rw"] ** 2 * d["Kw"]) + d["Tu"] / d["Tl"]))).to_numpy()


def hartmann3(d: pd.DataFrame) -> np.ndarray:
    a = np.array([[3.0, 10, 30], [0.1, 10, 35], [3.0, 10, 30], [0.1, 10, 35]])
    p = 1e-4 * np.array([[3689, 1170, 2673], [4699, 4387, 7470], [1091, 8732, 5547], [381, 5743, 8828]])
    c = np.array([1.0, 1.2, 3.0, 3.2])
    x = d[["x1", "x2", "x3"]].to_numpy()
    return -np.sum(c * np.exp(-np.sum(a[None] * (x[:, None, :] - p[None]) ** 2, axis=2)), axis=1)


FUNCTIONS = {"branin": branin, "borehole": borehole, "hartmann3": hartmann3}


def _frame(u: np.ndarray, box: dict) -> pd.DataFrame:
    lo = np.array([v[0] for v in box.values()])
    hi = np.array([v[1] for v in box.values()])
    return pd.DataFrame(lo + u * (hi - lo), columns=list(box))


def surrogate() -> None:
    """200 noise-free virtual runs of the Table 3 box (slow: a few minutes)."""
    import rsm_lrg

    box = BOXES["surrogate"]
    design = rsm_lrg.latin_hypercube({k: v for k, v in box.items()}, 200, seed=20261128, randomize=False)
    runs = rsm_lrg.simulate(design, noise_sd=0.0)
    runs = runs[list(box)].assign(y=runs["tcr_c_per_min"].to_numpy())
    runs.to_csv(HERE / "gp_surrogate.csv", index=False, float_format="%.17g")
    new = _frame(np.random.default_rng(20261128 + len(BOXES)).random((100, len(box))), box)
    new.to_csv(HERE / "gp_surrogate_new.csv", index=False, float_format="%.17g")


def main() -> None:
    rows = [(name, f, lo, hi) for name, box in BOXES.items() for f, (lo, hi) in box.items()]
    pd.DataFrame(rows, columns=["dataset", "factor", "low", "high"]).to_csv(HERE / "gp_boxes.csv", index=False,
                                                                           float_format="%.17g")
    for i, (name, box) in enumerate(BOXES.items()):
        if name == "surrogate":
            surrogate()
            continue
        rng = np.random.default_rng(20261128 + i)
        runs = _frame(qmc.LatinHypercube(d=len(box), seed=rng).random(RUNS[name]), box)
        y = FUNCTIONS[name](runs)
        if name == "hartmann3":
            y = y + rng.normal(0.0, 0.1, y.size)
        runs["y"] = y
        new = _frame(rng.random((100, len(box))), box)
        runs.to_csv(HERE / f"gp_{name}.csv", index=False, float_format="%.17g")
        new.to_csv(HERE / f"gp_{name}_new.csv", index=False, float_format="%.17g")


if __name__ == "__main__":
    main()
