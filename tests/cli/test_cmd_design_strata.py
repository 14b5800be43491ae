"""``design split-plot --very-hard-to-change`` (split-split-plot) and ``design strip-plot`` (issue
35, item 2): the CSV's group columns, ``evaluate``'s GLS criteria equal to a dense-V computation,
the round trip design -> simulated response -> ``fit --random-effect``, and bad input exiting 2
with one line naming the option."""

import json
import math

import numpy as np
import pandas as pd
import pytest
from _cli_errors import error_line

from rsm_lrg.cli import main

FACTORS = ["--factor", "T=100:200", "--factor", "P=1:2", "--factor", "x=0:1", "--factor", "v=0:1"]
SSP = ["design", "split-plot", *FACTORS, "--very-hard-to-change", "T", "--hard-to-change", "P",
       "--whole-plots", "6", "--subplots", "12", "--runs", "36", "--model", "2fi", "--seed", "4", "--starts", "2"]
STRIP = ["design", "strip-plot", "--factor", "A=0:1", "--factor", "B=0:1", "--factor", "C=0:1", "--row-factor", "A",
         "--column-factor", "B", "--rows", "6", "--columns", "5", "--model", "2fi", "--seed", "2", "--starts", "2"]


def _dense_d(df, groups, etas, p_model="2fi"):
    coded = df[[c for c in df.columns if c.startswith("coded_")]].to_numpy(dtype=float)
    n, k = coded.shape
    X = np.column_stack([np.ones(n)] + [coded[:, i] for i in range(k)]
                        + [coded[:, i] * coded[:, j] for i in range(k) for j in range(i + 1, k)])
    V = np.eye(n)
    for g, eta in zip(groups, etas):
        lab = df[g].to_numpy()
        V += eta * (lab[:, None] == lab[None, :])
    sign, logdet = np.linalg.slogdet(X.T @ np.linalg.solve(V, X))
    return math.exp(logdet / X.shape[1]) / n


def _respond(df, groups, seed):
    """Response of known fixed effects (10 + 2A - 1.5B + C + 0.8AC, coded) plus a normal effect per
    group of each stratum (sd 1) and run error (sd 0.5)."""
    rng = np.random.default_rng(seed)
    X = df[[c for c in df.columns if c.startswith("coded_")]].to_numpy(dtype=float)
    y = 10 + 2 * X[:, 0] - 1.5 * X[:, 1] + X[:, 2] + 0.8 * X[:, 0] * X[:, 2] + rng.normal(0, 0.5, len(df))
    for g in groups:
        u = rng.normal(0, 1.0, df[g].max() + 1)
        y = y + u[df[g].to_numpy()]
    out = df.copy()
    out["yield_pct"] = y
    return out


