"""The interactive report without a browser: the embedded model numbers, the page's
Content-Security-Policy, its size, the static variant, and ``rsm-lrg report`` with several
responses (the browser checks are in tests/browser/test_interactive_report.py)."""

from __future__ import annotations

import base64
import hashlib
import json
import re

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.report.interactive import _json_for_script, interactive_html, model_data
from rsm_lrg.terms import design_matrix

FACTORS = ["thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2"]


def data() -> pd.DataFrame:
    df = rsm_lrg.load_table4()
    df["wear_volume_m3_per_h"] = rsm_lrg.simulate(df[FACTORS], seed=1)["wear_volume_m3_per_h"].to_numpy()
    return df


@pytest.fixture(scope="module")
def fits():
    df = data()
    return {"tcr_c_per_min": rsm_lrg.fit(df, "tcr_c_per_min", factors=FACTORS),
            "wear_volume_m3_per_h": rsm_lrg.fit(df, "wear_volume_m3_per_h", factors=FACTORS)}


@pytest.fixture(scope="module")
def page(fits):
    return interactive_html(fits, goals=["minimize", "minimize"], source_name="table4.csv")


def _scripts(html: str) -> list[tuple[str, str]]:
    return re.findall(r"<script( type=\"application/json\" id=\"rsm-data\")?>(.*?)</script>", html, re.S)


def test_model_data_is_the_fit(fits):
    """The numbers the page multiplies are the fit's own: b, C σ² without blocks, σ², t."""
    from scipy import special

    f = fits["tcr_c_per_min"]
    m = model_data(f)
    form = m["interval"]
    assert m["b"] == f.coefficients["coded"].tolist()
    C = f.cov_unscaled[np.ix_(f.term_index, f.term_index)] * f.sigma2
    np.testing.assert_array_equal(np.array(form["cov_mean"]), C)
    np.testing.assert_array_equal(np.array(form["cov_se"]), C)
    assert form["s2_new"] == f.sigma2 and form["df"] == f.df_resid == 12 and "kr" not in form
    assert m["t"] == float(special.stdtrit(12, 0.975))  # t(0.975, 12) = 2.1788 (tables)
    assert m["t"] == pytest.approx(2.178813, abs=1e-6)
    # the page's row of the model matrix: for each term, the product of coded factors to their powers
    rng = np.random.default_rng(0)
    x = rng.uniform(-1, 1, (5, 4))
    X = design_matrix(x, f.terms)
    rows = np.array([[np.prod([xi[i] ** p for i, p in enumerate(t["p"]) if p]) for t in m["terms"]] for xi in x])
    np.testing.assert_allclose(rows, X, rtol=1e-15)
    # ŷ, CI, PI by the page's formulas in numpy equal predict
    ref = f.predict(x, coded=True, interval="both")
    q = np.einsum("ij,jk,ik->i", rows, np.array(form["cov_mean"]), rows)
    y = rows @ np.array(m["b"])
    np.testing.assert_allclose(y - m["t"] * np.sqrt(q), ref["ci_low"], rtol=1e-12)
    np.testing.assert_allclose(y + m["t"] * np.sqrt(q + form["s2_new"]), ref["pi_high"], rtol=1e-12)


@pytest.mark.slow
def test_model_data_with_a_categoric_factor():
    df = data()
    df["stage"] = np.random.default_rng(2).choice(["rfcms", "rms", "mix"], len(df))
    f = rsm_lrg.fit(df, "tcr_c_per_min", factors=FACTORS + ["stage"], model="2fi")
    m = model_data(f)
    assert m["factors"][4] == {"name": "stage", "letter": "E", "kind": "categoric", "levels": list(f.space.factors[4].levels)}
    assert sum(max(1, len(t["combos"])) for t in m["terms"]) == len(m["b"]) == len(f.column_names)
    e = next(t for t in m["terms"] if t["name"] == "E")
    assert e["cat"] == [[4, 3]] and e["combos"] == [[0], [1]]


def test_json_in_the_page_is_inert():
    text = _json_for_script({"name": "</script><script>alert(1)</script>", "x": "a&b\u2028"})
    assert "<" not in text and ">" not in text and "&" not in text and "\u2028" not in text
    assert json.loads(text) == {"name": "</script><script>alert(1)</script>", "x": "a&b\u2028"}
    with pytest.raises(ValueError):
        _json_for_script({"x": float("nan")})


def test_csp_allows_exactly_the_page_scripts_by_hash(page):
    import html

    csp = html.unescape(re.search(r'http-equiv="Content-Security-Policy" content="([^"]+)"', page).group(1))
    src = re.search(r"script-src ([^;]+);", csp).group(1).split()
    assert "default-src 'none'" in csp and "'unsafe-eval'" not in csp
    assert all(s.startswith("'sha256-") for s in src)  # no 'unsafe-inline', no host: only these scripts
    scripts = _scripts(page)
    assert [bool(j) for j, _ in scripts] == [True, False, False]
    hashes = ["'sha256-" + base64.b64encode(hashlib.sha256(body.encode()).digest()).decode() + "'"
              for j, body in scripts if not j]
    assert sorted(src) == sorted(hashes)
    assert "connect-src 'none'" in csp


