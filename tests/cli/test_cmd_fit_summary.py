"""``rsm-lrg fit-summary`` through rsm_lrg.cli.main."""

import json

from rsm_lrg.cli import main


def test_table4_suggests_quadratic(capsys):
    assert main(["fit-summary", "data/table4.csv", "--response", "tcr_c_per_min", "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["suggested"] == "quadratic" and d["n"] == 27
    cubic = [r for r in d["sequential"] if r["source"].startswith("Cubic")][0]
    assert cubic["aliased"] is True
    assert main(["fit-summary", "data/table4.csv", "--response", "tcr_c_per_min"]) == 0
    assert "Suggested model: Quadratic" in capsys.readouterr().out


def test_bad_column_is_one_error_line(capsys):
    assert main(["fit-summary", "data/table4.csv", "--response", "nope"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error:") and "table4.csv" in err[0] and "nope" in err[0]


MIX = ["fit-summary", "data/mixture_etch.csv", "--response", "erate", "--component", "x1", "--component", "x2",
       "--component", "x3"]


def test_mixture_fit_summary(capsys):
    # the Scheffé sequence (figures checked against R in tests/model/choice/test_mixture_fit_summary.py)
    assert main(MIX + ["--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["suggested"] == "special-cubic" and d["n"] == 14
    assert [r["source"] for r in d["sequential"]] == [
        "Mean vs Total", "Linear vs Mean", "Quadratic vs Linear", "Special Cubic vs Quadratic",
        "Cubic vs Special Cubic", "Residual", "Total"]
    lin = d["sequential"][1]
    assert lin["df"] == 2 and abs(lin["sum_sq"] - 133755.0) < 1e-6  # R: anova(lm(y ~ 1), lm(y ~ -1 + A + B + C))
    assert main(MIX) == 0
    out = capsys.readouterr().out
    assert "Suggested model: Special Cubic" in out and "Lack of fit tests" in out
    assert main(MIX + ["--transform", "log"]) == 0
    assert "Suggested model:" in capsys.readouterr().out


def test_mixture_errors_are_one_line(capsys):
    bad = MIX[:-1] + ["nope"]
    assert main(bad) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error:") and "mixture_etch.csv" in err[0] and "nope" in err[0]
    assert main(MIX[:-2]) == 2  # two of three components: rows do not sum to one total
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "row 1" in err[0] and "total" in err[0]
