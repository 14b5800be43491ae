"""``rsm-lrg evaluate`` on split-plot designs (issue 23): the GLS criteria under the variance
ratio beside the OLS evaluation, checked by plain numpy (dense V, exact cube moments); a
design without whole plots is evaluated as before."""

import itertools
import json
import math

import numpy as np
import pandas as pd
import pytest
from _cli_errors import error_line

from rsm_lrg.cli import main

FACTORS = ["--factor", "T=150:250", "--factor", "P=1:3", "--factor", "v=0.1:0.5", "--factor", "a=1:5"]


def _exponents(k: int) -> list[tuple[int, ...]]:
    """Intercept, linear, 2FI, squares (the quadratic model's column order)."""
    e = [tuple([0] * k)] + [tuple(int(i == j) for j in range(k)) for i in range(k)]
    e += [tuple(int(j in (a, b)) for j in range(k)) for a, b in itertools.combinations(range(k), 2)]
    return e + [tuple(2 * int(i == j) for j in range(k)) for i in range(k)]


def _dense(coded: np.ndarray, plots: np.ndarray, eta: float) -> dict:
    E = _exponents(coded.shape[1])
    X = np.column_stack([np.prod(coded ** np.array(e), axis=1) for e in E])
    V = np.eye(len(plots)) + eta * (plots[:, None] == plots[None, :])
    M = X.T @ np.linalg.inv(V) @ X
    n, p = X.shape

    def moment(e):  # E[prod x_i^e_i], x uniform on [-1, 1]^k
        return math.prod(0.0 if m % 2 else 1.0 / (m + 1) for m in e)

    W = np.array([[moment(np.add(a, b)) for b in E] for a in E])
    Minv = np.linalg.inv(M)
    return {"d": np.linalg.det(M) ** (1 / p) / n, "a": p / (n * np.trace(Minv)), "i": np.trace(Minv @ W)}


@pytest.fixture(scope="module")
def design(tmp_path_factory):
    path = tmp_path_factory.mktemp("sp") / "sp.csv"
    assert main(["design", "split-plot", *FACTORS, "--hard-to-change", "T", "--hard-to-change", "P",
                 "--whole-plots", "8", "--runs", "32", "--seed", "2", "--starts", "2", "-o", str(path)]) == 0
    return path


def _json(capsys, argv) -> dict:
    capsys.readouterr()
    assert main(argv + ["--json", "-"]) == 0
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize("eta", [None, 0.0, 3.0])
def test_gls_criteria_match_dense_route(design, capsys, eta):
    argv = ["evaluate", str(design), "--potential", "none"] + ([] if eta is None else ["--variance-ratio", str(eta)])
    out = _json(capsys, argv)
    g = out["split_plot"]
    df = pd.read_csv(design)
    coded = df[["coded_A", "coded_B", "coded_C", "coded_D"]].to_numpy(float)
    ref = _dense(coded, df["whole_plot"].to_numpy(), 1.0 if eta is None else eta)
    assert g["variance_ratio"] == (1.0 if eta is None else eta)
    assert g["d_efficiency"] == pytest.approx(ref["d"], rel=1e-9)
    assert g["a_efficiency"] == pytest.approx(ref["a"], rel=1e-9)
    assert g["i_average"] == pytest.approx(ref["i"], rel=1e-9)
    assert g["whole_plots"] == 8 and g["plot_sizes"] == [4, 4]
    if eta == 0.0:  # no whole-plot variance: GLS is OLS
        assert g["d_efficiency"] == pytest.approx(out["d_efficiency"], rel=1e-12)
        assert g["i_average"] == pytest.approx(out["i_average"], rel=1e-9)


def test_text_says_eta_and_ols(design, capsys):
    capsys.readouterr()
    assert main(["evaluate", str(design), "--potential", "none", "--variance-ratio", "2"]) == 0
    text = capsys.readouterr().out
    assert "Split-plot design: 8 whole plots (4 runs each)" in text
    assert "η = σ²_wp/σ² = 2" in text and "treat the runs as independent (OLS" in text


