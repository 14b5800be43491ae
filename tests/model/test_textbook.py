"""Textbook examples with published answers (independent of the paper).

* Montgomery, *Design and Analysis of Experiments* (8th ed.), Example 11.2 (chemical
  process CCD, 13 runs, axial 1.414): fitted model
  ŷ = 79.94 + 0.995 x1 + 0.515 x2 + 0.25 x1x2 - 1.376 x1² - 1.001 x2², stationary point
  x1 = 0.389, x2 = 0.306, ŷ_s = 80.21 (published to the digits shown).
* R ``rsm`` vignette (Lenth, "Response-Surface Methods in R, Using rsm", article-JSS),
  ChemReact data (Myers, Montgomery & Anderson-Cook 2009, Table 7.6), model
  ``Yield ~ Block + SO(x1, x2)`` with x1 = (Time - 85)/5, x2 = (Temp - 175)/5: lack of fit
  p ≈ 0.69, stationary point (0.37, 0.33) coded, a maximum, Time ≈ 87, Temp ≈ 177.
  The coded point to 7 digits (0.3722954, 0.3343802) is R rsm's printed ``xs`` for
  CR2.rsm; the closed form -½B⁻¹b of our coefficients is checked independently.
"""

import numpy as np
import pandas as pd
import pytest

import rsm_lrg

A = 1.414


@pytest.fixture(scope="module")
def montgomery():
    x = [(-1, -1), (-1, 1), (1, -1), (1, 1), (0, 0), (0, 0), (0, 0), (0, 0), (0, 0),
         (A, 0), (-A, 0), (0, A), (0, -A)]
    y = [76.5, 77.0, 78.0, 79.5, 79.9, 80.3, 80.0, 79.7, 79.8, 78.4, 75.6, 78.5, 77.0]
    df = pd.DataFrame(x, columns=["x1", "x2"])
    df["y"] = y
    return df


@pytest.fixture(scope="module")
def chemreact():
    return pd.DataFrame({
        "Time": [80, 80, 90, 90, 85, 85, 85, 85, 85, 85, 92.07, 77.93, 85, 85],
        "Temp": [170, 180, 170, 180, 175, 175, 175, 175, 175, 175, 175, 175, 182.07, 167.93],
        "Block": ["B1"] * 7 + ["B2"] * 7,
        "Yield": [80.5, 81.5, 82.0, 83.5, 83.9, 84.3, 84.0, 79.7, 79.8, 79.5, 78.4, 75.6, 78.5, 77.0],
    })


def test_montgomery_example_11_2_coefficients(montgomery):
    r = rsm_lrg.fit(montgomery, "y", factors=["x1=-1:1", "x2=-1:1"])
    ref = {"Intercept": 79.94, "A": 0.995, "B": 0.515, "AB": 0.25, "A^2": -1.376, "B^2": -1.001}
    for k, v in ref.items():  # published to 3 decimals -> 5e-4
        assert r.coefficients.loc[k, "coded"] == pytest.approx(v, abs=5e-4), k
    # cross-check with NumPy least squares (1e-10)
    X = np.column_stack([np.ones(13), montgomery.x1, montgomery.x2, montgomery.x1 * montgomery.x2,
                         montgomery.x1 ** 2, montgomery.x2 ** 2])
    b = np.linalg.lstsq(X, montgomery.y, rcond=None)[0]
    np.testing.assert_allclose(r.coefficients["coded"].to_numpy(), b, rtol=1e-10)


def test_montgomery_example_11_2_stationary_point(montgomery):
    r = rsm_lrg.fit(montgomery, "y", factors=["x1=-1:1", "x2=-1:1"])
    sp = r.stationary_point
    assert sp.coded["A"] == pytest.approx(0.389, abs=5e-4)  # published 0.389
    assert sp.coded["B"] == pytest.approx(0.306, abs=5e-4)  # published 0.306
    assert sp.predicted == pytest.approx(80.21, abs=5e-3)  # published 80.21
    assert sp.kind == "maximum"


