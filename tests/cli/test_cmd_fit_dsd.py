"""``fit --reduce dsd`` (issue 35, item 5): the two-stage analysis of a definitive screening design
on the command line, its JSON and text, and bad input exiting 2 with one line naming the option."""

import json

import numpy as np
import pandas as pd
import pytest
from _cli_errors import error_line

from rsm_lrg.cli import main


@pytest.fixture(scope="module")
def dsd_data(tmp_path_factory):
    """An 8-factor DSD with 3 centre runs, G and H left out as fake factors, and a response with
    known active terms (4A - 3C + 2.5D + 3AC + 4D^2, noise sd 1)."""
    tmp = tmp_path_factory.mktemp("dsd")
    design = tmp / "dsd.csv"
    args = ["design", "definitive-screening"] + [a for L in "ABCDEFGH" for a in ("--factor", f"{L}=0:1")]
    assert main([*args, "--center", "3", "--seed", "1", "-o", str(design)]) == 0
    df = pd.read_csv(design)
    X = df[[c for c in df.columns if c.startswith("coded_")]].to_numpy(dtype=float)
    rng = np.random.default_rng(3)
    df["strength_mpa"] = (50 + 4 * X[:, 0] - 3 * X[:, 2] + 2.5 * X[:, 3] + 3 * X[:, 0] * X[:, 2] + 4 * X[:, 3] ** 2
                          + rng.normal(0, 1, len(df)))
    data = tmp / "dsd_y.csv"
    df.drop(columns=["G", "H", "coded_G", "coded_H"]).to_csv(data, index=False)
    return data


def test_fit_reduce_dsd_json_and_text(dsd_data, capsys):
    assert main(["fit", str(dsd_data), "--response", "strength_mpa", "--reduce", "dsd", "--json", "-"]) == 0
    js = json.loads(capsys.readouterr().out)
    red = js["reduction"]
    assert red["method"] == "dsd" and red["alpha"] == 0.05
    assert red["kept"] == ["Intercept", "A", "C", "D", "AC", "D^2"]
    assert red["stage1"]["method"] == "fake factors and centre runs" and red["stage1"]["df"] == 7
    assert [e["term"] for e in red["stage1"]["effects"] if e["active"]] == ["A", "C", "D"]
    assert [s["terms"] for s in red["stage2"]["steps"]] == ["", "AC", "AC D^2"]
    assert (red["fake_df"], red["pure_error_df"], red["pairs"], red["centre_runs"]) == (2, 2, 8, 3)
    assert set(js["coefficients"]["coded"]) == {"Intercept", "A", "C", "D", "AC", "D^2"}
    assert main(["fit", str(dsd_data), "--response", "strength_mpa", "--reduce", "dsd"]) == 0
    out = capsys.readouterr().out
    assert "Definitive screening two-stage analysis (Jones & Nachtsheim 2017), alpha 0.05" in out
    assert "Model: A C D AC D^2 (second order: AC D^2)" in out


def test_alpha_in_sets_the_threshold(dsd_data, capsys):
    assert main(["fit", str(dsd_data), "--response", "strength_mpa", "--reduce", "dsd", "--alpha-in", "0.2",
                 "--json", "-"]) == 0
    assert json.loads(capsys.readouterr().out)["reduction"]["alpha"] == 0.2


@pytest.mark.parametrize("extra, needle", [
    (["--criterion", "aicc"], "error: --criterion"),
    (["--terms", "A B AB"], "error: --terms"),
    (["--model", "2fi"], "error: --model"),
])
def test_bad_options(dsd_data, capsys, extra, needle):
    line = error_line(capsys, main(["fit", str(dsd_data), "--response", "strength_mpa", "--reduce", "dsd", *extra]))
    assert line.startswith(needle), line


def test_not_a_fold_over_design(dsd_data, tmp_path, capsys):
    df = pd.read_csv(dsd_data).drop(index=4)
    bad = tmp_path / "bad.csv"
    df.to_csv(bad, index=False)
    line = error_line(capsys, main(["fit", str(bad), "--response", "strength_mpa", "--reduce", "dsd"]))
    assert "has no mirror run" in line and "fold-over pairs" in line