def test_named_whole_plot_column_and_data_csv(design, tmp_path, capsys):
    df = pd.read_csv(design)
    ref = _json(capsys, ["evaluate", str(design), "--potential", "none"])["split_plot"]
    renamed = tmp_path / "renamed.csv"
    df.rename(columns={"whole_plot": "furnace_batch"}).to_csv(renamed, index=False)
    got = _json(capsys, ["evaluate", str(renamed), "--potential", "none", "--whole-plot", "furnace_batch"])
    assert got["split_plot"]["d_efficiency"] == pytest.approx(ref["d_efficiency"], rel=1e-12)
    # a data sheet without coded columns: the whole-plot column is not a factor (labels as text)
    data = tmp_path / "data.csv"
    plain = df[["T", "P", "v", "a"]].assign(batch=[f"b{w}" for w in df["whole_plot"]])
    plain.to_csv(data, index=False)
    got = _json(capsys, ["evaluate", str(data), "--potential", "none", "--whole-plot", "batch"])
    assert got["p"] == 15 and got["split_plot"]["whole_plots"] == 8


def test_no_whole_plots_is_unchanged(tmp_path, capsys):
    ccd = tmp_path / "ccd.csv"
    assert main(["design", "central-composite", "--factor", "x=0:1", "--factor", "y=0:1", "--seed", "1",
                 "-o", str(ccd)]) == 0
    out = _json(capsys, ["evaluate", str(ccd)])
    assert "split_plot" not in out
    assert main(["evaluate", str(ccd)]) == 0
    assert "Split-plot" not in capsys.readouterr().out


def test_errors(design, tmp_path, capsys):
    capsys.readouterr()
    assert "--whole-plot" in error_line(capsys, main(["evaluate", str(design), "--whole-plot", "nope"]))
    assert "--variance-ratio" in error_line(capsys, main(["evaluate", str(design), "--variance-ratio", "-2"]))
    ccd = tmp_path / "ccd.csv"
    assert main(["design", "central-composite", "--factor", "x=0:1", "--factor", "y=0:1", "--seed", "1",
                 "-o", str(ccd)]) == 0
    capsys.readouterr()
    assert "--variance-ratio" in error_line(capsys, main(["evaluate", str(ccd), "--variance-ratio", "1"]))
    df = pd.read_csv(design)
    df.loc[5, "whole_plot"] = None
    holed = tmp_path / "holed.csv"
    df.to_csv(holed, index=False)
    line = error_line(capsys, main(["evaluate", str(holed)]))
    assert "whole_plot" in line and "row 6" in line


def test_comparison_reports_each_designs_gls(design, tmp_path, capsys):
    other = tmp_path / "other.csv"
    assert main(["design", "split-plot", *FACTORS, "--hard-to-change", "T", "--whole-plots", "8", "--runs", "32",
                 "--seed", "3", "--starts", "1", "-o", str(other)]) == 0
    out = _json(capsys, ["evaluate", str(design), str(other), "--potential", "none"])
    g = out["split_plot"]
    assert set(g) == {str(design), str(other)}
    for path in (design, other):
        df = pd.read_csv(path)
        coded = df[["coded_A", "coded_B", "coded_C", "coded_D"]].to_numpy(float)
        assert g[str(path)]["d_efficiency"] == pytest.approx(_dense(coded, df["whole_plot"].to_numpy(), 1.0)["d"],
                                                             rel=1e-9)
    assert main(["evaluate", str(design), str(other), "--potential", "none"]) == 0
    text = capsys.readouterr().out
    assert f"{design}: Split-plot design" in text and f"{other}: Split-plot design" in text


def test_library_returns_what_the_command_prints(design, capsys):
    """Design evaluation is in one place: ``evaluate_design`` of the split-plot design holds
    the GLS criteria the command prints (JSON and text), and refuses a variance ratio for a
    design without whole plots by naming it."""
    import rsm_lrg
    from rsm_lrg.errors import ParameterError

    out = _json(capsys, ["evaluate", str(design), "--potential", "none", "--variance-ratio", "2.5"])
    ev = rsm_lrg.evaluate_design(rsm_lrg.read_design(design), "quadratic", potential=None, variance_ratio=2.5)
    assert ev.to_dict()["split_plot"] == out["split_plot"]
    assert "Split-plot design: 8 whole plots (4 runs each)" in ev.summary()
    with pytest.raises(ParameterError) as info:
        rsm_lrg.evaluate_design(np.zeros((4, 2)) + [[-1, -1], [1, -1], [-1, 1], [1, 1]], "linear", variance_ratio=1.0)
    assert info.value.parameter == "variance_ratio"
