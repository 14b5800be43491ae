"""``rsm-lrg optimize --interval ci|pi|ti``, ``--factor-sd`` and ``--goal poe``: the JSON equals
the library (:func:`rsm_lrg.optimize.robust.optimize_robust`); bad input names the option."""

from __future__ import annotations

import json
from pathlib import Path

import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.cli import main
from rsm_lrg.optimize.robust import optimize_robust, parse_robust_goal
from tests.cli._cli_errors import error_line

ROOT = Path(__file__).parents[2]
T4 = str(ROOT / "data" / "table4.csv")
Y = "tcr_c_per_min"
HELI = str(ROOT / "tests" / "model" / "r" / "heli.csv")


def test_interval_optimum_equals_the_library(capsys):
    assert main(["optimize", T4, "--response", Y, "--goal", "minimize", "--interval", "ci", "--confidence", "0.9",
                 "--factor-sd", "velocity_m_s=0.02", "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    fit = rsm_lrg.fit(pd.read_csv(T4), Y)
    g, _ = parse_robust_goal(Y, "minimize")
    exp = optimize_robust({Y: fit}, [g], intervals={Y: "ci"}, confidence=0.9, factor_sd={"velocity_m_s": 0.02})
    assert d["actual"] == pytest.approx(exp.actual, rel=1e-12)
    r = d["responses"][Y]
    assert r["optimised"] == "ci_high" and r["value"] == pytest.approx(exp.responses[Y]["value"], rel=1e-12)
    assert r["predicted"] < r["high"] and r["poe"] > 0 and d["confidence"] == 0.9


def test_poe_goal_and_several_responses(capsys):
    assert main(["optimize", T4, "--response", Y, "--goal", "poe", "--factor-sd", "velocity_m_s=0.02",
                 "--factor-sd", "acceleration_m_s2=1", "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["responses"][Y]["optimised"] == "poe"
    argv = ["optimize", HELI, "--factor", "A", "--factor", "R", "--factor", "W", "--factor", "L",
            "--response", "ave", "--goal", "maximize", "--interval", "pi", "--limits", "360:400",
            "--response", "logSD", "--goal", "minimize", "--interval", "ti", "--limits", "40:90", "--json", "-"]
    assert main(argv) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["responses"]["ave"]["optimised"] == "pi_low" and d["responses"]["logSD"]["optimised"] == "ti_high"
    assert 0 <= d["desirability"] <= 1 and d["tolerance"] == 0.99


@pytest.mark.parametrize("extra, option", [
    (["--goal", "poe"], "--factor-sd"),
    (["--interval", "xi"], "--interval"),
    (["--interval", "ci", "--confidence", "2"], "--confidence"),
    (["--interval", "ti", "--tolerance", "0"], "--tolerance"),
    (["--factor-sd", "velocity_m_s=-2"], "--factor-sd"),
    (["--goal", "poe", "--factor-sd", "stroke_m=0.001", "--interval", "ci"], "--interval"),
])
def test_bad_options(capsys, extra, option):
    line = error_line(capsys, main(["optimize", T4, "--response", Y, *extra]))
    assert option in line


def test_plain_optimize_is_unchanged(capsys):
    assert main(["optimize", T4, "--response", Y, "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert "responses" not in d  # the classic optimum, not the interval optimiser


def test_mixture_from_the_command_line(capsys):
    etch = str(ROOT / "tests" / "model" / "r" / "mixture_etch.csv")
    comps = ["--component", "x1", "--component", "x2", "--component", "x3", "--model", "mixture-quadratic"]
    assert main(["optimize", etch, "--response", "erate", *comps, "--goal", "maximize", "--interval", "pi",
                 "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert sum(d["actual"].values()) == pytest.approx(1.0, abs=1e-12)
    assert d["responses"]["erate"]["optimised"] == "pi_low"
    line = error_line(capsys, main(["optimize", etch, "--response", "erate", *comps, "--goal", "maximize",
                                    "--interval", "pi", "--bound", "x1=0.1:0.5"]))
    assert "--bound" in line
