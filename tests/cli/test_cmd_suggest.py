"""``rsm-lrg suggest``: the next runs as a design CSV that the toolkit reads back, and bad input
as one ``error:`` line with exit status 2."""

import json
from pathlib import Path

import pandas as pd
import pytest
from _cli_errors import error_line

from rsm_lrg.cli import main

BRANIN = str(Path(__file__).parents[1] / "model" / "r" / "gp_branin.csv")
FACTORS = ["--factor", "x1=-5:10", "--factor", "x2=0:15"]


def test_writes_a_design_csv(tmp_path, capsys):
    out = tmp_path / "next.csv"
    assert main(["suggest", BRANIN, "--response", "y", *FACTORS, "--goal", "minimize", "--runs", "2", "--seed", "1",
                 "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "criterion ei: 2 setting(s)" in text
    d = pd.read_csv(out)
    assert list(d.columns) == ["std_order", "run_order", "coded_A", "coded_B", "x1", "x2"] and len(d) == 2
    assert d["x1"].between(-5, 10).all() and d["x2"].between(0, 15).all()
    # the design CSV's layout: coded columns, then the factors in actual units, coded as the fit codes them
    assert ((2 * d["x1"] - 5) / 15).round(9).tolist() == d["coded_A"].round(9).tolist()
    assert ((2 * d["x2"] - 15) / 15).round(9).tolist() == d["coded_B"].round(9).tolist()


def test_json_and_criterion(tmp_path, capsys):
    out = tmp_path / "next.csv"
    assert main(["suggest", BRANIN, "--response", "y", *FACTORS, "--goal", "target=50", "--criterion", "variance",
                 "--constraint", "x1 + x2 <= 10", "-o", str(out), "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["criterion"] == "variance" and d["goal"] == "target" and d["target"] == 50
    assert d["model"]["model"] == "gp" and len(d["runs"]) == 1
    assert d["runs"][0]["x1"] + d["runs"][0]["x2"] <= 10 + 1e-6


def test_the_loops_length_scale_bounds_by_default(tmp_path, capsys):
    # suggest is one step of the loop: km's upper bound (2 x the range) unless told otherwise
    got = {}
    for given in ([], ["--length-scale-bounds", "0.001:10"]):
        assert main(["suggest", BRANIN, "--response", "y", *FACTORS, "--goal", "minimize", "-o",
                     str(tmp_path / "n.csv"), "--force", "--json", "-", *given]) == 0
        got[bool(given)] = json.loads(capsys.readouterr().out)["model"]["gp"]["search"]["length_scale_bounds"]
    assert got == {False: [0.001, 2.0], True: [0.001, 10.0]}


def test_a_polynomial_suggests_runs_that_fit_reads_back(tmp_path, capsys):
    # --model quadratic: the least-squares fit's standard error in place of the kriging sd; the
    # runs are a design CSV that a fit of the runs plus these reads
    out = tmp_path / "next.csv"
    assert main(["suggest", BRANIN, "--response", "y", *FACTORS, "--model", "quadratic", "--criterion", "variance",
                 "--runs", "2", "--seed", "3", "-o", str(out), "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["model"]["model"] == "quadratic" and len(d["runs"]) == 2
    assert any("Wynn 1970" in n for n in d["notes"])
    runs = pd.read_csv(out)
    assert list(runs.columns) == ["std_order", "run_order", "coded_A", "coded_B", "x1", "x2"]
    # the prediction variance of a quadratic on a box is largest at a corner
    assert set(runs["coded_A"].abs().round(9)) == {1.0} and set(runs["coded_B"].abs().round(9)) == {1.0}


@pytest.mark.parametrize("args, option", [
    (["--goal", "sideways"], "--goal"),
    (["--runs", "0"], "--runs"),
    (["--criterion", "qei"], "--criterion"),
    (["--bound", "x1=3:1"], "--bound"),
    (["--model", "quartic"], "--model"),
    (["--model", "quadratic", "--kernel", "gauss"], "--kernel"),
    (["--model", "quadratic", "--length-scale-bounds", "0.01:2"], "--length-scale-bounds"),
    (["--nugget", "-2"], "--nugget"),
    (["--length-scale-bounds", "1:1"], "--length-scale-bounds"),
])
def test_bad_input_is_one_error_line(args, option, tmp_path, capsys):
    rc = main(["suggest", BRANIN, "--response", "y", *FACTORS, *args, "-o", str(tmp_path / "n.csv")])
    assert option in error_line(capsys, rc)
    assert not (tmp_path / "n.csv").exists()