def test_split_split_plot_cli_evaluate_and_fit(tmp_path, capsys):
    out = tmp_path / "ssp.csv"
    assert main([*SSP, "--variance-ratio", "2", "--subplot-variance-ratio", "0.5", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "6 whole plots (6 runs each)" in text and "12 groups in column subplot (3 runs each)" in text
    assert "very hard to change (whole plots): T" in text and "hard to change (sub-plots): P" in text
    df = pd.read_csv(out)
    assert list(df.columns[:4]) == ["std_order", "run_order", "whole_plot", "subplot"]
    assert df.groupby("whole_plot")["T"].nunique().max() == 1 and df.groupby("subplot")["P"].nunique().max() == 1
    assert df.groupby("subplot")["whole_plot"].nunique().max() == 1
    value = float(text.split("GLS criterion ")[1].split()[0])
    dense = _dense_d(df, ["whole_plot", "subplot"], [2.0, 0.5])
    assert value == pytest.approx(dense, rel=1e-5)
    assert main(["evaluate", str(out), "--model", "2fi", "--variance-ratio-of", "whole_plot=2",
                 "--variance-ratio-of", "subplot=0.5", "--json", "-"]) == 0
    g = json.loads(capsys.readouterr().out)["split_plot"]
    assert g["d_efficiency"] == pytest.approx(dense, rel=1e-10)
    assert g["strata"]["subplot"] == {"groups": 12, "sizes": [3, 3], "variance_ratio": 0.5}
    data = tmp_path / "ssp_y.csv"
    _respond(df, ["whole_plot", "subplot"], 1).to_csv(data, index=False)
    assert main(["fit", str(data), "--response", "yield_pct", "--model", "2fi", "--random-effect", "whole_plot",
                 "--random-effect", "subplot", "--json", "-"]) == 0
    js = json.loads(capsys.readouterr().out)
    assert list(js["variance_components"]) == ["whole_plot", "subplot", "residual"]
    assert {t["term"] for t in js["tests"]} >= {"A", "B", "C", "AC"}
    assert js["tests"][0]["p"] < 0.05  # T (A), 2 coded units between whole plots, is found


def test_strip_plot_cli_evaluate_and_fit(tmp_path, capsys):
    out = tmp_path / "strip.csv"
    assert main([*STRIP, "--row-variance-ratio", "3", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "6 groups in column strip_row (5 runs each)" in text and "5 groups in column strip_column" in text
    df = pd.read_csv(out)
    assert list(df.columns[:4]) == ["std_order", "run_order", "strip_row", "strip_column"]
    assert df.groupby("strip_row")["A"].nunique().max() == 1 and df.groupby("strip_column")["B"].nunique().max() == 1
    assert len(df.groupby(["strip_row", "strip_column"])) == 30
    dense = _dense_d(df, ["strip_row", "strip_column"], [3.0, 1.0])
    assert float(text.split("GLS criterion ")[1].split()[0]) == pytest.approx(dense, rel=1e-5)
    assert main(["evaluate", str(out), "--model", "2fi", "--variance-ratio-of", "strip_row=3", "--json", "-"]) == 0
    assert json.loads(capsys.readouterr().out)["split_plot"]["d_efficiency"] == pytest.approx(dense, rel=1e-10)
    assert main(["evaluate", str(out), "--model", "2fi"]) == 0
    assert "Random strata: strip_row 6 groups (5 runs), η 1; strip_column 5 groups (6 runs), η 1" in \
        capsys.readouterr().out
    data = tmp_path / "strip_y.csv"
    _respond(df, ["strip_row", "strip_column"], 2).to_csv(data, index=False)
    assert main(["fit", str(data), "--response", "yield_pct", "--model", "2fi", "--random-effect", "strip_row",
                 "--random-effect", "strip_column", "--json", "-"]) == 0
    js = json.loads(capsys.readouterr().out)
    assert list(js["variance_components"]) == ["strip_row", "strip_column", "residual"]


def _without(argv, *options):
    """``argv`` less each named option and its value."""
    out, skip = [], False
    for a in argv:
        if skip:
            skip = False
        elif a in options:
            skip = True
        else:
            out.append(a)
    return out


@pytest.mark.parametrize("argv, needle", [
    ([*_without(SSP, "--very-hard-to-change"), "-o", "X"], "error: --subplots: sub-plots belong"),
    ([*_without(SSP, "--subplots"), "-o", "X"], "error: --subplots: a split-split-plot"),
    ([*SSP, "--constraint", "x <= 0.5", "-o", "X"], "error: --constraint"),
    ([*_without(SSP, "--very-hard-to-change"), "--very-hard-to-change", "Q", "-o", "X"],
     "error: --very-hard-to-change: 'Q'"),
    ([*_without(SSP, "--whole-plots"), "--whole-plots", "1", "-o", "X"], "error: --whole-plots: 1 whole plots"),
    ([*_without(SSP, "--subplots"), "--subplots", "4", "-o", "X"], "error: --subplots: 4 sub-plots"),
    ([*_without(STRIP, "--column-factor"), "--column-factor", "A", "-o", "X"], "error: --column-factor: 'A' is already"),
    ([*_without(STRIP, "--rows"), "--rows", "1", "-o", "X"], "error: --rows: 5 runs cannot estimate"),
])
def test_bad_input_names_the_option(tmp_path, capsys, argv, needle):
    argv = [str(tmp_path / "d.csv") if a == "X" else a for a in argv]
    line = error_line(capsys, main(argv))
    assert line.startswith(needle), line
    assert not (tmp_path / "d.csv").exists()


def test_evaluate_unknown_stratum(tmp_path, capsys):
    out = tmp_path / "strip.csv"
    assert main([*STRIP, "-o", str(out)]) == 0
    capsys.readouterr()
    line = error_line(capsys, main(["evaluate", str(out), "--model", "2fi", "--variance-ratio-of", "subplot=2"]))
    assert "--variance-ratio-of" in line and "'subplot' is not a stratum" in line
    line = error_line(capsys, main(["evaluate", str(out), "--variance-ratio-of", "strip_row"]))
    assert line.startswith("error: --variance-ratio-of 'strip_row': expected COL=ETA")


def test_variance_ratio_of_on_a_split_plot_design(tmp_path, capsys):
    """One stratum: --variance-ratio-of whole_plot=ETA gives the closed-form split-plot criteria of
    --variance-ratio ETA (Goos & Vandebroek's V_b^-1 = I - c_b J against the dense inverse)."""
    out = tmp_path / "sp.csv"
    assert main(["design", "split-plot", *FACTORS, "--hard-to-change", "T", "--whole-plots", "4", "--runs", "12",
                 "--model", "linear", "--seed", "1", "--starts", "2", "-o", str(out)]) == 0
    capsys.readouterr()
    assert main(["evaluate", str(out), "--model", "linear", "--variance-ratio", "2.5", "--json", "-"]) == 0
    closed = json.loads(capsys.readouterr().out)["split_plot"]
    assert main(["evaluate", str(out), "--model", "linear", "--variance-ratio-of", "whole_plot=2.5", "--json", "-"]) == 0
    dense = json.loads(capsys.readouterr().out)["split_plot"]
    for key in ("d_efficiency", "a_efficiency", "i_average"):
        assert dense[key] == pytest.approx(closed[key], rel=1e-10)
    assert dense["strata"]["whole_plot"]["variance_ratio"] == 2.5
