"""``reproduce``: the paper side by side with the toolkit, each row with its tolerance.

Reference values are the paper's own printed numbers, read from the shipped data files
(Table 5, Eq. 19) or quoted in reproduce.py with their section; the tolerance rule is one
unit in the last printed digit unless a row says otherwise.
"""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from rsm_lrg.paper.reproduction import VERDICTS, Reproduction, _claim, _close, last_digit_unit, reproduce


@given(st.integers(0, 10**6), st.integers(0, 6))
def test_last_digit_unit_counts_printed_decimals(mantissa, decimals):
    printed = f"{mantissa / 10**decimals:.{decimals}f}"
    assert last_digit_unit(printed) == pytest.approx(10.0 ** -decimals, rel=1e-12)


def test_last_digit_unit_rejects_text():
    with pytest.raises(ValueError, match="cannot read"):
        last_digit_unit("about five")


def test_verdicts():
    assert _close("s", "q", "26.03", 26.0312).verdict == "pass"
    assert _close("s", "q", "26.03", 26.05).verdict == "FAIL"
    r = _close("s", "q", "26.03", 26.05, gap="input not given")
    assert (r.verdict, r.note) == ("not yet", "input not given")
    assert _close("s", "q", "26.03", 26.035, gap="input not given").verdict == "pass"  # a gap closes by itself
    assert _close("s", "q", "4.038", 2.8, tol=0.4038).verdict == "FAIL"
    assert _close("s", "q", "1.0", float("nan")).verdict == "FAIL"
    assert _claim("s", "q", "claim", "x", None, gap="not built").verdict == "not yet"
    assert _claim("s", "q", "claim", "x", False).verdict == "FAIL"


@pytest.fixture(scope="module")
def rep() -> Reproduction:
    messages = []
    r = reproduce(progress=messages.append)
    assert len(messages) == 5 and messages[0].startswith("[1/5]")
    return r


def _row(rep, text):
    hits = [r for r in rep.rows if text in r.quantity]
    assert hits, text
    return hits[0]


@pytest.mark.slow
def test_covers_what_the_issue_lists(rep):
    for text in ("heat source intensity Φ", "h, top and side faces", "h, front face", "steady temperature rise",
                 "time to thermal equilibrium", "RFCMS / RMS", "Fig. 9", "R² [-]", "optimum thickness_m",
                 "predicted κ at the optimum", "confirmation κ, 1.2 °C in 50 min", "prediction interval"):
        _row(rep, text)
    eq19 = [r for r in rep.rows if r.quantity.startswith("Eq. 19 coefficient")]
    assert len(eq19) == 15
    t5 = [r for r in rep.rows if r.section == "Table 5: ANOVA"]
    sources = {r.quantity.split(":")[0] for r in t5}
    assert {"Model", "A", "B", "C", "D", "AB", "AC", "AD", "BC", "BD", "CD", "A^2", "B^2", "C^2", "D^2",
            "Residual", "Lack of Fit", "Pure Error", "Cor Total"} <= sources


@pytest.mark.slow
def test_nothing_fails_and_every_gap_says_why(rep):
    assert set(r.verdict for r in rep.rows) <= set(VERDICTS)
    assert [r.quantity for r in rep.rows if r.verdict == "FAIL"] == []
    assert rep.ok
    for r in rep.rows:
        if r.verdict in ("not yet", "info"):
            assert len(r.note) > 20, r.quantity


@pytest.mark.slow
def test_paper_numbers_that_must_match(rep):
    # DIGEST §2 (checked): Phi 5.597e5 ("5.6 x 10^5"), h 8.82 and 22.45 W/(m^2 K)
    assert _row(rep, "heat source intensity Φ").verdict == "pass"
    assert _row(rep, "h, top and side faces").verdict == "pass"
    assert _row(rep, "h, front face").verdict == "pass"
    # Table 5 and Eq. 19 all within one unit of the last printed digit
    for r in rep.rows:
        if r.section in ("Table 5: ANOVA", "Eq. 19: coded coefficients of κ [°C/min]"):
            assert r.verdict == "pass", r
    # Section 4.3: F-order C > D > A > B; optimum at all-low corner; confirmation inside the PI
    assert _row(rep, "order of influence").toolkit == "C > D > A > B"
    assert _row(rep, "predicted κ at the optimum").toolkit_value == pytest.approx(0.022833, abs=5e-7)
    assert _row(rep, "prediction interval").verdict == "pass"
    assert _row(rep, "optimum acceleration_m_s2").toolkit_value == pytest.approx(20.0, abs=1e-9)


