"""rsm_lrg.readers and rsm_lrg.io.read_table: CSV dialects, Excel workbooks, Parquet files,
standard input; every bad variant is one InputError that names the file (and the row/column)."""

import io
import sys
import zipfile

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.datasets import data_path
from rsm_lrg.io import InputError, read_table, read_table_as
from rsm_lrg.readers import ReadAs, TableError, detect_separator, parse_csv

TABLE4 = data_path("table4.csv")


@pytest.fixture(scope="module")
def table4():
    return pd.read_csv(TABLE4)


def _same(a: pd.DataFrame, b: pd.DataFrame) -> None:
    assert list(a.columns) == list(b.columns)
    assert a.shape == b.shape
    np.testing.assert_array_equal(a.to_numpy(dtype=float), b.to_numpy(dtype=float))  # exact: same digits


@pytest.mark.parametrize("sep,decimal", [(";", ","), (";", "."), ("\t", "."), ("\t", ","), ("|", "."), (",", ".")])
def test_csv_dialects_read_the_same_numbers(tmp_path, table4, sep, decimal):
    p = tmp_path / "runs.csv"
    table4.to_csv(p, sep=sep, decimal=decimal, index=False)
    df, how = read_table_as(p, decimal=decimal)  # the separator detected
    _same(df, table4)
    assert how == ReadAs("csv", sep, decimal, True)
    df2, how2 = read_table_as(p, sep=sep, decimal=decimal)  # and given
    _same(df2, table4)
    assert not how2.sep_detected


def test_utf16_and_bom_text(tmp_path, table4):
    p = tmp_path / "unicode.txt"
    p.write_bytes(table4.to_csv(sep="\t", index=False).encode("utf-16"))  # Excel's "Unicode text"
    _same(read_table(p), table4)
    p.write_bytes(b"\xef\xbb\xbf" + table4.to_csv(sep=";", index=False).encode())
    _same(read_table(p), table4)


def test_xlsx_and_parquet_and_stdin(tmp_path, table4, monkeypatch):
    x = tmp_path / "runs.xlsx"
    table4.to_excel(x, index=False, sheet_name="Runs")
    df, how = read_table_as(x)
    _same(df, table4)
    assert how.describe() == "sheet 'Runs' of an Excel workbook"
    q = tmp_path / "runs.parquet"
    table4.to_parquet(q)
    df, how = read_table_as(q)
    _same(df, table4)
    assert how.format == "parquet"
    # standard input, in any of the formats (told by the first bytes)
    for raw in (x.read_bytes(), q.read_bytes(), table4.to_csv(sep=";", decimal=",", index=False).encode()):
        monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(raw)))
        _same(read_table("-", decimal="," if raw[:2] == b"or" else "."), table4)


def test_python_api_takes_a_frame_and_the_options(tmp_path, table4):
    assert read_table(table4) is table4  # a DataFrame is accepted as it is
    p = tmp_path / "semi.csv"
    table4.to_csv(p, sep=";", decimal=",", index=False)
    _same(rsm_lrg.read_table(p, sep=";", decimal=","), table4)
    ref = rsm_lrg.fit(table4, "tcr_c_per_min")
    got = rsm_lrg.fit(rsm_lrg.read_table(p, decimal=","), "tcr_c_per_min")
    assert got.to_dict()["coefficients"] == ref.to_dict()["coefficients"]


def test_xlsx_several_sheets_needs_sheet(tmp_path, table4):
    x = tmp_path / "book.xlsx"
    with pd.ExcelWriter(x) as w:
        pd.DataFrame({"note": ["read me"]}).to_excel(w, sheet_name="Notes", index=False)
        table4.to_excel(w, sheet_name="Runs", index=False)
    with pytest.raises(InputError, match=r"book\.xlsx: the workbook has 2 sheets \('Notes', 'Runs'\); choose one"):
        read_table(x)
    _same(read_table(x, sheet="Runs"), table4)
    with pytest.raises(InputError, match=r"book\.xlsx: no sheet 'Data' in the workbook \(sheets: 'Notes', 'Runs'\)"):
        read_table(x, sheet="Data")