def test_page_contract_and_size(page, fits):
    """Two responses, four factors: under 8 MB (issue 14), one control per factor and one
    prediction element per response with the data attributes."""
    size = len(page.encode("utf-8"))
    print(f"two-response four-factor page: {size / 1e6:.2f} MB")
    assert size < 8_000_000
    for f in FACTORS:
        assert re.search(rf'<input type="range" id="ctl-\d" data-factor="{f}" min="[^"]+" max="[^"]+" step="any"', page)
    for r in fits:
        assert re.search(rf'<tr data-prediction data-response="{r}" data-value="" data-ci-low="" data-ci-high="" '
                         r'data-pi-low="" data-pi-high="">', page)
    for sid in ("summary", "profiler", "overlay", "surfaces-3d", "data", "response-1", "response-2"):
        assert f'id="{sid}"' in page
    for i in (1, 2):  # every section of the one-response report, per response (surfaces: live above)
        for sid in ("anova", "statistics", "coefficients", "equation", "diagnostics", "stationary-point", "optimum"):
            assert f'id="{sid}-{i}"' in page
    assert "221.92" in page and "26.03" in page  # Table 5 F values in the first response's ANOVA


@pytest.mark.slow
def test_static_variant_has_no_script(fits):
    html = interactive_html(fits, static=True)
    import html as _html

    assert "<script" not in html and "script-src 'none'" in _html.unescape(html)
    assert html.count('class="diag"') == 2 * (6 + 12)  # per response: six diagnostics, six surfaces, six contours


@pytest.mark.slow
def test_bad_inputs_are_named(fits):
    df = data()
    other = rsm_lrg.fit(df, "tcr_c_per_min", factors=FACTORS[:3])
    with pytest.raises(ValueError, match="one report needs one factor set"):
        interactive_html({"a": fits["tcr_c_per_min"], "b": other})
    with pytest.raises(ValueError, match="low 2 is above high 1"):
        interactive_html(fits["tcr_c_per_min"], limits=(2.0, 1.0))
    with pytest.raises(ValueError, match="start must be"):
        interactive_html(fits["tcr_c_per_min"], start="middle")


@pytest.mark.slow
def test_cli_two_responses_with_their_own_options(tmp_path, capsys):
    from rsm_lrg.cli import main

    src = tmp_path / "d.csv"
    data().to_csv(src, index=False)
    out = tmp_path / "r.html"
    # a --limits right after a --response is that response's; the two --goal listed together
    # after the last --response are taken in --response order (cli.options.per_response_values)
    rc = main(["report", str(src), "--response", "tcr_c_per_min", "--reduce", "--limits", ":0.03",
               "--response", "wear_volume_m3_per_h", "--transform", "log", "--goal", "minimize", "--goal", "minimize",
               "--hold", "optimum", "-o", str(out)])
    assert rc == 0, capsys.readouterr().err
    html = out.read_text(encoding="utf-8")
    d = json.loads(re.search(r'id="rsm-data">(.*?)</script>', html, re.S).group(1))
    m1, m2 = d["models"]
    assert m1["response"] == "tcr_c_per_min" and len(m1["b"]) < 15  # reduced
    assert m2["transform"] == {"name": "log", "lam": 0.0, "constant": 0.0} and len(m2["b"]) == 15
    assert m1["limits"] == [None, 0.03] and m2["limits"] != [None, 0.03]
    # --hold optimum starts the profiler at the desirability optimum
    assert [c["value"] for c in d["controls"]] == [d["desirability"]["setting"][f] for f in FACTORS]
    assert "log-transformed response" in html
    # a bad --limits is named before any work
    rc = main(["report", str(src), "--response", "tcr_c_per_min", "--limits", "x", "-o", str(tmp_path / "x.html")])
    assert rc == 2 and "--limits" in capsys.readouterr().err


@pytest.mark.slow
def test_model_data_of_a_blocked_fit_predicts_the_average_block():
    """With blocks, the page's b and C leave the block columns out (as predict does)."""
    df = data()
    df["day"] = np.where(np.arange(len(df)) < 14, "one", "two")
    f = rsm_lrg.fit(df, "tcr_c_per_min", factors=FACTORS, block="day")
    m = model_data(f)
    assert len(m["b"]) == len(f.terms) == 15 and np.array(m["interval"]["cov_mean"]).shape == (15, 15)
    x = np.random.default_rng(1).uniform(-1, 1, (4, 4))
    X = design_matrix(x, f.terms)
    ref = f.predict(x, coded=True, interval="both")
    q = np.einsum("ij,jk,ik->i", X, np.array(m["interval"]["cov_mean"]), X)
    np.testing.assert_allclose(X @ np.array(m["b"]), ref["predicted"], rtol=1e-13)
    np.testing.assert_allclose(X @ np.array(m["b"]) - m["t"] * np.sqrt(q), ref["ci_low"], rtol=1e-12)


