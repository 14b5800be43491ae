"""Term selection of a generalised linear model (issue 35, items 1 and 5): ``fit(...,
family=..., reduce=...)`` searches with likelihood-ratio p-values, AICc or BIC from the GLM's
likelihood (:class:`rsm_lrg.model.pipelines.glm.GLMScorer`).

References: R's ``step(glm, k = log(n))`` (forward, backward, stepwise; marginality kept, the
same hierarchy) on MASS::birthwt (binomial), pscl::bioChemists and warpbreaks (poisson),
``tests/model/r/glm_select.R`` -> ``glm_select_expected.csv``; all-subsets against an
enumeration written here (each hierarchical 2FI sub-model fitted by ``fit(..., terms=...)``).
"""

import itertools
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg

R = Path(__file__).parents[1] / "r"
CASES = {
    "birthwt": ("glm_select_birthwt.csv", "low", ["age", "lwt", "ptl", "ftv"], "binomial"),
    "biochem": ("glm_select_biochem.csv", "art", ["ment", "phd", "kid5"], "poisson"),
    "warpbreaks": ("glm_warpbreaks.csv", "breaks", ["wool=cat:A,B", "tension=cat:L,M,H"], "poisson"),
}
EXPECTED = pd.read_csv(R / "glm_select_expected.csv", keep_default_na=False)


def _fit(name, **kw):
    path, y, xs, fam = CASES[name]
    return rsm_lrg.fit(pd.read_csv(R / path), y, factors=xs, family=fam, **kw)


def _kept(res):
    return " ".join(sorted(t for t in res.reduction.kept if t != "Intercept"))


@pytest.mark.parametrize("name,direction,expected", [tuple(r) for r in EXPECTED.itertuples(index=False)])
def test_bic_selection_chooses_what_r_step_chooses(name, direction, expected):
    res = _fit(name, model="2fi", reduce={"method": direction, "criterion": "bic"})
    assert _kept(res) == expected
    assert {t.name for t in res.model_terms} == set(expected.split())
    assert res.model == "2fi" and res.to_dict()["reduction"]["method"] == direction


@pytest.mark.slow
@pytest.mark.parametrize("name", ["birthwt", "biochem"])
@pytest.mark.parametrize("criterion", ["aicc", "bic"])
def test_all_subsets_equals_an_enumeration(name, criterion):
    k = len(CASES[name][2])
    L = "ABCD"[:k]
    mains, pairs = list(L), [a + b for a, b in itertools.combinations(L, 2)]
    best = None
    for r in range(len(mains) + 1):
        for ms in itertools.combinations(mains, r):
            allowed = [p for p in pairs if p[0] in ms and p[1] in ms]
            for q in range(len(allowed) + 1):
                for ps in itertools.combinations(allowed, q):
                    ts = list(ms) + list(ps)
                    if not ts:
                        continue
                    st = _fit(name, terms=ts).statistics
                    v = st[criterion]
                    if best is None or v < best[0]:
                        best = (v, set(ts))
    res = _fit(name, model="2fi", reduce={"method": "all-subsets", "criterion": criterion})
    assert set(_kept(res).split()) == best[1]
    assert res.statistics[criterion] == pytest.approx(best[0], rel=1e-10)
    assert res.reduction.subsets.iloc[0][criterion] == pytest.approx(best[0], rel=1e-10)


def test_likelihood_ratio_backward_and_text():
    res = _fit("biochem", model="quadratic", reduce=True)
    steps = res.reduction.steps
    assert (steps.p > 0.1).all() and (steps.action == "remove").all()
    drop = res.anova.set_index("source").drop(index="Model")
    from rsm_lrg.model.choice.reduce import removable

    last = {t.name for t in removable(list(res.terms))}
    assert (drop.loc[sorted(last), "p"] <= 0.1).all()  # what is left and removable is significant
    assert "likelihood-ratio p > 0.1" in res.summary()


def test_separated_start_model_is_refused():
    df = pd.DataFrame({"x": np.arange(8.0), "z": [1, 3, 2, 4, 1, 3, 2, 4.0], "y": [0, 0, 0, 0, 1, 1, 1, 1]})
    from rsm_lrg.model.pipelines.glm import SeparationError

    with pytest.raises(SeparationError):
        rsm_lrg.fit(df, "y", model="linear", family="binomial", reduce="forward")
