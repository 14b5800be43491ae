"""Box-Behnken designs against the published designs (Box & Behnken 1960, Technometrics
2(4):455-475; factor sets as transcribed in R rsm's bbd(), R/bbd.R ``reftbl``)."""

from itertools import combinations

import numpy as np
import pytest
from _design_helpers import block_orthogonality, multiset
from pyDOE3 import bbdesign

from rsm_lrg.design import BBD_SETS, box_behnken


def space(k):
    return {f"x{i + 1}": (0.0, 1.0) for i in range(k)}


# Box & Behnken (1960): edge (non-centre) runs for k = 3..7 — exact counts.
PUBLISHED_EDGE_RUNS = {3: 12, 4: 24, 5: 40, 6: 48, 7: 56}


@pytest.mark.parametrize("k", [3, 4, 5, 6, 7])
@pytest.mark.parametrize("center", [0, 1, 3, 6])
def test_run_counts_are_the_published_ones(k, center):
    d = box_behnken(space(k), center=center, seed=0)
    assert d.n_runs == PUBLISHED_EDGE_RUNS[k] + center
    assert d.n_center == center
    assert d.options["edge_runs"] == PUBLISHED_EDGE_RUNS[k]


@pytest.mark.parametrize("k", [3, 4, 5, 6, 7])
def test_edge_runs_vary_two_or_three_factors_and_are_balanced(k):
    X = box_behnken(space(k), center=0, randomize=False).coded_runs
    m = 2 if k <= 5 else 3  # published: pairs for k <= 5, triples for k = 6, 7
    assert set(np.count_nonzero(X, axis=1).tolist()) == {m}
    assert set(np.unique(X).tolist()) == {-1.0, 0.0, 1.0}
    np.testing.assert_array_equal(X.sum(axis=0), 0.0)
    plus, minus = (X == 1).sum(axis=0), (X == -1).sum(axis=0)
    np.testing.assert_array_equal(plus, minus)
    assert len(set(plus.tolist())) == 1  # every factor at +1 (and -1) equally often
    # no duplicated edge runs
    assert len(set(map(tuple, X))) == X.shape[0]
    # all odd moments (x_i, x_i x_j, x_i^3, x_i x_j^2) vanish: first-order orthogonality
    for i, j in combinations(range(k), 2):
        assert np.dot(X[:, i], X[:, j]) == 0
        assert np.sum(X[:, i] * X[:, j] ** 2) == 0


def test_factor_sets_are_the_published_incomplete_block_designs():
    # k = 6: 6 triples, every factor in 3, pairs {1,4},{2,5},{3,6} twice (Box & Behnken 1960).
    s6 = BBD_SETS[6]
    assert s6 == ((1, 2, 4), (2, 3, 5), (3, 4, 6), (1, 4, 5), (2, 5, 6), (1, 3, 6))
    assert all(sum(f in t for t in s6) == 3 for f in range(1, 7))
    # k = 7: the Fano plane, every pair of the 7 factors in exactly one triple.
    s7 = BBD_SETS[7]
    pairs = [p for t in s7 for p in combinations(t, 2)]
    assert len(pairs) == 21 == len(set(pairs))
    # k = 3, 4, 5: all pairs.
    for k in (3, 4, 5):
        assert sorted(BBD_SETS[k]) == list(combinations(range(1, k + 1), 2))


@pytest.mark.parametrize("k", [3, 4, 5])
def test_same_runs_as_pydoe3_where_pydoe3_is_right(k):
    ours = box_behnken(space(k), center=2, randomize=False).coded_runs
    assert multiset(ours) == multiset(bbdesign(k, center=2))


@pytest.mark.parametrize("k,pydoe3_edge", [(6, 60), (7, 84)])
def test_pydoe3_differs_from_the_published_design_for_6_and_7(k, pydoe3_edge):
    # pyDOE3 pairs every two factors: C(k,2)*4 edge runs, not the published 48 / 56.
    assert bbdesign(k, center=0).shape[0] == pydoe3_edge
    assert box_behnken(space(k), center=0).n_runs == PUBLISHED_EDGE_RUNS[k]


