"""``fit --random-effect COL`` (repeatable): REML with several random intercepts on the
command line (the JSON's ``tests`` and one variance component per column), ``predict`` and
``optimize`` on such a fit; bad input exits 2 with one line naming the option or column."""

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from rsm_lrg.cli import main

R = Path(__file__).parents[1] / "model" / "r"
SSP = str(R / "mixed_ssp.csv")  # the split-split-plot of tests/model/r/make_mixed_several.py
BASE = ["--response", "wear_um", "--factor", "temp_c", "--factor", "preload_kn", "--factor", "speed_m_s", "--factor",
        "lube_ml", "--model", "2fi", "--random-effect", "whole_plot", "--random-effect", "subplot"]


def _err(capsys) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error:"), err
    return err[0]


def test_fit_random_effects_json_matches_pbkrtest(capsys):
    assert main(["fit", SSP, *BASE, "--json", "-"]) == 0
    js = json.loads(capsys.readouterr().out)
    assert js["random_effect_columns"] == ["whole_plot", "subplot"] and js["method"] == "REML"
    assert list(js["variance_components"]) == ["whole_plot", "subplot", "residual"]
    exp = pd.read_csv(R / "mixed_several_kr_expected.csv")
    exp = exp[exp.dataset == "mixed_ssp"]
    tests = {t["term"]: t for t in js["tests"]}
    for row in exp.itertuples():
        t = tests[row.term.replace(":", "")]
        np.testing.assert_allclose([t["den_df"], t["f"], t["p"]], [row.den_df, row.f, row.p], rtol=1e-5)
    vc = pd.read_csv(R / "mixed_several_vc_expected.csv")
    for row in vc[vc.dataset == "mixed_ssp"].itertuples():
        assert js["variance_components"][row.component]["variance"] == pytest.approx(row.variance, rel=1e-6)


def test_fit_random_effects_text_and_predict(capsys):
    assert main(["fit", SSP, *BASE]) == 0
    out = capsys.readouterr().out
    assert "random intercepts per level of 'whole_plot' (8) and of 'subplot' (16)" in out
    assert "Kenward-Roger F tests" in out
    assert main(["predict", SSP, *BASE, "--at", "temp_c=180", "preload_kn=4", "speed_m_s=2", "lube_ml=10",
                 "--json", "-"]) == 0
    js = json.loads(capsys.readouterr().out)
    text = json.dumps(js)
    assert "pi_low" in text and "ci_low" in text


def test_optimize_on_several_random_effects(capsys):
    assert main(["optimize", SSP, *BASE, "--goal", "minimize", "--json", "-"]) == 0
    opt = json.loads(capsys.readouterr().out)
    assert opt["actual"]["speed_m_s"] == pytest.approx(3.0)


@pytest.mark.parametrize("args, needle", [
    (["--random-effect", "nope"], "random-effect column 'nope' not found"),
    (["--random-effect", "whole_plot"], "--random-effect: random-effect column 'whole_plot' is given twice"),
    (["--block", "whole_plot"], "--block"),
    (["--family", "poisson"], "--random-effect: not available with --family"),
])
def test_bad_random_effect_options_exit_2(args, needle, capsys):
    assert main(["fit", SSP, *BASE, *args]) == 2
    assert needle in _err(capsys)
