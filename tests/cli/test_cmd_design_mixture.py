"""``rsm-lrg design simplex-lattice | simplex-centroid | extreme-vertices`` (issue 22, item 1):
through rsm_lrg.cli.main; bad input exits 2 with one ``error:`` line naming the option and
leaves no file behind."""

import math
from fractions import Fraction

import numpy as np
import pandas as pd
import pytest
from _cli_errors import error_line

from rsm_lrg.cli import main

FLARE = ["--component", "magnesium=0.40:0.60", "--component", "sodium_nitrate=0.10:0.50",
         "--component", "strontium_nitrate=0.10:0.50", "--component", "binder=0.03:0.08"]


def test_simplex_lattice_csv(tmp_path, capsys):
    p = tmp_path / "lattice.csv"
    argv = ["design", "simplex-lattice", "--component", "oil", "--component", "additive", "--component", "thickener",
            "--degree", "3", "--center", "--axial", "--total", "100", "--seed", "4"]
    assert main(argv + ["-o", str(p)]) == 0
    out = capsys.readouterr().out
    assert "simplex-lattice design: 3 components, 14 runs" in out and "seed 4" in out
    df = pd.read_csv(p)
    assert list(df.columns) == ["std_order", "run_order", "coded_A", "coded_B", "coded_C", "oil", "additive",
                                "thickener"]
    assert sorted(df["std_order"]) == list(range(1, 15)) and df["run_order"].tolist() == list(range(1, 15))
    x = df[["oil", "additive", "thickener"]].to_numpy()
    for row in x:
        assert abs(math.fsum(row) - 100.0) <= 1e-12 * 100
    # the 10 lattice blends {0, 1/3, 2/3, 1} * 100 exactly (correctly rounded)
    lattice = {tuple(float(Fraction(100) * Fraction(i, 3)) for i in c)
               for c in [(a, b, 3 - a - b) for a in range(4) for b in range(4 - a)]}
    assert lattice <= {tuple(r) for r in x.tolist()}
    axial = {(float(Fraction(100 * 4, 6)), float(Fraction(100, 6)), float(Fraction(100, 6)))}
    assert axial <= {tuple(r) for r in x.tolist()}
    # the coded columns are the L-pseudo components x / 100
    assert np.allclose(df[["coded_A", "coded_B", "coded_C"]].to_numpy(), x / 100, atol=5e-13, rtol=0)
    q = tmp_path / "again.csv"
    assert main(argv + ["-o", str(q)]) == 0
    assert p.read_bytes() == q.read_bytes()


def test_simplex_centroid_standard_order(tmp_path, capsys):
    p = tmp_path / "scd.csv"
    assert main(["design", "simplex-centroid", "--component", "a", "--component", "b", "--component", "c",
                 "--component", "d", "--no-randomize", "-o", str(p)]) == 0
    df = pd.read_csv(p)
    assert len(df) == 15 and df["std_order"].tolist() == df["run_order"].tolist() == list(range(1, 16))
    assert df.iloc[-1][["a", "b", "c", "d"]].tolist() == [0.25] * 4


def test_extreme_vertices_flare_with_centroids(tmp_path, capsys):
    p = tmp_path / "flare.csv"
    assert main(["design", "extreme-vertices", *FLARE, "--centroids", "--no-randomize", "-o", str(p)]) == 0
    out = capsys.readouterr().out
    assert "27 runs (8 vertex, 12 edge, 6 plane, 1 centroid)" in out
    assert "implied bounds" in out and "sodium_nitrate 0.1..0.47 (given 0.1..0.5)" in out
    df = pd.read_csv(p)
    x = df[["magnesium", "sodium_nitrate", "strontium_nitrate", "binder"]].to_numpy()
    assert all(abs(math.fsum(r) - 1.0) <= 1e-12 for r in x)
    assert np.all(x >= [0.4, 0.1, 0.1, 0.03]) and np.all(x <= [0.6, 0.47, 0.47, 0.08])


def test_extreme_vertices_linear_constraint(tmp_path, capsys):
    p = tmp_path / "ev.csv"
    assert main(["design", "extreme-vertices", "--component", "a=0.1:0.7", "--component", "b=0.1:0.7",
                 "--component", "c=0.1:0.7", "--constraint", "A + B <= 0.6", "--seed", "1", "-o", str(p)]) == 0
    df = pd.read_csv(p)
    assert len(df) == 4 and np.all(df["a"] + df["b"] <= 0.6 + 1e-15)
    assert "constraints: A + B <= 0.6" in capsys.readouterr().out


@pytest.mark.parametrize("argv,needle", [
    (["simplex-lattice", "--component", "a", "--component", "a", "--degree", "2"], "--component: component 'a' is given twice"),
    (["simplex-lattice", "--component", "a", "--degree", "2"], "--component: a mixture needs at least 2"),
    (["simplex-lattice", "--component", "a", "--component", " ", "--degree", "2"], "--component: an empty name"),
    (["simplex-lattice", "--component", "a", "--component", "b", "--degree", "0"], "--degree"),
    (["simplex-lattice", "--component", "a", "--component", "b", "--degree", "x"], "--degree"),
    (["simplex-lattice", "--component", "a", "--component", "b", "--degree", "2", "--total", "nan"], "--total"),
    (["simplex-centroid", "--component", "a", "--component", "b", "--total", "0"], "--total"),
    (["simplex-centroid", "--component", "a=0:1", "--component", "b"], "--component: component 'a=0:1'"),
    (["extreme-vertices", "--component", "a=x:1", "--component", "b"], "--component: expected NAME=LOW:HIGH"),
    (["extreme-vertices", "--component", "a=0.5", "--component", "b"], "--component: expected NAME=LOW:HIGH"),
    (["extreme-vertices", "--component", "a=0.5:0.2", "--component", "b"], "'a': LOW 0.5 is above HIGH 0.2"),
    (["extreme-vertices", "--component", "a=0.6:0.9", "--component", "b=0.6:0.9"], "lower bounds sum to 1.2"),
    (["extreme-vertices", "--component", "a=0:0.3", "--component", "b=0:0.3"], "upper bounds sum to 0.6"),
    (["extreme-vertices", "--component", "a=0:1", "--component", "b", "--constraint", "a*b <= 0.1"],
     "--constraint: constraint 'a*b <= 0.1' is not linear"),
    (["extreme-vertices", "--component", "a=0:1", "--component", "b", "--constraint", "a >= 2"], "--constraint:"),
    (["extreme-vertices", "--component", "a=0:1", "--component", "b", "--constraint", "z <= 1"], "--constraint:"),
    (["extreme-vertices", "--component", "a=0.5:0.9", "--component", "b=0:0.5", "--component", "c=0:0.5",
      "--constraint", "b + c >= 0.5"], "--constraint: the region has no interior"),
])
def test_bad_input_exits_2_and_writes_nothing(tmp_path, capsys, argv, needle):
    p = tmp_path / "out.csv"
    line = error_line(capsys, main(["design", *argv, "-o", str(p)]))
    assert needle in line, line
    assert not p.exists() and list(tmp_path.iterdir()) == []
