"""The HTML report of a fit: the paper's numbers on the page, every section, escaping, safe writes.

Reference numbers: the paper's Table 5 (data/table5_anova.csv: F values printed with two
decimals, p values with four) and Eq. 19 (data/equation19_coded.csv, coefficients to five
decimals; DIGEST.md: refitting Table 4 matches every coefficient to 5 decimals).
"""

from __future__ import annotations

import itertools
import re

import numpy as np
import pandas as pd
import pytest
from _html_tables import read  # noqa: E402  (tests/report is on sys.path under pytest)

import rsm_lrg
from rsm_lrg.report import SECTION_IDS, report_context, to_html, write_report


@pytest.fixture(scope="module")
def table4_fit():
    return rsm_lrg.fit(rsm_lrg.load_table4(), "tcr_c_per_min")


@pytest.fixture(scope="module")
def table4_html(table4_fit):
    return to_html(table4_fit, source_name="data/table4.csv")


@pytest.fixture(scope="module")
def page(table4_html):
    return read(table4_html)


def test_every_section_is_there(page):
    for sid in SECTION_IDS:
        assert sid in page.text_by_id, sid


def test_six_surfaces_six_contours_six_diagnostics(page):
    ids = {a.get("id") for _, a in page.attrs}
    pairs = ["".join(p) for p in itertools.combinations("ABCD", 2)]
    for p in pairs:
        assert f"fig-surface-{p}" in ids and f"fig-contour-{p}" in ids
    for key in ("normal-plot", "residuals-vs-predicted", "residuals-vs-run", "predicted-vs-actual",
                "cooks-distance", "leverage"):
        assert f"fig-{key}" in ids
    imgs = [a for t, a in page.attrs if t == "img"]
    assert len(imgs) == 6 + 12
    assert all(a["src"].startswith("data:image/") for a in imgs)


def test_surface_captions_say_where_the_other_factors_are_held(page):
    cap = page.text_by_id["fig-surface-AB"]
    assert "held at their centre" in cap and "C (velocity_m_s) = 0.5" in cap and "D (acceleration_m_s2) = 30" in cap


def test_anova_matches_table5(page):
    """F values (two decimals) and p values (four) as printed in the paper's Table 5."""
    t5 = rsm_lrg.load_table5().set_index("source")
    rows = {r[0].replace(" **", "").replace(" *", ""): r for r in page.tables["anova-table"][1:]}
    pretty = {"A^2": "A²", "B^2": "B²", "C^2": "C²", "D^2": "D²"}
    for source, ref in t5.iterrows():
        row = rows[pretty.get(source, source)]
        _, ss, df, ms, f, p, _ = row
        assert int(df) == int(ref["df"]), source
        if isinstance(ref["p_value"], str) and ref["p_value"]:
            assert p == ref["p_value"].strip(), source
        if pd.notna(ref["f_value"]):
            paper_f = float(ref["f_value"])
            if paper_f >= 0.1 or paper_f == 0:
                assert f == f"{paper_f:.2f}", source
            elif paper_f >= 0.01:
                assert f == f"{paper_f:.2g}", source  # 0.082 (CD)
            else:
                assert f == "3.04 × 10⁻³", source  # A^2, printed 3.04 x 10^-3


