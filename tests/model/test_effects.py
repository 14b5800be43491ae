"""Effects of unreplicated two-level designs: Lenth's PSE, ME, SME and half-normal scores.

References: Montgomery (2013), *Design and Analysis of Experiments* 8th ed., Example 6.2 (the
filtration-rate 2^4: data and published effects); Lenth's own R package unrepx 1.0-2 for PSE
(``Lenth_pse``) on its published examples, with ME and SME from R's ``qt`` -- the script is
``r/lenth.R`` and its output ``r/lenth_expected.csv``.
"""

import itertools
from pathlib import Path
from statistics import NormalDist

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rsm_lrg import fit
from rsm_lrg.design.screening import definitive_screening
from rsm_lrg.model.effects import half_normal_quantiles, lenth_margins, lenth_pse, screening_effects

R_EXPECTED = pd.read_csv(Path(__file__).parent / "r" / "lenth_expected.csv")

# Montgomery Example 6.2: response at each treatment combination of the 2^4 (A temperature,
# B pressure, C concentration, D stirring rate)
FILTRATION = {"(1)": 45, "a": 71, "b": 48, "ab": 65, "c": 68, "ac": 60, "bc": 80, "abc": 65,
              "d": 43, "ad": 100, "bd": 45, "abd": 104, "cd": 75, "acd": 86, "bcd": 70, "abcd": 96}
# and the effects Montgomery publishes for it (Table 6.11)
PUBLISHED = {"A": 21.625, "B": 3.125, "AB": 0.125, "C": 9.875, "AC": -18.125, "BC": 2.375, "ABC": 1.875,
             "D": 14.625, "AD": 16.625, "BD": -0.375, "ABD": 4.125, "CD": -1.125, "ACD": -1.625,
             "BCD": -2.625, "ABCD": 1.375}
FACTORS = ["temperature=-1:1", "pressure=-1:1", "concentration=-1:1", "stirring=-1:1"]


def _filtration():
    rows = []
    for label, y in FILTRATION.items():
        s = "" if label == "(1)" else label
        rows.append({n.split("=")[0]: (1 if ch in s else -1) for n, ch in zip(FACTORS, "abcd")} | {"rate": y})
    return pd.DataFrame(rows)


def _saturated():
    terms = ["".join(c) for r in range(1, 5) for c in itertools.combinations("ABCD", r)]
    return fit(_filtration(), "rate", factors=FACTORS, terms=terms)


def test_effects_of_montgomery_example_6_2():
    eff = screening_effects(_saturated())
    got = dict(zip(eff.terms, eff.effects))
    assert set(got) == set(PUBLISHED)
    for term, value in PUBLISHED.items():
        assert got[term] == pytest.approx(value, abs=1e-12)
    r = R_EXPECTED.set_index("example").loc["montgomery62"]
    assert eff.pse == pytest.approx(r.pse, rel=1e-14)          # 2.625
    assert eff.me == pytest.approx(r.me, rel=1e-10)            # 6.748 (Montgomery: 6.75)
    assert eff.sme == pytest.approx(r.sme, rel=1e-10)          # 13.70 (Montgomery: 13.7)
    assert eff.df == 5.0
    # Montgomery's conclusion: A, C, D, AC, AD active
    assert set(eff.active) == {"A", "C", "D", "AC", "AD"}
    assert set(eff.active_simultaneous) == {"A", "D", "AC", "AD"}
    assert eff.notes == ()  # saturated and orthogonal: nothing to warn about


@pytest.mark.parametrize("example", list(R_EXPECTED.example))
def test_lenth_against_unrepx(example):
    r = R_EXPECTED.set_index("example").loc[example]
    e = np.array([float(v) for v in r.effects.split()])
    pse = lenth_pse(e)
    assert pse == pytest.approx(r.pse, rel=1e-14)
    me, sme, d = lenth_margins(pse, e.size)
    assert d == e.size / 3
    assert me == pytest.approx(r.me, rel=1e-10)
    assert sme == pytest.approx(r.sme, rel=1e-10)


@settings(max_examples=60, deadline=None)
@given(st.integers(min_value=1, max_value=200))
def test_half_normal_scores(m):
    q = half_normal_quantiles(m)
    assert np.all(np.diff(q) > 0) and q[0] > 0
    p = np.array([NormalDist().cdf(x) for x in q])
    assert np.allclose(p, 0.5 + 0.5 * (np.arange(1, m + 1) - 0.5) / m, atol=1e-12)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(min_value=-1e3, max_value=1e3, allow_nan=False), min_size=3, max_size=40),
       st.floats(min_value=0.01, max_value=100))
def test_pse_is_scale_equivariant_and_sign_blind(effects, c):
    e = np.array(effects)
    pse = lenth_pse(e)
    assert lenth_pse(-c * e) == pytest.approx(c * pse, rel=1e-12, abs=1e-300)
    assert pse <= 1.5 * np.median(np.abs(e)) * (1 + 1e-12)  # trimming only removes large effects


def test_scores_follow_the_ranks_and_the_frame_is_sorted():
    eff = screening_effects(_saturated())
    f = eff.to_frame()
    assert list(f.abs_effect) == sorted(f.abs_effect, reverse=True)
    assert np.allclose(np.sort(f.half_normal.to_numpy()), half_normal_quantiles(15))
    d = eff.to_dict()
    assert d["m"] == 15 and d["effects"][0]["term"] == "A" and d["active"] == list(eff.active)


def test_residual_df_and_unequal_variances_are_said():
    part = fit(_filtration(), "rate", factors=FACTORS, model="2fi")
    assert any("residual degrees of freedom" in n for n in screening_effects(part).notes)
    dsd = definitive_screening(["a=-1:1", "b=-1:1", "c=-1:1", "d=-1:1", "e=-1:1"], seed=1).to_frame()
    rng = np.random.default_rng(7)
    dsd["y"] = 3 * dsd["a"] - 2 * dsd["c"] + rng.normal(0, 0.1, len(dsd))
    eff = screening_effects(fit(dsd, "y", factors=["a=-1:1", "b=-1:1", "c=-1:1", "d=-1:1", "e=-1:1"], model="linear"))
    assert set(eff.active_simultaneous) == {"A", "C"}


def test_multi_df_terms_are_refused():
    df = _filtration()
    df["stage"] = ["x", "y", "z"] * 5 + ["x"]
    res = fit(df, "rate", factors=FACTORS[:2] + ["stage=cat"], model="linear")
    with pytest.raises(ValueError, match="degrees of freedom"):
        screening_effects(res)
