"""Design criteria of ``evaluate_design`` (D-, A-, G-efficiency, the average prediction
variance I), the alias matrix / correlation map of model and potential terms, and
``compare_designs`` (issue 13 item 7), against closed forms and independent routes."""

import itertools

import numpy as np
import pytest

from rsm_lrg.design import box_behnken, central_composite, full_factorial
from rsm_lrg.design.optimal import criterion_value, moment_matrix
from rsm_lrg.design.screening import alias_matrix, fractional_factorial
from rsm_lrg.model.evaluate import compare_designs, evaluate_design
from rsm_lrg.terms import model_terms


def _gauss_moments(powers, npts=4):
    """W = E[f f'] over the uniform square [-1, 1]^k by tensor Gauss-Legendre (exact for the
    polynomial degrees here): an independent route from moment_matrix's closed form."""
    x, w = np.polynomial.legendre.leggauss(npts)
    k = powers.shape[1]
    P = np.array(list(itertools.product(x, repeat=k)))
    Wt = np.prod(np.array(list(itertools.product(w, repeat=k))), axis=1) / 2 ** k
    F = np.prod(P[:, None, :] ** powers[None, :, :], axis=2)
    return (F * Wt[:, None]).T @ F


def test_two_level_factorial_linear_is_fully_efficient_and_i_is_five_twelfths():
    # 2^2 factorial, linear model: X'X = 4 I, so D = A = G = 1 exactly; W = diag(1, 1/3, 1/3)
    # on the square, I = trace((X'X)^-1 W) = (1 + 2/3)/4 = 5/12 (exact).
    d = full_factorial(["a=0:1", "b=0:1"], levels=2, randomize=False)
    e = evaluate_design(d, "linear")
    assert e.d_efficiency == pytest.approx(1.0, rel=1e-12)
    assert e.a_efficiency == pytest.approx(1.0, rel=1e-12)
    assert e.g_efficiency == pytest.approx(1.0, rel=1e-9)
    assert e.i_average == pytest.approx(5 / 12, rel=1e-12)
    # the region sample's mean SPV approximates n*I (Sobol' sample of 4096 points: 1 %)
    assert e.spv_region["mean"] == pytest.approx(4 * 5 / 12, rel=1e-2)
    out = e.to_dict()
    assert out["spv_average"] == pytest.approx(5 / 3, rel=1e-12) and out["potential"] == "2fi"


def test_3x3_factorial_quadratic_criteria_by_independent_routes():
    d = full_factorial(["a=0:1", "b=0:1"], levels=3, randomize=False)
    t = model_terms("AB", "quadratic")
    e = evaluate_design(d, "quadratic")
    x = d.coded_runs
    X = np.column_stack([np.ones(9), x[:, 0], x[:, 1], x[:, 0] * x[:, 1], x[:, 0] ** 2, x[:, 1] ** 2])  # by hand
    M = X.T @ X
    assert e.d_efficiency == pytest.approx(np.linalg.det(M) ** (1 / 6) / 9, rel=1e-12)
    assert e.a_efficiency == pytest.approx(6 / (9 * np.trace(np.linalg.inv(M))), rel=1e-12)
    powers = np.array([[0, 0], [1, 0], [0, 1], [1, 1], [2, 0], [0, 2]])
    W = _gauss_moments(powers)
    assert e.i_average == pytest.approx(np.trace(np.linalg.solve(M, W)), rel=1e-12)
    # the same numbers as the optimal designs' criteria
    assert e.i_average == pytest.approx(criterion_value(x, t, "I", moment_matrix(d.factors, t)), rel=1e-12)
    assert e.d_efficiency == pytest.approx(criterion_value(x, t, "D"), rel=1e-12)
    assert e.potential == "cubic"


def test_alias_map_of_a_half_fraction():
    # 2^(3-1) with C = AB (I = ABC): each main effect is aliased with the other two factors'
    # interaction, alias-matrix entry 1 and correlation +1 (Box, Hunter & Hunter 2005, ch. 6)
    d = fractional_factorial(["a=0:1", "b=0:1", "c=0:1"], generators="A B AB", randomize=False)
    e = evaluate_design(d, "linear")
    A = e.alias_matrix
    assert A.loc["A", "BC"] == 1.0 and A.loc["B", "AC"] == 1.0 and A.loc["C", "AB"] == 1.0
    assert A.loc["A", "AB"] == 0.0 and np.all(A.loc["Intercept"] == 0.0)
    assert e.correlation.loc["A", "BC"] == pytest.approx(1.0, abs=1e-12)
    assert e.correlation.loc["A", "B"] == 0.0
    assert "[A] = A + 1.000 BC" in e.summary()
    # the same matrix as the screening designs' alias_matrix (a separate implementation)
    d4 = fractional_factorial(["a=0:1", "b=0:1", "c=0:1", "d=0:1"], generators="A B C AB", randomize=False)
    A0, fitted, pot = alias_matrix(d4.coded_runs, "ABCD", "linear", "2fi")
    e4 = evaluate_design(d4, "linear", potential="2fi")
    np.testing.assert_allclose(e4.alias_matrix.loc[fitted, pot].to_numpy(), A0, atol=1e-12)
    assert evaluate_design(d4, "linear", potential=None).alias_matrix is None