def test_anova_sums_of_squares_are_the_fits(page, table4_fit):
    """The page shows the model layer's numbers at 3 significant figures (the paper's
    Table 5 prints 3; its rounding differs in the last digit for B^2 and Cor Total)."""
    rows = {re.sub(r" \*+$", "", r[0]): r for r in page.tables["anova-table"][1:]}
    a = table4_fit.anova.set_index("source")
    for source in ("Model", "A", "C", "Residual", "Lack of Fit", "Pure Error", "Cor Total"):
        txt = rows[source][1]
        m = re.fullmatch(r"([\d.]+) × 10([⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+)", txt)
        exp = int(m.group(2).translate(str.maketrans("⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "-0123456789")))
        value = float(m.group(1)) * 10.0 ** exp
        assert value == pytest.approx(float(f"{a.loc[source, 'sum_sq']:.3g}"), rel=1e-12), source
    assert rows["AB"][1] == "0.000" and rows["BC"][1] == "0.000"  # round-off shown as Table 5 does


def test_significant_terms_are_marked(page):
    """Note under Table 5: p < 0.01 significant (A, C, D, C^2), 0.01-0.05 less significant (B, AC)."""
    marks = {}
    for r in page.tables["anova-table"][1:]:
        m = re.fullmatch(r"(.+?)(?: (\*+))?", r[0])
        marks[m.group(1)] = m.group(2) or ""
    assert {k for k, v in marks.items() if v == "**"} == {"Model", "A", "C", "D", "C²"}
    assert {k for k, v in marks.items() if v == "*"} == {"B", "AC"}
    notes = page.text_by_id["anova-notes"]
    assert "In this case A, B, C, D, AC, C² are significant" in notes
    assert "The Model F-value of 26.03 implies the model is significant" in notes
    assert "Lack of Fit F-value of 10.75 implies the Lack of Fit is not significant" in notes


def test_coded_equation_is_eq19(page):
    eq19 = rsm_lrg.load_equation19()
    text = page.text_by_id["equation-coded"].split("=", 1)[1]
    shown = {"Intercept": 0.0}
    # numbers as the page writes them (rsm_lrg.present): 0.0075 or 4.1667 × 10⁻⁵
    tokens = re.findall(r"([+−-]?)\s*([\d.]+)(?:\s*×\s*10([⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+))?\s*([A-D][A-D²]*)?", text)
    for sign, num, exp, term in tokens:
        name = (term or "Intercept").replace("²", "^2")
        e = int(exp.translate(str.maketrans("⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "-0123456789"))) if exp else 0
        shown[name] = (-1 if sign in ("−", "-") else 1) * float(num) * 10.0 ** e
    for term, coef in eq19.items():
        assert shown.get(term, 0.0) == pytest.approx(coef, abs=5e-6), term  # 5 decimals
    assert "AB" not in shown and "BC" not in shown  # zero in Eq. 19, round-off in the fit


def test_actual_equation_and_statistics(page, table4_fit):
    eq = page.text_by_id["equation-actual"]
    assert "thickness_m·velocity_m_s" in eq and "stroke_m²" in eq
    stats = {r[0]: r[1] for r in page.tables["statistics-table"]}
    assert stats["R²"] == "0.9681"          # DIGEST: R^2 = 0.968 (paper "0.97")
    assert stats["Adjusted R²"] == "0.9309"  # DIGEST: 0.931
    assert stats["Predicted R²"] == "0.8184"  # DIGEST: 0.818
    assert stats["Adeq Precision"] == "18.46"  # DIGEST: 18.5


def test_coefficients_have_ci_and_vif(page, table4_fit):
    rows = page.tables["coefficients-table"]
    assert rows[0][:7] == ["Term", "Coefficient", "df", "Std. error", "95 % CI low", "95 % CI high", "VIF"]
    c = {r[0]: r for r in rows[1:]}
    ref = table4_fit.coefficients
    assert float(c["C"][4]) == pytest.approx(ref.loc["C", "ci_low"], rel=1e-3)
    assert float(c["C"][6]) == pytest.approx(ref.loc["C", "vif"], rel=1e-3)
    assert c["A²"][6] == "1.25"  # BBD with 4 factors: VIF of the squares (Design-Expert shows 1.25)


def test_optimum_and_stationary_point(page):
    opt = page.text_by_id["optimum"]
    # DIGEST: minimum at all coded -1, predicted 0.022833; PI 0.0159-0.0298
    assert "0.022833" in opt
    rows = page.tables["optimum-table"][1:]
    assert [r[2] for r in rows] == ["-1"] * 4
    lo, hi = map(float, re.search(r"prediction interval \(one new run\)\s*([\d.]+) … ([\d.]+)", opt).groups())
    assert lo == pytest.approx(0.0159, abs=5e-5) and hi == pytest.approx(0.0298, abs=5e-5)  # DIGEST, 3 s.f.
    assert "saddle" in page.text_by_id["stationary-point"]


@pytest.mark.slow
def test_markup_in_names_is_escaped():
    rng = np.random.default_rng(7)
    names = ["<script>alert(1)</script>", "<img src=x onerror=alert(2)>", "x\"&'$y$"]
    runs = [c for c in itertools.product([-1, 0, 1], repeat=3) if sum(map(abs, c)) == 2] + [(0, 0, 0)] * 3
    X = np.array(runs, dtype=float)
    y = 1 + X[:, 0] + 0.5 * X[:, 1] ** 2 + 0.1 * rng.normal(size=len(X))
    df = pd.DataFrame(X, columns=names)
    df["<b>resp</b>"] = y
    res = rsm_lrg.fit(df, "<b>resp</b>")
    html = to_html(res, title="<i>t</i>", source_name="<u>f.csv</u>")
    assert "<script>alert" not in html and "<img src=x" not in html
    assert "&lt;script&gt;alert(1)&lt;/script&gt;" in html
    assert "<b>resp</b>" not in html and "<i>t</i>" not in html and "<u>f.csv</u>" not in html
    page = read(html)
    assert page.tags.get("script", 0) == 0
    assert page.tags["img"] == 6 + 2 * 3  # the figures and nothing else
    assert not [a for _, a in page.attrs if "onerror" in a]


@pytest.mark.slow
def test_hold_at_optimum_and_bad_hold(table4_fit):
    ctx = report_context(table4_fit, hold="optimum")
    assert "held at the optimum" in ctx["surfaces"][0]["surface"].caption
    assert "acceleration_m_s2) = 20" in ctx["surfaces"][0]["surface"].caption
    with pytest.raises(ValueError, match="hold must be"):
        report_context(table4_fit, hold="middle")


def test_write_report_is_atomic_and_refuses_to_overwrite(tmp_path, table4_fit, monkeypatch):
    out = tmp_path / "r.html"
    out.write_text("keep me")
    with pytest.raises(ValueError, match="already exists"):
        write_report(table4_fit, out)
    assert out.read_text() == "keep me"
    html = "<!DOCTYPE html><p>x</p>"
    monkeypatch.setattr("rsm_lrg.report.fit_report.to_html", lambda *a, **k: html)
    write_report(table4_fit, out, force=True)
    assert out.read_text() == html
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.html"]  # no temporary file left


@pytest.mark.slow
def test_rows_without_a_response_are_shown_as_not_run():
    # rows 4 and 11 of Table 4 with their response removed: in the table, in file order
    d = rsm_lrg.load_table4()
    d.loc[[3, 10], "tcr_c_per_min"] = np.nan
    r = rsm_lrg.fit(d, "tcr_c_per_min")
    ctx = report_context(r)
    rows = ctx["data"]["rows"]
    assert [row[0] for row in rows] == list(range(1, 28))
    j = ctx["data"]["columns"].index("tcr_c_per_min")
    assert [row[0] for row in rows if row[j] == "not run"] == [4, 11]
    assert rows[3][1:j] == [int(d.iloc[3, 0])] + [d.iloc[3, c].item() for c in range(1, j - 1)]
    assert "2 rows without a response" in ctx["data"]["caption"]
    assert "not run" in read(to_html(r)).text_by_id["data"]
