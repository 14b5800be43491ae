"""Table formats: parsing input tables from bytes (CSV in any common dialect, Excel workbooks,
Parquet files), and the bytes of a workbook to write (:func:`xlsx_bytes`).

:func:`rsm_lrg.io.read_table` reads a file (or standard input) in its bounded, safe way and
hands the bytes here; this module knows the formats only:

- **CSV** (:func:`parse_csv`): the separator is one of ``,`` ``;`` tab ``|``, given or detected
  (:func:`detect_separator`: the one that splits the header into several columns and every
  line into as many; two that both do are refused as ambiguous, nothing is guessed), the
  decimal mark ``.`` or ``,`` (given, never guessed: a column of ``1,5`` read with ``.`` is an
  error that says to give ``,``). UTF-8 (with or without a byte-order mark) or UTF-16 with
  its byte-order mark (Excel's "Unicode text").
- **Excel** (:func:`parse_xlsx`): an ``.xlsx``/``.xlsm`` workbook through openpyxl; the sheet
  named, or the only one (a workbook of several sheets needs the name); the first row is the
  header; formulas are read as their stored values (a formula without one is refused).
- **Parquet** (:func:`parse_parquet`): a single file through pandas' Parquet engine.

Every parser returns the table and a :class:`ReadAs` that says what was read (stated by the
CLI); bad input raises :class:`TableError` with a sentence naming the row and column, to
which the caller prefixes the file name.
"""

from __future__ import annotations

import csv
import io
import re
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import pandas as pd

    from .table import ColumnTable

__all__ = ["TableError", "ReadAs", "SEPARATORS", "DECIMALS", "FORMATS", "detect_format", "detect_separator",
           "parse_csv", "parse_plain_csv", "PLAIN_MAX_BYTES", "parse_xlsx", "parse_parquet", "check_columns",
           "separator_name", "xlsx_bytes",
           "count_rows", "csv_chunks", "parquet_chunks", "write_csv_chunks", "write_csv_columns", "write_parquet_chunks",
           "keep_coded_text",
           "LEADING_ZERO", "check_control_characters", "CONTROL_CHARACTERS",
           "column_name_problem", "check_column_names", "row_of_line"]

#: CSV separators read (given with ``sep=`` / ``--sep`` or detected), in the order tried.
SEPARATORS = (",", ";", "\t", "|")
#: Decimal marks read (``decimal=`` / ``--decimal``); ``.`` unless given.
DECIMALS = (".", ",")
#: Table formats (``detect_format``).
FORMATS = ("csv", "xlsx", "parquet")

#: Lines looked at to detect the separator (beyond them the parser checks the rest).
SNIFF_LINES = 200

_ZIP_MAGIC = b"PK\x03\x04"
_PARQUET_MAGIC = b"PAR1"
_OLD_EXCEL_MAGIC = b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1"  # .xls (OLE2 compound file)
_DECIMAL_COMMA = re.compile(r"^\s*[-+]?\d*,\d+(?:[eE][-+]?\d+)?\s*$")
_DECIMAL_POINT = re.compile(r"^\s*[-+]?\d*\.\d+(?:[eE][-+]?\d+)?\s*$")


class TableError(ValueError):
    """A table that cannot be read as it is; the message names the row and the column (the
    caller puts the file name in front)."""


@dataclass(frozen=True)
class ReadAs:
    """What an input was read as.

    Attributes
    ----------
    format : str
        ``"csv"``, ``"xlsx"`` or ``"parquet"``.
    sep, decimal : str or None
        The CSV separator and decimal mark (``None`` for the other formats).
    sep_detected : bool
        True when the separator was detected rather than given.
    sheet : str or None
        The workbook sheet read.
    converted : tuple of str
        What was read otherwise than it was stored, each said in a phrase (numbers stored as
        text in a workbook, decimal columns of a Parquet file).
    """

    format: str
    sep: str | None = None
    decimal: str | None = None
    sep_detected: bool = False
    sheet: str | None = None
    converted: tuple[str, ...] = ()

    @property
    def plain(self) -> bool:
        """True for the plain comma-separated CSV with decimal points (nothing worth stating)."""
        return self.format == "csv" and self.sep == "," and self.decimal == "." and not self.converted

    def describe(self) -> str:
        """One phrase: ``CSV, separator ';' (detected), decimal ','``; ``sheet 'Runs' of an
        Excel workbook``; ``a Parquet file``.

        >>> ReadAs("csv", ";", ",", True).describe()
        "CSV, separator ';' (detected), decimal ','"
        >>> ReadAs("xlsx", sheet="Runs").describe()
        "sheet 'Runs' of an Excel workbook"
        """
        said = "".join(f"; {c}" for c in self.converted)
        if self.format == "xlsx":
            return f"sheet {self.sheet!r} of an Excel workbook{said}"
        if self.format == "parquet":
            return f"a Parquet file{said}"
        how = " (detected)" if self.sep_detected else ""
        return f"CSV, separator {separator_name(self.sep or ',')}{how}, decimal {self.decimal!r}"


def separator_name(sep: str) -> str:
    """``';'``, ``tab``: a separator as a message shows it.

    >>> separator_name("\\t"), separator_name(";")
    ('tab', "';'")
    """
    return "tab" if sep == "\t" else repr(sep)


def check_choice(value: str | None, allowed: tuple[str, ...], what: str) -> None:
    """Refuse a separator or decimal mark that is not one of ``allowed``."""
    if value is not None and value not in allowed:
        shown = ", ".join(separator_name(a) for a in allowed)
        raise TableError(f"{what} {separator_name(value)} is not one of {shown}")


