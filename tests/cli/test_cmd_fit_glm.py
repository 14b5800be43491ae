"""``fit --family binomial|poisson [--link L] [--trials COL]`` on the command line (issue 35,
item 1): the text and the JSON, and bad input exiting 2 with one line naming the option or the
cell. The numbers themselves are checked against R in ``tests/model/pipelines/test_glm_r.py``."""

import json
from pathlib import Path

import pandas as pd
import pytest
from _cli_errors import error_line

from rsm_lrg.cli import main

R = Path(__file__).parents[1] / "model" / "r"
BUDWORM = str(R / "glm_budworm.csv")  # Venables & Ripley (2002) sec. 7.2
WARP = str(R / "glm_warpbreaks.csv")  # R datasets::warpbreaks
BW = ["--response", "numdead", "--trials", "n", "--factor", "ldose", "--factor", "sex=cat:F,M", "--model", "2fi",
      "--family", "binomial"]


def test_fit_binomial_trials_json(capsys):
    assert main(["fit", BUDWORM, *BW, "--link", "probit", "--json", "-"]) == 0
    js = json.loads(capsys.readouterr().out)
    assert (js["family"], js["link"], js["trials"]) == ("binomial", "probit", "n")
    exp = pd.read_csv(R / "glm_stats_expected.csv").query("dataset == 'budworm' and link == 'probit'")
    assert js["deviance"] == pytest.approx(float(exp.set_index("stat").loc["deviance", "value"]), rel=1e-8)
    assert set(js["coefficients"]["coded"]) == set(js["std_errors"]["coded"]) == {"Intercept", "A", "B[F]", "AB[F]"}
    assert [r["source"] for r in js["anova"]] == ["Model", "A", "B", "AB"]
    assert all(r["chi_square"] > 0 and 0 <= r["p"] <= 1 for r in js["anova"])


def test_fit_poisson_text(capsys):
    assert main(["fit", WARP, "--response", "breaks", "--factor", "wool=cat:A,B", "--factor", "tension=cat:L,M,H",
                 "--model", "2fi", "--family", "poisson"]) == 0
    out = capsys.readouterr().out
    for needle in ("poisson (log link)", "Analysis of deviance", "Residual deviance 182.305", "AICc",
                   "log(mean count) in coded units", "No prediction interval"):
        assert needle in out, needle


def test_fit_json_file_also_prints_text(tmp_path, capsys):
    path = tmp_path / "glm.json"
    assert main(["fit", BUDWORM, *BW, "--json", str(path)]) == 0
    assert "Analysis of deviance" in capsys.readouterr().out
    assert json.loads(path.read_text())["link"] == "logit"


@pytest.mark.parametrize("extra,needle", [
    (["--link", "log"], "--link"),
    (["--transform", "log"], "--transform"),
    (["--block", "sex"], "--block"),
])
def test_bad_options_exit_2_naming_the_option(capsys, extra, needle):
    args = ["fit", BUDWORM, *BW, *extra]
    line = error_line(capsys, main(args))
    assert line.startswith(f"error: {needle}"), line


def test_trials_with_poisson(capsys):
    line = error_line(capsys, main(["fit", BUDWORM, "--response", "numdead", "--trials", "n", "--family", "poisson"]))
    assert line.startswith("error: --trials") and "binomial" in line


def test_link_without_family(capsys):
    line = error_line(capsys, main(["fit", BUDWORM, "--response", "numdead", "--link", "probit"]))
    assert line.startswith("error: --link") and "--family" in line


def test_bad_family_is_a_usage_error(capsys):
    line = error_line(capsys, main(["fit", BUDWORM, "--response", "numdead", "--family", "gamma"]))
    assert "--family" in line


def test_bad_cells_name_file_column_and_row(tmp_path, capsys):
    df = pd.read_csv(BUDWORM)
    df.loc[3, "numdead"] = 25
    path = tmp_path / "bad.csv"
    df.to_csv(path, index=False)
    line = error_line(capsys, main(["fit", str(path), *BW]))
    assert "bad.csv" in line and "'numdead', row 4" in line
    line = error_line(capsys, main(["fit", BUDWORM, "--response", "numdead", "--family", "binomial"]))
    assert "row 1: 1 is not 0 or 1" not in line and "is not 0 or 1" in line
    line = error_line(capsys, main(["fit", BUDWORM, *BW[:2], "--trials", "nope", "--family", "binomial"]))
    assert line.startswith("error: --trials") and "'nope' not found" in line


def test_separation_exits_2_with_one_line(tmp_path, capsys):
    path = tmp_path / "sep.csv"
    pd.DataFrame({"x": [1, 2, 3, 4, 5, 6], "pass": [0, 0, 0, 1, 1, 1]}).to_csv(path, index=False)
    line = error_line(capsys, main(["fit", str(path), "--response", "pass", "--model", "linear", "--family",
                                    "binomial"]))
    assert "completely separated" in line and "rows 1, 2, 3, 4, 5, 6" in line


def test_glm_term_selection(capsys):
    assert main(["fit", WARP, "--response", "breaks", "--factor", "wool=cat:A,B", "--factor", "tension=cat:L,M,H",
                 "--model", "2fi", "--family", "poisson", "--reduce", "stepwise", "--criterion", "bic",
                 "--json", "-"]) == 0
    js = json.loads(capsys.readouterr().out)
    assert js["reduction"]["method"] == "stepwise" and js["reduction"]["kept"] == ["Intercept", "A", "B", "AB"]
    assert main(["fit", WARP, "--response", "breaks", "--factor", "wool=cat:A,B", "--factor", "tension=cat:L,M,H",
                 "--model", "2fi", "--family", "poisson", "--reduce"]) == 0
    assert "Backward selection (likelihood-ratio p > 0.1, hierarchy kept)" in capsys.readouterr().out
