"""rsm_lrg.io: TOML reading and writing shared by the parameter and calibration files."""

import math
import os
import tomllib

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from rsm_lrg.io import InputError, read_toml, toml_value, write_output


def test_read_toml_errors_name_the_file(tmp_path):
    with pytest.raises(InputError, match=r"nope\.toml: no such calibration file"):
        read_toml(tmp_path / "nope.toml", "calibration file")
    with pytest.raises(InputError, match="is a directory"):
        read_toml(tmp_path)
    bad = tmp_path / "bad.toml"
    bad.write_text("a = = 1\n")
    with pytest.raises(InputError, match=r"bad\.toml: not valid TOML \(.*line 1"):
        read_toml(bad)
    latin = tmp_path / "latin.toml"
    latin.write_bytes(b'a = "\xe9"\n')
    with pytest.raises(InputError, match="not valid TOML"):
        read_toml(latin)


def test_read_toml_leaves_the_file_alone(tmp_path):
    f = tmp_path / "ok.toml"
    f.write_text('x = 1.5\n[t]\nname = "a"\n')
    before = f.read_bytes(), f.stat().st_mtime_ns
    assert read_toml(f) == {"x": 1.5, "t": {"name": "a"}}
    assert (f.read_bytes(), f.stat().st_mtime_ns) == before


def test_toml_value_numpy_scalars_and_non_finite():
    assert toml_value(np.float64(0.1)) == "0.1"
    assert toml_value(np.int32(7)) == "7"
    assert toml_value(np.bool_(True)) == "true"
    assert toml_value(float("inf")) == "nan"
    assert toml_value(None) == "nan"


_values = st.one_of(
    st.booleans(),
    st.integers(min_value=-(2 ** 63), max_value=2 ** 63 - 1),
    st.floats(allow_nan=False, allow_infinity=False),
    st.text(),
)


@given(st.lists(_values, max_size=6), _values)
def test_toml_value_round_trips_through_tomllib(items, scalar):
    # independent route: Python's own TOML parser reads back exactly what was written
    doc = f"x = {toml_value(scalar)}\ny = {toml_value(items)}\n"
    back = tomllib.loads(doc)
    assert back["x"] == scalar and type(back["x"]) is type(scalar)
    assert back["y"] == items


def test_calibration_file_round_trips(tmp_path):
    from rsm_lrg.surrogate.calibrate import calibration_toml, load_calibration, resolve_calibration

    cal = resolve_calibration("default")
    out = write_output(tmp_path / "c.toml", calibration_toml(cal))
    again = load_calibration(out)
    assert again.parameters == cal.parameters
    assert list(again.predicted) == list(cal.predicted)
    assert math.isclose(again.r2, cal.r2, rel_tol=0, abs_tol=0)


# ---------------------------------------------------------------- bounded reading, safe writing

from hypothesis import settings  # noqa: E402

import rsm_lrg.io as rio  # noqa: E402
from rsm_lrg.io import check_output, output_transaction, quote_user_value, read_input_bytes, read_table  # noqa: E402


@given(st.one_of(st.text(max_size=500), st.integers(), st.floats()), st.integers(min_value=1, max_value=80))
@settings(max_examples=200, deadline=None)
def test_quote_user_value_is_short_and_one_line(value, limit):
    q = quote_user_value(value, limit)
    assert "\n" not in q and "\r" not in q
    assert len(q) <= limit + 2 or (not isinstance(value, str) and len(repr(value)) <= limit + 2)
    if len(repr(value)) <= limit + (2 if isinstance(value, str) else 0):  # + the quotes
        assert q == repr(value)  # short values are shown exactly


def test_quote_user_value_huge_int_and_cell():
    assert quote_user_value(10 ** 5000) == "<int too long to show>"  # str() of it raises in Python 3.11+
    q = quote_user_value("z" * 10_000_000)
    assert len(q) <= 42 and q.startswith("'zzz") and q.endswith("\u2026'")


@pytest.mark.parametrize("path,word", [("/dev/zero", "regular file"), ("/dev/null", "regular file"),
                                       ("/", "directory"), ("/no/such/file.csv", "no such")])
def test_read_input_bytes_refuses_what_is_not_a_regular_file(path, word):
    with pytest.raises(InputError, match=word):
        read_input_bytes(path)


def test_read_input_bytes_fifo_does_not_block(tmp_path):
    fifo = tmp_path / "pipe.csv"
    os.mkfifo(fifo)  # opening it for reading would block until a writer came
    with pytest.raises(InputError, match="regular file"):
        read_table(fifo)