def detect_format(raw: bytes, suffix: str) -> str:
    """The format of an input from its first bytes (and its file name's ``suffix`` where the
    bytes say nothing): ``"xlsx"`` for a zip archive, ``"parquet"`` for ``PAR1``, else
    ``"csv"``. A name and content that disagree, and formats not read (``.xls``, ``.ods``),
    raise :class:`TableError`.

    >>> detect_format(b"PAR1....PAR1", ".parquet"), detect_format(b"a,b\\n1,2\\n", ".csv")
    ('parquet', 'csv')
    """
    suffix = suffix.lower()
    if raw.startswith(_OLD_EXCEL_MAGIC) or suffix == ".xls":
        raise TableError("is an old-style Excel .xls workbook, which is not read; save it as .xlsx or CSV")
    if suffix in (".ods", ".numbers"):
        raise TableError(f"a {suffix} spreadsheet is not read; save it as .xlsx or CSV")
    if raw.startswith(_ZIP_MAGIC):
        if suffix in (".csv", ".txt", ".tsv", ".parquet", ".pq"):
            raise TableError(f"is a zip archive (an Excel workbook?), not a {suffix} file; name it .xlsx to read it")
        return "xlsx"
    if raw.startswith(_PARQUET_MAGIC):
        return "parquet"
    if suffix in (".xlsx", ".xlsm"):
        raise TableError("is not an Excel workbook (an .xlsx file is a zip archive; this one is not)")
    if suffix in (".parquet", ".pq"):
        raise TableError("is not a Parquet file (it does not begin with 'PAR1')")
    return "csv"


# --- CSV ------------------------------------------------------------------------------------

def decode_text(raw: bytes) -> str:
    """The text of a CSV file: UTF-16 when it starts with a UTF-16 byte-order mark, else UTF-8
    (a UTF-8 byte-order mark dropped). Anything else raises :class:`TableError` naming the line."""
    if raw.startswith((b"\xff\xfe", b"\xfe\xff")):
        try:
            return raw.decode("utf-16")
        except UnicodeDecodeError:
            raise TableError("is not valid UTF-16 text (it starts with a UTF-16 byte-order mark)") from None
    if b"\x00" in raw:
        line = raw.count(b"\n", 0, raw.index(b"\x00")) + 1
        raise TableError(f"is not a CSV text file (it contains NUL bytes, {row_of_line(line)})")
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = raw.count(b"\n", 0, exc.start) + 1
        raise TableError(f"is not a UTF-8 CSV text file ({row_of_line(line)}); save it as CSV UTF-8") from None


def row_of_line(line: int) -> str:
    """Where the 1-based ``line`` of a CSV text is, in the words of every other reader error:
    the header, or the 1-based data row (line 2 is row 1).

    >>> row_of_line(1), row_of_line(202)
    ('in the header', 'row 201')
    """
    return "in the header" if line <= 1 else f"row {line - 1}"


def _field_counts(lines: list[str], sep: str) -> list[int]:
    try:
        return [len(row) for row in csv.reader(lines, delimiter=sep, skipinitialspace=True)]
    except csv.Error:
        return []


def detect_separator(text: str, decimal: str = ".") -> str:
    """The separator of a CSV text: among :data:`SEPARATORS` (``,`` left out with a decimal
    comma), the one that splits the header into two or more columns and each of the first
    :data:`SNIFF_LINES` lines into as many fields.

    Two separators that both do are ambiguous: :class:`TableError` asks for ``--sep``.
    When none does, the one that splits the header is returned (the parser then names the
    line that differs); when none splits the header, ``,``.

    >>> detect_separator("a;b;c\\n1,5;2;3\\n", decimal=",")
    ';'
    >>> detect_separator("a,b\\n1,2\\n")
    ','
    >>> detect_separator("a\\tb\\n1\\t2\\n")
    '\\t'
    """
    lines = [ln for ln in text.splitlines()[: SNIFF_LINES + 1] if ln.strip()]
    if not lines:
        return ","
    candidates = [s for s in SEPARATORS if not (decimal == "," and s == ",")]
    consistent, splits_header = [], []
    for sep in candidates:
        counts = _field_counts(lines, sep)
        if counts and counts[0] >= 2:
            splits_header.append(sep)
            if all(c == counts[0] for c in counts):
                consistent.append(sep)
    if len(consistent) == 1:
        return consistent[0]
    if len(consistent) > 1:
        shown = " and ".join(separator_name(s) for s in consistent)
        raise TableError(f"the separator is ambiguous (both {shown} split every line alike); give --sep")
    if splits_header:
        return splits_header[0]
    return "," if decimal == "." else ";"


def _header(text: str, sep: str) -> list[str]:
    try:
        return next(csv.reader(io.StringIO(text, newline=""), delimiter=sep, skipinitialspace=True), [])
    except csv.Error as exc:
        raise TableError(f"is not a valid CSV file (header: {exc})") from None


def parse_csv(raw: bytes, *, sep: str | None = None, decimal: str = ".") -> tuple[pd.DataFrame, ReadAs]:
    """Parse CSV bytes into a DataFrame.

    Parameters
    ----------
    raw : bytes
        The file's content (UTF-8, or UTF-16 with a byte-order mark).
    sep : str, optional
        One of :data:`SEPARATORS`; detected when None (:func:`detect_separator`).
    decimal : str
        ``"."`` or ``","``; a column that reads as numbers only with a decimal comma while
        ``"."`` was given is refused with a message that says so.

    Returns
    -------
    (DataFrame, ReadAs)
    """
    import pandas as pd

    check_choice(sep, SEPARATORS, "separator")
    check_choice(decimal, DECIMALS, "decimal mark")
    if sep is not None and sep == decimal:
        raise TableError(f"the separator and the decimal mark are both {sep!r}; give a different --sep")
    text = decode_text(raw)
    if not text.strip():
        raise TableError("the file is empty")
    detected = sep is None
    use = detect_separator(text, decimal) if sep is None else sep
    try:
        df = pd.read_csv(io.StringIO(text), sep=use, decimal=decimal, skipinitialspace=True, engine="c")
    except (pd.errors.ParserError, pd.errors.EmptyDataError, ValueError) as exc:
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise TableError(f"is not a valid CSV file ({first})") from None
    header = _header(text, use)
    if any(str(c).startswith("Unnamed:") or not str(c).strip() for c in df.columns):
        raise TableError("the header row has a blank column name")
    if not df.index.equals(pd.RangeIndex(len(df))):  # pandas took the first column for an index
        hint = ("a number written with a decimal comma? give --decimal , (and --sep)" if use == "," else
                "a missing column name?")
        raise TableError(f"line 2 has more fields than the header ({len(header)} columns); {hint}")
    check_columns(header, df)
    if df.shape[1] < 2:
        raise TableError(f"is not a CSV table (found a single column {_quote(df.columns[0])}); expected columns "
                         f"separated by one of {', '.join(separator_name(s) for s in SEPARATORS)} (or give --sep)")
    if use != ",":  # in a comma-separated file a quoted "1,030" may be a thousands separator
        _refuse_other_decimal(df, decimal)
    df.columns = [str(c) for c in df.columns]
    keep_coded_text(df, text, use, decimal)
    return df, ReadAs("csv", use, decimal, detected)


