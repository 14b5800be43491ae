"""``rsm-lrg design`` kinds of issue 13 (optimal, augment, screening, space-filling) and
crossed categoric factors (issue 12): through rsm_lrg.cli.main; bad input exits 2 with one
``error:`` line naming the option."""

import numpy as np
import pandas as pd
import pytest
from _cli_errors import error_line

from rsm_lrg.cli import main
from rsm_lrg.design import read_design
from rsm_lrg.design.constraints import Constraints
from rsm_lrg.factors import choose_factors

GUIDE = ["--factor", "velocity_m_s=0.2:1.0", "--factor", "acceleration_m_s2=5:40", "--factor", "stroke_m=0.02:0.1"]
MOTION = "velocity_m_s**2/acceleration_m_s2 <= stroke_m"


def test_optimal_with_constraint_and_seed(tmp_path, capsys):
    a, b = tmp_path / "a.csv", tmp_path / "b.csv"
    argv = ["design", "optimal", *GUIDE, "--constraint", MOTION, "--criterion", "I", "--runs", "14",
            "--seed", "5", "--starts", "2"]
    assert main(argv + ["-o", str(a)]) == 0
    assert main(argv + ["-o", str(b)]) == 0
    assert a.read_text() == b.read_text()
    out = capsys.readouterr().out
    assert "I-optimal for the quadratic model" in out and "constraints:" in out
    d = read_design(a)
    assert d.n_runs == 14
    cons = Constraints.parse([MOTION], d.factors)
    assert cons.feasible(d.actual).all()


def test_optimal_default_runs_and_categoric(tmp_path, capsys):
    p = tmp_path / "o.csv"
    assert main(["design", "optimal", "--factor", "x=0:1", "--factor", "y=0:1", "--factor", "stage=cat:rfcms,rms",
                 "--model", "2fi", "--criterion", "D", "--seed", "1", "--starts", "2", "-o", str(p)]) == 0
    df = pd.read_csv(p)
    assert len(df) == 7 + 10  # 2FI: 1 + 3 + 3 coefficients, + 5 lof + 5 replicates
    assert set(df["stage"]) == {"rfcms", "rms"} and (df["coded_C"] == df["stage"]).all()
    ch = choose_factors(df, exclude=set())
    assert ch.space["stage"].kind == "categoric"


def test_augment_keeps_runs_and_responses(tmp_path, capsys):
    base = tmp_path / "ff.csv"
    assert main(["design", "full-factorial", "--factor", "a=0:1", "--factor", "b=0:1", "--factor", "c=0:1",
                 "--levels", "2", "--center", "3", "--seed", "1", "-o", str(base)]) == 0
    df = pd.read_csv(base)
    df["y"] = np.arange(len(df), dtype=float)
    data = tmp_path / "data.csv"
    df.to_csv(data, index=False)
    before = data.read_bytes()
    out = tmp_path / "aug.csv"
    assert main(["design", "augment", str(data), "--method", "ccd", "--new-block", "--seed", "2",
                 "-o", str(out)]) == 0
    assert data.read_bytes() == before
    aug = pd.read_csv(out)
    assert len(aug) == len(df) + 8
    pd.testing.assert_frame_equal(aug.iloc[:len(df)].drop(columns="block").reset_index(drop=True), df,
                                  check_dtype=False)
    assert aug["y"].iloc[len(df):].isna().all() and aug["block"].tolist() == [1] * 11 + [2] * 8
    d = read_design(out)
    assert d.n_runs == 19 and d.n_blocks == 2
    # optimal augment for the quadratic model
    out2 = tmp_path / "aug2.csv"
    assert main(["design", "augment", str(data), "--runs", "5", "--seed", "2", "-o", str(out2)]) == 0
    assert len(pd.read_csv(out2)) == 16


@pytest.mark.parametrize("kind, extra, n", [
    ("definitive-screening", [], 13),
    ("plackett-burman", [], 8),
    ("fractional-factorial", ["--resolution", "3"], 8),
    ("latin-hypercube", ["--runs", "9"], 9),
    ("sobol", ["--runs", "8"], 8),
])
def test_screening_and_space_filling_kinds(kind, extra, n, tmp_path, capsys):
    p = tmp_path / "d.csv"
    facs = []
    for i in range(5):
        facs += ["--factor", f"x{i}=0:1"]
    assert main(["design", kind, *facs, *extra, "--seed", "3", "-o", str(p)]) == 0
    assert read_design(p).n_runs == n


