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
from rsm_lrg.model.readings.effects import half_normal_quantiles, lenth_margins, lenth_pse, screening_effects

R_EXPECTED = pd.read_csv(Path(__file__).parents[1] / "r" / "lenth_expected.csv")

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


# --- the largest estimable model (issue 25: effects' default on a fractional factorial) -------

def _word_product(a: str, b: str) -> str:
    """Product of two effect words modulo squares (A·AB = B): the alias arithmetic of a regular
    fraction, computed without the runs."""
    return "".join(sorted(set(a) ^ set(b)))


def _fraction(letters: str, generators: dict) -> np.ndarray:
    base = [L for L in letters if L not in generators]
    runs = np.array(list(itertools.product([-1.0, 1.0], repeat=len(base))))
    cols = {L: runs[:, i] for i, L in enumerate(base)}
    for L, word in generators.items():
        cols[L] = np.prod([cols[c] for c in word], axis=0)
    return np.column_stack([cols[L] for L in letters])


@pytest.mark.parametrize("letters,generators", [
    ("ABCDE", {"E": "ABCD"}),                 # 2^(5-1), resolution V (I = ABCDE)
    ("ABCDEFG", {"D": "AB", "E": "AC", "F": "BC", "G": "ABC"}),  # 2^(7-4), resolution III
    ("ABCDEF", {"E": "ABC", "F": "BCD"}),     # 2^(6-2), resolution IV
])
def test_largest_estimable_model_of_regular_fractions(letters, generators):
    from rsm_lrg.model.readings.effects import largest_estimable_model

    x = _fraction(letters, generators)
    m = largest_estimable_model(x, letters)
    n = len(x)
    assert len(m.terms) == n - 1  # saturated: every degree of freedom used
    assert set(letters) <= set(m.terms)  # every main effect kept
    # the defining relation from the generators (words of the group they generate)
    words = {""}
    for L, w in generators.items():
        words |= {_word_product(v, L + w) for v in words}
    words.discard("")
    assert {a.lstrip("-") for a in m.aliases["Intercept"]} == words  # I = the defining relation
    for t in m.terms:  # each kept term's chain is exactly t times each defining word
        expected = {_word_product(t, w) for w in words}
        got = {a.lstrip("-") for a in m.aliases.get(t, ())}
        assert got == expected, t
        # kept = the lowest order of its chain
        assert len(t) <= min(len(a) for a in expected)
    assert not m.partial  # a regular fraction has no partial aliasing
    # columns of the kept terms are mutually orthogonal
    X = np.column_stack([np.prod(x[:, [letters.index(c) for c in t]], axis=1) for t in m.terms])
    np.testing.assert_allclose(X.T @ X, n * np.eye(len(m.terms)))


def test_largest_estimable_model_full_factorial_and_plackett_burman():
    from rsm_lrg.design.screening import plackett_burman
    from rsm_lrg.model.readings.effects import largest_estimable_model

    full = np.array(list(itertools.product([-1.0, 1.0], repeat=4)))
    m = largest_estimable_model(full, "ABCD")
    assert len(m.terms) == 15 and not m.aliases and not m.partial
    # a 12-run Plackett-Burman in 8 factors: the two-factor interactions are partially aliased
    # with the main effects (Plackett & Burman 1946), so only the main effects are kept
    pb = plackett_burman({L: (0, 1) for L in "abcdefgh"}, randomize=False).coded_runs
    assert len(pb) == 12
    m = largest_estimable_model(pb, "ABCDEFGH")
    assert m.terms == tuple("ABCDEFGH") and "AB" in m.partial and not m.aliases
    # centre points change nothing; a room limit keeps fewer terms
    m = largest_estimable_model(np.vstack([full, np.zeros((3, 4))]), "ABCD", max_terms=10)
    assert len(m.terms) == 10 and m.terms[:4] == ("A", "B", "C", "D")


def test_effects_cli_default_is_the_largest_estimable_model(tmp_path, capsys):
    from rsm_lrg.cli import main

    x = _fraction("ABCDE", {"E": "ABCD"})
    y = 10 + 3 * x[:, 0] - 2 * x[:, 1] + 1.5 * x[:, 0] * x[:, 1] + 0.1 * np.sin(np.arange(16))
    df = pd.DataFrame(x, columns=list("pqrst")).assign(y=y)
    path = tmp_path / "ff.csv"
    df.to_csv(path, index=False)
    assert main(["effects", str(path), "--response", "y"]) == 0
    out = capsys.readouterr().out
    assert "15 one-df effects" in out and "AB = CDE" in out and "Active beyond SME: A, B, AB" in out
    assert main(["effects", str(path), "--response", "y", "--model", "full"]) == 2
    err = capsys.readouterr().err
    assert "16 runs cannot fit the full model (every interaction of 5 factors: 31 effects" in err