# --- plain CSV, read without pandas --------------------------------------------------------

#: The largest CSV file (bytes) :func:`parse_plain_csv` reads; a larger one is left to pandas
#: (1 MiB of numbers costs about 0.3 s of CPU here, pandas' import and C parser about 0.5 s;
#: past 2 MiB pandas is the quicker).
PLAIN_MAX_BYTES = 1 << 20

#: A cell of a plain CSV file: a whole number without a leading zero (``0``, ``-12``) or a
#: decimal (``0.4``, ``30.``, ``-1.25e-3``); ASCII digits only, no ``+`` before the number.
_PLAIN_NUMBER = re.compile(r"-?(?:0|[1-9][0-9]*)(?:\.[0-9]*)?(?:[eE][-+]?[0-9]{1,3})?")
#: The most a whole-number cell may be in a plain file: every such number converts to a double
#: exactly (a column holding decimals too is float64, as pandas makes it).
_PLAIN_INT_MAX = 2**53


def _same_double_as_pandas(cell: str) -> bool:
    """Whether pandas' C parser, in every version read (``>= 2.0``), gives ``float(cell)``.

    Since pandas 3.1 it parses with fast_float, correctly rounded as ``float`` is. Before, its
    default converter (``precise_xstrtod``, "high") keeps the first 17 digits of the mantissa
    (leading zeros counted; the rest are dropped, not rounded), makes of them the integer ``D``
    (digit by digit, ``D = 10 D + d`` in doubles, or in 64-bit integers and then converted) and
    multiplies or divides ``D`` by the tabled double ``10**|k|`` (``k`` the exponent written less
    the digits kept after the point). That is ``float``'s correctly rounded value when:

    - the digits dropped are zeros (then ``D 10**k`` is the decimal written);
    - ``D`` and each step to it are doubles exactly: ``D`` less its trailing zeros is at most
      ``2**53`` (so are all its prefixes), and each trailing zero's ``10 D`` is a double;
    - ``|k| <= 22``, so ``10**|k|`` is a double exactly (``5**22 < 2**53``).

    Then pandas makes one IEEE operation on exact operands, rounded once to nearest: the
    correctly rounded decimal (Clinger's fast path), which ``float`` gives.
    """
    mantissa, _, exp = cell.lstrip("-").lower().partition("e")
    whole, _, frac = mantissa.partition(".")
    digits = whole + frac
    kept, dropped = digits[:17], digits[17:]
    if len(whole) > 17 or dropped.strip("0"):
        return False
    if not -22 <= (int(exp) if exp else 0) - (len(kept) - len(whole)) <= 22:
        return False
    significant = kept.rstrip("0") or "0"
    value = int(significant)
    if value > _PLAIN_INT_MAX:
        return False
    for _ in range(len(kept) - len(significant)):
        value *= 10
        if int(float(value)) != value:
            return False
    return True


def _plain_column(cells: list[str]) -> Any:
    """The column ``pandas.read_csv`` makes of ``cells`` (int64 when every cell is a whole
    number, else float64), or None when a cell is not a plain number (:func:`parse_plain_csv`)."""
    import numpy as np

    match = _PLAIN_NUMBER.fullmatch
    if not all(map(match, cells)):
        return None
    joined = "".join(cells)
    if "." not in joined and "e" not in joined and "E" not in joined:  # whole numbers: int64
        values = list(map(int, cells))
        if max(map(abs, values)) > _PLAIN_INT_MAX:
            return None
        return np.array(values, dtype=np.int64)
    if "-0" in cells:  # a whole -0 is 0 in an all-whole chunk of a long file, -0.0 in a decimal one
        return None
    if "e" in joined or "E" in joined or max(map(len, cells)) > 15:  # else <= 15 digits, k in [-15, 0]: taken
        if not all(map(_same_double_as_pandas, cells)):
            return None
    return np.fromiter(map(float, cells), dtype=np.float64, count=len(cells))


def parse_plain_csv(raw: bytes, *, sep: str | None = None, decimal: str = ".") -> tuple[ColumnTable, ReadAs] | None:
    """Read a plain CSV file of numbers without pandas: the table :func:`parse_csv` would read,
    as a :class:`rsm_lrg.table.ColumnTable`, or None when the file is not plain (the caller then
    reads it with :func:`parse_csv`, which reads it or says what is wrong).

    Plain is: at most :data:`PLAIN_MAX_BYTES`; UTF-8 (a byte-order mark allowed); no quote
    character, no NUL; lines ended by ``\\n`` or ``\\r\\n`` (the last may lack it; empty lines
    after the header are skipped, as pandas skips them); the decimal mark ``.``; the separator given, or detected as :func:`parse_csv` detects
    it; a header of at least two names, each printable, non-empty, without spaces around it, not
    ``Unnamed:...``, none repeated, accepted by :func:`check_column_names`; at least one data
    row, each with as many fields as the header; every cell a number, ASCII digits: a whole
    number without a leading zero, at most ``2**53`` in size (``0``, ``-12``), or a decimal
    (``0.4``, ``30.``, ``-1.25e-3``, an exponent of at most three digits) that pandas converts
    as ``float`` does in every version (:func:`_same_double_as_pandas`: at most 17 digits, only
    zeros past them, a significand of at most ``2**53`` less its trailing zeros, a power of ten
    of at most 22 in size; a whole ``-0`` among decimals is not plain). A column of whole
    numbers is ``int64``, any other ``float64``: the dtypes and, bit for bit, the values of
    ``pandas.read_csv``.

    Parameters
    ----------
    raw : bytes
        The file's content.
    sep : str, optional
        One of :data:`SEPARATORS`; detected when None (:func:`detect_separator`).
    decimal : str
        The decimal mark; only ``"."`` is plain.

    Returns
    -------
    (ColumnTable, ReadAs) or None
        The table and what it was read as (the :class:`ReadAs` of :func:`parse_csv`), or None.

    >>> t, how = parse_plain_csv(b"x,y\\n-1,0.5\\n1,2.25\\n")
    >>> t["x"].dtype.name, t["y"].tolist(), how.sep
    ('int64', [0.5, 2.25], ',')
    >>> parse_plain_csv(b"x,y\\n01,0.5\\n") is None  # a code: text to parse_csv
    True
    """
    from .table import ColumnTable  # numpy: imported here, not with the module

    if decimal != "." or (sep is not None and sep not in SEPARATORS) or len(raw) > PLAIN_MAX_BYTES:
        return None
    if b'"' in raw or b"\x00" in raw or raw.startswith((b"\xff\xfe", b"\xfe\xff")):
        return None
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        return None
    body = text.replace("\r\n", "\n") if "\r" in text else text
    if "\r" in body:
        return None
    lines = body.split("\n")
    rows = [line for line in lines[1:] if line]  # empty lines are skipped, as pandas does
    if not rows:
        return None
    if sep is None:
        try:
            use = detect_separator(text, decimal)
        except TableError:
            return None
    else:
        use = sep
    names = lines[0].split(use)
    ncol = len(names)
    if ncol < 2 or len(set(names)) != ncol:
        return None
    for name in names:
        if not name or not name.isprintable() or name != name.strip() or name.startswith("Unnamed:"):
            return None
    try:
        check_column_names(names)
    except TableError:
        return None
    if any(line.count(use) != ncol - 1 for line in rows):
        return None
    cells = use.join(rows).split(use)
    columns = {}
    for j, name in enumerate(names):
        col = _plain_column(cells[j::ncol])
        if col is None:
            return None
        columns[name] = col
    return ColumnTable(columns), ReadAs("csv", use, decimal, sep is None)


