"""The GP beside the polynomial orders by leave-one-out (:mod:`rsm_lrg.model.choice.loo_compare`)."""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.model.choice.loo_compare import compare_loo, compare_with_polynomials

DATA = Path(__file__).parents[1] / "r" / "gp_branin.csv"
BRANIN = ["x1=-5:10", "x2=0:15"]


def test_rows_are_the_fit_summary_and_the_gp_loo():
    d = pd.read_csv(DATA)
    s = rsm_lrg.fit_summary(d, "y", factors=BRANIN)
    gp = rsm_lrg.fit(d, "y", factors=BRANIN, model="gp")
    c = compare_loo(s, gp)
    t = c.table.set_index("model")
    for r in s.statistics.itertuples(index=False):
        assert t.loc[r.source, "press"] == pytest.approx(r.press, rel=1e-12)
        assert t.loc[r.source, "pred_r2"] == pytest.approx(r.pred_r2, rel=1e-12)
    g = t.loc["GP (matern52, constant)"]
    assert g["press"] == pytest.approx(np.sum(gp.loo.residuals ** 2), rel=1e-12)
    # both predicted R² are 1 - PRESS / SS_total about the mean
    ss = float(np.sum((d.y - d.y.mean()) ** 2))
    assert g["pred_r2"] == pytest.approx(1 - g["press"] / ss, rel=1e-12)
    assert t.loc["Quadratic", "pred_r2"] == pytest.approx(1 - t.loc["Quadratic", "press"] / ss, rel=1e-9)
    # Branin on 20 runs: the GP's PRESS is below every polynomial's
    assert c.best == "GP (matern52, constant)"
    assert c.to_dict()["best"] == c.best and "Smallest PRESS" in c.summary()


def test_other_runs_refused():
    d = pd.read_csv(DATA)
    s = rsm_lrg.fit_summary(d, "y", factors=BRANIN)
    gp = rsm_lrg.fit(d.head(15), "y", factors=BRANIN, model="gp")
    with pytest.raises(ValueError, match="same runs"):
        compare_loo(s, gp)


def test_compare_with_polynomials_fits_them_on_the_gps_factors():
    # the GP's factors and ranges, not the columns' own: the same table as fit_summary with them
    d = pd.read_csv(DATA)
    gp = rsm_lrg.fit(d, "y", factors=BRANIN, model="gp")
    got = compare_with_polynomials(d, gp)
    want = compare_loo(rsm_lrg.fit_summary(d, "y", factors=BRANIN), gp)
    pd.testing.assert_frame_equal(got.table, want.table)
    assert got.best == want.best
    with pytest.raises(ValueError, match="same runs"):
        compare_with_polynomials(d.head(15), gp)