def test_compare_bbd_and_face_centred_ccd():
    f = ["a=0:1", "b=0:1", "c=0:1"]
    bbd = box_behnken(f, center=3, seed=1)
    fcd = central_composite(f, alpha="face", center=(1, 0), seed=1)
    assert bbd.n_runs == fcd.n_runs == 15
    c = compare_designs([bbd, fcd], "quadratic", names=["bbd", "fcd"])
    t = c.to_frame()
    for name, d in (("bbd", bbd), ("fcd", fcd)):
        e = evaluate_design(d, "quadratic")
        assert t.loc[name, "d_efficiency"] == pytest.approx(e.d_efficiency, rel=1e-12)
        assert t.loc[name, "g_efficiency"] == pytest.approx(e.g_efficiency, rel=1e-12)
        assert t.loc[name, "spv_average"] == pytest.approx(15 * e.i_average, rel=1e-12)
    for col in ("rel_d", "rel_a", "rel_g", "rel_i"):
        assert t[col].max() == pytest.approx(1.0, rel=1e-12) and (t[col] > 0).all()
    # the BBD has no corner runs: its SPV peaks at a cube corner, far above the FCD's
    # (max SPV 20.94 vs 11.96 by the exact boundary search), so its G-efficiency is lower
    assert t.loc["bbd", "spv_max"] > 1.5 * t.loc["fcd", "spv_max"]
    assert t.loc["bbd", "rel_g"] < 0.6
    d = c.to_dict()
    assert d["designs"] == ["bbd", "fcd"] and len(d["criteria"]) == 2 and len(d["evaluations"]) == 2
    assert "rel I" in c.summary()


def test_compare_errors():
    f = ["a=0:1", "b=0:1", "c=0:1"]
    bbd = box_behnken(f, center=3, seed=1)
    two = full_factorial(["a=0:1", "b=0:1"], levels=3, randomize=False)
    with pytest.raises(ValueError, match="small: has 2 factors"):
        compare_designs([bbd, two], names=["bbd", "small"])
    cube = full_factorial(f, levels=2, randomize=False)
    with pytest.raises(ValueError, match="cube: the quadratic model is not estimable"):
        compare_designs([bbd, cube], names=["bbd", "cube"])
    with pytest.raises(ValueError, match="at least two"):
        compare_designs([bbd])
    with pytest.raises(ValueError, match="potential"):
        evaluate_design(bbd, "quadratic", potential="linear")


@pytest.mark.slow
def test_correlation_lines_name_model_columns_only():
    # 12-run Plackett-Burman, 8 factors: each main effect is correlated +-1/3 with the 2FIs
    # that do not contain it (complex aliasing: Montgomery 2013, section 8.6.1; exact thirds, tol 1e-12);
    # its fold-over makes mains orthogonal to every 2FI. Pairs of two potential terms (AB ~ CD,
    # +-1/3 in both designs) say nothing about the linear model and are not listed.
    from rsm_lrg.design.augment import augment
    from rsm_lrg.design.screening import plackett_burman

    d = plackett_burman([f"x{i}=0:1" for i in range(8)], randomize=False)
    lines = evaluate_design(d, "linear", potential="2fi").summary().splitlines()
    start = next(i for i, t in enumerate(lines) if t.startswith("Largest correlations"))
    pairs = [t.strip() for t in lines[start + 1:] if " ~ " in t]
    assert pairs and all(p.split(" ~ ")[0] in "ABCDEFGH" for p in pairs)
    assert all(abs(abs(float(p.rsplit(": ", 1)[1])) - 1 / 3) < 1e-3 for p in pairs)
    e = evaluate_design(d, "linear", potential="2fi")
    assert abs(e.correlation.loc["A", "CF"]) == pytest.approx(1 / 3, abs=1e-12)
    folded = augment(d, "foldover", seed=1)
    text = evaluate_design(folded, "linear", potential="2fi").summary()
    assert "Largest correlations of model columns (with each other and with potential columns): none" in text
    assert " ~ " not in text
