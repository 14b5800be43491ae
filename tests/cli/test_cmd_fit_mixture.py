"""``fit --component ... --model mixture-quadratic|special-cubic``: the Scheffé fit from the
command line (numbers checked against R in tests/model/test_mixture_fit.py)."""

from __future__ import annotations

import json
from pathlib import Path

import pandas as pd
import pytest

from rsm_lrg.cli import main

DATA = Path(__file__).parents[1] / "model" / "r" / "mixture_etch_l.csv"
COMPS = ["--component", "x1=0.1:1", "--component", "x2=0.2:1", "--component", "x3=0.05:1"]


def test_fit_mixture_json(tmp_path, capsys):
    out = tmp_path / "fit.json"
    assert main(["fit", str(DATA), "--response", "erate", *COMPS, "--model", "special-cubic", "--json", str(out)]) == 0
    text = capsys.readouterr().out
    assert "Linear Mixture" in text and "Final equation in terms of real proportions" in text
    d = json.loads(out.read_text())
    assert d["model"] == "special-cubic" and d["intercept"] is False
    assert list(d["coefficients"]["coded"]) == ["A", "B", "C", "AB", "AC", "BC", "ABC"]
    assert set(d["coefficients"]["actual"]) == {"A", "B", "C", "AB", "AC", "BC", "ABC"}
    assert [r["source"] for r in d["anova"]] == ["Model", "Linear Mixture", "AB", "AC", "BC", "ABC", "Residual",
                                                 "Lack of Fit", "Pure Error", "Cor Total"]
    expected = pd.read_csv(DATA.parent / "mixture_expected.csv")
    want = expected[(expected.set == "etch_l") & (expected.model == "special-cubic") & (expected.quantity == "coef")]
    for row in want.itertuples():
        assert d["coefficients"]["coded"][row.term] == pytest.approx(float(row.value), rel=1e-9)


def test_fit_mixture_cubic_json(tmp_path, capsys):
    """The full cubic from the command line: keys AB(A-B) in the JSON (values checked against
    R in tests/model/test_mixture_cubic.py) and the real-proportion term printed as a product."""
    pest = DATA.parent / "mixture_pest.csv"
    out = tmp_path / "fit.json"
    args = ["fit", str(pest), "--response", "y", "--component", "x1", "--component", "x2", "--component", "x3"]
    assert main([*args, "--model", "mixture-cubic", "--json", str(out)]) == 0
    text = capsys.readouterr().out
    assert "Scheffé full cubic mixture" in text and "* x1 * x2 * (x1 - x2)" in text
    d = json.loads(out.read_text())
    keys = ["A", "B", "C", "AB", "AC", "BC", "ABC", "AB(A-B)", "AC(A-C)", "BC(B-C)"]
    assert list(d["coefficients"]["coded"]) == keys and set(d["coefficients"]["actual"]) == set(keys)
    expected = pd.read_csv(DATA.parent / "mixture_cubic_expected.csv")
    want = expected[(expected.set == "pest") & (expected.model == "mixture-cubic") & (expected.quantity == "coef")]
    for row in want.itertuples():
        assert d["coefficients"]["coded"][row.term] == pytest.approx(float(row.value), rel=1e-9)
    out2 = tmp_path / "fit2.json"
    assert main([*args, "--model", "mixture-cubic", "--terms", "A B C AB AB(A-B)", "--json", str(out2)]) == 0
    assert list(json.loads(out2.read_text())["coefficients"]["coded"]) == ["A", "B", "C", "AB", "AB(A-B)"]


def test_fit_mixture_terms_without_model(tmp_path, capsys):
    """--terms is the alternative to --model (README): with --component it is the Scheffé model."""
    out, ref = tmp_path / "t.json", tmp_path / "m.json"
    args = ["fit", str(DATA), "--response", "erate", *COMPS]
    assert main([*args, "--terms", "A B C AB AC BC ABC", "--json", str(out)]) == 0
    assert main([*args, "--model", "special-cubic", "--json", str(ref)]) == 0
    got, want = json.loads(out.read_text()), json.loads(ref.read_text())
    assert got["coefficients"]["coded"] == pytest.approx(want["coefficients"]["coded"], rel=1e-12)
    assert got["terms"] == want["terms"] and got["intercept"] is False


