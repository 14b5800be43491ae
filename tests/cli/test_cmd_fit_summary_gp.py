"""``rsm-lrg fit-summary --gp``: the GP's leave-one-out beside the polynomials' PRESS."""

import json
from pathlib import Path

import pytest
from _cli_errors import error_line

from rsm_lrg.cli import main

BRANIN = str(Path(__file__).parents[1] / "model" / "r" / "gp_branin.csv")
FACTORS = ["--factor", "x1=-5:10", "--factor", "x2=0:15"]


def test_text_and_json(capsys):
    assert main(["fit-summary", BRANIN, "--response", "y", *FACTORS, "--gp", "--kernel", "matern32"]) == 0
    out = capsys.readouterr().out
    assert "Leave-one-out: polynomials (PRESS) and the Gaussian process" in out and "GP (matern32, constant)" in out
    assert main(["fit-summary", BRANIN, "--response", "y", *FACTORS, "--gp", "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    models = [m["model"] for m in d["loo_comparison"]["models"]]
    assert models[-1] == "GP (matern52, constant)" and "Quadratic" in models


@pytest.mark.parametrize("args, option", [
    (["--kernel", "gauss"], "--kernel"),
    (["--gp", "--transform", "log"], "--gp"),
    (["--gp", "--nugget", "x"], "--nugget"),
])
def test_bad_input_is_one_error_line(args, option, capsys):
    assert option in error_line(capsys, main(["fit-summary", BRANIN, "--response", "y", *FACTORS, *args]))