@pytest.mark.slow
def test_text_and_frame(rep):
    text = rep.to_text()
    assert text.splitlines()[0].split() == ["quantity", "paper", "toolkit", "rel.", "diff", "tolerance", "verdict"]
    assert "Rows that do not match, and why:" in text or rep.counts()["not yet"] == 0
    df = rep.to_frame()
    assert list(df.columns)[:4] == ["section", "quantity", "paper", "toolkit"]
    assert len(df) == len(rep.rows)
    d = rep.to_dict()
    assert d["ok"] is True and sum(d["counts"].values()) == len(rep.rows)


def test_the_deprecated_report_alias_is_gone():
    # issue 21, "the house": rsm_lrg.report.reproduce (deprecated in issue 11) imported the
    # paper layer from the report layer below it; it is removed, the report layer imports no
    # higher layer, and the reproduction is at rsm_lrg.paper
    import importlib.util

    import rsm_lrg.paper as paper

    assert importlib.util.find_spec("rsm_lrg.report.reproduce") is None
    assert paper.reproduce.__module__ == "rsm_lrg.paper.reproduction"


@pytest.mark.slow
def test_thermal_row_compares_the_maximum_rise_and_shows_every_case(rep):
    # issue 15, Build 4: like with like -- the FEM's 4.038 K is a maximum (Section 3.1); the
    # plausible rail lengths x boundaries of rsm_lrg.physics.paper_checks each with its sources
    # and the paper statements it cannot meet
    from rsm_lrg.physics.paper_checks import RAIL_BOUNDARIES, RAIL_LENGTHS_M

    main = _row(rep, "steady temperature rise, maximum")
    assert main.paper == "4.038" and main.verdict in ("pass", "not yet")
    assert "rail length" in main.note and "no plausible case meets both" in main.note
    cases = [r for r in rep.rows if r.quantity.startswith("thermal case:")]
    assert len(cases) == len(RAIL_LENGTHS_M) * len(RAIL_BOUNDARIES)
    for r in cases:
        assert r.verdict == "info" and "95 % at" in r.toolkit and "Rail:" in r.note and "Boundary:" in r.note
        assert "cannot meet" in r.note or "meets the rise and the time" in r.note
    # the default case's value is the main row's
    default = next(r for r in cases if "rail 0.4 m, adiabatic base" in r.quantity)
    assert default.toolkit_value == main.toolkit_value


@pytest.mark.slow
def test_wear_rows_show_each_reading_and_the_deflection_it_needs(rep):
    # issue 15, Build 4: Eq. 13 is linear in the sliding distance, so each reading of
    # Eqs. 13-17 fixes the hinge deflection: 30.8, 30.8, 15.4, 18.5, 7.7 mm at s = 0.075 m
    # (DIGEST §3; paper_checks.wear_readings, exact algebra), to 0.05 mm
    readings = [r for r in rep.rows if r.quantity.startswith("wear ratio 58.93 %, reading:")]
    assert [round(1e3 * r.toolkit_value, 1) for r in readings] == [30.8, 30.8, 15.4, 18.5, 7.7]
    for r in readings:
        assert "→ Δδ =" in r.toolkit and "held ends" in r.toolkit
    main = _row(rep, "wear volume per unit time, RFCMS / RMS")
    assert "7.7-30.8 mm" in main.note


