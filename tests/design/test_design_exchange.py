"""The vectorised exchange step (issue 25: design search as fast as R's): the rank-two
updates that rank every (run, point) exchange at once agree with the exact criterion of each
exchanged design, and the Halton candidates are the published sequence."""

import numpy as np
import pytest

from rsm_lrg.design.exchange import (
    ExchangeProblem,
    _Rank2,
    candidate_pool,
    halton,
    information_criterion,
    moment_matrix,
)
from rsm_lrg.factors import FactorSpace
from rsm_lrg.terms import design_matrix, model_terms


def _exact(M, crit, W):
    """The criterion to minimise, by factorisation: -log det M, trace M^-1, trace M^-1 W."""
    if crit == "D":
        return -np.linalg.slogdet(M)[1]
    return float(np.trace(np.linalg.inv(M) if crit == "A" else np.linalg.solve(M, W)))


@pytest.mark.parametrize("crit", ["D", "I", "A"])
def test_batch_pairs_equal_the_exact_criterion_of_every_exchange(crit):
    space = FactorSpace.from_specs(["a=0:1", "b=0:1", "c=0:1"])
    terms = model_terms(space.letters, "quadratic")
    W = moment_matrix(space, terms) if crit == "I" else None
    prob = ExchangeProblem(space, terms, crit, W, None, candidate_pool(space, None, n=64, seed=3))
    rng = np.random.default_rng(0)
    D = rng.uniform(-1, 1, size=(14, 3))
    F = design_matrix(D, terms)
    M = F.T @ F
    # model rows of the fast path equal the general design matrix
    np.testing.assert_allclose(prob.rows(D), F, rtol=0, atol=1e-15)
    pts = rng.uniform(-1, 1, size=(40, 3))
    own = rng.integers(0, 14, size=40)
    G = design_matrix(pts, terms)
    fast = prob.batch_pairs(M, F, own, G)
    exact = np.array([_exact(M - np.outer(F[i], F[i]) + np.outer(g, g), crit, W) for i, g in zip(own, G)])
    np.testing.assert_allclose(fast, exact, rtol=1e-9)


def test_halton_is_the_radical_inverse_sequence():
    # Halton (1960): base 2 and 3 radical inverses of 1, 2, 3, ... (exact binary/ternary fractions)
    h = halton(8, 2, seed=None)
    np.testing.assert_array_equal(h[:, 0], [1 / 2, 1 / 4, 3 / 4, 1 / 8, 5 / 8, 3 / 8, 7 / 8, 1 / 16])
    np.testing.assert_allclose(h[:, 1], [1 / 3, 2 / 3, 1 / 9, 4 / 9, 7 / 9, 2 / 9, 5 / 9, 8 / 9], rtol=1e-15)
    shifted = halton(100, 5, seed=7)
    assert shifted.min() >= 0 and shifted.max() < 1
    np.testing.assert_array_equal(shifted, halton(100, 5, seed=7))  # the seed repeats it


@pytest.mark.parametrize("crit", ["D", "I", "A"])
def test_rank_two_updates_follow_a_sequence_of_exchanges(crit):
    # M^-1, K = A W A (A A for A), the criterion and the kept quadratic and cross forms after
    # twelve exchanges equal those of a fresh factorisation of the exchanged M
    space = FactorSpace.from_specs(["a=0:1", "b=0:1", "c=0:1"])
    terms = model_terms(space.letters, "quadratic")
    W = moment_matrix(space, terms) if crit == "I" else None
    rng = np.random.default_rng(5)
    F = design_matrix(rng.uniform(-1, 1, size=(16, 3)), terms)
    G = design_matrix(rng.uniform(-1, 1, size=(40, 3)), terms)
    st = _Rank2(crit, W)
    assert st.reset(F.T @ F)
    gq, xq = list(st.quad(G)), list(st.cross(G, F[15]))
    for step in range(12):
        i = step % 15  # run 15 stays: its cross forms with G are kept
        st.update(F[i].copy(), G[step])
        st.shift_quad(gq, st.projections(G))
        st.shift_cross(xq, st.projections(G), st.projections(F[15]))
        F[i] = G[step]
    M = F.T @ F
    fresh = _Rank2(crit, W)
    assert fresh.reset(M)
    np.testing.assert_allclose(st.A, np.linalg.inv(M), rtol=1e-9, atol=1e-9 * np.abs(fresh.A).max())
    assert st.base == pytest.approx(fresh.base, rel=1e-10)
    assert information_criterion(M, crit, W) == pytest.approx(-st.base if crit == "D" else st.base, rel=1e-10)
    for kept, new in zip(gq + xq, list(fresh.quad(G)) + list(fresh.cross(G, F[15]))):
        if new is None:
            assert kept is None and crit == "D"
            continue
        np.testing.assert_allclose(kept, new, rtol=1e-8, atol=1e-10 * np.abs(new).max())


