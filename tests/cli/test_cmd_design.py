"""``rsm-lrg design``: through a real subprocess and through rsm_lrg.cli.main."""

import subprocess
import sys

import numpy as np
import pandas as pd
import pytest

from rsm_lrg.cli import main
from rsm_lrg.design import box_behnken, read_design

PAPER = ["thickness_m=0.0001:0.0005", "stroke_m=0.04:0.06", "velocity_m_s=0.4:0.6",
         "acceleration_m_s2=20:40"]


def factor_args(specs):
    out = []
    for s in specs:
        out += ["--factor", s]
    return out


def run(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "rsm_lrg", *args], capture_output=True, text=True, cwd=cwd)


@pytest.mark.slow
def test_box_behnken_subprocess_writes_the_paper_design(tmp_path):
    out = tmp_path / "bbd.csv"
    r = run("design", "box-behnken", *factor_args(PAPER), "--center", "3", "--seed", "7", "-o", str(out))
    assert r.returncode == 0, r.stderr
    assert "27 runs" in r.stdout and "seed 7" in r.stdout and "1 block" in r.stdout
    df = pd.read_csv(out)
    assert list(df.columns) == ["std_order", "run_order", "coded_A", "coded_B", "coded_C", "coded_D",
                                "thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2"]
    # the same as the library with the same seed
    lib = box_behnken(PAPER, center=3, seed=7).to_frame()
    pd.testing.assert_frame_equal(df, lib, check_dtype=False)


def test_same_seed_same_file_different_seed_different_file(tmp_path, capsys):
    a, b, c = (tmp_path / n for n in ("a.csv", "b.csv", "c.csv"))
    base = ["design", "box-behnken", *factor_args(PAPER[:3])]
    assert main(base + ["--seed", "1", "-o", str(a)]) == 0
    assert main(base + ["--seed", "1", "-o", str(b)]) == 0
    assert main(base + ["--seed", "2", "-o", str(c)]) == 0
    assert a.read_text() == b.read_text() != c.read_text()


def test_no_randomize_and_blocks(tmp_path, capsys):
    p = tmp_path / "blk.csv"
    assert main(["design", "box-behnken", *factor_args(PAPER), "--blocks", "3", "--center", "2",
                 "--no-randomize", "-o", str(p)]) == 0
    assert "3 blocks" in capsys.readouterr().out
    d = read_design(p)
    assert d.n_runs == 24 + 3 * 2 and d.n_blocks == 3
    assert d.std_order.tolist() == d.run_order.tolist()


