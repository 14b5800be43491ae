"""A practitioner's own data, not the paper's: R rsm's data set ``heli`` (Box & Draper's
paper-helicopter flight times, a 4-factor central composite design in 2 blocks, 30 runs), fitted
with blocks and compared with R 4.2.2, rsm 2.10 and MASS: coefficients, partial sums of
squares, lack of fit, canonical analysis, ridge path, per-run diagnostics and Box-Cox.

Reference: ``tests/model/r/heli.R`` (writes ``heli.csv`` and ``heli_expected.csv``; rerun it
with ``Rscript tests/model/r/heli.R``). Tolerances are stated per check."""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.model.readings.ridge import ridge

HERE = Path(__file__).parent / "r"
FACTORS = ["A", "R", "W", "L"]


@pytest.fixture(scope="module")
def heli():
    return pd.read_csv(HERE / "heli.csv")


@pytest.fixture(scope="module")
def fit(heli):
    return rsm_lrg.fit(heli, "ave", factors=FACTORS, block="block")


@pytest.fixture(scope="module")
def ref():
    e = pd.read_csv(HERE / "heli_expected.csv", dtype={"key": str})
    return {(q, k): v for q, k, v in e.itertuples(index=False)}


def _get(ref, quantity):
    return {k: v for (q, k), v in ref.items() if q == quantity}


def test_coefficients_and_standard_errors(fit, ref):
    # R lm with contr.sum blocks on the same coding (observed min..max -> -1..1): 1e-9 relative
    # (least squares in double precision; R and rsm-lrg solve different but exact systems)
    c = fit.coefficients
    for term, value in _get(ref, "coef_coded").items():
        if term == "block1":
            assert fit.block_effects["B1"] == pytest.approx(value, rel=1e-9)
        else:
            assert c.loc[term, "coded"] == pytest.approx(value, rel=1e-9, abs=1e-9)
    for term, value in _get(ref, "se_coded").items():
        if term != "block1":
            assert c.loc[term, "std_error"] == pytest.approx(value, rel=1e-9)


def test_partial_sums_of_squares_and_lack_of_fit(fit, ref):
    # R drop1 (partial = Type III SS per term) and rsm's lack-of-fit table: 1e-9 relative
    a = fit.anova.set_index("source")
    for term, value in _get(ref, "partial_ss").items():
        assert a.loc[term, "sum_sq"] == pytest.approx(value, rel=1e-9)
    for source, value in _get(ref, "anova_ss").items():
        assert a.loc[source, "sum_sq"] == pytest.approx(value, rel=1e-9)
    for source, value in _get(ref, "anova_df").items():
        assert a.loc[source, "df"] == value
    assert a.loc["Lack of Fit", "p"] == pytest.approx(ref[("anova_p", "Lack of Fit")], rel=1e-7)


def test_canonical_analysis(fit, ref):
    # rsm canonical(threshold = 0): stationary point (coded and actual), eigenvalues (1e-9
    # relative) and the block-averaged prediction there (1e-9 relative)
    sp = fit.stationary_point
    for letter, value in _get(ref, "stationary_coded").items():
        assert sp.coded[letter] == pytest.approx(value, rel=1e-9)
    for name, value in _get(ref, "stationary_actual").items():
        assert sp.actual[name] == pytest.approx(value, rel=1e-9)
    eig = [ref[("eigenvalue", str(i))] for i in range(1, 5)]
    np.testing.assert_allclose(sorted(sp.eigenvalues, reverse=True), eig, rtol=1e-9)
    assert sp.predicted == pytest.approx(ref[("stationary_predicted", "ave")], rel=1e-9)
    assert sp.kind == "saddle"


def test_ridge_path(fit, ref):
    # rsm steepest(dist = c(0, 0.5, 1)) returns coded points rounded to 3 decimals: 5e-4 + 1e-9
    path = ridge(fit, "maximize", radius=1.0, step=0.5)
    for i, dist in enumerate(["0", "0.5", "1"]):
        want = [ref[(f"ridge_coded_{dist}", L)] for L in "ABCD"]
        np.testing.assert_allclose(path.coded[i], want, atol=5e-4 + 1e-9)


def test_diagnostics_and_box_cox(fit, ref):
    # R hatvalues, rstudent, cooks.distance, dffits (1e-8 relative); MASS::boxcox on a 1e-4
    # grid over -3..3: lambda at the grid's end (3) and the lower 95 % LR limit (1e-4, the grid)
    diag = fit.diagnostics()
    t = diag.to_frame().set_index("run")
    for col, q in [("leverage", "leverage"), ("externally_studentized", "ext_studentized"),
                   ("cooks_distance", "cooks"), ("dffits", "dffits")]:
        for run, value in _get(ref, q).items():
            assert t.loc[int(run), col] == pytest.approx(value, rel=1e-8)
    bc = diag.box_cox
    assert bc.lambda_best == pytest.approx(ref[("boxcox", "lambda")], abs=1e-4)
    assert bc.ci[0] == pytest.approx(ref[("boxcox", "ci_low")], abs=1e-4)
    assert bc.recommended == "none"  # lambda = 1 inside the interval
