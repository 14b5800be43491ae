"""The printed equations reproduce the model (issue 10, item 4).

Reference: the fitted model itself (FitResult.predict, coded units). The printed actual-units
equation is parsed back into numbers and evaluated at random points of the factor box; it
must agree to 1e-6 relative wherever the prediction is at least a tenth of the largest fitted
value (text.EQUATION_ACCURACY = 1e-7 of that largest value, absolute, everywhere in the box).
"""

import itertools
import re

import numpy as np
import pandas as pd
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import rsm_lrg
from rsm_lrg.model.faces.text import EQUATION_ACCURACY, equation_terms, format_equation

LINE = re.compile(r"^\s+([+-]) (\S+)((?: \* \S+)*)$")


def parse_equation(text: str, names: list[str]):
    """The printed equation as a function of the actual settings (an (m, k) array)."""
    lines = text.splitlines()[1:]
    terms = []
    for ln in lines:
        m = LINE.match(ln)
        assert m, ln
        coef = float(m.group(2)) * (-1.0 if m.group(1) == "-" else 1.0)
        powers = [0] * len(names)
        for factor in filter(None, m.group(3).split(" * ")):
            name, _, e = factor.strip().partition("^")
            powers[names.index(name)] += int(e or 1)
        terms.append((coef, powers))

    def f(x):
        x = np.asarray(x, dtype=float)
        return sum(c * np.prod(x ** np.array(p), axis=1) for c, p in terms)

    return f, terms


def _grid_fit(scales, centres, coefs, noise_seed):
    k = len(scales)
    names = [f"x{i}_u" for i in range(k)]
    grid = np.array(list(itertools.product([-1.0, 0.0, 1.0], repeat=k)))
    actual = grid * scales + centres
    df = pd.DataFrame(actual, columns=names)
    rng = np.random.default_rng(noise_seed)
    y = coefs[0] + grid @ coefs[1:1 + k] + (grid ** 2) @ coefs[1 + k:1 + 2 * k]
    y = y + grid[:, 0] * grid[:, 1] * coefs[-1] + rng.normal(0, 0.01 * (1 + np.abs(coefs).max()), len(grid))
    df["y"] = y
    return rsm_lrg.fit(df, "y", factors=names), names


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    k=st.integers(2, 3),
    exps=st.lists(st.integers(-6, 7), min_size=3, max_size=3),
    offsets=st.lists(st.floats(-4, 4), min_size=3, max_size=3),
    coefs=st.lists(st.floats(-10, 10), min_size=8, max_size=8),
    seed=st.integers(0, 2 ** 16),
)
def test_printed_actual_equation_reproduces_predictions(k, exps, offsets, coefs, seed):
    scales = 10.0 ** np.array(exps[:k], dtype=float)
    centres = scales * np.array(offsets[:k])
    coefs = np.array(coefs[:1 + 2 * k] + coefs[-1:])
    r, names = _grid_fit(scales, centres, coefs, seed)
    f, terms = parse_equation(format_equation(r, "actual"), names)
    pts = np.random.default_rng(seed).uniform(-1, 1, size=(200, k)) * scales + centres
    pred = r.predict(pts)["predicted"].to_numpy()
    Y = np.abs(r.fitted).max()
    err = np.abs(f(pts) - pred)
    assert np.all(err <= 1e-6 * np.abs(pred) + EQUATION_ACCURACY * Y + 1e-12 * Y)
    big = np.abs(pred) >= 0.1 * Y
    assert np.all(err[big] <= 1e-6 * np.abs(pred[big]))
    # every actual coefficient that is not exactly zero is printed
    assert len(terms) == sum(1 for t in equation_terms(r, "actual"))
    assert {t.name for t in equation_terms(r, "actual")} >= {k_ for k_, v in r.actual_coefficients.items()
                                                             if v != 0.0 and abs(r.coefficients["coded"].get(k_, 1.0)) > 1e-9}


def test_issue_example_large_term_on_a_small_coefficient_is_printed():
    # thickness ~1e-4 m next to a frequency of a few Hz: the freq_Hz^2 coefficient -0.0625
    # is tiny beside the thickness coefficients (~1e4..1e8) but its term (-0.0625 * 16 = -1)
    # is as large as the intercept. The old writer printed "+ 0 * freq_Hz^2".
    grid = np.array(list(itertools.product([1e-4, 2e-4, 3e-4], [2.0, 4.0, 6.0])))
    df = pd.DataFrame(grid, columns=["thickness_m", "freq_Hz"])
    t, fz = df["thickness_m"], df["freq_Hz"]
    df["y"] = 1.0 + 5e3 * t + 2e7 * t ** 2 + 0.5 * fz - 0.0625 * fz ** 2 + 30.0 * t * fz
    r = rsm_lrg.fit(df, "y")
    text = format_equation(r, "actual")
    assert "- 0.0625 * freq_Hz^2" in text
    f, _ = parse_equation(text, ["thickness_m", "freq_Hz"])
    np.testing.assert_allclose(f(grid), df["y"], rtol=1e-9)


def test_table4_equations_keep_design_expert_zeros():
    # Paper Table 5 / Eq. 19: AB and BC are exactly 0 in coded units (Design-Expert prints
    # 0.000); their round-off is not printed in either equation, and nothing else is dropped.
    r = rsm_lrg.fit(rsm_lrg.load_table4(), "tcr_c_per_min")
    coded = {t.name for t in equation_terms(r, "coded")}
    assert "AB" not in coded and "BC" not in coded and len(coded) == 13
    actual = equation_terms(r, "actual")
    assert {t.name for t in actual} == coded
    f, _ = parse_equation(format_equation(r, "actual"), r.space.names)
    x = r.data[r.space.names].to_numpy(dtype=float)
    np.testing.assert_allclose(f(x), r.fitted, rtol=1e-6)


def test_units_argument_is_checked():
    r = rsm_lrg.fit(rsm_lrg.load_table4(), "tcr_c_per_min")
    with pytest.raises(ValueError, match="units must be"):
        equation_terms(r, "metric")
