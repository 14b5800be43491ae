"""rsm_lrg.table and the plain-CSV reader that fills it (rsm_lrg.readers.parse_plain_csv,
rsm_lrg.io.read_table_as(column_table=True)): a plain file read without pandas is the table
pandas.read_csv makes of it (names, dtypes, values bit for bit, ReadAs), and anything else is
left to parse_csv (None), which reads it or raises its own error (issue 37, item 6)."""

import glob
import io
import math
import os
import random
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rsm_lrg.io import MAX_COLUMNS, InputError, read_table_as
from rsm_lrg.readers import (
    _PLAIN_NUMBER,
    PLAIN_MAX_BYTES,
    TableError,
    _same_double_as_pandas,
    parse_csv,
    parse_plain_csv,
)
from rsm_lrg.table import ColumnTable

ROOT = Path(__file__).resolve().parent.parent
TABLE4 = ROOT / "data" / "table4.csv"


def _bits(a: np.ndarray) -> np.ndarray:
    """The values as integers: int64 as they are, float64 as their bit patterns (-0.0 is not 0.0)."""
    return a.view(np.int64) if a.dtype == np.float64 else a


def _agree(raw: bytes, **kw) -> bool:
    """parse_plain_csv(raw) is None or the table parse_csv reads; parse_csv raising means None.
    Returns whether the file was plain."""
    plain = parse_plain_csv(raw, **kw)
    try:
        df, how = parse_csv(raw, **kw)
    except TableError:
        assert plain is None, raw
        return False
    if plain is None:
        return False
    table, plain_how = plain
    assert plain_how == how
    assert list(table.columns) == list(df.columns)
    assert table.shape == df.shape
    for c in df.columns:
        col = df[c].to_numpy()
        assert table[c].dtype == col.dtype, (c, raw)
        assert np.array_equal(_bits(table[c]), _bits(col)), (c, table[c], col, raw)
    return True


# --- cells: plain numbers of every kind, near the limits of "plain", and non-numbers --------

def _decimal(sign, whole, frac, point, exp):
    text = sign + whole + ("." + frac if point else "")
    return text + (f"e{exp}" if exp is not None else "")


_frac = st.text(alphabet="0123456789", max_size=18)
decimals = st.builds(
    _decimal,
    st.sampled_from(["", "-"]),
    st.one_of(st.integers(0, 999), st.integers(0, 10**18)).map(str),
    st.one_of(_frac, _frac.map(lambda f: f + "0" * 12)),  # trailing zeros: dropped past 17 digits
    st.booleans(),
    st.one_of(st.none(), st.none(), st.integers(-30, 30), st.sampled_from(["+05", "-005", "E3"])),
)
_odd = st.sampled_from([
    "-0", "-0.0", "0.", "30.", "1.e5", "9007199254740992", "9007199254740993", "9007199254740993.0",
    "0.30000000000000004", "1e22", "1e23", "123e-22", "1e-23", "01", "-007", "1,5", "nan", "inf", "-inf", "",
    "NA", ".5", "+1", " 1", "1 ", "1e", "x", "True", '"1"', "1_000", "\u0661"])
cells = st.one_of(
    st.integers(-10**6, 10**6).map(str),
    st.integers(-(2**53) - 3, 2**53 + 3).map(str),
    decimals,
    st.floats(allow_nan=False, allow_infinity=False).map(repr),  # 17 significant digits, 1e-300 ...
    st.floats(min_value=-1e3, max_value=1e3).map(lambda x: f"{x:.15g}"),
    _odd,
)
#: Columns as files hold them: whole numbers, decimals, both, numbers as Python writes them,
#: and anything (text, empty cells, codes, numbers past the fast path).
columns = st.sampled_from([
    st.integers(-10**4, 10**4).map(str),
    st.integers(-(2**53) - 3, 2**53 + 3).map(str),
    st.floats(min_value=-1e3, max_value=1e3).map(lambda x: f"{x:.15g}"),
    st.floats(min_value=-1e6, max_value=1e6).map(lambda x: f"{x:.6g}"),
    decimals,
    st.one_of(decimals, st.integers(-10**4, 10**4).map(str)),
    cells,
])
_good_names = st.lists(st.sampled_from(["x", "y", "z", "a b", "caf\u00e9", "NA", "nan", "1", "x.1"]), min_size=2,
                       max_size=4, unique=True)
names = st.one_of(_good_names, _good_names, _good_names, st.lists(st.sampled_from(
    ["x", "y", " p", "q ", "Unnamed: 1", "", "x", "\ufeffz", "caf\u00e9", "cafe\u0301"]), min_size=1, max_size=4))