def test_xlsx_trailing_blank_rows_and_columns_are_not_data(tmp_path, table4):
    import openpyxl

    x = tmp_path / "lab.xlsx"
    wb = openpyxl.Workbook()
    ws = wb.active
    ws.title = "Runs"
    ws.append(list(table4.columns))
    for row in table4.itertuples(index=False):
        ws.append(list(row))
    ws.cell(row=60, column=12, value=None)  # an empty cell far out: the used range grows
    ws.cell(row=40, column=1).value = "   "  # a blank-looking row
    wb.save(x)
    _same(read_table(x), table4)


def test_xlsx_formula_without_value_is_refused(tmp_path, table4):
    import openpyxl

    x = tmp_path / "f.xlsx"
    wb = openpyxl.Workbook()
    ws = wb.active
    ws.append(["a", "b", "y"])
    ws.append([1, 2, 3])
    ws.append([2, 3, "=A3+B3"])  # openpyxl stores no computed value
    wb.save(x)
    with pytest.raises(InputError, match=r"f\.xlsx: sheet 'Sheet' cell C3 holds a formula without a stored value"):
        read_table(x)


@pytest.mark.parametrize("text,decimal,message", [
    ("a;b\n1,5;2\n", ".", r"column 'a' row 1: '1,5' is written with a decimal comma; read the file with --decimal ,"),
    ("a;b\n1.5;2\n", ",", r"column 'a' row 1: '1.5' is written with a decimal point; read the file with --decimal \."),
    ("a;b;c\n1;2;3\n4;5\n", ".", r""),  # a short line reads as empty cells (checked later), not an error here
    ("a,b,c\n1,5,2,3\n", ".", r"line 2 has more fields than the header \(3 columns\); a number written with a decimal comma"),
    ("a;b,c\n1;2,3\n", ".", r"the separator is ambiguous \(both ',' and ';' split every line alike\); give --sep"),
    ("abc\n1\n", ".", r"is not a CSV table \(found a single column 'abc'\)"),
    ("a;a\n1;2\n", ".", r"column 'a' appears more than once in the header"),
    ("a;;c\n1;2;3\n", ".", r"the header row has a blank column name"),
    ("a;b\n", ".", r"has a header but no data rows"),
])
def test_bad_csv_variants(tmp_path, text, decimal, message):
    p = tmp_path / "bad.csv"
    p.write_text(text)
    if not message:
        assert read_table(p).shape == (2, 3)
        return
    with pytest.raises(InputError, match="^" + r"[^\n]*bad\.csv: " + message):
        read_table(p, decimal=decimal)


