"""D-optimal blocked mixture and mixture-process designs (issue 35, item 3):
``mixture_optimal(..., blocks=N)`` and :mod:`rsm_lrg.design.mixture_blocks`.

The check is R AlgDesign's ``optBlock`` (blocks as fixed effects) on the same candidate sets
(``data/mixture_cand_*.csv``, written by ``data/make_mixture_candidates.py``):
``data/mixture_blocks.R`` keeps the best of 10 seeds x 50 repeats in
``data/mixture_blocks_expected.csv`` (the design as candidate rows and blocks, and optBlock's
``D = det(X_c'X_c / N)^(1/k)`` with ``X_c`` the model's non-constant columns centred in their
block). Ours must be at least as D-efficient on that criterion, recomputed here for both
designs from their runs (R's design reproduces R's figure first).

optBlock's figures (AlgDesign 1.2.1.2): quad3 0.010413550398717168, proc3 0.029620942637808831,
flare4 0.00030350067304880989.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from rsm_lrg.design.mixture_blocks import block_sizes, blocked_log_det
from rsm_lrg.design.mixture_optimal import mixture_optimal
from rsm_lrg.errors import ParameterError
from rsm_lrg.terms import design_matrix, parse_term, scheffe_names

DATA = Path(__file__).parent / "data"
sys.path.insert(0, str(DATA))
from make_mixture_candidates import CASES, candidates  # noqa: E402

#: case: (Scheffé model, optBlock's formula without its constant, as products of columns)
MODELS = {
    "quad3": ("mixture-quadratic", ["A", "B", "AB", "AC", "BC"]),
    "proc3": ("mixture-quadratic", ["A", "B", "AB", "AC", "BC", "D", "AD", "BD", "ABD", "ACD", "BCD"]),
    "flare4": ("special-cubic", ["A", "B", "C", "AB", "AC", "AD", "BC", "BD", "CD", "ABC", "ABD", "ACD", "BCD"]),
}
PUBLISHED = {"quad3": 0.010413550398717168, "proc3": 0.029620942637808831, "flare4": 0.00030350067304880989}


def optblock_d(coded: np.ndarray, blocks: np.ndarray, columns: list[str]) -> float:
    """optBlock's D of a design: ``det(X_c'X_c / N)^(1/k)``."""
    X = np.column_stack([np.prod([coded[:, "ABCD".index(c)] for c in col], axis=0) for col in columns])
    Xc = X.copy()
    for b in np.unique(blocks):
        Xc[blocks == b] -= X[blocks == b].mean(axis=0)
    sign, ld = np.linalg.slogdet(Xc.T @ Xc / len(X))
    assert sign > 0
    return float(np.exp(ld / X.shape[1]))


@pytest.mark.parametrize("case", list(MODELS))
def test_blocked_d_at_least_as_good_as_optblock(case):
    bounds, cons, k = CASES[case]
    model, columns = MODELS[case]
    exp = pd.read_csv(DATA / "mixture_blocks_expected.csv").set_index("case").loc[case]
    cand = pd.read_csv(DATA / f"mixture_cand_{case}.csv").to_numpy()
    np.testing.assert_allclose(candidates(case).to_numpy(), cand, rtol=0, atol=1e-15)
    rows = np.array(str(exp["rows"]).split(), dtype=int) - 1
    rblocks = np.array(str(exp["blocks"]).split(), dtype=int)
    theirs = optblock_d(cand[rows], rblocks, columns)
    assert theirs == pytest.approx(float(exp["d"]), rel=1e-10) == pytest.approx(PUBLISHED[case], rel=1e-10)
    sizes = [int(s) for s in str(exp["sizes"]).split()]
    d = mixture_optimal(bounds, model=model, criterion="D", constraints=cons, process=["t=20:40"] if k else None,
                        blocks=len(sizes), block_size=sizes, seed=11, starts=5)
    assert d.n_runs == sum(sizes) and d.n_blocks == len(sizes)
    assert [int(np.sum(d.blocks == b)) for b in range(1, len(sizes) + 1)] == sizes
    ours = optblock_d(d.coded_runs, d.blocks, columns)
    assert ours >= theirs * (1 - 1e-9), (ours, theirs)
    # every run is a candidate point, and the reported value is det(M)^(1/P)/n of the written runs
    assert all(np.any(np.all(np.abs(cand - x) <= 1e-12, axis=1)) for x in d.coded_runs)
    letters = d.factors.letters
    q = d.n_components
    terms = [parse_term(n, letters) for n in scheffe_names(letters[:q], model, letters[q:])]
    P = len(terms) + len(sizes) - 1
    ld = blocked_log_det(design_matrix(d.coded_runs, terms), d.blocks - 1, len(sizes))
    assert d.options["criterion_value"] == pytest.approx(np.exp(ld / P) / d.n_runs, rel=1e-9)


def test_blocking_equals_the_block_adjusted_criterion():
    """log det of [Scheffé | block contrasts] differs from optBlock's block-centred log det by a
    constant for fixed block sizes: two different designs keep their order and their gap."""
    bounds, cons, _ = CASES["quad3"]
    model, columns = MODELS["quad3"]
    gaps = []
    for seed in (1, 2, 3):
        d = mixture_optimal(bounds, model=model, criterion="D", constraints=cons, blocks=2, block_size=7, seed=seed,
                            starts=1)
        rng = np.random.default_rng(seed)
        coded = d.coded_runs[rng.permutation(d.n_runs)]  # a worse blocking of the same points
        for x, b in ((d.coded_runs, d.blocks), (coded, d.blocks)):
            letters = d.factors.letters
            terms = [parse_term(n, letters) for n in scheffe_names(letters[:3], model)]
            ld = blocked_log_det(design_matrix(x, terms), b - 1, 2)
            gaps.append(ld - len(columns) * np.log(optblock_d(x, b, columns)))
    np.testing.assert_allclose(gaps, gaps[0], rtol=0, atol=1e-9)


def test_csv_has_a_block_column_the_fit_reads(tmp_path):
    bounds, cons, _ = CASES["quad3"]
    d = mixture_optimal(bounds, model="mixture-quadratic", criterion="D", constraints=cons, blocks=2, seed=5,
                        starts=2)
    assert d.n_runs == 6 + 1 + 10 and sorted(np.bincount(d.blocks)[1:].tolist()) == [8, 9]
    frame = pd.read_csv(pd.io.common.StringIO(d.csv_text()))
    assert list(frame.columns[:3]) == ["std_order", "run_order", "block"]
    # randomised within blocks: block 1's runs first
    assert frame.block.is_monotonic_increasing
    import rsm_lrg

    rng = np.random.default_rng(0)
    frame["y"] = 3 * frame.a + 5 * frame.b + 4 * frame.c + 2 * frame.a * frame.b + 0.5 * frame.block \
        + rng.normal(0, 0.05, len(frame))
    res = rsm_lrg.fit(frame, "y", components=["a", "b", "c"], block="block", model="mixture-quadratic")
    assert res.n_blocks == 2 and "Block" in list(res.anova.source)


def test_bad_blocking_is_refused_by_name():
    bounds, cons, _ = CASES["quad3"]
    for kw, name in (({"blocks": 1}, "blocks"), ({"blocks": 2, "criterion": "I"}, "criterion"),
                     ({"blocks": 2, "replicates": 2}, "replicates"), ({"blocks": 2, "runs": 6}, "runs"),
                     ({"blocks": 2, "runs": 14, "block_size": [7, 6]}, "block_size"),
                     ({"block_size": 7}, "block_size")):
        args = {"model": "mixture-quadratic", "criterion": "D", "constraints": cons, "seed": 1, **kw}
        with pytest.raises(ParameterError) as err:
            mixture_optimal(bounds, **args)
        assert err.value.parameter == name, (kw, err.value)


def test_block_sizes():
    assert block_sizes(14, 3) == [5, 5, 4]
    assert block_sizes(12, 3, 4) == [4, 4, 4]
    assert block_sizes(12, 2, [5, 7]) == [5, 7]