@st.composite
def csv_files(draw):
    header = draw(names)
    n = draw(st.integers(1, 8))
    data = [draw(st.lists(draw(columns), min_size=n, max_size=n)) for _ in header]
    sep = draw(st.sampled_from([",", ";", "\t"]))
    end = draw(st.sampled_from(["\n", "\r\n"]))
    lines = [sep.join(r) for r in [header, *zip(*data)]]
    for _ in range(draw(st.sampled_from([0, 0, 0, 1, 2]))):  # empty lines, skipped by pandas (after the header)
        lines.insert(draw(st.integers(0 if draw(st.integers(0, 9)) == 0 else 1, len(lines))), "")
    text = end.join(lines) + (end if draw(st.booleans()) else "")
    bom = b"\xef\xbb\xbf" if draw(st.integers(0, 9)) == 0 else b""
    return bom + text.encode(), draw(st.sampled_from([None, sep]))


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(csv_files())
def test_plain_reads_what_pandas_reads_bit_for_bit(case):
    """Random files, plain or nearly: whenever the plain reader takes one, parse_csv reads the
    same table; whenever parse_csv refuses one, the plain reader left it."""
    raw, sep = case
    _agree(raw, sep=sep)


def _placed(sign, digits, point, exp):
    """A decimal of the significand ``digits`` with the point after ``point`` of them."""
    point = min(point, len(digits))
    whole, frac = digits[:point].lstrip("0") or "0", digits[point:]
    return sign + whole + "." + frac + ("" if exp is None else f"e{exp}")


def _edge_decimal(rng: random.Random) -> str:
    """A decimal at the edges of the fast path: 14-20 digits, significands about 2**53 (with
    trailing zeros or not), powers of ten about +-22, or any short one."""
    kind = rng.randrange(5)
    if kind == 0:
        digits = str(2**53 + rng.randint(-10**4, 10**4))
    elif kind == 1:
        digits = str(rng.randint(10**13, 10**19))
    elif kind == 2:
        digits = str(rng.randint(1, 10**6)) + "0" * rng.randint(8, 16)
    elif kind == 3:
        digits = str(2**53 + rng.randint(-99, 99)) + "0" * rng.randint(1, 6)
    else:
        digits = str(rng.randint(0, 10**rng.randint(1, 15)))
    exp = rng.choice([None, None, rng.randint(-26, 26)])
    return _placed(rng.choice(["", "-"]), digits, rng.randint(0, len(digits) + 1), exp)


@settings(max_examples=100, deadline=None)
@given(st.integers(0, 2**32))
def test_each_cell_taken_is_the_double_pandas_reads(seed):
    """Cell by cell: every decimal the fast path takes is, bit for bit, the double pandas'
    default C parser reads (400 at a time in one float column: each cell converted alone)."""
    rng = random.Random(seed)
    values = [_edge_decimal(rng) for _ in range(400)]
    taken = [v for v in values if _PLAIN_NUMBER.fullmatch(v) and _same_double_as_pandas(v)]
    assert len(taken) > 100  # the edges are near: a good part is taken, the rest left to pandas
    got = pd.read_csv(io.StringIO("x\n0.5\n" + "\n".join(taken) + "\n"))["x"].to_numpy()[1:]
    want = np.array([float(v) for v in taken])
    assert got.dtype == np.float64
    assert np.array_equal(_bits(got), _bits(want)), [(v, a, b) for v, a, b in zip(taken, got, want)
                                                     if np.float64(a).tobytes() != np.float64(b).tobytes()]


def _precise_xstrtod(cell: str, *, integer_mantissa: bool) -> float:
    """pandas' "high" converter before 3.1 (pandas/_libs/src/parser/tokenizer.c,
    ``precise_xstrtod``), step for step in doubles: the first 17 digits of the mantissa (leading
    zeros counted) kept, the rest dropped; ``D = 10 D + d`` in doubles (2.x) or in 64-bit
    integers converted once (``integer_mantissa``); then one multiplication or division by the
    tabled double ``1e|k|``."""
    body = cell.lstrip("-")
    mantissa, _, exp = body.lower().partition("e")
    whole, _, frac = mantissa.partition(".")
    number, count, exponent, decimals = 0, 0, 0, 0
    for ch in whole:
        if count < 17:
            number = number * 10 + int(ch) if integer_mantissa else number * 10.0 + int(ch)
            count += 1
        else:
            exponent += 1
    for ch in frac:
        if count >= 17:
            break
        number = number * 10 + int(ch) if integer_mantissa else number * 10.0 + int(ch)
        count, decimals = count + 1, decimals + 1
    value = float(number) * (-1.0 if cell.startswith("-") else 1.0)
    exponent += (int(exp) if exp else 0) - decimals
    if exponent > 308:
        return math.copysign(math.inf, value) if value else value
    if exponent > 0:
        return value * float(f"1e{exponent}")
    if exponent < -308:
        return value / float(f"1e{-308 - exponent}") / 1e308 if exponent >= -616 else 0.0
    return value / float(f"1e{-exponent}")