def test_crossed_box_behnken_from_the_cli(tmp_path, capsys):
    p = tmp_path / "bb.csv"
    assert main(["design", "box-behnken", "--factor", "a=0:1", "--factor", "b=0:1", "--factor", "c=0:1",
                 "--factor", "stage=cat:rfcms,rms", "--seed", "1", "-o", str(p)]) == 0
    d = read_design(p)
    assert d.n_runs == 30 and d.factors["stage"].levels == ("rfcms", "rms")


@pytest.mark.parametrize("argv, expect", [
    (["design", "optimal", *GUIDE, "--constraint", "velocity_m_s + q <= 1"], "--constraint"),
    (["design", "optimal", *GUIDE, "--constraint", "velocity_m_s >= 5"], "--constraint"),
    (["design", "optimal", *GUIDE, "--constraint", "__import__('os') <= 1"], "--constraint"),
    (["design", "optimal", *GUIDE, "--runs", "4"], "--runs"),
    (["design", "optimal", *GUIDE, "--criterion", "E"], "--criterion"),
    (["design", "optimal", *GUIDE, "--model", "quartic"], "--model"),
    (["design", "optimal", "--factor", "x=1:0"], "factor"),
    (["design", "latin-hypercube", *GUIDE, "--runs", "1"], "--runs"),
    (["design", "sobol", *GUIDE, "--runs", "8", "--constraint", "stroke_m <= 0"], "--constraint"),
    (["design", "fractional-factorial", *GUIDE, "--generator", "A B Z"], "--generator"),
    (["design", "definitive-screening", *GUIDE], "factor"),
    (["design", "latin-hypercube", *GUIDE, "--runs", "9000", "--criterion", "maximin"], "--runs"),
    (["design", "optimal", *GUIDE, "--factor", "t=0:1", "--factor", "u=0:1", "--factor", "w=0:1",
      "--factor", "z=0:1", "--factor", "q=0:1", "--model", "cubic"], "--model"),
    (["design", "optimal", *GUIDE, "--starts", "100000"], "--starts"),
    # more replicates than runs: said so, not "12 runs leave -8 model points"
    (["design", "optimal", *GUIDE, "--runs", "12", "--replicates", "20"], "--runs: 0 lack-of-fit points and 20 replicates "
                                                                        "are more than the 12 runs"),
    # a region of measure zero (one corner: velocity 0.2 and acceleration 5 only) passes the
    # emptiness check on the corners but holds no point of the search: the constraint is named
    (["design", "optimal", *GUIDE, "--constraint", "velocity_m_s + acceleration_m_s2 <= 5.2"], "error: --constraint:"),
    (["design", "latin-hypercube", *GUIDE, "--runs", "5", "--constraint", "velocity_m_s + acceleration_m_s2 <= 5.2"],
     "error: --constraint:"),
    (["design", "sobol", *GUIDE, "--runs", "5", "--constraint", "velocity_m_s + acceleration_m_s2 <= 5.2"],
     "error: --constraint:"),
])
def test_bad_input_names_the_option(argv, expect, tmp_path, capsys):
    rc = main([*argv, "-o", str(tmp_path / "x.csv")])
    line = error_line(capsys, rc)
    assert expect in line, line
    assert not (tmp_path / "x.csv").exists()


def test_augment_bad_input(tmp_path, capsys):
    base = tmp_path / "ff.csv"
    assert main(["design", "full-factorial", "--factor", "a=0:1", "--factor", "b=0:1", "--levels", "2",
                 "--seed", "1", "-o", str(base)]) == 0
    capsys.readouterr()
    line = error_line(capsys, main(["design", "augment", str(base), "--method", "foldover", "--fold", "Q",
                                     "-o", str(tmp_path / "f.csv")]))
    assert "--fold" in line
    line = error_line(capsys, main(["design", "augment", str(base), "--method", "ccd", "--alpha", "-2",
                                     "-o", str(tmp_path / "f.csv")]))
    assert "--alpha" in line
    line = error_line(capsys, main(["design", "augment", str(base), "--model", "cubic", "--runs", "2",
                                     "-o", str(tmp_path / "f.csv")]))
    assert "--runs" in line
    line = error_line(capsys, main(["design", "augment", str(base), "--force", "-o", str(base)]))
    assert "input" in line
    (tmp_path / "junk.csv").write_text("a,b\n1,2\n")
    line = error_line(capsys, main(["design", "augment", str(tmp_path / "junk.csv"), "-o", str(tmp_path / "g.csv")]))
    assert "junk.csv" in line