def test_a_badly_conditioned_matrix_is_not_inverted():
    st = _Rank2("D", None)
    assert not st.reset(np.diag([1.0, 1e-10]))
    assert st.stale


@pytest.mark.parametrize("crit", ["D", "I"])
def test_fedorov_ends_where_no_exchange_of_a_run_for_a_candidate_gains(crit):
    # every (run, candidate) exchange, by exact factorisation: none improves the result
    space = FactorSpace.from_specs(["a=0:1", "b=0:1", "c=0:1"])
    terms = model_terms(space.letters, "quadratic")
    W = moment_matrix(space, terms) if crit == "I" else None
    prob = ExchangeProblem(space, terms, crit, W, None, candidate_pool(space, None, n=32, seed=1))
    start = prob.random_start(13, np.random.default_rng(2), grid=True)
    D, v = prob.fedorov(start, coarse=True)
    cands, G = prob.candidates, prob.cand_rows
    on = np.all(np.isin(cands, [-1.0, 0.0, 1.0]), axis=1)
    F = design_matrix(D, terms)
    M = F.T @ F + prob.ridge(len(D))
    assert v == pytest.approx(_exact(M, crit, W), rel=1e-12)
    assert v < prob.score(start)
    exchanged = [_exact(M - np.outer(f, f) + np.outer(g, g), crit, W) for f in F for g in G[on]]
    assert min(exchanged) >= v * (1 - 1e-9) if v > 0 else min(exchanged) >= v - 1e-9 * abs(v)
    # the same start gives the same design
    np.testing.assert_array_equal(prob.fedorov(start, coarse=True)[0], D)


def test_coordinate_exchange_ends_where_no_single_coordinate_move_gains():
    space = FactorSpace.from_specs(["a=0:1", "b=0:1", "c=0:1"])
    terms = model_terms(space.letters, "quadratic")
    prob = ExchangeProblem(space, terms, "D", None, None, candidate_pool(space, None, n=32, seed=1))
    start = np.random.default_rng(3).uniform(-1, 1, size=(12, 3))
    D, v = prob.exchange(start, polish=False)
    F = design_matrix(D, terms)
    M = F.T @ F + prob.ridge(len(D))
    assert v == pytest.approx(_exact(M, "D", None), rel=1e-12)
    for i in range(len(D)):
        for j in range(3):
            for level in np.linspace(-1, 1, 21):
                x = D[i].copy()
                x[j] = level
                g = design_matrix(x[None, :], terms)[0]
                assert _exact(M - np.outer(F[i], F[i]) + np.outer(g, g), "D", None) >= v - 1e-9 * abs(v)


def test_model_rows_of_a_cubic_model_equal_the_design_matrix():
    space = FactorSpace.from_specs(["a=0:1", "b=0:1", "c=0:1", "d=0:1"])
    terms = model_terms(space.letters, "cubic")
    prob = ExchangeProblem(space, terms, "D", None, None, candidate_pool(space, None, n=16, seed=1))
    X = np.random.default_rng(4).uniform(-1, 1, size=(30, 4))
    np.testing.assert_allclose(prob.rows(X), design_matrix(X, terms), rtol=1e-14, atol=1e-15)
    np.testing.assert_allclose(prob.rows(X.reshape(5, 6, 4)), design_matrix(X, terms).reshape(5, 6, -1), rtol=1e-14)


def test_grid_starts_only_where_the_grid_estimates_the_model():
    # x^3 equals x on -1/0/+1: a cubic model is singular on the grid, so grid starts and grid
    # candidates are the whole pool there; a quadratic is estimable on the grid
    space = FactorSpace.from_specs(["a=0:1", "b=0:1", "c=0:1"])
    pool = candidate_pool(space, None, n=64, seed=1)
    quad = ExchangeProblem(space, model_terms(space.letters, "quadratic"), "D", None, None, pool)
    cubic = ExchangeProblem(space, model_terms(space.letters, "cubic"), "D", None, None, pool)
    assert quad.grid_ok and not cubic.grid_ok
    assert len(quad._on_grid(pool)[0]) == 27 and len(cubic._on_grid(pool)[0]) == len(pool)
    D, v = cubic.improve(cubic.random_start(24, np.random.default_rng(0), grid=True), coarse=True)
    assert np.isfinite(v) and v == pytest.approx(cubic.score(D), rel=1e-12)
    assert np.linalg.matrix_rank(design_matrix(D, cubic.terms)) == cubic.p  # estimable, off the grid