def test_the_rule_against_pandas_before_3_1():
    """The rule holds for pandas' converter before it was fast_float (3.1), emulated here:
    every decimal it takes is what that converter made of it; loosened by a digit, by a
    power of ten or past 2**53, it would take decimals that converter made otherwise. Where
    the pandas installed is older, the emulation is checked against it."""
    rng = random.Random(20260411)
    values = [v for v in (_edge_decimal(rng) for _ in range(20000)) if _PLAIN_NUMBER.fullmatch(v)]
    wrong_if_taken = 0
    for v in values:
        for variant in (False, True):
            old = _precise_xstrtod(v, integer_mantissa=variant)
            same = np.float64(old).tobytes() == np.float64(float(v)).tobytes()
            if _same_double_as_pandas(v):
                assert same, (v, variant, old, float(v))
            wrong_if_taken += not same
    assert wrong_if_taken > 1000  # the edges are where the old converter went wrong
    for v in ["0.30000000000000004", "9007199254740993.0", "1e23", "0.10000000000000000555"]:
        assert not _same_double_as_pandas(v)
    for v in ["1.5e23", "9007199254740992e-22", "900719925474099.2", "1.00000000000000000000"]:
        assert _same_double_as_pandas(v)
    if tuple(int(x) for x in pd.__version__.split(".")[:2]) < (3, 1):
        got = pd.read_csv(io.StringIO("x\n0.5\n" + "\n".join(values) + "\n"))["x"].to_numpy()[1:]
        emulated = [np.array([_precise_xstrtod(v, integer_mantissa=i) for v in values]) for i in (False, True)]
        assert any(np.array_equal(_bits(got), _bits(old)) for old in emulated)


def test_the_fast_path_limits(tmp_path):
    """Cells at the edges of "plain": each either read as pandas reads it or left to pandas,
    and the ones pandas' pre-3.1 converter truncates or rounds twice are left to it."""
    plain = {"0.4", "-1.25e-3", "30.", "1.e5", "-0.0", "123456789012345.6", "900719925474099.2",
             "9007199254740992.0", "1e22", "1.00000000000000000", "0.50000000000000000000",
             "-12.500000000000000000e-3", "1e-22", "123e-22", "1.5E+3", "-12", "9007199254740992"}
    left = {"0.30000000000000004",  # 18 digits with its leading 0: the 18th is dropped before 3.1
            "9007199254740993.0", "12345678901234567.8", "1e23", "1e-23", "0.1e-22", "5e-324",
            "1.7976931348623157e308", "9007199254740993", "-9007199254740993", "1e1000",
            "0.10000000000000000001", "12345678901234567000.0", "9007199254740993000000.0"}
    for cell in plain | left:
        raw = f"x,y\n{cell},0.5\n1.5,2\n".encode()
        assert _agree(raw) is (cell in plain), cell
        raw = f"x,y\n{cell},0\n1,2\n".encode()  # with whole numbers below it: a float64 column still
        assert _agree(raw) is (cell in plain), cell
    assert parse_plain_csv(b"x,y\n-0,1\n0.5,2\n") is None  # whole -0 among decimals: -0.0 or 0.0 by chunk
    t, _ = parse_plain_csv(b"x,y\n-0,1\n0,2\n")
    assert t["x"].dtype == np.int64 and t["x"].tolist() == [0, 0]


