"""Augmenting designs: optimal runs for a bigger model, star + centre points, fold-over."""

import numpy as np
import pytest

from rsm_lrg.design import full_factorial
from rsm_lrg.design.augment import augment
from rsm_lrg.design.screening import alias_matrix, fractional_factorial
from rsm_lrg.errors import ParameterError
from rsm_lrg.terms import design_matrix, model_terms

CUBE = ["a=0:1", "b=10:20", "c=-1:1"]


def _base():
    return full_factorial(CUBE, levels=2, center=3, seed=1)  # 2^3 + 3 centre runs


def _originals_untouched(orig, aug):
    frame = aug.to_frame()
    first = frame.iloc[:orig.n_runs]
    o = orig.to_frame()
    np.testing.assert_array_equal(first[["coded_A", "coded_B", "coded_C"]].to_numpy(float),
                                  o[["coded_A", "coded_B", "coded_C"]].to_numpy(float))
    assert first["std_order"].tolist() == o["std_order"].tolist()
    assert first["run_order"].tolist() == list(range(1, orig.n_runs + 1))
    assert (frame["std_order"].iloc[orig.n_runs:] > orig.n_runs).all()


@pytest.mark.parametrize("crit", ["D", "I"])
def test_optimal_augment_makes_the_quadratic_estimable(crit):
    d = _base()
    t = model_terms(d.factors.letters, "quadratic")
    assert np.linalg.matrix_rank(design_matrix(d.coded_runs, t)) < len(t)  # squares aliased
    a = augment(d, "optimal", model="quadratic", criterion=crit, runs=6, seed=2, starts=2)
    assert a.n_runs == d.n_runs + 6
    assert np.linalg.matrix_rank(design_matrix(a.coded_runs, t)) == len(t)
    _originals_untouched(d, a)
    assert np.all(np.abs(a.coded_runs) <= 1.0)


def test_ccd_augment_gives_the_central_composite_design():
    d = _base()
    a = augment(d, "ccd", center=2, new_block=True, seed=1)
    alpha = 8 ** 0.25  # rotatable for a 2^3 cube (Box & Hunter 1957)
    star = a.coded_runs[a.blocks == 2]
    assert len(star) == 8 and a.n_blocks == 2
    nz = star[np.any(star != 0, axis=1)]
    assert sorted(np.abs(nz).max(axis=1).tolist()) == pytest.approx([alpha] * 6)
    _originals_untouched(d, a)
    t = model_terms(d.factors.letters, "quadratic")
    assert np.linalg.matrix_rank(design_matrix(a.coded_runs, t)) == len(t)


def test_foldover_clears_main_effects_of_2fi_aliases():
    # 2^(4-1)_III with D = AB: main effects aliased with 2FIs (alias matrix entries 1);
    # the full fold-over (Box, Hunter & Hunter 2005, section 6.8) clears every one
    d = fractional_factorial(["a=0:1", "b=0:1", "c=0:1", "d=0:1"], generators="A B C AB", randomize=False)
    A0, fitted, _ = alias_matrix(d.coded_runs, "ABCD", "linear", "2fi")
    mains = [fitted.index(L) for L in "ABCD"]
    assert np.abs(A0[mains]).max() == pytest.approx(1.0)
    f = augment(d, "foldover", seed=3)
    assert f.n_runs == 16
    A1, _, _ = alias_matrix(f.coded_runs, "ABCD", "linear", "2fi")
    assert np.abs(A1[mains]).max() == 0.0
    _originals_untouched_4 = f.coded_runs[:8]
    np.testing.assert_array_equal(_originals_untouched_4, d.coded_runs[np.argsort(d.run_order)])


def test_augment_errors():
    d = _base()
    with pytest.raises(ParameterError, match="'Z' is not a factor of the design") as info:
        augment(d, "foldover", fold=["Z"])
    assert info.value.parameter == "fold"
    with pytest.raises(ValueError, match="method"):
        augment(d, "magic")
    bbd = full_factorial(CUBE, levels=3, randomize=False)
    with pytest.raises(ValueError, match="two-level"):
        augment(bbd, "ccd")


def test_ccd_augment_of_a_crossed_factorial_adds_stars_per_level():
    d = full_factorial(["a=0:1", "b=0:1", "stage=cat:rfcms,rms"], levels=2, seed=1)
    a = augment(d, "ccd", center=1, seed=1)
    new = a.coded_runs[d.n_runs:]
    assert len(new) == 2 * (4 + 1) and a.options["alpha"] == pytest.approx(4 ** 0.25)  # 2^2 cube per level
    for lv in (0.0, 1.0):
        assert int(np.sum(new[:, 2] == lv)) == 5


# -- optimal augmentation in a new block: the block effect is a nuisance parameter -------------
# Existing runs: the 2^2 factorial + one centre run (block 1); the quadratic model in A, B
# (6 terms). Added runs form block 2. The references below are an exhaustive enumeration of
# every multiset of added runs from the 3 x 3 grid {-1, 0, 1}^2, with the block column written
# out by hand (+1 in block 1, -1 in block 2: the sum-to-zero coding the fit uses), independent
# of the exchange code.

import itertools  # noqa: E402

from rsm_lrg.design.optimal import moment_matrix  # noqa: E402

GRID3 = np.array(list(itertools.product([-1.0, 0.0, 1.0], repeat=2)))


def _square():
    return full_factorial(["a=0:1", "b=0:1"], levels=2, center=1, randomize=False)


