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


@pytest.mark.parametrize("k", [0, 1, 2, 8, 9])
def test_wrong_number_of_factors(k):
    with pytest.raises(ValueError, match="3 to 7 factors"):
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