@pytest.mark.parametrize("raw", [
    b"x,y\n01,2\n",                 # a code with a leading zero: text
    b"x,y\n1,\n",                   # an empty cell
    b"\nx,y\n1,2\n",                # an empty line before the header
    b"x,y\n\n\n",                   # only empty lines below it
    b"x,y\n1,2\n \n",               # a line of a space
    b"x, y\n1,2\n",                 # a space before a name
    b"x,y\n 1,2\n",                 # a space before a number
    b'"x",y\n1,2\n',                # a quote
    b"x,x\n1,2\n",                  # a name twice
    b"x,\n1,2\n",                   # a blank name
    b"x\n1\n",                      # one column
    b"x,y\n",                       # no data row
    b"x,y\n1,2,3\n",                # more fields than the header
    b"x,y\n1\n",                    # fewer
    b"x,y\r1,2\r",                  # old Mac line ends
    b"x;y\n1,5;2\n",                # a decimal comma
    b"x,y\nnan,1\n",                # a missing value
    b"x,y\ninf,1\n",
    b"\xff\xfex\x00,\x00y\x00\n\x001\x00,\x002\x00\n\x00",  # UTF-16
    b"x,\xe9\n1,2\n",               # not UTF-8
    b"caf\xc3\xa9,cafe\xcc\x81\n1,2\n",  # the same name in NFC
    b"x,y\x1b\n1,2\n",              # a control character in a name
    b"x,y\n+1,2\n",
    b"x,y\n\xd9\xa1,2\n",           # an Arabic-Indic digit: float() reads it, pandas does not
])
def test_not_plain(raw):
    assert parse_plain_csv(raw) is None
    _agree(raw)


def test_plain_forms():
    t, _ = parse_plain_csv(b"x,y\r\n1,2\r\n\r\n3,4.5\r\n\r\n")  # empty lines skipped, as pandas does
    assert t.shape == (2, 2) and t["x"].tolist() == [1, 3] and t["y"].tolist() == [2.0, 4.5]
    _agree(b"x,y\r\n1,2\r\n\r\n3,4.5\r\n\r\n")
    t, how = parse_plain_csv(b"\xef\xbb\xbfa b;y\r\n-1;0.5\r\n2;-1.25e-3")
    assert how.sep == ";" and how.sep_detected and t.columns == ("a b", "y")
    assert t["a b"].tolist() == [-1, 2] and t["y"].tolist() == [0.5, -0.00125]
    assert parse_plain_csv(b"x,y\n1,2\n", sep=";") is None  # one column with the separator given
    assert parse_plain_csv(b"x,y\n1,2\n", decimal=",") is None
    assert parse_plain_csv(b"x,y\n" + b"1,2\n" * (PLAIN_MAX_BYTES // 4)) is None  # large: pandas is quicker


def _csv_files():
    seen = sorted({*glob.glob(str(ROOT / "data" / "**" / "*.csv"), recursive=True),
                   *glob.glob(str(ROOT / "tests" / "**" / "*.csv"), recursive=True),
                   *glob.glob(str(ROOT / "rsm_lrg" / "data" / "*.csv"))})
    return [Path(p) for p in seen]


def test_every_csv_file_of_the_project():
    files = _csv_files()
    assert len(files) >= 10
    plain = [p.relative_to(ROOT).as_posix() for p in files if _agree(p.read_bytes())]
    assert {"data/table4.csv", "rsm_lrg/data/table4.csv"} <= set(plain), plain  # mixture_etch: 18 digits


def test_table4_is_plain_and_read_without_pandas():
    table, how = parse_plain_csv(TABLE4.read_bytes())
    assert isinstance(table, ColumnTable) and table.shape == (27, 6) and how.plain
    code = ("import sys\nfrom rsm_lrg.readers import parse_plain_csv\nfrom rsm_lrg.io import read_table_as\n"
            f"t, _ = parse_plain_csv(open({str(TABLE4)!r}, 'rb').read())\n"
            f"u, _ = read_table_as({str(TABLE4)!r}, column_table=True)\n"
            "assert type(u).__name__ == 'ColumnTable', type(u)\n"
            "print('pandas' in sys.modules, 'numpy' in sys.modules)\n")
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, cwd=ROOT, check=True)
    assert out.stdout.split() == ["False", "True"], out


# --- read_table_as(column_table=True) ---------------------------------------------------------

def test_read_table_as_column_table(tmp_path, monkeypatch):
    table, how = read_table_as(TABLE4, column_table=True)
    df, how_df = read_table_as(TABLE4)
    assert isinstance(table, ColumnTable) and isinstance(df, pd.DataFrame) and how == how_df
    for c in df.columns:
        assert np.array_equal(_bits(table[c]), _bits(df[c].to_numpy())) and table[c].dtype == df[c].dtype
    monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(TABLE4.read_bytes())))  # standard input too
    piped, how_piped = read_table_as("-", column_table=True)
    assert isinstance(piped, ColumnTable) and how_piped == how and piped.columns == table.columns
    p = tmp_path / "coded.csv"
    p.write_bytes(b"lot,y\n01,1.5\n02,2.5\n")  # not plain: a DataFrame, as without the option
    got, _ = read_table_as(p, column_table=True)
    assert isinstance(got, pd.DataFrame) and got["lot"].tolist() == ["01", "02"]


