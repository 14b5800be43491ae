"""Scheffé mixture and mixture-process models with fixed blocks (issue 35, item 3):
``fit(components=..., block=COL)`` against R ``lm``.

Reference numbers: ``tests/model/r/mixture_blocks.R`` (R 4.2.2, stats only; kept beside its
outputs ``mixture_blocks_*_expected.csv``) on two blocked designs made by
``r/make_mixture_blocks.py`` (rsm-lrg's D-optimal blocked designs, responses simulated from a
stated model): a three-component quadratic in 3 blocks of 7, and a quadratic crossed with a
process factor in 2 blocks of 12. Coefficients and standard errors to 1e-9 relative; the
ANOVA as Design-Expert computes a blocked mixture (Block removed first, Linear Mixture and the Model
after the blocks, the non-linear terms partial, lack of fit against the pure error of
``y ~ block + setting``) to 1e-9.
"""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.cli import main

R = Path(__file__).parent / "r"
CASES = {"quad3": ({"model": "mixture-quadratic"}, None),
         "proc3": ({"model": "mixture-quadratic"}, ["t"])}
_FITS: dict = {}


def _fit(name):
    if name not in _FITS:
        extra, process = CASES[name]
        _FITS[name] = rsm_lrg.fit(pd.read_csv(R / f"mixture_blocks_{name}.csv"), "y", components=["a", "b", "c"],
                                  factors=process, block="block", **extra)
    return _FITS[name]


@pytest.mark.parametrize("name", list(CASES))
def test_coefficients_match_lm(name):
    res = _fit(name)
    exp = pd.read_csv(R / "mixture_blocks_coef_expected.csv")
    exp = exp[exp.dataset == name].set_index("term")
    coef = res.coefficients
    assert sorted(coef.index) == sorted(exp.index)
    exp = exp.loc[coef.index]
    np.testing.assert_allclose(coef.coded, exp.estimate, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(coef.std_error, exp.std_error, rtol=1e-9)


@pytest.mark.parametrize("name", list(CASES))
def test_anova_matches_lm_blocks_first(name):
    res = _fit(name)
    exp = pd.read_csv(R / "mixture_blocks_anova_expected.csv")
    exp = exp[(exp.dataset == name) & (exp.df > 0)].set_index("source")
    ours = res.anova.set_index("source")
    assert sorted(ours.index) == sorted(exp.index)
    exp = exp.loc[ours.index]
    np.testing.assert_allclose(ours.sum_sq, exp.sum_sq, rtol=1e-9, atol=1e-9 * float(exp.sum_sq.max()))
    assert list(ours.df) == list(exp.df)
    tested = exp.f.notna()
    np.testing.assert_allclose(ours.f[tested], exp.f[tested], rtol=1e-8)
    np.testing.assert_allclose(ours.p[tested], exp.p[tested], rtol=1e-8, atol=1e-300)
    # R² without the blocks (Design-Expert): SS_model / (SS_model + SS_res)
    ss_m, ss_r = float(exp.sum_sq["Model"]), float(exp.sum_sq["Residual"])
    assert res.statistics.r2 == pytest.approx(ss_m / (ss_m + ss_r), rel=1e-10)


def test_blocks_change_the_fit_not_the_average_block_prediction_form(tmp_path, capsys):
    """The CLI prints the Block row and the block effects; the equation is the average block's."""
    path = R / "mixture_blocks_quad3.csv"
    out = tmp_path / "fit.json"
    assert main(["fit", str(path), "--response", "y", "--component", "a", "--component", "b", "--component", "c",
                 "--model", "mixture-quadratic", "--block", "block", "--json", str(out)]) == 0
    text = capsys.readouterr().out
    assert "Block " in text and "Block effects (sum to zero)" in text and "Linear Mixture" in text
    res = _fit("quad3")
    unblocked = rsm_lrg.fit(pd.read_csv(path), "y", components=["a", "b", "c"], model="mixture-quadratic")
    assert res.sigma2 < 0.3 * unblocked.sigma2  # the batch shifts (1.2, -0.7) are taken out


def test_block_column_refused_by_name():
    d = pd.read_csv(R / "mixture_blocks_quad3.csv")
    d.loc[3, "block"] = None
    with pytest.raises(ValueError, match="block column 'block', row 4: is empty"):
        rsm_lrg.fit(d, "y", components=["a", "b", "c"], block="block", model="mixture-quadratic")