def test_force_overwrites_and_without_it_refuses(tmp_path, capsys):
    p = tmp_path / "d.csv"
    args = ["design", "box-behnken", *factor_args(PAPER[:3]), "-o", str(p)]
    assert main(args + ["--seed", "1"]) == 0
    before = p.read_text()
    assert main(args + ["--seed", "2"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error:") and "already exists" in err[0]
    assert p.read_text() == before
    assert main(args + ["--seed", "2", "--force"]) == 0
    assert p.read_text() != before


@pytest.mark.parametrize("args,needle", [
    (["box-behnken", "--factor", "a=0:1", "--factor", "b=0:1"], "3 to 7, 9 to 12 or 16 factors"),
    (["box-behnken", "--factor", "a=1:0", "--factor", "b=0:1", "--factor", "c=0:1"], "LOW must be below HIGH"),
    (["box-behnken", "--factor", "a=0:1", "--factor", "b=0:1", "--factor", "c=0:1", "--center", "-2"],
     "must not be negative"),
    (["box-behnken", "--factor", "a=0:1", "--factor", "a=0:2", "--factor", "c=0:1"], "more than once"),
    (["box-behnken", "--factor", "a=0:1", "--factor", "b=0:1", "--factor", "c=0:1", "--blocks", "2"],
     "orthogonal blocking"),
    (["box-behnken", "--factor", "a=0:1", "--factor", "b=0:1", "--factor", "c=0:1", "--factor", "d=0:1",
      "--blocks", "2"], "3 blocks"),
    (["box-behnken", "--factor", "a", "--factor", "b=0:1", "--factor", "c=0:1"], "LOW:HIGH"),
    (["central-composite", "--factor", "a=0:1", "--factor", "b=0:1", "--alpha", "steep"], "alpha"),
    (["full-factorial", "--factor", "a=0:1", "--levels", "1"], "levels"),
])
def test_bad_input_is_one_error_line_exit_2(tmp_path, args, needle):
    out = tmp_path / "x.csv"
    r = run("design", *args, "-o", str(out))
    assert r.returncode == 2, r.stdout + r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error:"), r.stderr
    assert needle in lines[0]
    assert not out.exists()


def test_missing_output_is_a_usage_error():
    r = run("design", "box-behnken", *factor_args(PAPER))
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error:") and "-o" in lines[0]


def test_central_composite_cli(tmp_path, capsys):
    p = tmp_path / "ccd.csv"
    assert main(["design", "central-composite", "--factor", "t=100:200", "--factor", "p=1:3",
                 "--factor", "v=0:1", "--alpha", "orthogonal", "--center", "2,3", "--blocks", "2",
                 "--seed", "5", "-o", str(p)]) == 0
    out = capsys.readouterr().out
    assert "central-composite" in out and "2 blocks" in out
    d = read_design(p)
    assert d.n_runs == 8 + 2 + 6 + 3 and d.n_blocks == 2
    q = tmp_path / "ccf.csv"
    assert main(["design", "central-composite", "--factor", "t=100:200", "--factor", "p=1:3",
                 "--face", "faced", "--center", "1", "-o", str(q)]) == 0
    assert set(np.unique(read_design(q).coded_runs)) == {-1.0, 0.0, 1.0}
    r = tmp_path / "num.csv"
    assert main(["design", "central-composite", "--factor", "t=100:200", "--factor", "p=1:3",
                 "--alpha", "1.5", "-o", str(r)]) == 0
    assert np.max(read_design(r).coded_runs) == 1.5


def test_full_factorial_cli(tmp_path, capsys):
    p = tmp_path / "ff.csv"
    assert main(["design", "full-factorial", "--factor", "a=0:2", "--factor", "b=5:7", "--levels", "3",
                 "--no-randomize", "-o", str(p)]) == 0
    df = pd.read_csv(p)
    assert len(df) == 9 and sorted(set(df["a"])) == [0.0, 1.0, 2.0]


def test_full_factorial_defaults_to_two_levels_and_augments_to_a_ccd(tmp_path, capsys):
    # the classic route: a 2^3 factorial with centre points, then star points make it a CCD
    p, ccd = tmp_path / "ff.csv", tmp_path / "ccd.csv"
    assert main(["design", "full-factorial", "--factor", "a=0:2", "--factor", "b=5:7", "--factor", "c=1:3",
                 "--center", "2", "--seed", "1", "-o", str(p)]) == 0
    df = pd.read_csv(p)
    assert len(df) == 10 and sorted(set(df["a"])) == [0.0, 1.0, 2.0]  # 8 corners, 2 centres
    assert main(["design", "augment", str(p), "--method", "ccd", "--seed", "2", "-o", str(ccd)]) == 0
    assert len(pd.read_csv(ccd)) > 10


def test_library_hints_are_written_as_options(tmp_path, capsys):
    p = tmp_path / "ff3.csv"
    assert main(["design", "full-factorial", "--factor", "a=0:2", "--factor", "b=5:7", "--levels", "3",
                 "--seed", "1", "-o", str(p)]) == 0
    capsys.readouterr()
    assert main(["design", "augment", str(p), "--method", "ccd", "-o", str(tmp_path / "x.csv")]) == 2
    err = capsys.readouterr().err
    assert "use --method optimal" in err and "method='optimal'" not in err


def test_design_csv_feeds_default_factor_selection(tmp_path, capsys):
    # fit picks factors by default: the coded_ columns must not be among them.
    from rsm_lrg.factors import FactorSpace

    p = tmp_path / "d.csv"
    assert main(["design", "box-behnken", *factor_args(PAPER), "-o", str(p)]) == 0
    df = pd.read_csv(p)
    df["y"] = 1.0 + np.arange(len(df))
    assert FactorSpace.from_data(df, exclude=["y"]).names == [s.split("=")[0] for s in PAPER]


def test_constraint_beginning_with_a_minus_is_a_value(tmp_path, capsys):
    # argparse alone reads "-A+B<=1" as an unknown option ("expected one argument")
    import pandas as pd

    from rsm_lrg.cli import main

    out = tmp_path / "d.csv"
    assert main(["design", "optimal", "--factor", "A=-1:1", "--factor", "B=-1:1", "--model", "quadratic",
                 "--runs", "8", "--constraint", "-A+B<=1", "--seed", "3", "-o", str(out)]) == 0
    d = pd.read_csv(out)
    assert len(d) == 8 and bool(((-d["A"] + d["B"]) <= 1 + 1e-12).all())
    assert "constraints: -A+B <= 1" in capsys.readouterr().out


@pytest.mark.parametrize("name", ["a\nb", "a\tb", "a\x1b[31mb", "a\x85b"])
def test_design_refuses_a_name_its_other_commands_refuse(name, tmp_path, capsys):
    # issue 36: `design box-behnken --factor 'a<newline>b=0:1'` wrote a design whose column name
    # `evaluate` and `fit` then refused; the one rule (rsm_lrg.readers.column_name_problem) now
    # refuses it at design, with the same message
    out = tmp_path / "d.csv"
    assert main(["design", "box-behnken", "--factor", f"{name}=0:1", "--factor", "b=0:1", "--factor", "c=0:1",
                 "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "holds a control character" in err[0] and "rename the column" in err[0], err
    assert not out.exists()
    bad = tmp_path / "bad.csv"
    bad.write_text(f'"{name}",b,y\n1,2,3\n2,3,4\n3,1,5\n')
    assert main(["evaluate", str(bad)]) == 2
    assert err[0].split("error: ", 1)[1] in capsys.readouterr().err
