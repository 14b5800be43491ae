"""Augmenting designs: optimal runs for a bigger model, star + centre points, fold-over."""

import numpy as np
import pytest

from rsm_lrg.design import full_factorial
from rsm_lrg.design.augment import augment
from rsm_lrg.design.screening import alias_matrix, fractional_factorial
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
    with pytest.raises(ValueError, match="fold"):
        augment(d, "foldover", fold=["Z"])
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
