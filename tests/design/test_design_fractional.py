"""Two-level fractional factorials by resolution and by generators, checked against the
published minimum-aberration designs (Montgomery, Design and Analysis of Experiments, 8th ed.
2013, Table 8.14, from Box, Hunter & Hunter 2005) and against an exhaustive search.

Every number here is exact (integer runs, +-1 columns, word counts): tolerance 0."""

import itertools
import math

import numpy as np
import pytest

from rsm_lrg.cli import main
from rsm_lrg.design.screening import (
    _FF_TABLE,
    _defining_words,
    _table_masks,
    alias_groups,
    fractional_factorial,
)


def _factors(k):
    return [f"x{i}=0:1" for i in range(k)]


def _shortest_word(X):
    """Resolution of a +-1 design by brute force over column subsets (independent of the
    generator masks): the fewest columns whose product is constant."""
    k = X.shape[1]
    for r in range(2, k + 1):
        for combo in itertools.combinations(range(k), r):
            v = np.prod(X[:, combo], axis=1)
            if np.all(v == v[0]):
                return r
    return None


# (factors, resolution asked) -> runs of the smallest fraction: Montgomery (2013), Table 8.14
# (3 factors at III: 4 runs; 4 at IV: 8; 5 at V: 16; 7 at III: 8, at IV: 16, at V: 64;
# 8 at V: 64; 9 at IV: 32; 10 and 11 at V: 128; 15 at III: 16) and the saturation bounds
# 2^q - 1 factors at III, 2^(q-1) at IV (Box, Hunter & Hunter 2005, ch. 6-7).
SMALLEST = [(3, 3, 4), (4, 3, 8), (4, 4, 8), (5, 3, 8), (5, 4, 16), (5, 5, 16), (6, 4, 16), (6, 5, 32),
            (6, 6, 32), (7, 3, 8), (7, 4, 16), (7, 5, 64), (8, 3, 16), (8, 4, 16), (8, 5, 64), (9, 4, 32),
            (9, 5, 128), (10, 5, 128), (11, 4, 32), (11, 5, 128), (12, 4, 32), (15, 3, 16), (16, 3, 32),
            (16, 4, 32), (17, 4, 64), (31, 3, 32)]


@pytest.mark.parametrize("k, res, runs", SMALLEST)
def test_smallest_fraction_of_the_resolution_asked(k, res, runs):
    d = fractional_factorial(_factors(k), resolution=res, randomize=False)
    assert d.n_runs == runs
    X = d.coded_runs
    assert set(np.unique(X)) == {-1.0, 1.0}
    assert np.array_equal(X.T @ X, runs * np.eye(k))  # orthogonal main effects, exact
    got = d.options["resolution"]
    assert got is not None and got >= res  # never a lower resolution than asked
    if k <= 12:
        assert _shortest_word(X) == got


def test_no_fraction_reaches_the_resolution_gives_the_full_factorial_and_says_so():
    # 4 factors at resolution V: every 2^(4-1) fraction has a word of length <= 4
    d = fractional_factorial(_factors(4), resolution=5, randomize=False)
    assert d.n_runs == 16 and d.options["resolution"] is None
    assert "full 2^4 factorial" in d.summary() and "resolution 5" in d.summary()


def _wlp(q, gens, k):
    counts = [0] * (k + 1)
    for w in _defining_words(q, gens):
        counts[bin(w).count("1")] += 1
    return tuple(counts[3:])


SMALL_ENTRIES = [(k, q, words) for k, entries in _FF_TABLE.items() for q, _, words in entries
                 if math.comb(2 ** q - 1 - q, k - q) <= 20000]


@pytest.mark.parametrize("k, q, words", SMALL_ENTRIES)
def test_table_entries_have_minimum_aberration(k, q, words):
    # exhaustive search over every set of k - q distinct interaction columns of the 2^q basic
    # factors: the table's word-length pattern is the lexicographically smallest (Fries &
    # Hunter 1980's minimum aberration), an independent check of the transcribed generators
    cands = [m for m in range(1, 2 ** q) if bin(m).count("1") >= 2]
    best = min(_wlp(q, list(c), k) for c in itertools.combinations(cands, k - q))
    assert _wlp(q, _table_masks(words), k) == best