@pytest.mark.parametrize("args, message", [
    (["--model", "quadratic"], "error: --model: mixture components (--component) need a Scheffé model"),
    (["--model", "mixture-cubic", "--terms", "A B C AB BA(B-A)"], "error: --terms: model term 'BA(B-A)'"),
])
def test_fit_mixture_bad_model(args, message, capsys):
    assert main(["fit", str(DATA), "--response", "erate", *COMPS, *args]) == 2
    err = capsys.readouterr().err
    assert err.startswith(message) and err.count("\n") == 1


def test_fit_mixture_bad_row(tmp_path, capsys):
    d = pd.read_csv(DATA)
    d.loc[6, "x2"] += 0.01
    bad = tmp_path / "bad.csv"
    d.to_csv(bad, index=False)
    out = tmp_path / "fit.json"
    assert main(["fit", str(bad), "--response", "erate", *COMPS, "--model", "mixture-linear", "--json", str(out)]) == 2
    err = capsys.readouterr().err
    assert "row 7: the components sum to 1.01" in err and err.count("\n") == 1
    assert not out.exists()


def test_fit_report_of_a_mixture(tmp_path, capsys):
    """fit --report writes the static page with the ternary contour and the trace plot."""
    out = tmp_path / "r.html"
    assert main(["fit", str(DATA), "--response", "erate", *COMPS, "--model", "mixture-quadratic",
                 "--report", str(out)]) == 0
    html = out.read_text()
    assert 'id="fig-ternary"' in html and 'id="fig-trace"' in html


def test_fit_mixture_process_keys(tmp_path, capsys):
    data = DATA.parent / "mixture_fishp.csv"
    out = tmp_path / "fit.json"
    assert main(["fit", str(data), "--response", "y", "--component", "x1", "--component", "x2", "--component", "x3",
                 "--factor", "z1", "--factor", "z2", "--model", "mixture-linear", "--json", str(out)]) == 0
    d = json.loads(out.read_text())
    assert list(d["coefficients"]["coded"]) == ["A", "B", "C", "AD", "AE", "BD", "BE", "CD", "CE"]
    assert [f["letter"] for f in d["factors"]] == ["A", "B", "C", "D", "E"]
    assert [f.get("component", False) for f in d["factors"]] == [True, True, True, False, False]
    assert "process factor" in capsys.readouterr().out


def test_confirm_at_a_blend(capsys):
    expected = pd.read_csv(DATA.parent / "mixture_expected.csv")
    want = expected[(expected.set == "etch_l") & (expected.model == "special-cubic") & (expected.quantity == "predict")]
    want = dict(zip(want.term, want.value.astype(float)))
    args = ["confirm", str(DATA), "--response", "erate", *COMPS, "--model", "special-cubic",
            "--at", "x1=0.3", "x2=0.3", "x3=0.4", "--observed", "700", "--json", "-"]
    assert main(args) == 0
    c = json.loads(capsys.readouterr().out)  # R's predict(..., interval = "prediction") at the blend
    assert c["predicted"] == pytest.approx(want["fit"], rel=1e-9)
    assert c["pi"] == pytest.approx([want["pi_low"], want["pi_high"]], rel=1e-9)
    bad = ["confirm", str(DATA), "--response", "erate", *COMPS, "--model", "special-cubic",
           "--at", "x1=0.3", "x2=0.4", "x3=0.4", "--observed", "700"]
    assert main(bad) == 2
    assert "error: --at: prediction point 1: the components sum to 1.1" in capsys.readouterr().err



@pytest.mark.parametrize("edit, comps, message", [
    ({1: ("erate", ""), 3: ("x2", "abc")}, ["x1", "x2", "x3"], "column 'x2', row 4: holds 'abc'"),
    ({}, ["x1", "x2", "erate"], "component 'erate' is the response"),
    ({}, ["x1=0.5:0.2", "x2", "x3"], "component 'x1': LOW must be below HIGH"),
    ({}, ["x1", "x1", "x3"], "component 'x1' is given twice"),
])
def test_fit_mixture_bad_input_named(tmp_path, capsys, edit, comps, message):
    d = pd.read_csv(DATA).astype(object)
    for i, (col, v) in edit.items():
        d.loc[i, col] = v
    path = tmp_path / "d.csv"
    d.to_csv(path, index=False)
    args = ["fit", str(path), "--response", "erate", "--model", "mixture-linear"]
    for c in comps:
        args += ["--component", c]
    assert main(args) == 2
    err = capsys.readouterr().err
    assert message in err and err.startswith("error: ") and err.count("\n") == 1