#: A cell that is a whole number written with a leading zero (``01``, ``-007``): a code.
LEADING_ZERO = r"^\s*[+-]?0\d+\s*$"


def keep_coded_text(df: pd.DataFrame, text: str, sep: str, decimal: str) -> None:
    """Keep, as the text in the file, every column that pandas read as numbers but that holds
    a whole number written with a leading zero (``01``, ``007``: lot or batch codes), so that a
    categoric factor's levels are compared as written (``01`` is not ``1``; issue 26). Used as
    a numeric factor such a column still reads as numbers (``pd.to_numeric``)."""
    import pandas as pd

    if not re.search(r'(^|[,;|\t\n])[ \t"]*[+-]?0[0-9]', text):  # cheap: no such cell anywhere
        return
    numeric = [c for c in df.columns if pd.api.types.is_numeric_dtype(df[c]) and not pd.api.types.is_bool_dtype(df[c])]
    if not numeric:
        return
    as_text = pd.read_csv(io.StringIO(text), sep=sep, skipinitialspace=True, dtype=str, keep_default_na=False,
                          engine="c")
    as_text.columns = list(df.columns)
    for c in numeric:
        col = as_text[c].str.strip()
        if col.str.match(LEADING_ZERO).any():
            df[c] = col.where(col != "", None).astype(object)


def _refuse_other_decimal(df: pd.DataFrame, decimal: str) -> None:
    """A text column whose every value is a number once read with the other decimal mark
    (``1,5`` read with ``.``, or ``1.5`` read with ``,``) means the wrong mark was given: say
    so, naming the column and the first such row, rather than leave the column out as text."""
    import pandas as pd

    pattern = _DECIMAL_COMMA if decimal == "." else _DECIMAL_POINT
    for name in df.columns:
        col = df[name]
        if not (col.dtype == object or pd.api.types.is_string_dtype(col.dtype)):
            continue
        values = col.dropna().astype(str)
        if values.empty:
            continue
        other = values.str.match(pattern)
        if not other.any():
            continue
        rest = values[~other].str.strip()
        if decimal == ",":
            rest = rest.str.replace(",", ".", regex=False)
        if bool(rest.map(_is_number).all()):
            i = int(other[other].index[0]) + 1  # the frame's index is 0, 1, ... (checked by parse_csv)
            mark, option = ("a decimal comma", "--decimal ,") if decimal == "." else ("a decimal point", "--decimal .")
            raise TableError(f"column {_quote(name)} row {i}: {_quote(values[other].iloc[0])} is written with "
                             f"{mark}; read the file with {option}")


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _quote(value: Any, limit: int = 40) -> str:
    text = repr(str(value)[: limit + 1])
    return text if len(str(value)) <= limit else text[:-1][: limit] + "\u2026" + text[0]


def check_columns(header: list[Any], df: pd.DataFrame) -> None:
    """Refuse a table with a blank or repeated column name (``header``: the names as written,
    before pandas renames a repeated ``x`` to ``x.1``), or without data rows."""
    seen = set()
    for name in header:
        if name is None or not str(name).strip():
            raise TableError("the header row has a blank column name")
        if str(name) in seen:
            raise TableError(f"column {_quote(name)} appears more than once in the header")
        seen.add(str(name))
    if df.shape[0] == 0:
        raise TableError("has a header but no data rows")


def column_name_problem(name: Any) -> str | None:
    """Why ``name`` cannot name a column, or None: one rule for every command that reads a
    column (the readers) or writes one (``design``): no control character at all (tab and line
    breaks included: a name is printed on one line, and in a CSV header).

    >>> column_name_problem("stroke_m") is None
    True
    >>> column_name_problem("a" + chr(10) + "b")[:38]
    "the column name 'a\\\\nb' holds a control"
    """
    m = _NAME_CONTROL.search(str(name))
    if m:
        return f"the column name {_quote(name)} holds a control character ({m.group()!r}); rename the column"
    return None


_NAME_CONTROL = re.compile("[\x00-\x1f\x7f-\x9f]")


def check_column_names(names: Any) -> None:
    """Refuse column names that cannot be told apart or printed: one holding a control character
    (:func:`column_name_problem`), one given twice, or two that are the same text once
    normalised (Unicode NFC: ``é`` written as one code point or as ``e`` and a combining accent;
    a name typed in an option would match either): :class:`TableError` naming them.

    >>> try:
    ...     check_column_names(["caf" + chr(0xE9), "cafe" + chr(0x301)])
    ... except TableError as exc:
    ...     print(str(exc)[-92:])
    are the same text in Unicode NFC (one is written with combining accents); rename one of them
    """
    import unicodedata

    seen: dict[str, Any] = {}
    for c in names:
        problem = column_name_problem(c)
        if problem:
            raise TableError(problem)
        key = unicodedata.normalize("NFC", str(c))
        if key in seen:
            if str(seen[key]) == str(c):
                raise TableError(f"column {_quote(c)} appears more than once")
            raise TableError(f"the column names {_quote(seen[key])} and {_quote(c)} are the same text in Unicode NFC "
                             "(one is written with combining accents); rename one of them")
        seen[key] = c