def test_half_fraction_in_yates_order_montgomery_table_8_3():
    # 2^(4-1)_IV, I = ABCD: runs (1), ad, bd, ab, cd, ac, bc, abcd (Montgomery 2013, Table 8.3)
    d = fractional_factorial(["a=0:1", "b=0:1", "c=0:1", "d=0:1"], resolution=4, randomize=False)
    assert d.options["generators"] == "D = ABC"
    labels = ["".join(ch for ch, v in zip("abcd", row) if v > 0) or "(1)" for row in d.coded_runs]
    assert labels == ["(1)", "ad", "bd", "ab", "cd", "ac", "bc", "abcd"]


def test_saturated_2_7_4_alias_structure_montgomery_section_8_5():
    # 2^(7-4)_III with D = AB, E = AC, F = BC, G = ABC; aliases ignoring 3FIs and higher
    # (Montgomery 2013, section 8.5.2): A = BD = CE = FG, ..., G = CD = BE = AF
    d = fractional_factorial(_factors(7), resolution=3, randomize=False)
    assert d.n_runs == 8 and d.options["generators"] == "D = AB, E = AC, F = BC, G = ABC"
    groups = {g[0]: sorted(g[1:]) for g in d.options["aliases"] if len(g[0]) == 1}
    assert groups == {"A": ["BD", "CE", "FG"], "B": ["AD", "CF", "EG"], "C": ["AE", "BF", "DG"],
                      "D": ["AB", "CG", "EF"], "E": ["AC", "BG", "DF"], "F": ["AG", "BC", "DE"],
                      "G": ["AF", "BE", "CD"]}


def test_generator_forms_agree_and_signs_follow():
    a = fractional_factorial(_factors(5), generators="A B C AB AC", randomize=False)
    b = fractional_factorial(_factors(5), generators="D=AB, E = ac", randomize=False)
    assert np.array_equal(a.coded_runs, b.coded_runs)
    X = a.coded_runs
    assert np.array_equal(X[:, 3], X[:, 0] * X[:, 1]) and np.array_equal(X[:, 4], X[:, 0] * X[:, 2])
    neg = fractional_factorial(_factors(4), generators="D=-ABC", randomize=False).coded_runs
    assert np.array_equal(neg[:, 3], -neg[:, 0] * neg[:, 1] * neg[:, 2])
    assert ["AB", "-CD"] in alias_groups(neg, "ABCD")


@pytest.mark.parametrize("gen, match", [
    ("A B C A", "confounds two main effects"),
    ("A B C ABCD", "not a basic factor"),
    ("A B D ABD", "not a basic factor"),
    ("D=AB D=AC", "two generators"),
    ("A B Z", "expected 4 words"),
    ("A B C Z", "not a factor letter"),
    ("A B C AA", "repeats a letter"),
    ("", "empty"),
])
def test_bad_generators_are_refused(gen, match):
    with pytest.raises(ValueError, match=match):
        fractional_factorial(_factors(4), generators=gen)


def test_cli_names_the_option_and_prints_the_resolution(tmp_path, capsys):
    facs = [a for i in range(7) for a in ("--factor", f"x{i}=0:1")]
    out = tmp_path / "ff.csv"
    assert main(["design", "fractional-factorial", *facs, "--resolution", "5", "--seed", "1", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "64 runs" in text and "resolution VII" in text and "G = ABCDEF" in text
    assert main(["design", "fractional-factorial", *facs[:4], "--resolution", "3", "-o", str(tmp_path / "x.csv")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: --factor:") and not (tmp_path / "x.csv").exists()
    assert main(["design", "fractional-factorial", *facs, "--generator", "", "-o", str(tmp_path / "y.csv")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: --generator:")
