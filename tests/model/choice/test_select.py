"""Term selection (issue 35, item 5): ``reduce="forward"|"backward"|"stepwise"|"all-subsets"``
by p, AICc or BIC, hierarchy kept (:mod:`rsm_lrg.model.choice.select`).

References:

* forward, backward and stepwise by BIC on 2FI models: R's ``step(k = log(n))`` (which keeps
  marginality, the same hierarchy), ``tests/model/r/select.R`` -> ``select_step_expected.csv``,
  on mtcars, swiss, stackloss (R datasets) and the paper's Table 4;
* all-subsets by AICc and BIC on quadratic models: an exhaustive enumeration written here
  (every subset of the terms, the hierarchical ones kept, each fitted by ``numpy.linalg.lstsq``);
* forward and stepwise by p: a greedy search written here from the textbook definition
  (partial F of the entering term in the model with it; Montgomery, *Introduction to Linear
  Regression Analysis*, 5th ed., sec. 10.2.2).
"""

import itertools
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from scipy import stats

import rsm_lrg
from rsm_lrg.model.build.spec import REDUCE_METHODS, ReduceSpec, SpecError

R = Path(__file__).parents[1] / "r"
ROOT = Path(__file__).parents[3]
CASES = {
    "mtcars": (R / "select_mtcars.csv", "mpg", ["wt", "hp", "qsec", "disp"]),
    "swiss": (R / "select_swiss.csv", "Fertility", ["Agriculture", "Examination", "Education", "Catholic"]),
    "stackloss": (R / "select_stackloss.csv", "stack.loss", ["Air.Flow", "Water.Temp", "Acid.Conc."]),
    "table4": (ROOT / "data" / "table4.csv", "tcr_c_per_min",
               ["thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2"]),
}


def _data(name):
    path, y, xs = CASES[name]
    return pd.read_csv(path), y, xs


def _fit(name, model, **reduce):
    df, y, xs = _data(name)
    return rsm_lrg.fit(df, y, factors=xs, model=model, reduce=reduce)


def _kept(res):
    return " ".join(sorted(t for t in res.reduction.kept if t != "Intercept"))


# -- R step() ---------------------------------------------------------------------------
STEP = pd.read_csv(R / "select_step_expected.csv", keep_default_na=False)


@pytest.mark.parametrize("name,direction,expected", [tuple(r) for r in STEP.itertuples(index=False)])
def test_bic_selection_chooses_what_r_step_chooses(name, direction, expected):
    res = _fit(name, "2fi", method=direction, criterion="bic")
    assert _kept(res) == expected


def test_backward_and_forward_differ_where_r_says_so():
    # swiss: the backward search stops at a larger local optimum than the forward one (R agrees)
    assert _kept(_fit("swiss", "2fi", method="backward", criterion="bic")) != \
        _kept(_fit("swiss", "2fi", method="forward", criterion="bic"))


# -- exhaustive enumeration ---------------------------------------------------------------
def _coded(df, xs):
    out = []
    for x in xs:
        v = df[x].to_numpy(dtype=float)
        lo, hi = v.min(), v.max()
        out.append(((v - lo) - (hi - v)) / (hi - lo))
    return np.column_stack(out)


def _quadratic_terms(k):
    """Exponent tuples of the quadratic model's terms (no intercept), with our names."""
    L = "ABCDEFG"[:k]
    terms = []
    for i in range(k):
        terms.append((tuple(int(j == i) for j in range(k)), L[i]))
    for i, j in itertools.combinations(range(k), 2):
        terms.append((tuple(int(m in (i, j)) for m in range(k)), L[i] + L[j]))
    for i in range(k):
        terms.append((tuple(2 * int(j == i) for j in range(k)), L[i] + "^2"))
    return terms


def _criteria(rss, n, p):
    K = p + 1
    base = n * math.log(rss / n) + n * math.log(2 * math.pi) + n
    return base + 2 * K + 2 * K * (K + 1) / (n - K - 1), base + K * math.log(n)


def _enumerate(name, hierarchy=True):
    """Every subset of the quadratic model's terms (hierarchical ones only when asked), fitted
    by lstsq: ``{frozenset(names): (aicc, bic)}``."""
    df, y, xs = _data(name)
    x, yv = _coded(df, xs), df[y].to_numpy(dtype=float)
    n, terms = len(yv), _quadratic_terms(len(xs))
    cols = {nm: np.prod(x ** np.array(e), axis=1) for e, nm in terms}
    out = {}
    for r in range(len(terms) + 1):
        for sub in itertools.combinations(terms, r):
            if hierarchy and any(all(a <= b for a, b in zip(e2, e)) and e2 != e and (e2, n2) not in sub
                                 for e, _ in sub for e2, n2 in terms):
                continue
            X = np.column_stack([np.ones(n)] + [cols[nm] for _, nm in sub])
            p = X.shape[1]
            if n - p - 2 <= 0:
                continue
            beta, *_ = np.linalg.lstsq(X, yv, rcond=None)
            rss = float(np.sum((yv - X @ beta) ** 2))
            out[frozenset(nm for _, nm in sub)] = _criteria(rss, n, p)
    return out