#: Control characters (C0 but tab, line feed and carriage return; DEL; C1): never in a name or
#: a cell of a table, and printed to a terminal they are commands (``ESC [ 31 m``, ``ESC ] 0 ;``
#: retitles the window): a table holding one is refused, naming the column and the row.
CONTROL_CHARACTERS = "[\x00-\x08\x0b\x0c\x0e-\x1f\x7f-\x9f]"


def check_control_characters(df: pd.DataFrame | ColumnTable) -> None:
    """Refuse a table whose column names hold a control character (any: tab and line breaks
    included) or whose text cells hold one of :data:`CONTROL_CHARACTERS`: :class:`TableError`
    naming the column and the 1-based data row, the character escaped.

    >>> import pandas as pd
    >>> try:
    ...     check_control_characters(pd.DataFrame({"a": ["x", "y" + chr(27) + "[31m"]}))
    ... except TableError as exc:
    ...     print(str(exc)[:52])
    column 'a', row 2 holds a control character ('\\x1b')

    A :class:`rsm_lrg.table.ColumnTable` (numbers only) has its names checked, without pandas.
    """
    from .table import ColumnTable

    check_column_names(df.columns)
    if isinstance(df, ColumnTable):
        return
    import pandas as pd

    cells = re.compile(CONTROL_CHARACTERS)
    for c in df.columns:
        col = df[c]
        if not (col.dtype == object or pd.api.types.is_string_dtype(col.dtype)):
            continue
        text = col.map(lambda v: v if isinstance(v, str) else "")
        hit = text.str.contains(CONTROL_CHARACTERS, regex=True).to_numpy()
        if hit.any():
            i = int(hit.nonzero()[0][0])
            ch = cells.search(text.iloc[i])
            raise TableError(f"column {_quote(c)}, row {i + 1} holds a control character "
                             f"({ch.group() if ch else ''!r}); remove it (it is never data, and a terminal "
                             "would obey it)")


# --- Excel ----------------------------------------------------------------------------------

def parse_xlsx(raw: bytes, *, sheet: str | None = None, max_rows: int | None = None,
               max_columns: int | None = None, max_bytes: int | None = None,
               max_cells: int | None = None) -> tuple[pd.DataFrame, ReadAs]:
    """Read one sheet of an ``.xlsx`` workbook: its first row the header, one run per row below.

    Parameters
    ----------
    raw : bytes
        The workbook file's content.
    sheet : str, optional
        The sheet's name; needed when the workbook has more than one.
    max_rows, max_columns : int, optional
        Limits: a sheet past them is refused (nothing past them is read).
    max_bytes, max_cells : int, optional
        The most bytes the workbook may unpack to, checked from its zip directory before any
        part is parsed (default :data:`MAX_UNPACKED_BYTES`), and the most cells the sheet may
        hold, counted as it is read (default :data:`MAX_CELLS`).

    Fully empty rows, and columns empty from the header down, are not part of the table (as
    blank lines in a CSV file). A formula cell is read as the value Excel stored with it. A
    cell holding TRUE or FALSE is an error naming it; a column of numbers stored as text is
    read as numbers and said in ``ReadAs.converted``. A damaged workbook (truncated, corrupt
    XML, entity expansion), a chart sheet, or one past a limit is a :class:`TableError`.
    """
    import pandas as pd

    try:
        import openpyxl  # type: ignore[import-untyped]
    except ImportError as exc:  # a declared dependency; the message says what to install
        raise TableError(f"reading an Excel workbook needs openpyxl (pip install openpyxl: {exc})") from None
    _check_unpacked_size(raw, MAX_UNPACKED_BYTES if max_bytes is None else max_bytes)
    try:
        book = openpyxl.load_workbook(io.BytesIO(raw), read_only=True, data_only=True)
    except Exception as exc:  # zipfile.BadZipFile, KeyError, lxml/xml errors: a broken workbook
        raise TableError(f"is not a readable Excel workbook ({type(exc).__name__}: {str(exc)[:80]})") from None
    try:
        names = list(book.sheetnames)
        shown = ", ".join(_quote(n) for n in names[:8]) + (" …" if len(names) > 8 else "")
        if sheet is None:
            if len(names) != 1:
                raise TableError(f"the workbook has {len(names)} sheets ({shown}); choose one with --sheet NAME")
            sheet = names[0]
        elif sheet not in names:
            raise TableError(f"no sheet {_quote(sheet)} in the workbook (sheets: {shown})")
        ws = book[sheet]
        if not hasattr(ws, "iter_rows"):
            raise TableError(f"sheet {_quote(sheet)} is a chart sheet, not a table of runs; choose a worksheet with "
                             "--sheet NAME")
        try:
            rows = _sheet_rows(ws, max_rows, max_columns, sheet, MAX_CELLS if max_cells is None else max_cells)
        except TableError:
            raise
        except Exception as exc:  # the sheet's XML, parsed as it is read: truncated, corrupt, entity expansion
            raise TableError(f"is not a readable Excel workbook (sheet {_quote(sheet)}: {type(exc).__name__}: "
                             f"{str(exc)[:80]})") from None
    finally:
        book.close()
    if not rows:
        raise TableError(f"sheet {_quote(sheet)} is empty")
    header, body = rows[0], rows[1:]
    width = max(len(r) for r in rows)
    header = header + [None] * (width - len(header))
    keep = [j for j in range(width)
            if header[j] is not None and str(header[j]).strip() or any(j < len(r) and r[j] is not None for r in body)]
    for j in keep:
        if header[j] is None or not str(header[j]).strip():
            raise TableError(f"sheet {_quote(sheet)}: the header row has a blank column name (column "
                             f"{_column_letter(j)})")
    names_out = [str(header[j]).strip() for j in keep]
    body = [r for r in body if any(v is not None and not (isinstance(v, str) and not v.strip()) for v in r)]
    data = [[(r[j] if j < len(r) else None) for j in keep] for r in body]
    df = pd.DataFrame(data, columns=names_out)
    _check_formula_values(raw, sheet, df)
    check_columns(names_out, df)
    df = df.infer_objects()
    converted = _numbers_stored_as_text(df)
    if df.shape[1] < 2:
        raise TableError(f"sheet {_quote(sheet)} has a single column {_quote(names_out[0])}; expected one column "
                         "per factor and response")
    return df, ReadAs("xlsx", sheet=sheet, converted=converted)


