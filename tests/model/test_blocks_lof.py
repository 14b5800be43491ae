"""Pure error and lack of fit with blocks (issue 10, item 6) against R rsm 2.10.6.

Reference: ``tests/model/r/blocks_lof.R`` (``summary(rsm(y ~ Block + SO(...)))$lof``, whose
pure error is the residual of ``y ~ Block + PE(x1, ...)``) run on the CSVs beside it, output
``blocks_lof_expected.csv`` (17 digits). Tolerance 1e-9 relative.
"""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.model.choice.summary import fit_summary
from rsm_lrg.model.readings.anova import pure_error

R_DIR = Path(__file__).parent / "r"
CASES = {
    # name: (factors, model)
    "blocks_bbd3": (["temp_c", "time_min", "conc_pct"], "quadratic"),  # BBD run once in each of 2 blocks
    "blocks_ccd2": (["p_bar", "flow_l_min"], "quadratic"),  # CCD: factorial / axial blocks, centre in both
    "blocks_fact3": (["a_mm", "b_s", "c_k"], "2fi"),  # 2^3 + centres, uneven over 3 blocks
}
ROWS = {"Residuals": "Residual", "Lack of fit": "Lack of Fit", "Pure error": "Pure Error"}


def _expected(name):
    ref = pd.read_csv(R_DIR / "blocks_lof_expected.csv")
    return ref[ref.dataset == name].set_index("source")


@pytest.mark.parametrize("name", sorted(CASES))
def test_fit_lack_of_fit_matches_r_rsm(name):
    factors, model = CASES[name]
    d = pd.read_csv(R_DIR / f"{name}.csv")
    r = rsm_lrg.fit(d, "y", factors=factors, block="Block", model=model)
    an = r.anova.set_index("source")
    ref = _expected(name)
    for r_name, ours in ROWS.items():
        assert an.loc[ours, "df"] == ref.loc[r_name, "df"], r_name
        assert an.loc[ours, "sum_sq"] == pytest.approx(ref.loc[r_name, "sum_sq"], rel=1e-9), r_name
    assert an.loc["Lack of Fit", "f"] == pytest.approx(ref.loc["Lack of fit", "f"], rel=1e-9)
    assert an.loc["Lack of Fit", "p"] == pytest.approx(ref.loc["Lack of fit", "p"], rel=1e-9)


@pytest.mark.parametrize("name", sorted(CASES))
def test_fit_summary_lack_of_fit_matches_r_rsm(name):
    factors, model = CASES[name]
    d = pd.read_csv(R_DIR / f"{name}.csv")
    s = fit_summary(d, "y", factors=factors, block="Block")
    lof = s.lack_of_fit.set_index("source")
    ref = _expected(name)
    label = {"quadratic": "Quadratic", "2fi": "2FI"}[model]
    assert lof.loc[label, "df"] == ref.loc["Lack of fit", "df"]
    assert lof.loc[label, "sum_sq"] == pytest.approx(ref.loc["Lack of fit", "sum_sq"], rel=1e-9)
    assert lof.loc[label, "p"] == pytest.approx(ref.loc["Lack of fit", "p"], rel=1e-9)
    assert lof.loc["Pure Error", "df"] == ref.loc["Pure error", "df"]
    assert lof.loc["Pure Error", "sum_sq"] == pytest.approx(ref.loc["Pure error", "sum_sq"], rel=1e-9)


def test_replicated_in_two_blocks_has_pure_error():
    # The BBD run once per block: no setting repeats inside a block (except the centre),
    # yet 13 distinct settings in 30 runs with 1 block df leave 16 df of pure error.
    d = pd.read_csv(R_DIR / "blocks_bbd3.csv")
    r = rsm_lrg.fit(d, "y", factors=CASES["blocks_bbd3"][0], block="Block")
    assert r.pure_error.df == 30 - 13 - 1 and r.pure_error.n_groups == 13 and r.pure_error.block_df == 1


def test_without_blocks_pure_error_is_within_group_ss():
    # Myers, Montgomery & Anderson-Cook Sec. 2.7: SS_PE = sum over groups of (y - group mean)^2,
    # df = n - (number of distinct settings); the block argument absent or with one level
    # changes nothing.
    rng = np.random.default_rng(3)
    keys = rng.integers(0, 4, size=(40, 2)).astype(float)
    y = rng.normal(size=40)
    pe = pure_error(keys, y)
    g = pd.Series(y).groupby([keys[:, 0], keys[:, 1]])
    ref = float(sum(((v - v.mean()) ** 2).sum() for _, v in g))
    assert pe.ss == pytest.approx(ref, rel=1e-12) and pe.df == 40 - g.ngroups and pe.block_df == 0
    one = pure_error(keys, y, blocks=np.zeros(40, dtype=int))
    assert one.ss == pe.ss and one.df == pe.df


def test_blocks_without_shared_settings_add_no_block_df():
    # Every setting in one block only: the block effects are absorbed by the setting means,
    # so pure error is the within-group SS again.
    keys = np.repeat(np.arange(6.0), 2)[:, None]
    y = np.arange(12.0) ** 1.5
    blocks = (np.arange(12) >= 6).astype(int)
    a, b = pure_error(keys, y), pure_error(keys, y, blocks)
    assert b.block_df == 0 and b.df == a.df == 6 and b.ss == pytest.approx(a.ss, rel=1e-12)


@pytest.mark.parametrize("name", sorted(CASES))
def test_actual_coefficients_and_block_contrasts_match_r_rsm(name):
    # R rsm fits SO()/FO()+TWI() in actual units (blocks_coef_expected.csv, same script):
    # every factor coefficient equals rsm-lrg's actual-units coefficient to 1e-9, and R's
    # treatment contrast BlockK equals our (sum-to-zero) effect of block K minus block 1.
    factors, model = CASES[name]
    d = pd.read_csv(R_DIR / f"{name}.csv")
    r = rsm_lrg.fit(d, "y", factors=factors, block="Block", model=model)
    ref = pd.read_csv(R_DIR / "blocks_coef_expected.csv")
    ref = ref[ref.dataset == name].set_index("term")["estimate"]
    letter = dict(zip(factors, r.space.letters))
    checked = 0
    for term, value in ref.items():
        if term == "(Intercept)":
            continue
        if term.startswith("Block"):
            k = int(term[len("Block"):])
            ours = r.block_effects[f"B{k}"] - r.block_effects["B1"]
        else:
            inner, rest = term.split(")", 1)
            parts = rest.split(":") if rest else [f.strip() for f in inner.split("(", 1)[1].split(",")]
            ours_name = "".join(letter[p.split("^")[0]] + ("^" + p.split("^")[1] if "^" in p else "") for p in parts)
            ours = r.actual_coefficients[ours_name]
        assert ours == pytest.approx(value, rel=1e-9), term
        checked += 1
    assert checked == len(ref) - 1
