"""Balanced split-plot factorials: when REML's estimate is inside the parameter space, REML is
the ANOVA estimator and the Kenward–Roger F tests are the classical split-plot F tests exactly
(Kenward & Roger 1997, Sec. 5): the whole-plot factor against the whole-plot error mean square
on G - 2 df, the sub-plot factor and the interaction against the sub-plot error on
n - G - 2 df (containment). Checked on random responses (hypothesis) by the sums of squares."""

import numpy as np
import pandas as pd
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import rsm_lrg


def _design(r: int, k: int) -> pd.DataFrame:
    """A (2 levels) on whole plots, r whole plots per level; B (2 levels) k times per level in each."""
    rows = []
    g = 0
    for a in (-1.0, 1.0):
        for _ in range(r):
            g += 1
            for b in (-1.0, 1.0):
                for _ in range(k):
                    rows.append({"wp": f"P{g}", "a": a, "b": b})
    return pd.DataFrame(rows)


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(r=st.integers(2, 4), k=st.integers(1, 2), seed=st.integers(0, 2**31 - 1),
       sd_wp=st.floats(0.3, 3.0))
def test_kr_equals_classical_split_plot_anova(r, k, seed, sd_wp):
    d = _design(r, k)
    rng = np.random.default_rng(seed)
    wp_eff = {w: rng.normal(0, sd_wp) for w in d.wp.unique()}
    d["y"] = 1.0 + 0.5 * d.a - 0.3 * d.b + d.wp.map(wp_eff) + rng.normal(0, 1.0, len(d))
    n, G = len(d), d.wp.nunique()
    # classical split-plot ANOVA by sums of squares
    ybar = d.y.mean()
    wmean = d.groupby("wp").y.transform("mean")
    amean = d.groupby("a").y.transform("mean")
    bmean = d.groupby("b").y.transform("mean")
    abmean = d.groupby(["a", "b"]).y.transform("mean")
    ss_a = float(((amean - ybar) ** 2).sum())
    ss_wpe = float(((wmean - amean) ** 2).sum())
    ss_b = float(((bmean - ybar) ** 2).sum())
    ss_ab = float(((abmean - amean - bmean + ybar) ** 2).sum())
    ss_tot = float(((d.y - ybar) ** 2).sum())
    ss_spe = ss_tot - ss_a - ss_wpe - ss_b - ss_ab
    df_wpe, df_spe = G - 2, n - G - 2
    ms_wpe, ms_spe = ss_wpe / df_wpe, ss_spe / df_spe
    m = n // G
    assume(ms_wpe > ms_spe * 1.05)  # REML's estimate inside (sigma2_wp = (MS_wpe - MS_spe) / m > 0)
    res = rsm_lrg.fit(d, "y", factors=["a", "b"], terms="A B AB", whole_plot="wp")
    assert res.mixed.sigma2 == pytest.approx(ms_spe, rel=1e-8)
    assert res.mixed.sigma2_group == pytest.approx((ms_wpe - ms_spe) / m, rel=1e-7)
    t = {x.term: x for x in res.tests}
    assert t["A"].den_df == pytest.approx(df_wpe, rel=1e-7)
    assert t["A"].f == pytest.approx(ss_a / ms_wpe, rel=1e-7)
    for term, ss in (("B", ss_b), ("AB", ss_ab)):
        assert t[term].den_df == pytest.approx(df_spe, rel=1e-7)
        assert t[term].f == pytest.approx(ss / ms_spe, rel=1e-7)