#: The most bytes a workbook may unpack to (its XML parts, as the zip's directory declares them;
#: Python's zip reader never gives more than declared): past it the workbook is refused before
#: any part is parsed, so a small file that unpacks to gigabytes cannot exhaust memory or time.
MAX_UNPACKED_BYTES = 400 * 1024 * 1024
#: The most cells a sheet may hold (rows times columns read, empty cells in a row included).
MAX_CELLS = 20_000_000


def _check_unpacked_size(raw: bytes, limit: int) -> None:
    import zipfile

    try:
        with zipfile.ZipFile(io.BytesIO(raw)) as z:
            total = sum(max(0, i.file_size) for i in z.infolist())
    except (zipfile.BadZipFile, OSError, ValueError, EOFError) as exc:
        raise TableError(f"is not a readable Excel workbook ({type(exc).__name__}: {str(exc)[:80]})") from None
    if total > limit:
        raise TableError(f"unpacks to {total / 2**20:,.1f} MiB, more than the limit of {limit / 2**20:,.1f} MiB for "
                         "a workbook (the bound on bytes, checked before reading)")


def _numbers_stored_as_text(df: pd.DataFrame) -> tuple[str, ...]:
    """Convert, in place, each column whose every filled cell is a number or a number stored
    as text (a workbook's "number stored as text" cells), with at least one such text, to
    numbers; a column of whole numbers with a leading zero (``01``: codes) stays text, as in a
    CSV file. Returns one phrase per column converted."""
    import pandas as pd

    said = []
    for c in df.columns:
        col = df[c]
        if not (col.dtype == object or pd.api.types.is_string_dtype(col.dtype)):
            continue
        cells = col.tolist()
        texts = [v for v in cells if isinstance(v, str) and v.strip()]
        if not texts or any(re.match(LEADING_ZERO, t) for t in texts):
            continue
        num = pd.to_numeric(col.map(lambda v: v.strip() if isinstance(v, str) else v), errors="coerce")
        filled = [not (v is None or (isinstance(v, str) and not v.strip()) or (isinstance(v, float) and v != v))
                  for v in cells]
        if all(ok is False or pd.notna(x) for ok, x in zip(filled, num.tolist())):
            df[c] = num.astype(float)
            said.append(f"column {_quote(c)} holds {len(texts)} number{'s' if len(texts) > 1 else ''} stored as "
                        "text, read as numbers")
    return tuple(said)


def _column_letter(j: int) -> str:
    out = ""
    j += 1
    while j:
        j, r = divmod(j - 1, 26)
        out = chr(65 + r) + out
    return out


def _sheet_rows(ws: Any, max_rows: int | None, max_columns: int | None, sheet: str = "",
                max_cells: int = 0) -> list[list[Any]]:
    rows: list[list[Any]] = []
    cells = 0
    for i, row in enumerate(ws.iter_rows(values_only=True)):
        values = list(row)
        while values and values[-1] is None:
            values.pop()
        if max_columns is not None and len(values) > max_columns:
            raise TableError(f"row {i + 1} of the sheet has {len(values)} columns, more than the limit of {max_columns}")
        if max_rows is not None and i > max_rows:
            raise TableError(f"the sheet has more than {max_rows} data rows, the limit for a table held in memory")
        cells += len(values)
        if max_cells and cells > max_cells:
            raise TableError(f"the sheet has more than {max_cells:,} cells (by row {i + 1}), the limit for a table "
                             "held in memory (the bound on cells)")
        for j, v in enumerate(values):
            if isinstance(v, bool):  # TRUE is no 1.0, nor a level by accident
                name = rows[0][j] if rows and j < len(rows[0]) else None
                col = f" (column {_quote(name)}, row {i})" if i and name is not None else ""
                raise TableError(f"sheet {_quote(sheet)}, cell {_column_letter(j)}{i + 1}{col}: holds "
                                 f"{str(v).upper()}, a truth value; write a number (or a level as text)")
        rows.append(values)
    while rows and not rows[-1]:
        rows.pop()
    return rows


def _check_formula_values(raw: bytes, sheet: str, df: pd.DataFrame) -> None:
    """A formula saved without its value (a workbook written by a program that does not
    compute) reads as an empty cell: refuse it, naming the cell, rather than leave it out."""
    if not bool(df.isna().to_numpy().any()):
        return
    import openpyxl

    book = openpyxl.load_workbook(io.BytesIO(raw), read_only=True, data_only=False)
    try:
        for row in book[sheet].iter_rows():
            for cell in row:
                value = getattr(cell, "value", None)
                if isinstance(value, str) and value.startswith("="):
                    coord = getattr(cell, "coordinate", "?")
                    raise TableError(f"sheet {_quote(sheet)} cell {coord} holds a formula without a stored value "
                                     "(open and save the workbook in Excel, or paste values)")
    finally:
        book.close()


# --- Parquet --------------------------------------------------------------------------------

