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