@pytest.mark.parametrize(("raw", "kw"), [
    (b"x,x\n1,2\n", {}), (b"x,y\n1,2,3\n", {}), (b"x,y\n", {}), (b"x,y\n\n", {}), (b"x\n1\n", {}),
    (b"x;y\n1,5;2\n", {}), (b"caf\xc3\xa9,cafe\xcc\x81\n1,2\n", {}), (b"x,y\x1b\n1,2\n", {}),
    (b"x,y\n1,2\n", {"sep": ";"}), (b"x,y\n1,2\n", {"sep": ","}), (b"x;y\n1;2\n", {"sep": ";", "decimal": ";"}),
    (b"x,y\n1,2\n", {"sep": "x"}), (b"x,y\n1,2\n", {"decimal": ","}), (b"x,y\n1,2\n", {"sheet": "Runs"}),
    (b",".join(b"c%d" % i for i in range(MAX_COLUMNS + 1)) + b"\n" + b",".join(b"1" for _ in range(MAX_COLUMNS + 1)),
     {}),
    (b"x,y\n" + b"1," + b"1" * (2 << 20) + b"\n", {}),  # a line past the limit (and past PLAIN_MAX_BYTES)
])
def test_read_table_as_column_table_same_result(tmp_path, raw, kw):
    """The same error for a bad file, or the same table (a DataFrame when it is not plain)."""
    p = tmp_path / "t.csv"
    p.write_bytes(raw)
    try:
        plain = read_table_as(p, column_table=True, **kw)
    except InputError as exc:
        with pytest.raises(InputError) as frame_exc:
            read_table_as(p, **kw)
        assert str(exc) == str(frame_exc.value)
        return
    frame = read_table_as(p, **kw)
    assert plain[1] == frame[1]
    got = plain[0].to_frame() if isinstance(plain[0], ColumnTable) else plain[0]
    pd.testing.assert_frame_equal(got, frame[0])


def test_read_table_as_column_table_limits(tmp_path, monkeypatch):
    import rsm_lrg.io as rio

    p = tmp_path / "rows.csv"
    p.write_bytes(b"x,y\n" + b"1,2\n" * 11)
    monkeypatch.setattr(rio, "MAX_ROWS", 10)
    with pytest.raises(InputError, match="11 data rows, more than the limit of 10"):
        read_table_as(p, column_table=True)


# -- the ColumnTable itself (rsm_lrg.table) ------------------------------------------------------
def test_column_table_holds_read_only_number_columns():
    from rsm_lrg.table import ColumnTable, column_names, column_values, n_rows, take_rows

    t = ColumnTable({"a": [1, 2, 3], "b": np.array([0.5, -0.0, 2.0])})
    assert t.shape == (3, 2) and len(t) == 3 and n_rows(t) == 3 and column_names(t) == ["a", "b"]
    assert t["a"].dtype == np.int64 and t["b"].dtype == np.float64
    with pytest.raises(ValueError):
        t["b"][0] = 1.0  # read-only: a fit cannot change the file's numbers
    assert t.copy() is t
    sub = take_rows(t, [2, 0])
    assert column_values(sub, "a").tolist() == [3, 1] and column_values(sub, "b").tolist() == [2.0, 0.5]
    assert t.to_numpy().dtype == np.float64 and t.to_numpy(dtype=float).shape == (3, 2)
    frame = t.to_frame()
    assert list(frame.columns) == ["a", "b"] and frame["a"].dtype == np.int64
    assert np.array_equal(frame["b"].to_numpy().view(np.int64), t["b"].view(np.int64))  # -0.0 kept
    assert take_rows(frame, [2, 0])["a"].tolist() == [3, 1]  # the same helpers read a DataFrame
    assert column_values(frame, "b").tolist() == [0.5, -0.0, 2.0]


@pytest.mark.parametrize("cols, what", [
    ({}, "at least one column"),
    ({"a": [1, 2], "b": [1.0]}, "different lengths"),
    ({"a": ["x", "y"]}, "int64 or float64"),
    ({"a": [[1, 2]]}, "1-D"),
    ({"a": [True, False]}, "int64 or float64"),
])
def test_column_table_refuses_what_it_cannot_hold(cols, what):
    from rsm_lrg.table import ColumnTable

    with pytest.raises(ValueError, match=what):
        ColumnTable(cols)