def parse_parquet(raw: bytes, *, max_rows: int | None = None, max_columns: int | None = None,
                  max_bytes: int | None = None) -> tuple[pd.DataFrame, ReadAs]:
    """Read a single Parquet file (every row group) into a DataFrame; its index, if any was
    stored, becomes columns. Limits as for :func:`parse_xlsx` (checked from the file's
    metadata before the data are read: ``max_bytes`` bounds the bytes its row groups unpack
    to). A decimal column is read as floating-point numbers and said in ``ReadAs.converted``."""
    limit = MAX_UNPACKED_BYTES if max_bytes is None else max_bytes
    import pandas as pd

    try:
        import pyarrow.parquet as pq  # type: ignore[import-untyped]
    except ImportError as exc:
        raise TableError(f"reading a Parquet file needs pyarrow (pip install pyarrow: {exc})") from None
    try:
        meta = pq.ParquetFile(io.BytesIO(raw)).metadata
        if max_rows is not None and meta.num_rows > max_rows:
            raise TableError(f"has {meta.num_rows} rows, more than the limit of {max_rows} for a table held in "
                             "memory; fit a folder of Parquet files instead (read partition by partition with Dask)")
        if max_columns is not None and meta.num_columns > max_columns:
            raise TableError(f"has {meta.num_columns} columns, more than the limit of {max_columns}")
        unpacked = sum(meta.row_group(i).total_byte_size for i in range(meta.num_row_groups))
        if unpacked > limit:
            raise TableError(f"unpacks to {unpacked / 2**20:,.1f} MiB, more than the limit of "
                             f"{limit / 2**20:,.1f} MiB for a table held in memory (the bound on bytes, "
                             "checked from the file's metadata before reading); fit a folder of Parquet files instead")
        df = pq.read_table(io.BytesIO(raw)).to_pandas()
    except TableError:
        raise
    except Exception as exc:  # pyarrow.ArrowInvalid, OSError: a damaged or truncated file
        raise TableError(f"is not a readable Parquet file ({type(exc).__name__}: {str(exc)[:80]})") from None
    if not isinstance(df.index, pd.RangeIndex):
        df = df.reset_index()
    names = [str(c) for c in df.columns]
    check_columns(names, df)
    df.columns = names
    if df.shape[1] < 2:
        raise TableError(f"has a single column {_quote(names[0])}; expected one column per factor and response")
    return df, ReadAs("parquet", converted=_decimal_columns(df))


def _decimal_columns(df: pd.DataFrame) -> tuple[str, ...]:
    """Convert, in place, each column of exact decimals (a Parquet ``decimal`` column, read as
    Python ``Decimal`` objects) to floating-point numbers, which is what a fit computes with;
    returns one phrase per column converted."""
    import decimal

    import pandas as pd

    said = []
    for c in df.columns:
        col = df[c]
        if col.dtype != object:
            continue
        vals = [v for v in col.tolist() if v is not None]
        if vals and all(isinstance(v, decimal.Decimal) for v in vals):
            df[c] = pd.to_numeric(col.map(lambda v: None if v is None else float(v)), errors="coerce").astype(float)
            said.append(f"column {_quote(c)} holds decimals, read as floating-point numbers")
    return tuple(said)


def xlsx_bytes(frame: pd.DataFrame, sheet: str = "Design") -> bytes:
    """An ``.xlsx`` workbook of one sheet holding ``frame`` (header row frozen; empty cells for
    missing values, numbers at full precision), as bytes to write atomically.

    Read back with :func:`parse_xlsx` it gives the same table.
    """
    import pandas as pd

    buf = io.BytesIO()
    with pd.ExcelWriter(buf, engine="openpyxl") as writer:
        frame.to_excel(writer, sheet_name=sheet, index=False)
        ws = writer.sheets[sheet]
        ws.freeze_panes = "A2"
        for j, name in enumerate(frame.columns):
            ws.column_dimensions[_column_letter(j)].width = max(10, min(40, len(str(name)) + 2))
    return buf.getvalue()


# --- tables too large to hold: piece by piece ---------------------------------------------

#: Bytes read at a time when counting the lines of a CSV file.
_BLOCK = 1 << 22


#: The longest line of a CSV file read piece by piece (:func:`count_rows`), as for a file read
#: whole (:data:`rsm_lrg.io.MAX_LINE_BYTES`) [bytes]: a longer one is refused, naming its row,
#: before any of it is parsed (a 2 GB line was buffered until memory ran out).
MAX_STREAM_LINE_BYTES = 1024 * 1024


def count_rows(fh: Any, fmt: str, *, max_line_bytes: int = MAX_STREAM_LINE_BYTES) -> int:
    """Data rows of an open CSV (lines with text, less the header) or Parquet file (from its
    metadata), read in blocks: memory stays bounded whatever the file's size. The file is
    left at its start. A CSV line longer than ``max_line_bytes`` is a :class:`TableError`
    naming its row (the header, or data row N), found in this pass, before any parsing."""
    import numpy as np

    fh.seek(0)
    if fmt == "parquet":
        import pyarrow.parquet as pq

        try:
            n = int(pq.ParquetFile(fh).metadata.num_rows)
        except Exception as exc:
            raise TableError(f"is not a readable Parquet file ({type(exc).__name__}: {str(exc)[:80]})") from None
        fh.seek(0)
        return n
    lines, last, run = 0, b"\n", 0  # run: bytes of the line under way since its last newline
    while True:
        block = fh.read(_BLOCK)
        if not block:
            break
        nl = np.flatnonzero(np.frombuffer(block, dtype=np.uint8) == 10)
        if nl.size:
            lengths = np.diff(np.concatenate([[-1], nl])) - 1
            lengths[0] += run
            over = np.flatnonzero(lengths > max_line_bytes)
            run = len(block) - int(nl[-1]) - 1
        else:
            over = np.zeros(0, dtype=int)
            run += len(block)
        if over.size or run > max_line_bytes:
            line = lines + (int(over[0]) if over.size else int(nl.size)) + 1
            raise TableError(f"{row_of_line(line)} is longer than the limit of {max_line_bytes} bytes "
                             "(a line that long is no design row)")
        lines += int(nl.size)
        last = block[-1:]
    fh.seek(0)
    return lines + (last != b"\n") - 1


