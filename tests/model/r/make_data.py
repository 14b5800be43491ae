"""Writes the data sets that the R scripts beside it read (run once; the CSVs are committed).

    python tests/model/r/make_data.py && Rscript tests/model/r/blocks_lof.R && Rscript tests/model/r/lm_accuracy.R \
        && Rscript tests/model/r/core_check.R

Floats are written with 17 significant digits, so R reads exactly the numbers Python holds.
"""

from pathlib import Path

import numpy as np
import pandas as pd

import rsm_lrg

HERE = Path(__file__).parent


def _write(df: pd.DataFrame, name: str) -> None:
    df.to_csv(HERE / name, index=False, float_format="%.17g")


def blocks_data() -> None:
    rng = np.random.default_rng(20261123)
    # 1. a Box–Behnken design in 3 factors (15 runs, 3 centre runs), run once in each of two
    #    blocks: every setting appears once per block, so pure error comes from across blocks.
    bbd = rsm_lrg.box_behnken({"temp_c": (150, 210), "time_min": (10, 30), "conc_pct": (1, 5)}, center=3,
                              randomize=False).to_frame()[["temp_c", "time_min", "conc_pct"]]
    d1 = pd.concat([bbd.assign(Block=1), bbd.assign(Block=2)], ignore_index=True)
    x = (d1[["temp_c", "time_min", "conc_pct"]].to_numpy() - [180, 20, 3]) / [30, 10, 2]
    d1["y"] = (50 + 4 * x[:, 0] - 3 * x[:, 1] + 2 * x[:, 2] + 1.5 * x[:, 0] * x[:, 1] - 5 * x[:, 0] ** 2
               + 0.8 * x[:, 2] ** 3 + 2.0 * (d1["Block"] == 2) + rng.normal(0, 0.7, len(d1)))
    _write(d1, "blocks_bbd3.csv")
    # 2. a central composite design in 2 factors in two blocks (factorial + 3 centre runs,
    #    axial + 3 centre runs): only the centre spans the blocks.
    ccd = rsm_lrg.central_composite({"p_bar": (1, 3), "flow_l_min": (2, 6)}, center=(3, 3), randomize=False)
    c = ccd.to_frame()
    c["Block"] = np.asarray(ccd.blocks) if ccd.blocks is not None else np.r_[np.ones(7), 2 * np.ones(7)]
    c = c[["p_bar", "flow_l_min", "Block"]]
    x = (c[["p_bar", "flow_l_min"]].to_numpy() - [2, 4]) / [1, 2]
    c["y"] = 10 + x[:, 0] - 2 * x[:, 1] + 0.5 * x[:, 0] * x[:, 1] + x[:, 1] ** 2 - 0.7 * (c["Block"] == 2) \
        + rng.normal(0, 0.3, len(c))
    _write(c, "blocks_ccd2.csv")
    # 3. a 2^3 factorial with centre runs spread unevenly over three blocks, some corners
    #    repeated in another block (2FI model).
    corners = np.array([[a, b, cc] for a in (-1, 1) for b in (-1, 1) for cc in (-1, 1)], dtype=float)
    half1 = corners[np.prod(corners, axis=1) > 0]
    half2 = corners[np.prod(corners, axis=1) < 0]
    rows = ([(*r, 1) for r in corners] + [(0, 0, 0, 1)] * 2 + [(*r, 2) for r in half1] + [(0, 0, 0, 2)] * 2
            + [(*r, 3) for r in half2] + [(0, 0, 0, 3)] + [(*corners[0], 3), (*corners[7], 3)])
    f = pd.DataFrame(rows, columns=["a_mm", "b_s", "c_k", "Block"])
    f["a_mm"] = 5 + 2 * f["a_mm"]
    f["b_s"] = 60 + 30 * f["b_s"]
    f["c_k"] = 300 + 10 * f["c_k"]
    x = (f[["a_mm", "b_s", "c_k"]].to_numpy() - [5, 60, 300]) / [2, 30, 10]
    f["y"] = (3 + 0.4 * x[:, 0] + 0.2 * x[:, 1] - 0.3 * x[:, 0] * x[:, 2] + 0.5 * (x[:, 0] ** 2)
              + np.array([0.0, 0.3, -0.2])[f["Block"].to_numpy() - 1] + rng.normal(0, 0.1, len(f)))
    _write(f, "blocks_fact3.csv")


def lm_data() -> None:
    rng = np.random.default_rng(7)
    n = 24
    # 1. factors on wildly different scales (1e-4 m and 1e6 Hz) and an ordinary one
    thick = rng.uniform(1e-4, 3e-4, n)
    freq = rng.uniform(1e6, 5e6, n)
    temp = rng.uniform(20, 80, n)
    d = pd.DataFrame({"thickness_m": thick, "freq_hz": freq, "temp_c": temp})
    x = np.column_stack([(thick - 2e-4) / 1e-4, (freq - 3e6) / 2e6, (temp - 50) / 30])
    d["y"] = 7 + x[:, 0] - 0.5 * x[:, 1] + 0.3 * x[:, 0] * x[:, 1] - 0.0625 * x[:, 1] ** 2 + 0.2 * x[:, 2] ** 2 \
        + rng.normal(0, 0.05, n)
    _write(d, "lm_scales.csv")
    # 2. a response near 1e9: small variation on a large offset
    d2 = d[["thickness_m", "freq_hz", "temp_c"]].copy()
    d2["y"] = 1e9 + 3 * x[:, 0] - 2 * x[:, 2] + 0.7 * x[:, 0] * x[:, 2] + 0.4 * x[:, 1] ** 2 + rng.normal(0, 0.2, n)
    _write(d2, "lm_offset.csv")


def coded(name: str) -> None:
    """The coded model matrix columns A, B, C that rsm_lrg.fit uses, for R's lm."""
    df = pd.read_csv(HERE / name)
    r = rsm_lrg.fit(df, "y", factors=["thickness_m", "freq_hz", "temp_c"])
    out = r.coded.copy()
    out["y"] = r.y
    _write(out, name.replace(".csv", "_coded.csv"))


def core_data() -> None:
    """A central composite design in 4 coded factors (axial 1.5, 4 centre runs, the cube
    replicated once) plus 10 runs anywhere in the box, response on an offset of 1e4: the
    regression core against R (core_check.R)."""
    import itertools

    rng = np.random.default_rng(11_2026)
    cube = np.array(list(itertools.product([-1.0, 1.0], repeat=4)))
    axial = np.vstack([s * 1.5 * np.eye(4)[i] for i in range(4) for s in (-1.0, 1.0)])
    x = np.vstack([cube, cube, axial, np.zeros((4, 4)), rng.uniform(-1, 1, (10, 4))])
    y = (1e4 + 3 * x[:, 0] - 2 * x[:, 1] + 0.5 * x[:, 2] + x[:, 0] * x[:, 3] - 1.2 * x[:, 1] ** 2
         + 0.4 * x[:, 0] ** 2 * x[:, 1] + rng.normal(0, 0.5, len(x)))
    _write(pd.DataFrame({"x1": x[:, 0], "x2": x[:, 1], "x3": x[:, 2], "x4": x[:, 3], "y": y}), "core_ccd4.csv")


if __name__ == "__main__":
    core_data()
    blocks_data()
    lm_data()
    coded("lm_scales.csv")
    coded("lm_offset.csv")
