"""``fit --reduce forward|backward|stepwise|all-subsets --criterion p|aicc|bic [--alpha-in A]``
(issue 35, item 5) on the command line; the choices themselves are checked in
``tests/model/choice/test_select.py``."""

import json

import pytest
from _cli_errors import error_line

from rsm_lrg.cli import main

BASE = ["fit", "data/table4.csv", "--response", "tcr_c_per_min"]


@pytest.mark.parametrize("extra,method,criterion", [
    (["--reduce"], None, "p"), (["--reduce", "backward"], None, "p"),
    (["--reduce", "forward", "--alpha-in", "0.1"], "forward", "p"),
    (["--reduce", "stepwise", "--criterion", "bic"], "stepwise", "bic"),
    (["--reduce", "all-subsets"], "all-subsets", "aicc"),
    (["--reduce", "backward", "--criterion", "bic"], "backward", "bic"),
])
def test_reduce_methods_json(capsys, extra, method, criterion):
    assert main(BASE + extra + ["--json", "-"]) == 0
    red = json.loads(capsys.readouterr().out)["reduction"]
    assert red.get("method") == method and red["criterion"] == criterion
    # every method keeps the paper's reduced model on Table 4 (A, B, C, D, AC, C^2, D^2)
    assert red["kept"] == ["Intercept", "A", "B", "C", "D", "AC", "C^2", "D^2"]


def test_alpha_in(capsys):
    # D^2 enters at p between 0.05 and 0.1: --alpha-in 0.05 leaves it out
    assert main(BASE + ["--reduce", "forward", "--alpha-in", "0.05", "--json", "-"]) == 0
    red = json.loads(capsys.readouterr().out)["reduction"]
    assert red["kept"] == ["Intercept", "A", "B", "C", "D", "AC", "C^2"] and red["alpha_in"] == 0.05


def test_all_subsets_text(capsys):
    assert main(BASE + ["--reduce", "all-subsets", "--criterion", "bic"]) == 0
    out = capsys.readouterr().out
    assert "All-subsets selection (BIC, hierarchy kept): kept A B C D AC C^2 D^2" in out
    assert "1337 hierarchical models compared" in out


def test_backward_text_is_unchanged(capsys):
    assert main(BASE + ["--reduce"]) == 0
    assert "Backward elimination (p > 0.1, hierarchy kept): removed BC, AB, A^2, CD, BD, B^2, AD" in \
        capsys.readouterr().out


@pytest.mark.parametrize("extra,needle", [
    (["--reduce", "all-subsets", "--criterion", "p"], "--criterion"),
    (["--reduce", "stepwise", "--alpha-in", "0.2"], "--alpha-in"),
    (["--reduce", "sideways"], "--reduce"),
    (["--criterion", "r2"], "--criterion"),
])
def test_bad_values_exit_2(capsys, extra, needle):
    line = error_line(capsys, main(BASE + extra))
    assert needle in line