def test_chemreact_rsm_vignette(chemreact):
    r = rsm_lrg.fit(chemreact, "Yield", factors=["Time=80:90", "Temp=170:180"], block="Block")
    lof = r.anova.set_index("source").loc["Lack of Fit"]
    assert lof["p"] == pytest.approx(0.69, abs=0.005)  # vignette: p ≈ 0.69
    sp = r.stationary_point
    assert sp.kind == "maximum" and sp.inside
    assert sp.coded["A"] == pytest.approx(0.3722954, abs=1e-6)  # R rsm xs (printed 7 digits)
    assert sp.coded["B"] == pytest.approx(0.3343802, abs=1e-6)
    assert round(sp.actual["Time"]) == 87 and round(sp.actual["Temp"]) == 177  # vignette
    # closed form -1/2 B^-1 b from the coefficient table (independent algebra)
    c = r.coefficients["coded"]
    b = np.array([c["A"], c["B"]])
    B = np.array([[c["A^2"], c["AB"] / 2], [c["AB"] / 2, c["B^2"]]])
    np.testing.assert_allclose([sp.coded["A"], sp.coded["B"]], -0.5 * np.linalg.solve(B, b), rtol=1e-12)
    np.testing.assert_allclose(sp.eigenvalues, sorted(np.linalg.eigvalsh(B), reverse=True), rtol=1e-12)
    # blocks: sum-to-zero effects, pure error within blocks (3 + 3 centre runs -> 4 df)
    assert sum(r.block_effects.values()) == pytest.approx(0.0, abs=1e-12)
    assert r.to_dict()["block_effects"].keys() == {"B1", "B2"}
    assert int(r.anova.set_index("source").loc["Pure Error", "df"]) == 4
    # Block SS (sequential, entered first) = between-block SS of the means
    m = chemreact.groupby("Block")["Yield"].mean()
    ss_b = 7 * ((m - chemreact.Yield.mean()) ** 2).sum()
    assert r.anova.set_index("source").loc["Block", "sum_sq"] == pytest.approx(ss_b, rel=1e-12)


def test_chemreact_slopes_match_treatment_coded_lstsq(chemreact):
    # R uses treatment contrasts for Block: only the intercept differs; the response-surface
    # coefficients must equal an independent lstsq with a 0/1 block dummy (1e-10).
    r = rsm_lrg.fit(chemreact, "Yield", factors=["Time=80:90", "Temp=170:180"], block="Block")
    x1 = (chemreact.Time - 85) / 5
    x2 = (chemreact.Temp - 175) / 5
    X = np.column_stack([np.ones(14), (chemreact.Block == "B2").astype(float), x1, x2, x1 * x2, x1 ** 2, x2 ** 2])
    b = np.linalg.lstsq(X, chemreact.Yield, rcond=None)[0]
    np.testing.assert_allclose(r.coefficients["coded"].to_numpy()[1:], b[2:], rtol=1e-9)
    # sum-to-zero intercept = treatment intercept + half the B2 effect
    assert r.coefficients.loc["Intercept", "coded"] == pytest.approx(b[0] + b[1] / 2, rel=1e-12)


def test_r_threshold_rule():
    # R rsm canonical(threshold=): eigenvalues below the threshold count as zero and the
    # stationary point is restricted to the remaining eigen-directions.
    from rsm_lrg.factors import FactorSpace
    from rsm_lrg.model.build.terms import model_terms
    from rsm_lrg.model.readings.canonical import canonical_analysis

    space = FactorSpace.from_ranges({"u": (-1, 1), "v": (-1, 1)})
    terms = model_terms(space.letters, "quadratic")
    coefs = {"Intercept": 1.0, "A": 1.0, "B": 2.0, "AB": 0.0, "A^2": -1.0, "B^2": -1e-6}
    exact = canonical_analysis(coefs, terms, space)
    assert exact.coded["B"] == pytest.approx(1e6)
    r_like = canonical_analysis(coefs, terms, space, threshold=1e-4)
    assert r_like.coded == pytest.approx({"A": 0.5, "B": 0.0})
    assert r_like.eigenvalues == (0.0, -1.0)
