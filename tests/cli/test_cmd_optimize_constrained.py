"""``rsm-lrg optimize`` with several ``--response`` and ``--constraint``: the desirability
optimum inside the constrained region; constraint errors are one ``error: --constraint:`` line
(exit 2) and no output file."""

import json

import numpy as np
import pandas as pd
import pytest

from rsm_lrg.cli import main

EXPR = "v**2/a <= 0.02"


@pytest.fixture(scope="module")
def csv(tmp_path_factory):
    rng = np.random.default_rng(7)
    g = np.linspace(-1, 1, 5)
    x1, x2 = np.array(np.meshgrid(g, g)).reshape(2, -1)
    df = pd.DataFrame({"v": 0.6 + 0.4 * x1, "a": 22.5 + 17.5 * x2})
    df["y1"] = 5 + 2.0 * x1 + 0.5 * x2 - 0.6 * x1 ** 2 + 0.3 * x1 * x2 + rng.normal(0, 0.02, len(df))
    df["y2"] = 3 + 0.4 * x1 + 1.2 * x2 + 0.5 * x2 ** 2 + rng.normal(0, 0.02, len(df))
    path = tmp_path_factory.mktemp("opt") / "runs.csv"
    df.to_csv(path, index=False)
    return str(path)


def _argv(csv, *extra):
    return ["optimize", csv, "--response", "y1", "--goal", "maximize", "--limits", "3:7",
            "--response", "y2", "--goal", "minimize", "--limits", "2:5.5", "--importance", "3",
            "--importance", "2", *extra]


def test_multi_response_with_constraint_is_feasible(csv, tmp_path, capsys):
    out = tmp_path / "best.json"
    assert main(_argv(csv, "--json", str(out))) == 0
    free = json.loads(out.read_text())
    assert free["actual"]["v"] ** 2 / free["actual"]["a"] > 0.02  # the box optimum breaks it
    out2 = tmp_path / "held.json"
    assert main(_argv(csv, "--constraint", EXPR, "--json", str(out2))) == 0
    d = json.loads(out2.read_text())
    assert d["actual"]["v"] ** 2 / d["actual"]["a"] <= 0.02 + 1e-9
    assert 0 < d["desirability"] < free["desirability"]
    capsys.readouterr()
    assert main(_argv(csv, "--constraint", EXPR)) == 0  # the text face
    assert "Desirability optimum" in capsys.readouterr().out


@pytest.mark.parametrize("extra, needle", [
    (["--constraint", "v >= 2"], "no setting inside the factor ranges"),
    (["--constraint", "q <= 1"], "unknown name"),
    (["--constraint", EXPR, "--bound", "v=0.9:1.0", "--bound", "a=5:10"], "no feasible setting"),
])
def test_constraint_errors_exit_2_with_one_line_and_no_file(csv, tmp_path, capsys, extra, needle):
    out = tmp_path / "never.json"
    assert main(_argv(csv, *extra, "--json", str(out))) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: --constraint: ") and needle in err[0]
    assert not out.exists()
