"""The safe constraint parser (rsm_lrg.design.constraints)."""

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rsm_lrg.design.constraints import Constraints
from rsm_lrg.factors import FactorSpace

SP = FactorSpace.from_ranges([("velocity_m_s", 0.2, 1.0), ("acceleration_m_s2", 5.0, 20.0), ("stroke_m", 0.02, 0.1)])


def test_linear_by_letters_and_names_and_the_linear_system():
    c = Constraints.parse(["0.5*A + B <= 12", "stroke_m >= 0.03"], SP)
    assert c.is_linear and len(c) == 2
    X = np.array([[1.0, 11.0, 0.05], [1.0, 12.0, 0.05], [0.5, 10.0, 0.02]])
    assert c.feasible(X).tolist() == [True, False, False]
    A, b = c.linear_system(coded=False)
    np.testing.assert_allclose(A, [[0.5, 1, 0], [0, 0, -1]])
    np.testing.assert_allclose(b, [12, -0.03])
    # coded form agrees with the actual one at random coded points (exact linear map)
    Ac, bc = c.linear_system(coded=True)
    rng = np.random.default_rng(0)
    C = rng.uniform(-1, 1, (50, 3))
    Xa = SP.decode(C)
    np.testing.assert_allclose(C @ Ac.T - bc, Xa @ A.T - b, atol=1e-12)


def test_nonlinear_motion_profile_constraint_and_margin():
    c = Constraints.parse("velocity_m_s**2/acceleration_m_s2 <= stroke_m", SP)
    assert not c.is_linear
    df = pd.DataFrame({"velocity_m_s": [0.5, 1.0], "acceleration_m_s2": [10.0, 5.0], "stroke_m": [0.04, 0.06]})
    assert c.feasible(df).tolist() == [True, False]
    np.testing.assert_allclose(c.margin(df)[:, 0], [0.04 - 0.025, 0.06 - 0.2])
    assert c.feasible({"velocity_m_s": 0.5, "acceleration_m_s2": 10.0, "stroke_m": 0.025}).all()  # boundary


def test_chain_functions_and_caret_power():
    c = Constraints.parse(["0.3 <= A <= 0.8", "sqrt(A^2 + 0) <= max(B, 1)"], SP)
    assert len(c) == 3 and c.expressions[0] == "0.3 <= A"
    assert c.feasible([[0.5, 6, 0.05], [0.9, 6, 0.05], [0.2, 6, 0.05]]).tolist() == [True, False, False]


@pytest.mark.parametrize("expr, match", [
    ("A + B", "comparison"),
    ("A == 1", "only <="),
    ("A + Z <= 1", "unknown name 'Z'"),
    ("__import__('os').system('x') <= 1", "not allowed"),
    ("A.real <= 1", "not allowed"),
    ("A + <= 1", "not a valid expression"),
    ("1 <= 2", "no factor"),
    ("A + B >= 1000", "empty"),
    ("(lambda: 1)() <= A", "not allowed"),
    ("'x' <= A", "not a number"),
    ("", "empty expression"),
])
def test_bad_expressions_name_the_expression(expr, match):
    with pytest.raises(ValueError, match=match):
        Constraints.parse([expr], SP)


def test_categoric_factor_refused_and_undefined_points_infeasible():
    sp = FactorSpace.from_specs(["x=0:1", "stage=cat:a,b"])
    with pytest.raises(ValueError, match="categoric"):
        Constraints.parse("stage <= 1", sp)
    c = Constraints.parse("log(x) >= -3", sp)  # log(0) = -inf: outside
    assert c.feasible(np.array([[0.0, "a"], [0.5, "b"]], dtype=object)).tolist() == [False, True]


@settings(max_examples=50, deadline=None)
@given(st.floats(-5, 5), st.floats(-5, 5), st.floats(-5, 5))
def test_linear_feasibility_matches_direct_arithmetic(a, b, r):
    # property: the parsed expression gives the same side as plain arithmetic
    c = Constraints.parse([f"{a!r}*A + {b!r}*B <= {r!r}"], SP, check_empty=False)
    X = np.random.default_rng(1).uniform([0.2, 5, 0.02], [1, 20, 0.1], (30, 3))
    lhs = a * X[:, 0] + b * X[:, 1]
    sure = np.abs(lhs - r) > 1e-6 * (1 + np.abs(lhs) + abs(r))
    assert (c.feasible(X)[sure] == (lhs <= r)[sure]).all()