@pytest.mark.parametrize("name", ["mtcars", "stackloss", "table4"])
@pytest.mark.parametrize("criterion", ["aicc", "bic"])
def test_all_subsets_equals_an_exhaustive_enumeration(name, criterion):
    models = _enumerate(name)
    i = 0 if criterion == "aicc" else 1
    ranked = sorted(models.items(), key=lambda kv: kv[1][i])
    res = _fit(name, "quadratic", method="all-subsets", criterion=criterion)
    sel = res.reduction
    assert set(_kept(res).split()) == set(ranked[0][0])
    assert sel.n_compared == len(models) or sel.n_compared >= len(models)
    top = sel.subsets
    for r, (terms, crit) in zip(top.itertuples(), ranked[:len(top)]):
        assert set(r.terms.split()) == set(terms)
        assert (r.aicc, r.bic)[i] == pytest.approx(crit[i], rel=1e-9)
    # the fit carries the chosen terms only
    assert {t.name for t in res.model_terms} == set(ranked[0][0])


def test_all_subsets_without_hierarchy_is_the_plain_exhaustive_search():
    models = _enumerate("stackloss", hierarchy=False)
    best = min(models.items(), key=lambda kv: kv[1][1])
    res = _fit("stackloss", "quadratic", method="all-subsets", criterion="bic", hierarchy=False)
    assert set(_kept(res).split()) == set(best[0])
    assert res.reduction.n_compared == 2 ** 9


# -- p-value forward and stepwise -------------------------------------------------------------
def _greedy_p(name, alpha_in=0.1, alpha_out=0.1, stepwise=False):
    df, y, xs = _data(name)
    x, yv = _coded(df, xs), df[y].to_numpy(dtype=float)
    n, terms = len(yv), _quadratic_terms(len(xs))
    cols = {nm: np.prod(x ** np.array(e), axis=1) for e, nm in terms}
    expo = dict((nm, e) for e, nm in terms)

    def inside(a, b):
        return a != b and all(u <= v for u, v in zip(expo[a], expo[b]))

    def p_of(model, t):
        X1 = np.column_stack([np.ones(n)] + [cols[m] for m in model])
        X0 = np.column_stack([np.ones(n)] + [cols[m] for m in model if m != t])
        rss1 = np.sum((yv - X1 @ np.linalg.lstsq(X1, yv, rcond=None)[0]) ** 2)
        rss0 = np.sum((yv - X0 @ np.linalg.lstsq(X0, yv, rcond=None)[0]) ** 2)
        df1 = n - X1.shape[1]
        return stats.f.sf((rss0 - rss1) / (rss1 / df1), 1, df1)

    model = []
    while True:
        cand = [t for _, t in terms if t not in model and all(s in model for _, s in terms if inside(s, t))]
        scored = [(p_of(model + [t], t), t) for t in cand]
        if not scored or min(scored)[0] >= alpha_in:
            break
        model.append(min(scored)[1])
        while stepwise:
            drop = [t for t in model if not any(inside(t, u) for u in model)]
            worst = max((p_of(model, t), t) for t in drop)
            if worst[0] <= alpha_out:
                break
            model.remove(worst[1])
    return " ".join(sorted(model))


@pytest.mark.parametrize("name", ["mtcars", "swiss", "stackloss", "table4"])
@pytest.mark.parametrize("method", ["forward", "stepwise"])
def test_p_value_selection_equals_a_greedy_search(name, method):
    res = _fit(name, "quadratic", method=method, criterion="p", alpha_in=0.05, alpha_out=0.1)
    assert _kept(res) == _greedy_p(name, 0.05, 0.1, stepwise=method == "stepwise")
    steps = res.reduction.steps
    assert (steps[steps.action == "add"].p < 0.05).all()


# -- the rest ------------------------------------------------------------------------------
def test_backward_by_p_and_aicc_is_unchanged():
    df = rsm_lrg.load_table4()
    for crit in ("p", "aicc"):
        old = rsm_lrg.fit(df, "tcr_c_per_min", reduce={"criterion": crit})
        new = rsm_lrg.fit(df, "tcr_c_per_min", reduce={"criterion": crit, "method": "backward"})
        assert old.reduction.kept == new.reduction.kept and type(old.reduction).__name__ == "Reduction"


def test_selection_json_and_text():
    res = _fit("table4", "quadratic", method="all-subsets")
    d = res.to_dict()["reduction"]
    assert d["method"] == "all-subsets" and d["criterion"] == "aicc" and len(d["subsets"]) == 5
    assert d["subsets"][0]["rank"] == 1 and d["kept"][0] == "Intercept"
    assert res.reduction.describe().startswith("All-subsets selection (AICc, hierarchy kept): kept A B C D AC")


@pytest.mark.parametrize("value,param", [
    ({"method": "sideways"}, "reduce"), ({"method": "all-subsets", "criterion": "p"}, "criterion"),
    ({"criterion": "r2"}, "criterion"), ({"method": "stepwise", "alpha_in": 0.2, "alpha_out": 0.1}, "alpha_in"),
    ({"method": "forward", "alpha_in": 1.5}, "alpha_in"),
])
def test_bad_reduce_values_name_their_parameter(value, param):
    with pytest.raises(SpecError) as exc:
        ReduceSpec.build(value)
    assert exc.value.parameter == param


def test_methods_not_available_for_mixtures_and_reml():
    from rsm_lrg.datasets import load_mixture_etch

    with pytest.raises(SpecError, match="mixture model is reduced by backward"):
        rsm_lrg.fit(load_mixture_etch(), "erate", components=["x1", "x2", "x3"], model="mixture-quadratic",
                    reduce="forward")
    cake = pd.read_csv(ROOT / "data" / "cake_split_plot.csv")
    with pytest.raises(SpecError, match="Kenward-Roger"):
        rsm_lrg.fit(cake, "y", factors=["x1", "x2"], whole_plot="Ovenrun", reduce="stepwise")


def test_cli_choices_agree():
    from rsm_lrg.cli.options import REDUCE_METHOD_NAMES

    assert REDUCE_METHOD_NAMES == REDUCE_METHODS
