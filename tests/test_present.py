"""``rsm_lrg.present``: the one number format, the p-value text and the round-off rule.

Reference values are exact decimal arithmetic (what a number must read as), the paper's
Table 5 formats (SS ``1.61 × 10⁻⁴``, F two decimals, p four decimals or ``<0.0001``) and
the Table 4 fit (ANOVA rows AB and BC are round-off, 2.5e-34 against a total of 1.14e-3).
"""

from __future__ import annotations

import re

import pandas as pd
import pytest
from hypothesis import given
from hypothesis import strategies as st

from rsm_lrg.present import ROUND_OFF, clean, clean_anova, format_number, format_p, format_sci

_SUP = str.maketrans("⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "-0123456789")


def _read(text: str) -> float:
    """Parse a number as :func:`format_number` writes it (either style)."""
    m = re.fullmatch(r"(-?[\d.]+)(?: × 10([⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+))?", text)
    if m:
        return float(f"{m.group(1)}e{m.group(2).translate(_SUP)}") if m.group(2) else float(m.group(1))
    return float(text)


finite = st.floats(allow_nan=False, allow_infinity=False, min_value=-1e300, max_value=1e300).filter(
    lambda x: x == 0 or abs(x) > 1e-300)


@given(finite, st.integers(1, 8))
def test_number_reads_back_to_its_significant_figures(x, digits):
    """Exact: the text is x rounded to ``digits`` significant figures (half a unit in the last place)."""
    for style in ("unicode", "ascii"):
        text = format_number(x, digits, style=style)
        assert _read(text) == pytest.approx(x, rel=0.5 * 10.0 ** (1 - digits) * (1 + 1e-9), abs=0.0), (text, style)


@given(finite, st.integers(1, 8))
def test_unicode_never_uses_e_notation_and_both_styles_agree(x, digits):
    u = format_number(x, digits)
    a = format_number(x, digits, style="ascii")
    assert "e" not in u
    assert _read(u) == _read(a)


def test_the_issue_examples_read_alike():
    # issue 10 item 9: '6.972e-05' next to '1.61 × 10⁻⁴' — one notation now
    assert format_number(6.972e-05) == "6.972 × 10⁻⁵"
    assert format_sci(1.61e-4) == "1.61 × 10⁻⁴"
    assert format_number(0.0001) == "0.0001"   # Table 3 thickness as printed
    assert format_number(0.033667, 5) == "0.033667"  # Eq. 19 intercept
    assert format_number(27) == "27" and format_number(True) == "yes" and format_number("x") == "x"
    assert format_number(float("nan"), missing="—") == "—" and format_number(None) == ""


def test_p_values_as_design_expert_prints_them():
    # Table 5: "<0.0001", "0.0390", "0.0880"
    assert [format_p(p) for p in (8.2e-7, 0.03896, 0.0880485, float("nan"))] == ["<0.0001", "0.0390", "0.0880", ""]
    assert format_p(3e-9, style="ascii") == "< 0.0001"


@given(st.floats(-1e6, 1e6, allow_nan=False), st.floats(1e-6, 1e6))
def test_round_off_rule(x, scale):
    c = clean(x, scale)
    assert c == (0.0 if abs(x) <= ROUND_OFF * scale else x)


def test_clean_anova_zeroes_round_off_rows_only():
    import rsm_lrg

    r = rsm_lrg.fit(rsm_lrg.load_table4(), "tcr_c_per_min")
    before = r.anova.copy()
    a = clean_anova(r.anova).set_index("source")
    pd.testing.assert_frame_equal(r.anova, before)  # the stored ANOVA is not changed
    raw = r.anova.set_index("source")
    total = raw.loc["Cor Total", "sum_sq"]
    for src in ("AB", "BC"):  # Table 5 prints 0.000 (exactly zero by the BBD's symmetry)
        assert abs(raw.loc[src, "sum_sq"]) <= ROUND_OFF * total
        assert (a.loc[src, "sum_sq"], a.loc[src, "mean_sq"], a.loc[src, "f"], a.loc[src, "p"]) == (0, 0, 0, 1)
    keep = [s for s in raw.index if s not in ("AB", "BC")]
    pd.testing.assert_frame_equal(a.loc[keep], raw.loc[keep])


def test_clean_anova_records_is_clean_anova_before_the_frame():
    from rsm_lrg.present import clean_anova_records, table_records

    nan = float("nan")
    rows = [{"source": "Model", "sum_sq": 1.0, "df": 3, "mean_sq": 0.33, "f": 9.0, "p": 0.01},
            {"source": "AB", "sum_sq": 2.5e-34, "df": 1, "mean_sq": 2.5e-34, "f": 7e-30, "p": 0.99},
            {"source": "BC", "sum_sq": -1e-20, "df": 1, "mean_sq": nan, "f": nan, "p": nan},
            {"source": "Residual", "sum_sq": 0.1, "df": 4, "mean_sq": 0.025, "f": nan, "p": nan},
            {"source": "Cor Total", "sum_sq": 1.1, "df": 8, "mean_sq": nan, "f": nan, "p": nan}]
    want = clean_anova(pd.DataFrame(rows))
    got = pd.DataFrame(clean_anova_records([dict(r) for r in rows]))
    pd.testing.assert_frame_equal(got, want, check_exact=True)
    assert want.loc[1, "p"] == 1.0 and want.loc[2, "sum_sq"] == 0.0 and want.loc[2, "f"] != want.loc[2, "f"]
    assert [(r.source, r.df) for r in table_records(want)] == [(r["source"], r["df"]) for r in rows]