def test_bad_binary_variants(tmp_path, table4):
    x = tmp_path / "runs.xlsx"
    table4.to_excel(x, index=False)
    q = tmp_path / "runs.parquet"
    table4.to_parquet(q)
    cases = {
        "cut.xlsx": (x.read_bytes()[:2000], r"cut\.xlsx: is not a readable Excel workbook"),
        "text.xlsx": (b"a,b\n1,2\n", r"text\.xlsx: is not an Excel workbook"),
        "cut.parquet": (q.read_bytes()[: len(q.read_bytes()) // 2], r"cut\.parquet: is not a readable Parquet file"),
        "text.parquet": (b"a,b\n1,2\n", r"text\.parquet: is not a Parquet file"),
        "old.xls": (b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1" + b"\0" * 100, r"old\.xls: is an old-style Excel \.xls"),
        "book.csv": (x.read_bytes(), r"book\.csv: is a zip archive \(an Excel workbook\?\), not a \.csv file"),
        "latin1.csv": ("a;b\n1;2\n\u00b0C;3\n".encode("latin-1"), r"latin1\.csv: is not a UTF-8 CSV text file \(row 2\)"),
    }
    for name, (raw, message) in cases.items():
        p = tmp_path / name
        p.write_bytes(raw)
        with pytest.raises(InputError, match=message):
            read_table(p)
    zipped = tmp_path / "other.xlsx"  # a zip archive that is not a workbook
    with zipfile.ZipFile(zipped, "w") as z:
        z.writestr("hello.txt", "hi")
    with pytest.raises(InputError, match=r"other\.xlsx: is not a readable Excel workbook"):
        read_table(zipped)


def test_options_that_do_not_fit_the_format(tmp_path, table4):
    q = tmp_path / "runs.parquet"
    table4.to_parquet(q)
    with pytest.raises(InputError, match=r"runs\.parquet: --sep and --decimal are for CSV text; this is PARQUET"):
        read_table(q, decimal=",")
    with pytest.raises(InputError, match=r"--sheet 'x' is for an Excel workbook"):
        read_table(q, sheet="x")
    with pytest.raises(InputError, match=r"--sep ':' is not one of"):
        read_table(q, sep=":")
    p = tmp_path / "a.csv"
    p.write_text("a;b\n1;2\n")
    with pytest.raises(InputError, match=r"the separator and the decimal mark are both ','"):
        read_table(p, sep=",", decimal=",")


def test_empty_stdin_is_an_error(monkeypatch):
    monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(b"")))
    with pytest.raises(InputError, match=r"<stdin>: nothing was read"):
        read_table("-")


def test_detect_separator_rules():
    assert detect_separator("x;y\n1;2\n3;4\n") == ";"
    assert detect_separator("x|y\n1|2\n") == "|"
    assert detect_separator("x,y\n1,2\n3,4,5\n") == ","  # the one that splits the header; the parser names line 3
    assert detect_separator("x\n1\n") == ","
    with pytest.raises(TableError):
        detect_separator("a;b,c\n1;2,3\n")


def test_parse_csv_decimal_comma_exact():
    df, how = parse_csv(b"x;y\n0,1;-2,5e-3\n1,25;3\n", decimal=",")
    assert df["x"].tolist() == [0.1, 1.25] and df["y"].tolist() == [-0.0025, 3.0]
    assert how.describe() == "CSV, separator ';' (detected), decimal ','"


# --- piece by piece (simulate's large designs) ---------------------------------------------

def test_count_rows_and_pieces_equal_the_whole(tmp_path, table4):
    from rsm_lrg.readers import count_rows, csv_chunks, parquet_chunks, write_csv_chunks, write_parquet_chunks

    p = tmp_path / "semi.csv"
    table4.to_csv(p, sep=";", decimal=",", index=False)
    q = tmp_path / "t.parquet"
    table4.to_parquet(q)
    with open(p, "rb") as fh:
        assert count_rows(fh, "csv") == 27
        how, pieces = csv_chunks(fh, decimal=",", chunk_rows=10)
        parts = list(pieces)
    assert how == ReadAs("csv", ";", ",", True) and [len(x) for x in parts] == [10, 10, 7]
    assert parts[2].index[0] == 20  # rows numbered in the whole file
    _same(pd.concat(parts, ignore_index=True), table4)
    p.write_bytes(p.read_bytes().rstrip(b"\n"))  # no final newline
    with open(p, "rb") as fh:
        assert count_rows(fh, "csv") == 27
    with open(q, "rb") as fh:
        assert count_rows(fh, "parquet") == 27
        _, pieces = parquet_chunks(fh, chunk_rows=8)
        parts = list(pieces)
    assert [len(x) for x in parts] == [8, 8, 8, 3]
    _same(pd.concat(parts, ignore_index=True), table4)
    # written piece by piece: one CSV (header once) and one Parquet file
    buf = io.BytesIO()
    assert write_csv_chunks(buf, parts) == 27
    assert buf.getvalue().decode() == table4.to_csv(index=False, float_format="%.10g", lineterminator="\n")
    buf = io.BytesIO()
    assert write_parquet_chunks(buf, parts) == 27
    _same(pd.read_parquet(io.BytesIO(buf.getvalue())), table4)
    with pytest.raises(TableError, match="different columns"):
        write_csv_chunks(io.BytesIO(), [parts[0], parts[1].rename(columns={"order": "run"})])


def test_pieces_refuse_what_the_whole_refuses(tmp_path):
    from rsm_lrg.readers import csv_chunks

    p = tmp_path / "bad.csv"
    p.write_text("a;b\n" + "1;2\n" * 30 + "1,5;2\n")
    with open(p, "rb") as fh:
        _, pieces = csv_chunks(fh, chunk_rows=10)
        with pytest.raises(TableError, match=r"column 'a' row 31: '1,5' is written with a decimal comma"):
            list(pieces)
    p.write_text("a;a\n1;2\n")
    with open(p, "rb") as fh, pytest.raises(TableError, match="'a' appears more than once"):
        csv_chunks(fh)


def test_two_column_names_alike_once_normalised_are_refused(tmp_path):
    # issue 36: a constraint on the decomposed 'é' was applied to the other column, the composed
    # 'é'; two names that are the same text in Unicode NFC are ambiguous: refused by name
    p = tmp_path / "nfc.csv"
    p.write_bytes("caf\u00e9,cafe\u0301,y\n1,2,3\n2,3,4\n3,1,5\n".encode())
    with pytest.raises(InputError, match="the column names 'caf.' and 'cafe.' are the same text in Unicode NFC"):
        read_table(p)


# --- issue 36: workbooks and Parquet files that lied or crashed ---------------------------------

def _table4_xlsx() -> bytes:
    from rsm_lrg.readers import xlsx_bytes

    return xlsx_bytes(pd.read_csv(data_path("table4.csv")), "Runs")


def _with_sheet_xml(raw: bytes, change) -> bytes:
    zin = zipfile.ZipFile(io.BytesIO(raw))
    out = io.BytesIO()
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as zout:
        for item in zin.infolist():
            data = zin.read(item.filename)
            zout.writestr(item, change(data) if item.filename == "xl/worksheets/sheet1.xml" else data)
    return out.getvalue()


def _body(xml: bytes) -> bytes:
    return xml.split(b"?>", 1)[-1]


_LAUGHS = (b'<?xml version="1.0"?><!DOCTYPE z [<!ENTITY a "aaaaaaaaaa">'
           + b"".join(f'<!ENTITY {chr(98 + k)} "{("&" + chr(97 + k) + ";") * 10}">'.encode() for k in range(8))
           + b"]>")


@pytest.mark.parametrize(("kind", "change", "words"), [
    ("truncated sheet", lambda x: x[: len(x) // 2], ["not a readable Excel workbook", "sheet 'Runs'"]),
    ("entity expansion", lambda x: _LAUGHS + _body(x).replace(b"<v>1</v>", b"<v>&i;</v>", 1),
     ["not a readable Excel workbook", "sheet 'Runs'"]),
    ("external entity", lambda x: b'<?xml version="1.0"?><!DOCTYPE z [<!ENTITY e SYSTEM "file:///etc/hostname">]>'
     + _body(x).replace(b"<v>1</v>", b"<v>&e;</v>", 1), ["not a readable Excel workbook"]),
])
def test_a_damaged_workbook_is_one_error(kind, change, words):
    with pytest.raises(TableError) as info:
        rsm_lrg.readers.parse_xlsx(_with_sheet_xml(_table4_xlsx(), change))
    for w in words:
        assert w in str(info.value), (kind, str(info.value))


def test_a_truncated_workbook_through_the_command_line_is_exit_2(tmp_path, capsys):
    from rsm_lrg.cli import main

    raw = _with_sheet_xml(_table4_xlsx(), lambda x: x[: len(x) // 2])
    (tmp_path / "t.xlsx").write_bytes(raw)
    for argv in (["fit", str(tmp_path / "t.xlsx"), "--response", "tcr_c_per_min"], ["evaluate", str(tmp_path / "t.xlsx")]):
        assert main(argv) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and "t.xlsx: is not a readable Excel workbook" in err[0], err


def test_a_chart_sheet_is_refused_by_name():
    import openpyxl
    from openpyxl.chart import BarChart, Reference

    book = openpyxl.load_workbook(io.BytesIO(_table4_xlsx()))
    chart = BarChart()
    chart.add_data(Reference(book["Runs"], min_col=6, min_row=1, max_row=28), titles_from_data=True)
    book.create_chartsheet("Plot").add_chart(chart)
    buf = io.BytesIO()
    book.save(buf)
    with pytest.raises(TableError, match="sheet 'Plot' is a chart sheet"):
        rsm_lrg.readers.parse_xlsx(buf.getvalue(), sheet="Plot")
    assert rsm_lrg.readers.parse_xlsx(buf.getvalue(), sheet="Runs")[0].shape == (27, 6)


def _edited(cells: dict) -> bytes:
    import openpyxl

    book = openpyxl.load_workbook(io.BytesIO(_table4_xlsx()))
    ws = book["Runs"]
    for ref, value in cells.items():
        if ref.endswith(":text"):
            col = int(ref.split(":")[0])
            for (c,) in ws.iter_rows(min_row=2, min_col=col, max_col=col):
                c.value = str(c.value)
        else:
            ws[ref] = value
    buf = io.BytesIO()
    book.save(buf)
    return buf.getvalue()


def test_numbers_stored_as_text_are_read_as_numbers_and_said():
    # issue 36: stroke_m held as text (Excel's green triangle) was silently left out of the factors
    df, how = rsm_lrg.readers.parse_xlsx(_edited({"3:text": None}))
    ref = pd.read_csv(data_path("table4.csv"))
    assert df["stroke_m"].dtype == float and np.array_equal(df["stroke_m"].to_numpy(), ref["stroke_m"].to_numpy())
    assert how.converted == ("column 'stroke_m' holds 27 numbers stored as text, read as numbers",)
    assert "stored as text, read as numbers" in how.describe()


@pytest.mark.parametrize("ref", ["F5", "C3"])
def test_a_true_cell_is_an_error_naming_it(ref):
    # issue 36: TRUE in the response was fitted as 1.0, in a named factor it stretched the range
    with pytest.raises(TableError, match=rf"cell {ref} \(column '\w+', row {int(ref[1:]) - 1}\): holds TRUE"):
        rsm_lrg.readers.parse_xlsx(_edited({ref: True}))


def test_bounds_on_bytes_and_cells_are_checked_before_reading():
    raw = _table4_xlsx()
    with pytest.raises(TableError, match="unpacks to .* MiB, more than the limit of 0.0 MiB"):
        rsm_lrg.readers.parse_xlsx(raw, max_bytes=1000)
    with pytest.raises(TableError, match=r"more than 100 cells .* \(the bound on cells\)"):
        rsm_lrg.readers.parse_xlsx(raw, max_cells=100)


def test_a_decimal_parquet_column_is_read_as_numbers():
    import decimal

    import pyarrow as pa
    import pyarrow.parquet as pq

    ref = pd.read_csv(data_path("table4.csv"))
    table = pa.Table.from_pandas(ref, preserve_index=False)
    dec = pa.array([decimal.Decimal(repr(v)) for v in ref["stroke_m"]], type=pa.decimal128(12, 6))
    table = table.set_column(table.schema.get_field_index("stroke_m"), "stroke_m", dec)
    buf = io.BytesIO()
    pq.write_table(table, buf)
    df, how = rsm_lrg.readers.parse_parquet(buf.getvalue())
    assert df["stroke_m"].dtype == float and np.allclose(df["stroke_m"], ref["stroke_m"], rtol=0, atol=1e-12)
    assert how.converted == ("column 'stroke_m' holds decimals, read as floating-point numbers",)
    with pytest.raises(TableError, match="unpacks to .* more than the limit"):
        rsm_lrg.readers.parse_parquet(buf.getvalue(), max_bytes=100)


def test_a_utf16_header_of_too_many_columns_is_refused_before_parsing(tmp_path):
    text = "\ufeff" + ",".join(f"c{i}" for i in range(3000)) + "\n" + ",".join("1" for _ in range(3000)) + "\n"
    (tmp_path / "wide.csv").write_bytes(text.encode("utf-16-le"))
    with pytest.raises(InputError, match="the header has 3000 columns, more than the limit of 1000"):
        read_table(tmp_path / "wide.csv")


# -- write_csv_columns: a table of NumPy columns written without pandas ----------------------------
@pytest.mark.parametrize("seed", range(40))
def test_write_csv_columns_writes_what_pandas_writes(seed):
    from rsm_lrg.readers import write_csv_chunks, write_csv_columns

    rng = np.random.default_rng(seed)
    n = int(rng.integers(1, 30))
    f = rng.normal(size=n) * 10.0 ** rng.integers(-300, 300, size=n)
    for value, share in ((np.nan, 0.1), (np.inf, 0.05), (-np.inf, 0.05), (-0.0, 0.05), (0.1 + 0.2, 0.05)):
        f[rng.random(n) < share] = value
    cols = {"whole": rng.integers(-2**53, 2**53, size=n), "a, b": f, 'say "x"': rng.random(n) < 0.5,
            "rounded": np.round(rng.normal(size=n), 3)}
    mine, theirs = io.BytesIO(), io.BytesIO()
    assert write_csv_columns(mine, list(cols), cols) == n
    write_csv_chunks(theirs, [pd.DataFrame(cols)])
    assert mine.getvalue() == theirs.getvalue()


def test_write_csv_columns_refuses_text():
    from rsm_lrg.readers import TableError, write_csv_columns

    with pytest.raises(TableError, match="not numbers"):
        write_csv_columns(io.BytesIO(), ["x"], {"x": np.array(["a"], dtype=object)})