def test_without_plotly_the_cli_says_so_in_one_line(tmp_path, capsys, monkeypatch):
    import importlib.util

    from rsm_lrg.cli import main

    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec", lambda name, *a: None if name == "plotly" else real(name, *a))
    src = tmp_path / "d.csv"
    rsm_lrg.load_table4().to_csv(src, index=False)
    rc = main(["report", str(src), "--response", "tcr_c_per_min", "-o", str(tmp_path / "r.html")])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1 and "pip install" in err[0] and "--static" in err[0]
    assert not (tmp_path / "r.html").exists()


@pytest.mark.slow
def test_static_pages_with_a_categoric_factor():
    """Surfaces over the numeric pairs only, the stage held at a level (named in the caption)."""
    from rsm_lrg.report import to_html

    df = data()
    df["stage"] = np.random.default_rng(7).choice(["rfcms", "rms"], len(df))
    f = rsm_lrg.fit(df, "tcr_c_per_min", factors=FACTORS + ["stage"], model="2fi")
    static = interactive_html(f, static=True)
    assert static.count('class="diag"') == 6 + 2 * 6  # six diagnostics, a surface and a contour per numeric pair
    page = to_html(f, hold="optimum")
    level = f.optimize("minimize").actual["stage"]
    assert f"E (stage) = {level}" in page and page.count("<figure") == 18


def _top_level(fragment: str) -> list[tuple[str, dict, str]]:
    """The top-level elements of a notebook output: (tag, attributes, text), parsed as a
    browser parses them (html.parser decodes the attributes)."""
    from html.parser import HTMLParser

    out: list = []

    class P(HTMLParser):
        depth = 0

        def handle_starttag(self, tag, attrs):
            if self.depth == 0:
                out.append([tag, dict(attrs), ""])
            self.depth += tag not in ("br", "img", "input", "meta")

        def handle_endtag(self, tag):
            self.depth -= 1

        def handle_data(self, d):
            if out and self.depth == 1:
                out[-1][2] += d

    P(convert_charrefs=True).feed(fragment)
    return [tuple(e) for e in out]


def test_notebook_profiler_carries_plotly_once_per_session():
    """The first profiler displayed in a kernel session carries plotly.js, the page's script
    and its style into the notebook once (inert text blocks named by their SHA-256); every
    later one is a few kB: a frame whose page asks for them. A hostile response name stays
    inside the frame's page, escaped."""
    from rsm_lrg.report.interactive import notebook_reset, plotly_js

    df = rsm_lrg.load_table4().rename(columns={"tcr_c_per_min": "κ'</script><b onclick=x>"})
    fit = rsm_lrg.fit(df, "κ'</script><b onclick=x>", factors=FACTORS)
    notebook_reset()
    first, second = fit.profiler(), fit.reduce().profiler()
    one, two = first._repr_html_(), second._repr_html_()
    lib = plotly_js()
    assert one.count(lib) == 1 and lib not in two and lib in first.html  # .save() stays whole
    assert len(two) < 20_000 and len(first.html) > 4_000_000  # 15.1 kB against 4.87 MB (Table 4, full quadratic)
    els1, els2 = _top_level(one), _top_level(two)
    assert [e[0] for e in els1] == ["script"] * 4 + ["iframe"]  # 3 assets, the host script, the frame
    assert [e[0] for e in els2] == ["script", "iframe"]
    blocks = {e[1]["data-rsm-lrg-asset"]: e[2] for e in els1[:3]}
    assert all(e[1]["type"] == "text/plain" for e in els1[:3])
    assert {hashlib.sha256(t.encode()).hexdigest() for t in blocks.values()} == set(blocks)
    for prof, els in ((first, els1), (second, els2)):
        frame = els[-1][1]
        assert frame["srcdoc"] == prof.notebook and frame["sandbox"] == "allow-scripts allow-downloads"
        asked = json.loads(re.search(r'id="rsm-assets">(.*?)</script>', prof.notebook).group(1))
        assert [h for _, h in asked] == list(blocks)  # the frame asks for exactly what the first carried
        csp = re.search(r'Content-Security-Policy" content="([^"]+)"', prof.notebook).group(1)
        assert "&#39;unsafe-inline&#39;; script-src &#39;sha256-" in csp  # hashes only (style may be inline)
        assert "<b onclick" not in prof.notebook and "&lt;b onclick=x&gt;" in prof.notebook
    for _, attrs, text in els1[:-1] + els2[:-1]:
        assert "<b onclick" not in text and not any("onclick" in str(v) for v in attrs.values())  # no user text outside the frame
    notebook_reset()
    assert lib in second._repr_html_()  # carried again after a reset
