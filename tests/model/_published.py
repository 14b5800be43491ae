"""Published data sets used by the analysis-workbench tests (with their sources)."""

import pandas as pd

#: Trebuchet Box-Behnken experiment: Lawson, *Design and Analysis of Experiments with R*
#: (CRC 2015), data ``Treb`` of R package daewr; coding x1 = (A-6)/2, x2 = (B-15)/5,
#: x3 = (C-2.5)/0.5. R rsm output (summary, anova, steepest) as printed in the R course notes
#: that run ``rsm(y ~ SO(x1, x2, x3), data = Treb)`` and ``steepest(treb.quad, dist =
#: seq(0, 1.412, by = 0.1))``.
TREB = pd.DataFrame({
    "A": [4, 8, 4, 8, 4, 8, 4, 8, 6, 6, 6, 6, 6, 6, 6],
    "B": [10, 10, 20, 20, 15, 15, 15, 15, 10, 20, 10, 20, 15, 15, 15],
    "C": [2.5, 2.5, 2.5, 2.5, 2.0, 2.0, 3.0, 3.0, 2.0, 2.0, 3.0, 3.0, 2.5, 2.5, 2.5],
    "y": [33, 85, 86, 113, 75, 105, 40, 89, 83, 108, 49, 101, 88, 91, 91],
})
TREB_FACTORS = ["A=4:8", "B=10:20", "C=2:3"]

#: R rsm ``steepest(treb.quad, dist = seq(0, 1.412, by = 0.1))``: dist, x1, x2, x3, yhat.
TREB_STEEPEST = [
    (0.0, 0.000, 0.000, 0.000, 90.000), (0.1, 0.064, 0.067, -0.037, 92.909),
    (0.2, 0.124, 0.139, -0.073, 95.626), (0.3, 0.180, 0.215, -0.105, 98.120),
    (0.4, 0.232, 0.297, -0.134, 100.455), (0.5, 0.277, 0.385, -0.158, 102.599),
    (0.6, 0.315, 0.480, -0.175, 104.590), (0.7, 0.345, 0.580, -0.185, 106.424),
    (0.8, 0.368, 0.686, -0.185, 108.154), (0.9, 0.384, 0.795, -0.177, 109.783),
    (1.0, 0.393, 0.905, -0.161, 111.318), (1.1, 0.397, 1.017, -0.137, 112.817),
    (1.2, 0.398, 1.127, -0.107, 114.259), (1.3, 0.395, 1.236, -0.073, 115.673),
    (1.4, 0.390, 1.344, -0.034, 117.077),
]

#: Cement grout experiment, block 1 (2^3 cube + 3 centre runs): daewr ``cement`` data
#: (Lawson 2015); R: ``anova(rsm(y ~ SO(x1, x2, x3), data = cement, subset = Block == 1))``
#: gives FO 465.12 (3 df), TWI 0.25 (3 df), PQ 37.88 (1 df: the squares are aliased),
#: Residuals 5.79 (3 df).
CEMENT1 = pd.DataFrame({
    "x1": [-1, 1, -1, 1, -1, 1, -1, 1, 0, 0, 0],
    "x2": [-1, -1, 1, 1, -1, -1, 1, 1, 0, 0, 0],
    "x3": [-1, -1, -1, -1, 1, 1, 1, 1, 0, 0, 0],
    "y": [109.5, 117.0, 110.5, 121.0, 120.0, 130.0, 124.0, 132.0, 117.0, 117.0, 115.0],
})

#: Montgomery, *Design and Analysis of Experiments* (8th ed.), Example 11.1: 2^2 factorial
#: with 5 centre runs, first-order fit y = 40.44 + 0.775 x1 + 0.325 x2; the path of steepest
#: ascent moves Δx2 = (0.325/0.775) Δx1 = 0.42 Δx1.
MONTGOMERY_11_1 = pd.DataFrame({
    "x1": [-1, -1, 1, 1, 0, 0, 0, 0, 0],
    "x2": [-1, 1, -1, 1, 0, 0, 0, 0, 0],
    "y": [39.3, 40.0, 40.9, 41.5, 40.3, 40.5, 40.7, 40.2, 40.6],
})

#: Montgomery, DAE (8th ed.), Example 11.2 (13-run CCD, axial 1.414), as in test_textbook.py.
_A = 1.414
MONTGOMERY_11_2 = pd.DataFrame(
    [(-1, -1), (-1, 1), (1, -1), (1, 1), (0, 0), (0, 0), (0, 0), (0, 0), (0, 0), (_A, 0), (-_A, 0), (0, _A), (0, -_A)],
    columns=["x1", "x2"])
MONTGOMERY_11_2["y"] = [76.5, 77.0, 78.0, 79.5, 79.9, 80.3, 80.0, 79.7, 79.8, 78.4, 75.6, 78.5, 77.0]