@pytest.mark.parametrize("k", [4, 7])
def test_rotatable_for_4_and_7_factors(k):
    # Box & Behnken (1960): the 4- and 7-factor designs are exactly rotatable:
    # sum x_i^4 = 3 sum x_i^2 x_j^2 for every i != j (exact integer arithmetic).
    X = box_behnken(space(k), center=3, randomize=False).coded_runs
    for i, j in combinations(range(k), 2):
        assert np.sum(X[:, i] ** 4) == 3 * np.sum(X[:, i] ** 2 * X[:, j] ** 2)


@pytest.mark.parametrize("k,nb", [(4, 3), (5, 2)])
@pytest.mark.parametrize("center", [0, 1, 2, 5])
def test_published_blocking_is_orthogonal(k, nb, center):
    d = box_behnken(space(k), center=center, blocks=nb, seed=11)
    assert d.n_blocks == nb
    assert d.n_runs == PUBLISHED_EDGE_RUNS[k] + nb * center  # centre runs are per block
    counts = np.bincount(d.blocks)[1:]
    assert counts.tolist() == [PUBLISHED_EDGE_RUNS[k] // nb + center] * nb
    # block indicators orthogonal to every linear, interaction and quadratic column
    assert block_orthogonality(d.coded_runs, d.blocks) < 1e-12


def test_4_factor_blocks_are_pairs_of_disjoint_pairs():
    d = box_behnken(space(4), center=0, blocks=3, randomize=False)
    for b in (1, 2, 3):
        X = d.coded_runs[d.blocks == b]
        varied = {tuple(np.flatnonzero(r) + 1) for r in X}
        assert len(varied) == 2
        a, c = varied
        assert not set(a) & set(c)


def test_unblocked_designs_are_not_orthogonally_blocked_by_accident():
    # Sanity check of the helper: a random split into blocks is not orthogonal.
    d = box_behnken(space(4), center=0, randomize=False)
    rng = np.random.default_rng(0)
    fake = rng.integers(1, 4, size=d.n_runs)
    assert block_orthogonality(d.coded_runs, fake) > 0.1


@pytest.mark.parametrize("k,blocks", [(3, 2), (4, 2), (5, 3), (6, 2), (7, 2), (4, 4)])
def test_unpublished_blockings_are_refused(k, blocks):
    with pytest.raises(ValueError, match="block"):
        box_behnken(space(k), blocks=blocks)


@pytest.mark.parametrize("k", [0, 1, 2, 8, 13, 17])
def test_wrong_number_of_factors(k):
    with pytest.raises(ValueError, match="3 to 7, 9 to 12 or 16 factors"):
        box_behnken(space(k))


def test_negative_centre_points():
    with pytest.raises(ValueError, match="must not be negative"):
        box_behnken(space(3), center=-1)


def test_non_integer_centre_points():
    with pytest.raises((ValueError, TypeError)):
        box_behnken(space(3), center=1.5)


def test_same_seed_same_order_and_different_seeds_differ():
    a = box_behnken(space(4), center=3, seed=42).to_frame()
    b = box_behnken(space(4), center=3, seed=42).to_frame()
    c = box_behnken(space(4), center=3, seed=43).to_frame()
    assert a.equals(b)
    assert not a["std_order"].equals(c["std_order"])
    # a Generator is accepted; equal state -> equal order
    g = box_behnken(space(4), center=3, seed=np.random.default_rng(42)).to_frame()
    h = box_behnken(space(4), center=3, seed=np.random.default_rng(42)).to_frame()
    assert g.equals(h)


def test_randomised_within_blocks():
    d = box_behnken(space(4), center=2, blocks=3, seed=5)
    f = d.to_frame()
    # rows in run order, blocks consecutive and in order
    assert f["run_order"].tolist() == list(range(1, d.n_runs + 1))
    assert f["block"].tolist() == sorted(f["block"].tolist())
    # each block holds the same standard-order runs as without randomisation
    s = box_behnken(space(4), center=2, blocks=3, randomize=False).to_frame()
    for b in (1, 2, 3):
        assert sorted(f.loc[f.block == b, "std_order"]) == sorted(s.loc[s.block == b, "std_order"])
    assert not f["std_order"].equals(s["std_order"])


def test_no_randomize_is_standard_order():
    f = box_behnken(space(5), center=3, randomize=False).to_frame()
    assert f["std_order"].tolist() == f["run_order"].tolist() == list(range(1, 44))
    assert list(f.columns[:2]) == ["std_order", "run_order"]
    # centre runs last in standard order
    assert (f.iloc[-3:][[c for c in f.columns if c.startswith("coded_")]] == 0).all().all()


def test_seed_is_recorded_when_drawn():
    d = box_behnken(space(3))
    seed = d.options["seed"]
    assert isinstance(seed, int)
    assert box_behnken(space(3), seed=seed).to_frame().equals(d.to_frame())


def test_factor_inputs_are_equivalent():
    from rsm_lrg.factors import FactorSpace

    a = box_behnken({"p": (1, 3), "q": (0, 10), "r": (-1, 1)}, seed=1).to_frame()
    b = box_behnken(["p=1:3", "q=0:10", "r=-1:1"], seed=1).to_frame()
    c = box_behnken(FactorSpace.from_specs(["p=1:3", "q=0:10", "r=-1:1"]), seed=1).to_frame()
    assert a.equals(b) and b.equals(c)


def test_top_level_lazy_names():
    import rsm_lrg

    assert rsm_lrg.box_behnken is box_behnken
    for name in ("Design", "central_composite", "full_factorial", "read_design"):
        assert callable(getattr(rsm_lrg, name))


# --- 9 to 12 and 16 factors (issue 25) ------------------------------------------------------
# Box & Behnken (1960), Table: edge runs and the set size of each design; with the published
# centre runs (10, 10, 12, 12, 12) they are the published totals 130, 170, 188, 204, 396.
LARGE = {9: (120, 3, 10, 130), 10: (160, 4, 10, 170), 11: (176, 5, 12, 188), 12: (192, 4, 12, 204),
         16: (384, 4, 12, 396)}


@pytest.mark.parametrize("k", sorted(LARGE))
def test_large_designs_have_the_published_size_and_balance(k):
    edge, m, n0, total = LARGE[k]
    d = box_behnken(space(k), center=n0, randomize=False)
    assert d.n_runs == total and d.options["edge_runs"] == edge
    X = d.coded_runs[:edge]
    assert set(np.count_nonzero(X, axis=1).tolist()) == {m}  # each run varies one set of m factors
    assert set(np.unique(X).tolist()) == {-1.0, 0.0, 1.0}
    # no run repeated, but in the 9-factor design: its first parallel class (3 triples, 24 runs)
    # is run twice, as published
    assert len(set(map(tuple, X))) == (edge - 24 if k == 9 else edge)
    # balance: every factor at +1 and at -1 equally often, and equally often across factors
    plus, minus = (X == 1).sum(axis=0), (X == -1).sum(axis=0)
    np.testing.assert_array_equal(plus, minus)
    assert len(set(plus.tolist())) == 1
    # every factor in the same number r of sets (equal replication of the incomplete blocks)
    sets = BBD_SETS[k]
    r = {sum(f in s for s in sets) for f in range(1, k + 1)}
    assert len(r) == 1
    # the odd moments vanish: first-order orthogonal, and linear columns orthogonal to the
    # interaction and quadratic columns (x_i x_j^2, x_i x_j x_l sums 0)
    for i, j in combinations(range(k), 2):
        assert np.dot(X[:, i], X[:, j]) == 0
        assert np.sum(X[:, i] * X[:, j] ** 2) == 0
    # the full quadratic model is estimable with the centre runs
    cols = [np.ones(len(d.coded_runs))] + [d.coded_runs[:, i] for i in range(k)]
    cols += [d.coded_runs[:, i] * d.coded_runs[:, j] for i, j in combinations(range(k), 2)]
    cols += [d.coded_runs[:, i] ** 2 for i in range(k)]
    F = np.column_stack(cols)
    assert np.linalg.matrix_rank(F) == F.shape[1] == 1 + 2 * k + k * (k - 1) // 2


def test_large_designs_pair_structure_as_published():
    # 11 factors: the symmetric (11, 5, 2) BIBD (every pair in exactly two quintuples)
    pairs11 = [p for s in BBD_SETS[11] for p in combinations(s, 2)]
    assert all(pairs11.count(p) == 2 for p in combinations(range(1, 12), 2))
    # 9 factors: the 12 lines of the affine plane of order 3 (every pair once), plus its
    # first parallel class again (pairs within those triples twice)
    nine = BBD_SETS[9]
    plane = nine[:12]
    assert sorted(p for s in plane for p in combinations(s, 2)) == list(combinations(range(1, 10), 2))
    assert nine[12:] == nine[:3] and sorted(f for s in nine[:3] for f in s) == list(range(1, 10))
    # 10, 12, 16 factors: partially balanced (two pair counts), every pair varied together at
    # least once (so every interaction is estimable)
    for k in (10, 12, 16):
        counts = {sum(set(p) <= set(s) for s in BBD_SETS[k]) for p in combinations(range(1, k + 1), 2)}
        assert len(counts) == 2 and min(counts) >= 1, (k, counts)


def test_11_factor_sets_run_the_resolution_v_half_fraction():
    d = box_behnken(space(11), center=0, randomize=False)
    X = d.coded_runs[:16]  # the first set (3, 7, 8, 9, 11)
    cols = X[:, [2, 6, 7, 8, 10]]
    np.testing.assert_array_equal(np.prod(cols[:, :4], axis=1), cols[:, 4])  # E = ABCD
    assert len({tuple(r) for r in cols}) == 16


@pytest.mark.parametrize("k", [4, 7, 9, 10, 11, 12, 16])
def test_rotatable_only_for_4_and_7_factors(k):
    # Box & Behnken (1960): 4 and 7 factors are rotatable; the larger designs are not
    # ([iiii] = r 2^m / N against [iijj] = lambda 2^m / N: r = 3 lambda only for those two)
    X = box_behnken(space(k), center=3, randomize=False).coded_runs
    ratios = {float(np.sum(X[:, i] ** 4) / np.sum(X[:, i] ** 2 * X[:, j] ** 2))
              for i, j in combinations(range(k), 2) if np.sum(X[:, i] ** 2 * X[:, j] ** 2) > 0}
    if k in (4, 7):
        assert ratios == {3.0}
    else:
        assert 3.0 not in ratios or len(ratios) > 1
    if k == 11:  # a BIBD: one ratio r / lambda = 5 / 2 for every pair
        assert ratios == {2.5}


@pytest.mark.parametrize("k,nb", [(9, 5), (16, 6)])
def test_published_blocking_of_9_and_16_factors_is_orthogonal(k, nb):
    edge, _, _, _ = LARGE[k]
    d = box_behnken(space(k), center=2, blocks=nb, seed=3)
    assert d.n_blocks == nb and d.n_runs == edge + nb * 2
    assert np.bincount(d.blocks)[1:].tolist() == [edge // nb + 2] * nb
    assert block_orthogonality(d.coded_runs, d.blocks) < 1e-12


def test_cli_writes_a_16_factor_design(tmp_path):
    import pandas as pd

    from rsm_lrg.cli import main

    out = tmp_path / "bbd16.csv"
    argv = ["design", "box-behnken", "--center", "12", "--seed", "1", "-o", str(out)]
    for i in range(16):
        argv += ["--factor", f"f{i}=0:{i + 1}"]
    assert main(argv) == 0
    assert len(pd.read_csv(out)) == 396
