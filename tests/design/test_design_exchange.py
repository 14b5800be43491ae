"""The vectorised exchange step (issue 25: design search as fast as R's): the rank-two
updates that rank every (run, point) exchange at once agree with the exact criterion of each
exchanged design, and the Halton candidates are the published sequence."""

import numpy as np
import pytest

from rsm_lrg.design.exchange import ExchangeProblem, candidate_pool, halton, moment_matrix
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