def _block_value(coded, n_old, crit, with_block=True):
    """Criterion (to minimise) of coded runs, the first ``n_old`` in block 1, the rest in
    block 2; ``with_block=False`` ignores the blocks."""
    t = model_terms("AB", "quadratic")
    X = design_matrix(coded, t)
    p = X.shape[1]
    if with_block:
        X = np.column_stack([X, np.r_[np.ones(n_old), -np.ones(len(coded) - n_old)]])
    M = X.T @ X
    if np.linalg.matrix_rank(M) < M.shape[0]:
        return np.inf
    if crit == "D":
        return -np.linalg.slogdet(M)[1]
    V = np.linalg.inv(M)[:p, :p]  # model-term block of the inverse (block column dropped)
    if crit == "A":
        return float(np.trace(V))
    W = moment_matrix(_square().factors, t)
    return float(np.trace(V @ W))


def _enumerate(old, m, crit, with_block=True):
    """Best value and the best multisets of m added runs on the 3 x 3 grid."""
    vals = [(_block_value(np.vstack([old, GRID3[list(s)]]), len(old), crit, with_block), s)
            for s in itertools.combinations_with_replacement(range(9), m)]
    best = min(v for v, _ in vals)
    return best, [s for v, s in vals if v <= best + 1e-9 * max(1.0, abs(best))]


@pytest.mark.parametrize("crit, m", [("D", 4), ("A", 4), ("I", 5)])
def test_new_block_augment_matches_exhaustive_search_with_the_block(crit, m):
    d = _square()
    old = d.coded_runs
    best, sets = _enumerate(old, m, crit)
    a = augment(d, "optimal", model="quadratic", criterion=crit, runs=m, new_block=True, seed=1, starts=3)
    assert a.options["block_aware"] is True
    new = a.coded_runs[d.n_runs:]
    v = _block_value(a.coded_runs, d.n_runs, crit)
    # the exchange searches the continuous square, so it can only match or beat the grid's best;
    # in these cases the grid optimum is the optimum found (the added runs lie on the grid)
    assert v == pytest.approx(best, rel=1e-9, abs=1e-12)
    assert np.all(np.isin(new, (-1.0, 0.0, 1.0)))
    chosen = sorted(map(tuple, new.tolist()))
    assert chosen in [sorted(map(tuple, GRID3[list(s)].tolist())) for s in sets]
    # the reported criterion is the full-matrix one (D: det(M)^(1/7) / n with the block column)
    if crit == "D":
        assert a.options["criterion_value"] == pytest.approx(np.exp(-v / 7) / a.n_runs, rel=1e-9)
    else:
        assert a.options["criterion_value"] == pytest.approx(v, rel=1e-9)


def test_the_block_column_changes_the_d_optimal_choice():
    # 3 runs added in a new block. Enumeration on the 3 x 3 grid: the D-best multisets with the
    # block column (e.g. (-1,-1), (0,1), (1,0); -log det M = -9.47700) and without it (e.g. the
    # axial (-1,0), (0,-1), (0,1); -9.41638 when the block is then fitted) share no member, and
    # the block-ignoring choice loses a factor exp(0.0606) = 1.063 in det M once the block is
    # fitted. The block removes the added runs' mean from the information: only their spread
    # about their own mean (and the between-block contrast of the intercept) remains.
    d = _square()
    old = d.coded_runs
    best_b, sets_b = _enumerate(old, 3, "D", with_block=True)
    _, sets_u = _enumerate(old, 3, "D", with_block=False)
    assert not set(sets_b) & set(sets_u)
    ignored = min(_block_value(np.vstack([old, GRID3[list(s)]]), 5, "D") for s in sets_u)
    assert best_b == pytest.approx(-9.477003077, abs=1e-8)
    assert ignored == pytest.approx(-9.416378455, abs=1e-8)
    a = augment(d, "optimal", model="quadratic", criterion="D", runs=3, new_block=True, seed=1, starts=3)
    v = _block_value(a.coded_runs, 5, "D")
    assert v <= best_b + 1e-9  # continuous search: at least as good as the grid's best
    # the same search ignoring blocks (no new block) is worse once the block is fitted
    u = augment(d, "optimal", model="quadratic", criterion="D", runs=3, new_block=False, seed=1, starts=3)
    assert u.options["block_aware"] is False
    assert _block_value(u.coded_runs, 5, "D") > v + 0.05


def test_new_block_augment_keeps_the_runs_and_fits_with_the_block():
    from rsm_lrg.model import fit

    d = _base()  # 2^3 + 3 centre runs, randomised run order
    a = augment(d, "optimal", model="quadratic", criterion="I", runs=8, new_block=True, seed=4, starts=2)
    _originals_untouched(d, a)
    assert a.blocks[:d.n_runs].tolist() == [1] * d.n_runs and a.blocks[d.n_runs:].tolist() == [2] * 8
    frame = a.to_frame()
    x = a.coded_runs
    shift = np.where(a.blocks == 2, 3.0, 0.0)  # a block shift of 3 response units
    wiggle = 0.01 * np.sin(np.arange(a.n_runs))  # deterministic, so the fit has a residual
    frame["y"] = 10 + 2 * x[:, 0] - x[:, 1] + 0.5 * x[:, 0] * x[:, 2] + 1.5 * x[:, 1] ** 2 + shift + wiggle
    r = fit(frame, "y", factors=["a", "b", "c"], block="block", model="quadratic")
    coef = r.coefficients["coded"]
    assert np.all(np.isfinite(coef.to_numpy()))
    for term, b in {"A": 2.0, "B": -1.0, "AC": 0.5, "B^2": 1.5, "C^2": 0.0}.items():
        assert coef[term] == pytest.approx(b, abs=0.05)  # true surface, wiggle 0.01 per run