def test_table_limits_name_the_file_and_the_limit(tmp_path, monkeypatch):
    p = tmp_path / "t.csv"
    p.write_text("a,b\n" + "1,2\n" * 50)
    monkeypatch.setattr(rio, "MAX_ROWS", 10)
    with pytest.raises(InputError, match=r"t\.csv: has 50 data rows, more than the limit of 10"):
        read_table(p)
    monkeypatch.setattr(rio, "MAX_ROWS", 100)
    monkeypatch.setattr(rio, "MAX_COLUMNS", 1)
    with pytest.raises(InputError, match=r"t\.csv: the header has 2 columns, more than the limit of 1"):
        read_table(p)
    monkeypatch.setattr(rio, "MAX_COLUMNS", 1000)
    with pytest.raises(InputError, match=r"t\.csv: is .* larger than the limit"):
        read_input_bytes(p, limit=100)
    p.write_text("a,b\n1," + "2" * 2_000_000 + "\n")
    with pytest.raises(InputError, match=r"t\.csv: line 2 is longer than the limit of 1 MiB"):
        read_table(p)
    assert len(read_table(tmp_path.joinpath("ok.csv").write_text("a,b\n1,2\n") and tmp_path / "ok.csv")) == 1


def test_header_with_quoted_comma_counts_as_one_column(tmp_path):
    p = tmp_path / "q.csv"
    p.write_text('"a,b",c\n1,2\n')
    assert list(read_table(p).columns) == ["a,b", "c"]


def test_check_output_reasons(tmp_path):
    afile = tmp_path / "afile"
    afile.write_text("x")
    cases = [("", "empty"), (afile / "o.json", "not a directory"), (tmp_path / "no" / "o.json", "does not exist"),
             (tmp_path, "is a directory"), (afile, "already exists"), ("/dev/null", "regular file")]
    for path, word in cases:
        with pytest.raises(InputError, match=word):
            check_output(path, option="--json")
    assert check_output(afile, force=True) == afile
    with pytest.raises(InputError, match=r"cannot write --json .*afile: it is the input file"):
        check_output(afile, force=True, inputs=[afile], option="--json")
    link = tmp_path / "link"
    link.symlink_to(afile)
    hard = tmp_path / "hard"
    os.link(afile, hard)
    for p in (link, hard, tmp_path / "." / "afile"):
        with pytest.raises(InputError, match="input file"):
            check_output(p, force=True, inputs=[afile])
    assert sorted(x.name for x in tmp_path.iterdir()) == ["afile", "hard", "link"]


def test_output_transaction_writes_all_or_nothing(tmp_path):
    a, b = tmp_path / "a.txt", tmp_path / "b.txt"
    with pytest.raises(RuntimeError):
        with output_transaction():
            write_output(a, "A")
            assert not a.exists()  # staged, not yet in place
            raise RuntimeError("the second output failed")
    assert list(tmp_path.iterdir()) == []
    with output_transaction():
        write_output(a, "A")
        write_output(b, b"B")
    assert a.read_text() == "A" and b.read_bytes() == b"B"
    assert sorted(x.name for x in tmp_path.iterdir()) == ["a.txt", "b.txt"]


def test_output_transaction_undoes_earlier_renames_when_one_fails(tmp_path):
    a, b = tmp_path / "a.txt", tmp_path / "b.txt"
    a.write_text("old a")
    with pytest.raises(InputError, match=r"cannot write .*b\.txt"):
        with output_transaction():
            write_output(a, "new a", force=True)
            write_output(b, "new b")
            b.mkdir()  # the target turns into a directory before the rename
            (b / "keep").write_text("k")
    assert a.read_text() == "old a"  # restored
    assert sorted(x.name for x in tmp_path.iterdir()) == ["a.txt", "b.txt"] and (b / "keep").exists()


def test_output_transaction_never_writes_an_input(tmp_path):
    inp = tmp_path / "in.csv"
    inp.write_text("a,b\n1,2\n")
    with pytest.raises(InputError, match="input file"):
        with output_transaction(inputs=[inp]):
            write_output(tmp_path / "." / "in.csv", "overwritten", force=True)
    assert inp.read_text() == "a,b\n1,2\n"


def test_a_file_appearing_meanwhile_is_not_clobbered_without_force(tmp_path):
    a, b = tmp_path / "a.txt", tmp_path / "b.txt"
    with pytest.raises(InputError, match=r"b\.txt: it already exists"):
        with output_transaction():
            write_output(a, "A")
            write_output(b, "B")
            b.write_text("someone else's")  # after the checks, before the renames
    assert b.read_text() == "someone else's" and not a.exists()
    assert sorted(x.name for x in tmp_path.iterdir()) == ["b.txt"]
    with output_transaction():
        write_output(b, "B", force=True)
    assert b.read_text() == "B"


def test_remembered_float_columns_converts_a_column_once_inside_the_block():
    import pandas as pd

    from rsm_lrg.io import float_column, remembered_float_columns

    df = pd.DataFrame({"a": [1, 2, 3], "b": [0.5, 1.5, 2.5]})
    with remembered_float_columns():
        first = float_column(df, "a")
        assert float_column(df, "a") is first
        other = df.copy()
        assert float_column(other, "a") is not first  # another frame, its own conversion
    assert float_column(df, "a") is not first  # outside the block: converted anew
    assert first.tolist() == [1.0, 2.0, 3.0] and first.dtype == float
