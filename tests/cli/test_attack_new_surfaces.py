"""The new surfaces attacked as a user would (issue 36, last paragraph): ``predict``,
``design-space``, ``suggest``, Gaussian-process fits (junk hyper-parameters, duplicated points,
one run, a constant response), binomial fits (separation, a response outside 0..1, a trials
column with zeros), a simulator asked for 10¹² draws, ``--spec`` with LOW > HIGH, NaN and inf
in ``--at``. Every one exits 0 with a right answer or 2 with one ``error:`` line naming the
option or the column (and row)."""

from __future__ import annotations

import pandas as pd
import pytest

from rsm_lrg.cli import main
from rsm_lrg.datasets import data_path

TABLE = str(data_path("table4.csv"))
R = ["--response", "tcr_c_per_min"]
AT = ["--at", "thickness_m=0.0003", "stroke_m=0.05", "velocity_m_s=0.5", "acceleration_m_s2=30"]
FACTORS = ["thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2"]


@pytest.fixture
def files(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    d = pd.read_csv(TABLE)
    pd.concat([d] * 3).to_csv("dup.csv", index=False)  # every setting three times
    d.iloc[:1].to_csv("one.csv", index=False)
    d.assign(tcr_c_per_min=0.03).to_csv("const.csv", index=False)
    d.assign(wp=1).to_csv("wp1.csv", index=False)
    pts = d[FACTORS].head(3).astype(object)
    pts.loc[1, "stroke_m"] = "inf"
    pts.to_csv("pts_inf.csv", index=False)
    pd.DataFrame({"x": [1, 2, 3, 4, 5, 6], "y": [0, 0, 0, 1, 1, 1]}).to_csv("sep.csv", index=False)
    pd.DataFrame({"x": [1, 2, 3, 4, 5, 6], "y": [0, 0.5, 0, 1, 1, 1]}).to_csv("half.csv", index=False)
    bud = pd.DataFrame({"ldose": [0, 1, 2, 3, 4, 5] * 2, "sex": ["M"] * 6 + ["F"] * 6,
                        "dead": [1, 4, 9, 13, 18, 20, 0, 2, 6, 10, 12, 16], "n": [20] * 12})
    bud.assign(n=[20, 20, 0] + [20] * 9).to_csv("trials0.csv", index=False)
    bud.assign(dead=[1, 4, 25] + list(bud["dead"][3:])).to_csv("over.csv", index=False)
    return tmp_path


def _one_error(capsys, *words):
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error:"), err
    for w in words:
        assert w in err[0], (w, err[0])
    return err[0]


CASES = {
    "at-nan": (["predict", TABLE, *R, "--at", "thickness_m=nan", "stroke_m=0.05", "velocity_m_s=0.5",
                "acceleration_m_s2=30"], ["--at", "thickness_m=nan"]),
    "at-inf": (["predict", TABLE, *R, "--at", "thickness_m=inf", "stroke_m=0.05", "velocity_m_s=0.5",
                "acceleration_m_s2=30"], ["--at", "finite"]),
    "predict-spec-low-above-high": (["predict", TABLE, *R, *AT, "--draws", "100", "--seed", "1", "--spec",
                                     "tcr_c_per_min=0.05:0.01"], ["--spec", "LOW must be below HIGH"]),
    "predict-spec-nan": (["predict", TABLE, *R, *AT, "--draws", "100", "--seed", "1", "--spec",
                          "tcr_c_per_min=nan:0.05"], ["--spec", "finite"]),
    "predict-1e12-draws": (["predict", TABLE, *R, *AT, "--draws", "1000000000000", "--seed", "1"], ["--draws"]),
    "predict-points-inf": (["predict", TABLE, *R, "--points", "pts_inf.csv"], ["pts_inf.csv", "'stroke_m', row 2"]),
    "design-space-spec-low-above-high": (["design-space", TABLE, *R, "--spec", "tcr_c_per_min=0.05:0.01"],
                                         ["--spec", "low limit must be below"]),
    "design-space-1e12-draws": (["design-space", TABLE, *R, "--spec", "tcr_c_per_min=:0.03", "--draws",
                                 "1000000000000"], ["--draws"]),
    "gp-nugget-huge": (["fit", TABLE, *R, "--model", "gp", "--nugget", "1e308"], ["--nugget", "every run would be noise"]),
    "gp-nugget-nan": (["fit", TABLE, *R, "--model", "gp", "--nugget", "nan"], ["--nugget"]),
    "gp-nugget-zero-on-duplicates": (["fit", "dup.csv", *R, "--model", "gp", "--nugget", "0"], ["--nugget", "25 setting"]),
    "gp-one-run": (["fit", "one.csv", *R, "--model", "gp"], ["one.csv", "constant"]),
    "gp-constant-response": (["fit", "const.csv", *R, "--model", "gp"], ["const.csv", "'tcr_c_per_min' is constant"]),
    "suggest-nugget-huge": (["suggest", TABLE, *R, "-o", "n.csv", "--nugget", "1e308"], ["--nugget"]),
    "suggest-bound-low-above-high": (["suggest", TABLE, *R, "-o", "n.csv", "--bound", "thickness_m=0.0005:0.0001"],
                                     ["--bound", "LOW must be below HIGH"]),
    "suggest-1e9-runs": (["suggest", TABLE, *R, "-o", "n.csv", "--runs", "1000000000"], ["--runs"]),
    "binomial-separation": (["fit", "sep.csv", "--response", "y", "--factor", "x", "--family", "binomial", "--model",
                             "linear"], ["sep.csv", "separated"]),
    "binomial-response-outside-0-1": (["fit", "half.csv", "--response", "y", "--factor", "x", "--family", "binomial",
                                       "--model", "linear"], ["half.csv", "'y', row 2", "0.5"]),
    "binomial-trials-zero": (["fit", "trials0.csv", "--response", "dead", "--factor", "ldose", "--factor", "sex",
                              "--trials", "n", "--family", "binomial", "--model", "linear"],
                             ["trials0.csv", "trials column 'n', row 3"]),
    "binomial-successes-above-trials": (["fit", "over.csv", "--response", "dead", "--factor", "ldose", "--factor",
                                         "sex", "--trials", "n", "--family", "binomial", "--model", "linear"],
                                        ["over.csv", "'dead', row 3"]),
    "random-effect-one-level": (["fit", "wp1.csv", *R, "--factor", "thickness_m", "--factor", "stroke_m", "--factor",
                                 "velocity_m_s", "--factor", "acceleration_m_s2", "--whole-plot", "wp"],
                                ["wp1.csv", "'wp'", "single level"]),
}


@pytest.mark.parametrize("name", list(CASES))
def test_attack_ends_with_one_line_naming_the_culprit(name, files, capsys):
    argv, words = CASES[name]
    assert main(argv) == 2
    _one_error(capsys, *words)
    assert not (files / "n.csv").exists()


def test_gp_on_duplicated_points_estimates_the_noise(files, capsys):
    """Every setting three times with the same value: the nugget is estimated (and said), and
    since the copies agree exactly it comes out small beside the process variance (no noise
    between copies), not an error."""
    import json

    assert main(["fit", "dup.csv", *R, "--model", "gp", "--json", "-"]) == 0
    js = json.loads(capsys.readouterr().out)
    assert any("nugget estimated: 25 setting(s)" in n for n in js["notes"]), js["notes"]
    assert 0.0 <= js["gp"]["nugget"] < 1e-2 * js["gp"]["variance"]
