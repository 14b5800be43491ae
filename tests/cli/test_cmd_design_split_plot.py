"""``rsm-lrg design split-plot`` (issue 23): through rsm_lrg.cli.main; bad input exits 2 with one
``error:`` line naming the option and leaves no file behind."""

import math

import numpy as np
import pandas as pd
import pytest
from _cli_errors import error_line

from rsm_lrg.cli import main
from rsm_lrg.design import read_design

FACTORS = ["--factor", "T=150:250", "--factor", "P=1:3", "--factor", "v=0.1:0.5", "--factor", "a=1:5"]
HARD = ["--hard-to-change", "T", "--hard-to-change", "P"]


def _dense_d(coded, plots, eta):
    """GLS D by plain numpy: linear + 2FI + squares, dense V = I + eta [same plot]."""
    k = coded.shape[1]
    cols = [np.ones(len(coded))] + [coded[:, i] for i in range(k)]
    cols += [coded[:, i] * coded[:, j] for i in range(k) for j in range(i + 1, k)]
    cols += [coded[:, i] ** 2 for i in range(k)]
    X = np.column_stack(cols)
    V = np.eye(len(plots)) + eta * (plots[:, None] == plots[None, :])
    sign, logdet = np.linalg.slogdet(X.T @ np.linalg.solve(V, X))
    return math.exp(logdet / X.shape[1]) / len(coded)


def test_split_plot_csv(tmp_path, capsys):
    out = tmp_path / "sp.csv"
    argv = ["design", "split-plot", *FACTORS, *HARD, "--whole-plots", "8", "--runs", "32", "--model", "quadratic",
            "--seed", "7", "--starts", "4", "-o", str(out)]
    assert main(argv) == 0
    text = capsys.readouterr().out
    assert "D-optimal split-plot design for the quadratic model (15 terms)" in text
    assert "8 whole plots (4 runs each)" in text and "eta = 1" in text
    assert "randomised between and within whole plots" in text and f"wrote {out}" in text
    df = pd.read_csv(out)
    assert list(df.columns) == ["std_order", "run_order", "whole_plot", "coded_A", "coded_B", "coded_C", "coded_D",
                                "T", "P", "v", "a"]
    assert df["run_order"].tolist() == list(range(1, 33))
    assert df["whole_plot"].tolist() == sorted(df["whole_plot"])  # whole plots contiguous, numbered in run order
    assert df.groupby("whole_plot")[["T", "P"]].nunique().max().max() == 1
    assert df["T"].between(150, 250).all() and df["a"].between(1, 5).all()
    d = read_design(out)
    value = float(text.split("GLS criterion ")[1].split(";")[0])
    assert value == pytest.approx(_dense_d(d.coded_runs, d.whole_plots, 1.0), rel=1e-5)
    again = tmp_path / "again.csv"
    assert main(argv[:-1] + [str(again)]) == 0
    assert again.read_text() == out.read_text()


def test_split_plot_i_eta_categoric_constraint(tmp_path, capsys):
    out = tmp_path / "sp.csv"
    assert main(["design", "split-plot", "--factor", "oil=cat:A,B", "--factor", "v=0.1:0.5", "--factor", "a=1:5",
                 "--hard-to-change", "oil", "--whole-plots", "6", "--runs", "20", "--model", "2fi",
                 "--criterion", "I", "--variance-ratio", "2.5", "--constraint", "v + 0.1*a <= 0.8",
                 "--seed", "1", "--starts", "2", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "I-optimal split-plot design" in text and "eta = 2.5" in text
    assert "20 runs do not divide into 6 whole plots: 2 whole plots of 4 runs and 4 of 3" in text
    df = pd.read_csv(out)
    assert df.groupby("whole_plot")["oil"].nunique().max() == 1 and set(df["oil"]) == {"A", "B"}
    assert (df["v"] + 0.1 * df["a"] <= 0.8 + 1e-9).all()


@pytest.mark.parametrize("extra, option", [
    (["--hard-to-change", "Q", "--whole-plots", "8", "--runs", "32"], "--hard-to-change"),
    (["--whole-plots", "5", "--runs", "32"], "--whole-plots"),
    (["--whole-plots", "8", "--runs", "12"], "--runs"),
    (["--whole-plots", "8", "--runs", "32", "--variance-ratio", "-1"], "--variance-ratio"),
    (["--whole-plots", "8", "--runs", "32", "--variance-ratio", "nan"], "--variance-ratio"),
    (["--whole-plots", "8", "--runs", "32", "--variance-ratio", "inf"], "--variance-ratio"),
    (["--whole-plots", "0", "--runs", "32"], "--whole-plots"),
    (["--whole-plots", "8", "--runs", "32", "--constraint", "T + nothing <= 1"], "--constraint"),
    (["--whole-plots", "8", "--runs", "32", "--criterion", "A"], "--criterion"),
])
def test_split_plot_errors(tmp_path, capsys, extra, option):
    out = tmp_path / "bad.csv"
    hard = [] if "--hard-to-change" in extra else HARD
    rc = main(["design", "split-plot", *FACTORS, *hard, *extra, "--seed", "1", "--starts", "1", "-o", str(out)])
    line = error_line(capsys, rc)
    assert option in line
    assert not out.exists()


def test_split_plot_needs_hard_to_change(tmp_path, capsys):
    out = tmp_path / "bad.csv"
    rc = main(["design", "split-plot", *FACTORS, "--whole-plots", "8", "--runs", "32", "-o", str(out)])
    assert "--hard-to-change" in error_line(capsys, rc)
    assert not out.exists()


def test_augment_refuses_a_split_plot_design(tmp_path, capsys):
    src, out = tmp_path / "sp.csv", tmp_path / "aug.csv"
    assert main(["design", "split-plot", *FACTORS, *HARD, "--whole-plots", "8", "--runs", "32", "--model", "linear",
                 "--seed", "1", "--starts", "1", "-o", str(src)]) == 0
    capsys.readouterr()
    line = error_line(capsys, main(["design", "augment", str(src), "--runs", "4", "--seed", "1", "-o", str(out)]))
    assert "split-plot" in line and str(src) in line
    assert not out.exists()