def csv_chunks(fh: Any, *, sep: str | None = None, decimal: str = ".",
               chunk_rows: int = 100_000) -> tuple[ReadAs, Any]:
    """A CSV file read ``chunk_rows`` rows at a time: ``(ReadAs, iterator of DataFrames)``.

    The separator is detected from the file's first lines (:func:`detect_separator`) unless
    given; the header is checked as :func:`parse_csv` checks it, and every piece for the
    other decimal mark. Each piece's index continues the one before (rows numbered from the
    file's first data row). UTF-8 text only (UTF-16 files are read whole, :func:`parse_csv`).
    """
    import pandas as pd

    check_choice(sep, SEPARATORS, "separator")
    check_choice(decimal, DECIMALS, "decimal mark")
    fh.seek(0)
    head = fh.read(1 << 20)
    fh.seek(0)
    if head.startswith((b"\xff\xfe", b"\xfe\xff")) or b"\x00" in head:
        raise TableError("a UTF-16 or binary file cannot be read piece by piece; save it as CSV UTF-8")
    try:
        text = head.decode("utf-8-sig", errors="strict" if len(head) < (1 << 20) else "ignore")
    except UnicodeDecodeError as exc:
        line = head.count(b"\n", 0, exc.start) + 1
        raise TableError(f"is not a UTF-8 CSV text file ({row_of_line(line)}); save it as CSV UTF-8") from None
    if len(head) == (1 << 20):
        text = text[: text.rfind("\n") + 1] or text  # whole lines only
    detected = sep is None
    use = detect_separator(text, decimal) if sep is None else sep
    header = _header(text, use)
    if len(header) < 2:
        raise TableError(f"is not a CSV table (found a single column {_quote(header[0] if header else '')}); "
                         "expected columns separated by one of , ; tab | (or give --sep)")
    check_columns(header, pd.DataFrame(index=[0]))
    import io as _io

    stream = _io.TextIOWrapper(fh, encoding="utf-8-sig", newline="")
    try:
        reader = pd.read_csv(stream, sep=use, decimal=decimal, skipinitialspace=True, chunksize=int(chunk_rows))
    except (pd.errors.ParserError, pd.errors.EmptyDataError, ValueError, UnicodeDecodeError) as exc:
        raise TableError(f"is not a valid CSV file ({str(exc).strip().splitlines()[0][:120]})") from None

    def pieces():
        try:
            for chunk in reader:
                if not chunk.index.equals(pd.RangeIndex(chunk.index[0], chunk.index[0] + len(chunk))):
                    raise TableError(f"a line near data row {int(chunk.index[0]) + 1} has more fields than the "
                                     f"header ({len(header)} columns)")
                chunk.columns = [str(c) for c in chunk.columns]
                if use != ",":
                    _refuse_other_decimal(chunk, decimal)
                yield chunk
        except (pd.errors.ParserError, UnicodeDecodeError) as exc:
            raise TableError(f"is not a valid CSV file ({str(exc).strip().splitlines()[0][:120]})") from None
        finally:
            try:
                stream.detach()  # the caller closes the file
            except ValueError:  # closed already
                pass

    return ReadAs("csv", use, decimal, detected), pieces()


def parquet_chunks(fh: Any, *, chunk_rows: int = 100_000) -> tuple[ReadAs, Any]:
    """A Parquet file read ``chunk_rows`` rows at a time (record batches):
    ``(ReadAs, iterator of DataFrames)``; each piece's index continues the one before."""
    try:
        import pyarrow.parquet as pq
    except ImportError as exc:
        raise TableError(f"reading a Parquet file needs pyarrow (pip install pyarrow: {exc})") from None
    try:
        pf = pq.ParquetFile(fh)
        names = [str(n) for n in pf.schema_arrow.names]
    except Exception as exc:
        raise TableError(f"is not a readable Parquet file ({type(exc).__name__}: {str(exc)[:80]})") from None
    if len(names) < 2:
        raise TableError(f"has a single column {_quote(names[0]) if names else ''}; expected one column per factor")

    def pieces():
        start = 0
        try:
            for batch in pf.iter_batches(batch_size=int(chunk_rows)):
                df = batch.to_pandas()
                df.columns = [str(c) for c in df.columns]
                df.index = range(start, start + len(df))
                start += len(df)
                yield df
        except TableError:
            raise
        except Exception as exc:
            raise TableError(f"is not a readable Parquet file ({type(exc).__name__}: {str(exc)[:80]})") from None

    import pandas as pd

    check_columns(names, pd.DataFrame(index=[0]))  # the names; rows are counted piece by piece
    return ReadAs("parquet"), pieces()


def write_csv_chunks(fh: Any, frames: Any, *, float_format: str = "%.10g") -> int:
    """Write DataFrames one after the other as one CSV file (the header once, from the first)
    to the binary file ``fh``; returns the rows written. The columns of every piece must be
    those of the first."""
    rows, columns = 0, None
    for df in frames:
        if columns is None:
            columns = list(df.columns)
        elif list(df.columns) != columns:
            raise TableError("the pieces of the table have different columns")
        fh.write(df.to_csv(index=False, header=rows == 0, float_format=float_format,
                           lineterminator="\n").encode("utf-8"))
        rows += len(df)
    return rows


def write_csv_columns(fh: Any, names: list[str], columns: dict, *, float_format: str = "%.10g") -> int:
    """Write a table of NumPy columns as CSV to the binary file ``fh`` without pandas: the bytes
    :func:`write_csv_chunks` writes of the same table as a DataFrame (``to_csv`` with
    ``float_format``: whole numbers as they are, floats by ``float_format`` and NaN as an empty
    cell, truth values ``True``/``False``, quoted where the CSV dialect needs it).

    Parameters
    ----------
    fh : binary file
        Where the CSV goes.
    names : list of str
        The header, in column order.
    columns : dict of str to numpy.ndarray
        One 1-D array per name (int, float or bool), all of one length.
    float_format : str
        The ``%`` format of a float cell.

    Returns
    -------
    int
        The rows written.

    Raises
    ------
    TableError
        A column that is not whole numbers, floats or truth values.
    """
    cells: list[list[str]] = []
    for name in names:
        values = columns[name]
        kind = values.dtype.kind
        if kind == "b":
            cells.append(["True" if v else "False" for v in values.tolist()])
        elif kind in "iu":
            cells.append([str(v) for v in values.tolist()])
        elif kind == "f":
            cells.append(["" if v != v else float_format % v for v in values.tolist()])
        else:
            raise TableError(f"column {name!r} holds {values.dtype} values, not numbers")
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(names)
    writer.writerows(zip(*cells))
    fh.write(buf.getvalue().encode("utf-8"))
    return len(cells[0]) if cells else 0


def write_parquet_chunks(fh: Any, frames: Any) -> int:
    """Write DataFrames one after the other as one Parquet file (one row group each, the
    schema of the first) to the binary file ``fh``; returns the rows written."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    writer = None
    rows = 0
    try:
        for df in frames:
            if writer is None:
                table = pa.Table.from_pandas(df, preserve_index=False)
                writer = pq.ParquetWriter(fh, table.schema)
            else:
                table = pa.Table.from_pandas(df, schema=writer.schema, preserve_index=False)
            writer.write_table(table)
            rows += len(df)
    finally:
        if writer is not None:
            writer.close()
    return rows
