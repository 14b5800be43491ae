"""rsm_lrg.report.region: the page's copy of --constraint/--bound agrees with Constraints."""

import math

import numpy as np
import pytest

from rsm_lrg.design.constraints import Constraints
from rsm_lrg.report.region import region_data


def _space():
    import pandas as pd

    from rsm_lrg.factors import choose_factors

    df = pd.DataFrame({"thickness_m": [1e-4, 5e-4], "stroke_m": [0.02, 0.10], "velocity_m_s": [0.2, 1.0],
                       "acceleration_m_s2": [5.0, 40.0], "y": [1.0, 2.0]})
    return choose_factors(df, None, exclude=["y"]).space


FUNCS = {"sqrt": math.sqrt, "exp": math.exp, "log": math.log, "log10": math.log10, "abs": abs, "min": min, "max": max}


def evaluate(t, s):
    """The tree as profiler.js's evalTree reads it."""
    if isinstance(t, float):
        return t
    if "f" in t:
        return s[t["f"]]
    if "call" in t:
        return FUNCS[t["call"]](*[evaluate(a, s) for a in t["args"]])
    a = evaluate(t["a"], s)
    if t["op"] == "neg":
        return -a
    b = evaluate(t["b"], s)
    ops = {"+": lambda: a + b, "-": lambda: a - b, "*": lambda: a * b, "/": lambda: a / b, "**": lambda: a ** b}
    return ops[t["op"]]()


@pytest.mark.parametrize("expr", [
    "velocity_m_s**2/acceleration_m_s2 <= stroke_m",   # the README's guide study
    "C^2 <= B*D",                                      # the same by letters, ^ for a power
    "-A*1000 + sqrt(B) >= 0.1 - max(C, 0.5)/10",
    "0.3 <= velocity_m_s <= 0.8",                      # a chain: two inequalities
])
def test_trees_agree_with_constraints_at_random_settings(expr):
    space = _space()
    region = region_data(space, [expr])
    parsed = Constraints.parse([expr], space, check_empty=False)
    assert len(region["constraints"]) == len(parsed)
    rng = np.random.default_rng(3)
    X = np.column_stack([rng.uniform(f.low, f.high, 500) for f in space.factors])
    want = parsed.margin(X)  # one column per inequality: rhs - lhs
    want = np.asarray(want).reshape(len(X), -1)
    for i, row in enumerate(X):
        s = dict(zip(space.names, row))
        for j, c in enumerate(region["constraints"]):
            got = evaluate(c["rhs"], s) - evaluate(c["lhs"], s)
            assert got == pytest.approx(want[i, j], rel=1e-12, abs=1e-15)


def test_bounds_are_two_inequalities_each():
    region = region_data(_space(), None, {"velocity_m_s": (0.3, 0.5)})
    assert [c["text"] for c in region["constraints"]] == ["velocity_m_s >= 0.3", "velocity_m_s <= 0.5"]
    s = {"velocity_m_s": 0.6}
    c = region["constraints"][1]
    assert evaluate(c["rhs"], s) - evaluate(c["lhs"], s) < 0


def test_nothing_given_is_no_region():
    assert region_data(_space()) is None


def test_a_bad_constraint_is_a_value_error():
    with pytest.raises(ValueError, match="unknown name"):
        region_data(_space(), ["speed <= 1"])