@pytest.mark.slow
def test_surrogate_loo_is_reported_next_to_the_paper_press_r2(rep):
    # issue 15, Build 3: the calibrated surrogate's leave-one-out R2 beside Eq. 19's PRESS R2
    # (0.818: Table 4 refitted, DIGEST §5, to 0.0005)
    from rsm_lrg.datasets import data_path
    from rsm_lrg.surrogate.calibrate import load_calibration

    r = _row(rep, "surrogate leave-one-out R²")
    cal = load_calibration(data_path("calibration.toml"))
    assert r.paper.startswith("0.818")
    assert f"LOO R² {cal.loo_r2:.3f}" in r.toolkit
    assert r.verdict == ("pass" if cal.loo_r2 >= 0.8184 else "not yet")


@pytest.mark.slow
def test_fig9_wear_row_shows_both_motion_profiles(rep):
    # issue 15: the wear ordering of the Fig. 9 setting under the default trapezoidal strokes
    # (RFCMS slides 0.04-0.2 % more: frame ringing) and under 10 ms jerk-limited strokes
    # (RFCMS below RMS at every stroke), from the surrogate (tests/surrogate for the numbers)
    r = _row(rep, "Fig. 9 setting: wear of RFCMS / RMS")
    trap, scurve = r.toolkit.split("; S-curve 10 ms ")
    ratios = lambda text: [float(x.split(": ")[1]) for x in text.removeprefix("trapezoid ").split(", ")]  # noqa: E731
    assert all(v > 1 for v in ratios(trap)) and all(v < 1 for v in ratios(scurve))
    assert "Akribis" in r.note


@pytest.mark.slow
def test_rig_fatigue_and_fig9_rows(rep):
    # issue 34: both carriages on one rail and base (model v6), the working stage's rise at the 81 Table 3
    # settings within 5 K, the two-carriage heat balance to 1e-12, the contact-mechanics conductance beside
    # the fitted one, where a leaf yields and where it fails in fatigue, and Fig. 9 said plainly
    from rsm_lrg.datasets import data_path
    from rsm_lrg.surrogate.calibrate import load_calibration

    cal = load_calibration(data_path("calibration.toml"))
    assert cal.model in ("v6", "v6-alone") and cal.loo_models
    assert _row(rep, "the rig (model v6): both carriages").verdict == "info"
    assert _row(rep, "working stage rise in 50 min").verdict == "pass"
    assert _row(rep, "heat balance of the two-carriage network").verdict == "pass"
    c = _row(rep, "ball contacts, one side")
    assert "Hertz/Yovanovich 0.350" in c.toolkit
    fitted = next(p for p in cal.parameters if p.name == "ball_contact_conductance_w_k").value
    assert c.toolkit_value == pytest.approx(fitted, rel=1e-12) and 0.35 / 3 <= fitted <= 3 * 0.3505
    y = _row(rep, "leaf past yield in the Table 3 box")
    assert "y ≤ 0.10 mm" in y.toolkit and y.toolkit_value > 0
    f = _row(rep, "leaf fatigue in the Table 3 box")
    assert f.toolkit_value >= y.toolkit_value > 0 and "Goodman" in f.note
    # Fig. 9: the ordering is a pass only on the friction heat alone (no drive heat in model v6)
    fig9 = _row(rep, "Fig. 9: TCR of RMS > RFCMS")
    assert fig9.verdict in ("pass", "not yet")
    if fig9.verdict == "not yet":
        assert "said plainly" in fig9.note
    a = _row(rep, "what the model cannot explain: the thickness effect")
    assert a.toolkit_value < 0.00367
    loo = _row(rep, "surrogate leave-one-out R²")
    assert "inside every fold" in loo.note and "0.894" in loo.note


@pytest.mark.slow
def test_the_hybrid_is_printed_beside_the_polynomials(rep):
    # issue 34, item 4: the physics prior's LOO R² beside the quadratic's 0.818, linear + C²'s 0.894
    # and the physics alone, with a verdict that names the winner
    from rsm_lrg.paper.hybrid import hybrid_comparison

    h = hybrid_comparison()
    for name, r2, _ in h.rows:
        row = _row(rep, f"hybrid: {name} ")
        assert row.toolkit.startswith(f"{r2:.3f}") and row.verdict == "info"
    verdict = _row(rep, "hybrid: physics prior + polynomial discrepancy, verdict").toolkit
    assert "no hybrid beats linear + C² (0.894)" in verdict
