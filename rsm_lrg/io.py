"""Reading input tables and writing outputs safely.

Every command reads its data through :func:`read_table` (clear errors that name the file,
the column and the row; the file is only ever opened for reading): CSV in any common dialect,
an Excel workbook, a single Parquet file or standard input (``-``); the formats are parsed by
:mod:`rsm_lrg.readers` from the bytes read here. Outputs are written through
:func:`write_output` (atomic: a temporary file in the same directory, then a rename; an
existing file is kept unless ``force=True``).

Inputs are read in a bounded way (:func:`read_input_bytes`): only regular files (a device
such as ``/dev/zero``, a named pipe or a directory is refused at once, so nothing can hang)
and at most :data:`MAX_TABLE_BYTES`, :data:`MAX_LINE_BYTES` per line, :data:`MAX_COLUMNS`
columns and :data:`MAX_ROWS` rows, far beyond any experiment.

Outputs: :func:`check_output` says why a path cannot be written (empty, a directory, a
device, existing without ``force``, one of the inputs, its directory missing or not
writable); inside :func:`output_transaction` every :func:`write_output` is staged and the
files are renamed into place together when the block ends, or all removed when it raises.
The CLI checks every output before a command runs, then runs it inside one transaction.
User values quoted in messages go through :func:`quote_user_value` (short, one line).
"""

from __future__ import annotations

import contextlib
import contextvars
import errno
import math
import os
import re
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any, BinaryIO

__all__ = ["InputError", "quote_user_value", "show_path", "read_input_bytes", "open_input", "check_output",
           "output_transaction", "output_stream", "register_input", "committing", "read_table", "read_table_as",
           "read_stdin_bytes", "read_toml", "check_nesting", "toml_value", "write_output", "dump_json", "to_jsonable",
           "numeric_column", "float_column", "float_values", "remembered_float_columns", "check_number_kinds",
           "is_empty_cell", "cell_error", "COMMA_NUMBER"]


class InputError(ValueError):
    """Bad input from the user: the CLI prints it as one ``error:`` line and exits 2."""


def quote_user_value(value: Any, limit: int = 40) -> str:
    """``repr``-like quoted text of a user's value for an error message, cut to about ``limit``
    characters with ``…`` so that a 10 MB cell or a 300-digit number cannot flood the message.

    Strings are quoted as by ``repr``; other values are shown as ``repr(value)``.

    >>> quote_user_value("abc")
    "'abc'"
    >>> quote_user_value("x" * 100, limit=10)
    "'xxxxxxxxx…'"
    >>> quote_user_value(1.5)
    '1.5'
    >>> len(quote_user_value("9" * 300)) <= 42
    True
    """
    limit = max(int(limit), 1)
    if isinstance(value, str):
        shown = repr(value[: limit + 1])  # escapes newlines and control characters
        if len(value) <= limit and len(shown) <= limit + 2:
            return shown
        quote, body = shown[0], shown[1:-1]
        return quote + body[: limit - 1] + "\u2026" + quote
    if type(value).__module__ == "numpy" and hasattr(value, "item"):
        value = value.item()  # a numpy scalar reads as the number, not np.float64(inf)
    try:
        text = repr(value)
    except Exception:  # any object must be quotable (str of a 5000-digit int raises)
        text = f"<{type(value).__name__} too long to show>"
    return text if len(text) <= limit else text[: limit - 1] + "\u2026"


#: Limits on input files, far beyond any experiment: a file past them is refused at once
#: (rather than hanging or exhausting memory) with a message naming the file and the limit.
MAX_TABLE_BYTES = 200 * 1024 * 1024
MAX_TEXT_BYTES = 10 * 1024 * 1024  # TOML parameter and calibration files
MAX_LINE_BYTES = 1024 * 1024
MAX_COLUMNS = 1000
MAX_ROWS = 1_000_000  # a million runs; fitting that many takes about 10 s and 1 GB


def _mib(n: int) -> str:
    return f"{n / (1024 * 1024):g} MiB"


def read_input_bytes(path: str | os.PathLike, what: str = "file", *, limit: int = MAX_TABLE_BYTES) -> bytes:
    """The bytes of an input file, read in a bounded way, or :class:`InputError` naming it.

    Refuses what is not a regular file (a directory, a device such as ``/dev/zero``, a named
    pipe or a socket: reading those could hang or never end) and files larger than ``limit``
    bytes; reads at most ``limit + 1`` bytes, so a file growing meanwhile cannot exhaust memory.
    The file is only ever opened for reading.
    """
    import stat

    p = Path(path)
    if not str(path).strip():
        raise InputError(f"an empty path was given for the {what}")
    register_input(p)
    try:
        st = os.stat(p)
    except FileNotFoundError:
        raise InputError(f"{_show(p)}: no such {what}") from None
    except OSError as exc:
        raise InputError(f"{_show(p)}: cannot be read ({exc.strerror or type(exc).__name__})") from None
    except ValueError:  # an embedded NUL character
        raise InputError(f"{_show(p)}: not a valid file name (it contains a NUL character)") from None
    if stat.S_ISDIR(st.st_mode):
        raise InputError(f"{_show(p)}: is a directory, not a{'n' if what[0] in 'aeiou' else ''} {what}")
    if not stat.S_ISREG(st.st_mode):
        raise InputError(f"{_show(p)}: is not a regular file (it is a device, pipe or socket)")
    if st.st_size > limit:
        raise InputError(f"{_show(p)}: is {_mib(st.st_size)}, larger than the limit of {_mib(limit)} for a {what}")
    try:
        fd = os.open(p, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0))
        with os.fdopen(fd, "rb") as fh:
            if not stat.S_ISREG(os.fstat(fh.fileno()).st_mode):  # replaced since the check
                raise InputError(f"{_show(p)}: is not a regular file, not a {what}")
            raw = fh.read(limit + 1)
    except OSError as exc:
        raise InputError(f"{_show(p)}: cannot be read ({exc.strerror or type(exc).__name__})") from None
    if len(raw) > limit:
        raise InputError(f"{_show(p)}: is larger than the limit of {_mib(limit)} for a {what}")
    return raw


def open_input(path: str | os.PathLike, what: str = "file"):
    """An input file opened for reading in binary, for a reader that goes through it piece by
    piece (:mod:`rsm_lrg.surrogate.stream`: no size limit, memory bounded by the piece): the
    checks of :func:`read_input_bytes` but the size (a directory, device, pipe or socket is
    refused at once, so nothing hangs), or :class:`InputError` naming it."""
    import stat

    p = Path(path)
    if not str(path).strip():
        raise InputError(f"an empty path was given for the {what}")
    register_input(p)
    try:
        fd = os.open(p, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0))
    except FileNotFoundError:
        raise InputError(f"{_show(p)}: no such {what}") from None
    except IsADirectoryError:
        raise InputError(f"{_show(p)}: is a directory, not a{'n' if what[0] in 'aeiou' else ''} {what}") from None
    except OSError as exc:
        raise InputError(f"{_show(p)}: cannot be read ({exc.strerror or type(exc).__name__})") from None
    except ValueError:
        raise InputError(f"{_show(p)}: not a valid file name (it contains a NUL character)") from None
    mode = os.fstat(fd).st_mode
    if not stat.S_ISREG(mode):
        os.close(fd)
        if stat.S_ISDIR(mode):
            raise InputError(f"{_show(p)}: is a directory, not a{'n' if what[0] in 'aeiou' else ''} {what}")
        raise InputError(f"{_show(p)}: is not a regular file (it is a device, pipe or socket)")
    return os.fdopen(fd, "rb")


def _check_table_shape(p: Path, raw: bytes) -> None:
    """Refuse, before parsing, a table with a line over :data:`MAX_LINE_BYTES`, more than
    :data:`MAX_COLUMNS` columns (split by any of the separators read) or more than
    :data:`MAX_ROWS` rows."""
    import csv

    import numpy as np

    from .readers import SEPARATORS

    nl = np.flatnonzero(np.frombuffer(raw, dtype=np.uint8) == 10)
    ends = np.concatenate([[-1], nl, [len(raw)]])
    lengths = np.diff(ends) - 1
    if lengths.size and int(lengths.max()) > MAX_LINE_BYTES:
        line = int(np.argmax(lengths > MAX_LINE_BYTES)) + 1
        raise InputError(f"{_show(p)}: line {line} is longer than the limit of {_mib(MAX_LINE_BYTES)}")
    rows = int(np.count_nonzero(lengths > 0)) - 1
    if rows > MAX_ROWS:
        raise InputError(f"{_show(p)}: has {rows} data rows, more than the limit of {MAX_ROWS} {_HELD}")
    first = raw[: int(nl[0]) if nl.size else len(raw)].decode("utf-8-sig", errors="replace")
    ncol = 0
    for sep in SEPARATORS:
        try:
            ncol = max(ncol, len(next(csv.reader([first], delimiter=sep), [])))
        except csv.Error:
            ncol = max(ncol, first.count(sep) + 1)
    if ncol > MAX_COLUMNS:
        raise InputError(f"{_show(p)}: the header has {ncol} columns, more than the limit of {MAX_COLUMNS}")


def show_path(p: str | os.PathLike, limit: int = 120) -> str:
    """A path for a message, shortened in the middle when very long."""
    text = str(p).replace("\n", "\\n").replace("\r", "\\r").replace("\0", "\\0")
    if len(text) <= limit:
        return text
    half = (limit - 1) // 2
    return text[:half] + "\u2026" + text[-half:]


_show = show_path


#: Said of the limits on a table held in memory: how to go further.
_HELD = ("for a table held in memory; for more, fit a folder of Parquet or CSV files (read partition by "
         "partition with Dask)")

#: The name standard input goes by in messages.
STDIN_NAME = "<stdin>"


def read_stdin_bytes(limit: int = MAX_TABLE_BYTES) -> bytes:
    """Standard input's bytes (at most ``limit``), or :class:`InputError`: when it is a
    terminal (nothing piped in: reading would wait for typing) or larger than ``limit``."""
    stream = getattr(sys.stdin, "buffer", None)
    if stream is None or sys.stdin.closed:
        raise InputError("- names standard input, but there is none to read")
    try:
        terminal = sys.stdin.isatty()
    except (ValueError, AttributeError):  # closed, or not a file
        terminal = False
    if terminal:
        raise InputError("- names standard input, but nothing is piped in (cat runs.csv | rsm-lrg ... -)")
    try:
        raw = stream.read(limit + 1)
    except OSError as exc:  # opened write-only (0>file), a descriptor that cannot be read
        raise InputError(f"{STDIN_NAME}: cannot be read ({exc.strerror or type(exc).__name__})") from None
    if len(raw) > limit:
        raise InputError(f"{STDIN_NAME}: is larger than the limit of {_mib(limit)} {_HELD}")
    return raw


def read_table(path, *, sep: str | None = None, decimal: str = ".", sheet: str | None = None):
    """Read a table into a DataFrame, or raise :class:`InputError` naming the problem.

    Parameters
    ----------
    path : str, os.PathLike or pandas.DataFrame
        A CSV file, an Excel workbook (``.xlsx``), a single Parquet file, or ``"-"`` for
        standard input (any of the three formats); a DataFrame is returned as it is. The
        format is told by the file's first bytes (:func:`rsm_lrg.readers.detect_format`).
    sep : str, optional
        The CSV separator: ``","``, ``";"``, ``"\\t"`` or ``"|"``; detected when None.
    decimal : str
        The CSV decimal mark, ``"."`` (default) or ``","``.
    sheet : str, optional
        The workbook sheet; needed when the workbook has several.

    Returns
    -------
    pandas.DataFrame
        The table, one column per header cell, numbers as numbers.

    Notes
    -----
    Checks: the file exists and is a file, is not empty, has a header row and at least one
    data row, no duplicated or blank column names, and is within the limits
    (:data:`MAX_TABLE_BYTES`, :data:`MAX_ROWS`, :data:`MAX_COLUMNS`). What was read (format,
    separator, decimal mark, sheet) is returned by :func:`read_table_as`.
    """
    return read_table_as(path, sep=sep, decimal=decimal, sheet=sheet)[0]


def read_table_as(path, *, sep: str | None = None, decimal: str = ".", sheet: str | None = None,
                  column_table: bool = False):
    """:func:`read_table` that also returns what it read: ``(DataFrame, ReadAs)`` (a
    :class:`rsm_lrg.readers.ReadAs`; ``None`` for a DataFrame given).

    With ``column_table=True`` a plain CSV file of numbers (:func:`rsm_lrg.readers.parse_plain_csv`,
    standard input too) is read without pandas, into a :class:`rsm_lrg.table.ColumnTable` of the
    same columns, dtypes and values, after the same checks (and limits); any other input is read
    as without it, into a DataFrame, with the same errors."""
    from . import readers

    pd = sys.modules.get("pandas")  # a DataFrame given means pandas is imported; else none is imported here
    if pd is not None and isinstance(path, pd.DataFrame):
        return path, None
    stdin = str(path) == "-"
    p = Path(STDIN_NAME if stdin else path)
    name = STDIN_NAME if stdin else _show(p)
    try:
        readers.check_choice(sep, readers.SEPARATORS, "--sep")
        readers.check_choice(decimal, readers.DECIMALS, "--decimal")
    except readers.TableError as exc:
        raise InputError(str(exc)) from None
    raw = read_stdin_bytes(MAX_TABLE_BYTES) if stdin else read_input_bytes(p, "file", limit=MAX_TABLE_BYTES)
    if not raw.strip():
        raise InputError(f"{name}: the file is empty" if not stdin else f"{name}: nothing was read (empty input)")
    try:
        kind = readers.detect_format(raw, "" if stdin else p.suffix)
        if kind != "xlsx" and sheet is not None:
            raise readers.TableError(f"--sheet {quote_user_value(sheet)} is for an Excel workbook; this is {kind.upper()}")
        if kind != "csv" and (sep is not None or decimal != "."):
            raise readers.TableError(f"--sep and --decimal are for CSV text; this is {kind.upper()}")
        if kind == "xlsx":
            df, how = readers.parse_xlsx(raw, sheet=sheet, max_rows=MAX_ROWS, max_columns=MAX_COLUMNS)
        elif kind == "parquet":
            df, how = readers.parse_parquet(raw, max_rows=MAX_ROWS, max_columns=MAX_COLUMNS)
        elif raw.startswith((b"\xff\xfe", b"\xfe\xff")):  # UTF-16: the limits are checked on its text too
            try:
                _check_table_shape(p, raw.decode("utf-16").encode("utf-8"))
            except UnicodeDecodeError:
                pass  # parse_csv says it is not valid UTF-16
            df, how = readers.parse_csv(raw, sep=sep, decimal=decimal)
            if len(df) > MAX_ROWS or df.shape[1] > MAX_COLUMNS:
                raise readers.TableError(f"has {len(df)} rows and {df.shape[1]} columns, more than the limits of "
                                         f"{MAX_ROWS} and {MAX_COLUMNS}")
        else:
            _check_table_shape(p, raw)
            plain = readers.parse_plain_csv(raw, sep=sep, decimal=decimal) if column_table else None
            if plain is not None:
                readers.check_control_characters(plain[0])  # the names: numbers hold no control character
                return plain
            df, how = readers.parse_csv(raw, sep=sep, decimal=decimal)
        readers.check_control_characters(df)  # names and levels are printed: never a terminal command
        return df, how
    except readers.TableError as exc:
        raise InputError(f"{name}: {exc}") from None


#: Limits on a TOML input (and any JSON one: :func:`check_nesting`), far beyond any parameter or calibration file: nesting
#: depth (tables and arrays), and the size of a whole number (64-bit).
MAX_NESTING = 32
MAX_INTEGER = 2**63 - 1

_FLOAT_WORDS = ("inf", "+inf", "-inf", "nan", "+nan", "-nan")


def _finite_float_literal(text: str) -> float:
    """``parse_float`` for TOML and JSON: a float literal that overflows (``1e400``) is an
    error, not inf (the words ``inf`` and ``nan`` stay what they say)."""
    v = float(text)
    if not math.isfinite(v) and text.strip().lower() not in _FLOAT_WORDS:
        raise ValueError(f"the number {text[:20]} is beyond the range of a float")
    return v


def check_nesting(obj: Any, p: Path, *, depth: int = MAX_NESTING) -> None:
    """Refuse a parsed TOML or JSON value nested deeper than ``depth`` (tables, dotted keys,
    arrays) or holding a whole number beyond 64 bits, naming the file and the key."""
    stack: list[tuple[Any, int, str]] = [(obj, 0, "")]
    while stack:
        v, d, key = stack.pop()
        where = f" (at {quote_user_value(key, 60)})" if key else ""
        if isinstance(v, (dict, list)):
            if d >= depth:
                raise InputError(f"{_show(p)}: nested more than {depth} levels deep{where}")
            items = v.items() if isinstance(v, dict) else enumerate(v)
            for k, x in items:
                stack.append((x, d + 1, f"{key}.{k}" if key and isinstance(v, dict) else f"{key}[{k}]"
                              if key else str(k)))
        elif isinstance(v, int) and not isinstance(v, bool) and abs(v) > MAX_INTEGER:
            raise InputError(f"{_show(p)}: a whole number{where} is larger than a 64-bit integer "
                             f"({len(str(abs(v)))} digits)")


def read_toml(path: str | os.PathLike, what: str = "file") -> dict:
    """Parse a TOML file, or raise :class:`InputError` naming it (missing, a directory, or not
    valid TOML with the parser's line and column). ``what`` names the kind of file in the
    "no such ..." message (``"calibration file"``). Bounded: at most :data:`MAX_NESTING`
    levels deep, whole numbers within 64 bits and floats finite (``1e400`` is refused; the
    words ``inf`` and ``nan`` are kept), each refused with the file named."""
    import tomllib

    p = Path(path)
    raw = read_input_bytes(p, what, limit=MAX_TEXT_BYTES)
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        raise InputError(f"{_show(p)}: not valid TOML (not UTF-8 text)") from None
    try:
        out = tomllib.loads(text, parse_float=_finite_float_literal)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{_show(p)}: not valid TOML ({str(exc)[:150]})") from None
    except RecursionError:
        raise InputError(f"{_show(p)}: nested too deeply to read (at most {MAX_NESTING} levels)") from None
    except ValueError as exc:  # a whole number of more than 4300 digits, a float beyond range
        msg = str(exc)
        if "digits" in msg or "integer string conversion" in msg:
            msg = "a whole number has thousands of digits, far more than a 64-bit integer"
        raise InputError(f"{_show(p)}: cannot be read ({msg[:150]})") from None
    check_nesting(out, p)
    return out


def toml_value(x: Any) -> str:
    """One value as TOML source: booleans, integers, floats (``repr``, round-trips exactly;
    ``None`` and non-finite numbers as ``nan``), strings (quoted, escaped) and lists of them.

    >>> print(toml_value([1, 0.5, True, 'a "b"', None]))
    [1, 0.5, true, "a \\"b\\"", nan]
    """
    import numbers

    if isinstance(x, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in x) + "]"
    if x is None:
        return "nan"
    if isinstance(x, bool) or type(x).__name__ in ("bool", "bool_"):
        return "true" if x else "false"
    if isinstance(x, numbers.Integral):
        return str(int(x))
    if isinstance(x, numbers.Real):
        return repr(float(x)) if math.isfinite(x) else "nan"
    out = []
    for ch in str(x):
        if ch in '"\\':
            out.append("\\" + ch)
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04x}")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


#: A number written with a comma (``1,234`` or ``0,5``): ambiguous, refused with a hint.
COMMA_NUMBER = re.compile(r"^\s*[+-]?(\d{1,3}(,\d{3})+(\.\d*)?|\d*,\d+)\s*$")


def is_empty_cell(raw) -> bool:
    """An empty cell: None, NaN, blank text, pandas' NA or NaT.

    Parameters
    ----------
    raw : object
        The cell.

    Returns
    -------
    bool
        Whether it is empty.
    """
    return raw is None or (isinstance(raw, float) and math.isnan(raw)) or str(raw).strip() == "" \
        or type(raw).__name__ in ("NAType", "NaTType")


def cell_error(name: str, row: int, raw) -> ValueError:
    """The error for one bad cell (row is 1-based): empty, a comma number, or not a number.

    Parameters
    ----------
    name : str
        The column.
    row : int
        The row, 1-based.
    raw : object
        The cell as read.

    Returns
    -------
    ValueError
        The error (to raise).
    """
    where = f"column {quote_user_value(name)}, row {row}"
    if is_empty_cell(raw):
        return ValueError(f"{where}: is empty")
    if isinstance(raw, str) and COMMA_NUMBER.match(raw):
        return ValueError(f"{where}: holds {quote_user_value(raw.strip())}, a number with a comma (a thousands "
                          "separator or a decimal comma is ambiguous); write it with a decimal point and no commas")
    return ValueError(f"{where}: holds {quote_user_value(raw)}, not a finite number")


def check_number_kinds(col, name: str) -> None:
    """Refuse a column that holds truth values or complex numbers where numbers are read:
    ``True`` is no 1.0 (a spreadsheet's TRUE cell, an object column holding ``True``) and a
    complex number has no place on a factor's axis (its imaginary part would be dropped). A
    ValueError naming the column and the first such row (1-based).

    >>> import pandas as pd
    >>> check_number_kinds(pd.Series([0.5, True], dtype=object), "y")
    Traceback (most recent call last):
    ...
    ValueError: column 'y', row 2: holds True, a truth value, not a number
    """
    import numpy as np
    import pandas as pd

    where = f"column {quote_user_value(name)}"
    if pd.api.types.is_bool_dtype(col.dtype):
        raise ValueError(f"{where}, row 1: holds {bool(col.iloc[0])!r}, a truth value, not a number" if len(col)
                         else f"{where}: holds truth values, not numbers")
    if pd.api.types.is_complex_dtype(col.dtype):
        raise ValueError(f"{where}: holds complex numbers; a factor or a response is a real number")
    if col.dtype != object:
        return
    for i, v in enumerate(col.tolist()):
        if isinstance(v, (bool, np.bool_)):
            raise ValueError(f"{where}, row {i + 1}: holds {bool(v)!r}, a truth value, not a number")
        if isinstance(v, (complex, np.complexfloating)):
            raise ValueError(f"{where}, row {i + 1}: holds the complex number {quote_user_value(v)}; a factor or a "
                             "response is a real number")


#: ``{(id(frame), name): (frame, column)}`` while :func:`remembered_float_columns` is active.
_FLOAT_COLUMNS: contextvars.ContextVar[dict | None] = contextvars.ContextVar("float_columns", default=None)


@contextlib.contextmanager
def remembered_float_columns() -> Iterator[None]:
    """Inside the block, :func:`float_column` converts and checks each column of a frame once
    (the checks of one fit read the same factor columns four times; the frames are not changed
    in between). Nested blocks share the outer one's memory.

    Yields
    ------
    None
        Inside the block.
    """
    if _FLOAT_COLUMNS.get() is not None:
        yield
        return
    token = _FLOAT_COLUMNS.set({})
    try:
        yield
    finally:
        _FLOAT_COLUMNS.reset(token)


def float_column(data, name: str):
    """The column ``name`` as floats, or a ValueError naming the first bad row (1-based):
    an empty cell, text, a truth value or a complex number (:func:`check_number_kinds`).

    Parameters
    ----------
    data : pandas.DataFrame
        The table.
    name : str
        The column.

    Returns
    -------
    numpy.ndarray
        The column as floats.
    """
    memo = _FLOAT_COLUMNS.get()
    if memo is not None:
        seen = memo.get((id(data), name))
        if seen is not None and seen[0] is data:  # the frame itself is kept, so its id is not reused
            return seen[1]
        out = _float_column(data, name)
        memo[(id(data), name)] = (data, out)
        return out
    return _float_column(data, name)


def float_values(data, name: str):
    """The column ``name`` as a float64 array, checked as :func:`float_column` checks it, of a
    DataFrame or of a :class:`rsm_lrg.table.ColumnTable` (whose columns are numbers already:
    only their finiteness is checked, and no pandas is imported).

    Parameters
    ----------
    data : pandas.DataFrame or rsm_lrg.table.ColumnTable
        The table.
    name : str
        The column.

    Returns
    -------
    numpy.ndarray
        1-D float64.
    """
    import numpy as np

    from .table import is_column_table

    if is_column_table(data):
        arr = np.asarray(data[name], dtype=float)
        finite = np.isfinite(arr)
        if not finite.all():
            i = int(np.flatnonzero(~finite)[0])
            raise cell_error(name, i + 1, arr[i])
        return arr
    return float_column(data, name).to_numpy(dtype=float)


def _float_column(data, name: str):
    import numpy as np
    import pandas as pd

    col = data[name]
    if isinstance(col, pd.DataFrame):  # a name given to several columns
        raise ValueError(f"column {quote_user_value(name)} appears {col.shape[1]} times in the data; rename all but one")
    if col.dtype.kind in "fiu":  # numbers already (the usual CSV column): no conversion, one finiteness check
        arr = col.to_numpy(dtype=float, na_value=np.nan)
        finite = np.isfinite(arr)
        if finite.all():
            # floats already: the column itself under pandas 3, which copies on write (the caller
            # cannot change ``data`` through it, and the copy would cost more than the check)
            return col if col.dtype == np.float64 and int(pd.__version__.split(".")[0]) >= 3 else col.astype(float)
        i = int(np.flatnonzero(~finite)[0])
        raise cell_error(name, i + 1, col.iloc[i])
    check_number_kinds(col, name)
    num = pd.to_numeric(col, errors="coerce")
    bad = num.isna() | ~np.isfinite(num.to_numpy(dtype=float, na_value=np.nan))
    if bad.any():
        i = int(np.flatnonzero(bad.to_numpy())[0])
        raise cell_error(name, i + 1, col.iloc[i])
    return num.astype(float)


def numeric_column(df, name: str, where: str = ""):
    """Column ``name`` of ``df`` as float, or InputError naming the first bad row (1-based)."""
    if name not in df.columns:
        raise InputError(f"{where}column {name!r} not found (columns: {', '.join(map(str, df.columns))})")
    try:
        return float_column(df, name)
    except ValueError as exc:
        raise InputError(f"{where}{exc}") from None


_TRANSACTION: contextvars.ContextVar[_Transaction | None] = contextvars.ContextVar("rsm_lrg_outputs", default=None)


class _Transaction:
    """Outputs staged by :func:`write_output` inside :func:`output_transaction`."""

    def __init__(self, inputs, labels=None):
        self.inputs = [Path(x) for x in inputs]
        self.labels = {os.path.abspath(k): v for k, v in (labels or {}).items()}
        self.staged: list[tuple[str, Path, bool]] = []  # (temporary file, target, force)
        self.streams: list[tuple[int, bytes, Path]] = []  # (descriptor, data, path named): written last
        self.temporaries: list[str] = []  # every temporary file named, from before it is created

    def label(self, path) -> str | None:
        """The option that named ``path`` (``--json``), when known."""
        return self.labels.get(os.path.abspath(path))

    def discard(self) -> None:
        """Remove every temporary file (while :func:`committing` is true: a signal handler
        then only records its signal, so no file is left half-way through)."""
        before = _STATE[0]
        _STATE[0] = "cleaning"
        try:
            for tmp in [*(t for t, *_ in self.staged), *self.temporaries]:
                _unlink(tmp)
            self.staged = []
            self.streams = []
            self.temporaries = []
        finally:
            _STATE[0] = "idle" if before == "committed" else before

    def commit(self) -> None:
        """Rename every staged file into place, then write the streams (``/dev/stdout``); if
        one step fails, every file already placed is put back as it was (the file it replaced
        restored from its backup, a new file removed) and the error is raised. While it runs,
        :func:`committing` is true (a signal handler then lets it finish, or asks with
        :func:`abort_commit` that it be undone: :class:`CommitAborted` is then raised after the
        roll-back); once it has succeeded :func:`committed` is true (the command is done)."""
        _STATE[0] = "committing"
        try:
            self._commit()
        finally:
            if _STATE[0] != "committed":
                _STATE[0] = "idle"

    def _commit(self) -> None:
        done: list[tuple[Path, str | None]] = []  # (target, backup of the file it replaced)
        try:
            for tmp, target, force in self.staged:
                _still_replaceable(target, self.label(target))
                backup, moved = _keep_backup(target) if force and os.path.lexists(target) else (None, False)
                try:
                    _place(tmp, target, force, self.label(target))
                except BaseException:
                    if backup and moved:  # the file was moved aside: put it back
                        _restore(backup, target)
                    elif backup:  # a link or a copy: the file itself never left
                        _drop_backup(backup)
                    raise
                done.append((target, backup))
            for fd, data, path in self.streams:
                _write_stream(fd, data, path, self.label(path))
            # the point of no return, free of races with a signal handler (it runs between two
            # statements of this thread): a handler that ran before the state became
            # "committed" asked for the abort, which is seen on the next line; one that runs
            # after it sees "committed" and leaves the outputs be
            _STATE[0] = "committed"
            if _ABORT[0]:
                _STATE[0] = "committing"
                raise CommitAborted()
        except BaseException as exc:
            lost = []
            for target, backup in reversed(done):
                if backup:
                    if not _restore(backup, target):
                        lost.append(f"{_show(target)} (kept as {_show(backup)})")
                else:
                    _unlink(target)
            self.discard()
            if lost and isinstance(exc, Exception):
                raise InputError(f"{exc}; could not put back {', '.join(lost)}") from None
            raise
        for _, backup in done:
            if backup:
                _drop_backup(backup)
        self.staged = []
        self.streams = []


_BACKUP_PREFIX = ".rsm-lrg-backup."
#: Where the outputs stand: "idle", "committing" (being placed or put back), "cleaning"
#: (temporary files being removed) or "committed" (all placed: the command has done its work).
_STATE = ["idle"]
_ABORT = [False]


class CommitAborted(BaseException):
    """A signal asked (:func:`abort_commit`) that the outputs being placed be taken back: they
    were, and the command ends as if the signal had come before (no output written). A
    BaseException, as the signal's own exception is."""


def committing() -> bool:
    """True while an :func:`output_transaction` places its files, puts them back or removes its
    temporary files: a signal handler should let that finish rather than interrupt it
    half-way (and may ask with :func:`abort_commit` that the placed outputs be taken back)."""
    return _STATE[0] in ("committing", "cleaning")


def committed() -> bool:
    """True once the outputs of the running command are all in place: a signal that comes
    later finds the command's work done (it can no longer be taken back)."""
    return _STATE[0] == "committed"


def abort_commit() -> None:
    """Ask the commit under way (:func:`committing`) to put back every output it placed and
    raise :class:`CommitAborted`, so that a command stopped by a signal leaves no output."""
    _ABORT[0] = True


def reset_commit_state() -> None:
    """A new command begins: no commit under way, done or asked to abort."""
    _STATE[0] = "idle"
    _ABORT[0] = False


def _still_replaceable(target: Path, label: str | None) -> None:
    """At the commit, what now stands at ``target`` may be replaced: nothing, a regular file
    or a symbolic link; a directory, device, pipe or socket that appeared since the checks
    (a concurrent writer) is never replaced."""
    import stat

    try:
        mode = os.lstat(target).st_mode
    except OSError:
        return
    if not (stat.S_ISREG(mode) or stat.S_ISLNK(mode)):
        what = f"{label} " if label else ""
        raise InputError(f"cannot write {what}{_show(target)}: it is no longer a regular file (a directory, "
                         f"device, pipe or socket appeared there); it is never replaced")


def _keep_backup(target: Path) -> tuple[str, bool]:
    """Keep the file at ``target`` before it is replaced, so that a failed commit can put it
    back: a hard link beside it (the file stays in place); where a hard link is refused
    (``protected_hardlinks``, a file system without them), the file renamed into a private
    directory beside it (same file system: the very file, owner and mode kept); where that
    is refused too, a copy. Returns the backup's path and whether the file was moved there
    (it must then be put back if the new file cannot be placed), or raises
    :class:`InputError` (nothing replaced) when no backup can be made."""
    import shutil
    import tempfile

    parent = target.parent if str(target.parent) else Path(".")
    try:
        d = tempfile.mkdtemp(prefix=_BACKUP_PREFIX, dir=parent)
    except OSError as exc:
        raise InputError(f"cannot write {_show(target)}: no backup of the file it replaces can be kept "
                         f"({exc.strerror or type(exc).__name__})") from None
    backup = os.path.join(d, "file")
    try:
        os.link(target, backup, follow_symlinks=False)
        return backup, False
    except OSError:
        pass
    try:
        os.rename(target, backup)
        return backup, True
    except OSError:
        pass
    try:
        if os.path.islink(target):
            os.symlink(os.readlink(target), backup)
        else:
            shutil.copy2(target, backup, follow_symlinks=False)
        return backup, False
    except OSError as exc:
        _drop_backup(backup)
        raise InputError(f"cannot write {_show(target)}: no backup of the file it replaces can be kept "
                         f"({exc.strerror or type(exc).__name__})") from None


def _restore(backup: str, target: Path) -> bool:
    """Put ``backup`` (from :func:`_keep_backup`) back at ``target``; True when done."""
    try:
        os.replace(backup, target)
    except OSError:
        return False
    _drop_backup(backup)
    return True


def _drop_backup(backup: str) -> None:
    _unlink(backup)
    try:
        os.rmdir(os.path.dirname(backup))
    except OSError:
        pass


def _write_stream(fd: int, data: bytes, path: Path, label: str | None) -> None:
    """Write ``data`` through the open descriptor ``fd`` (``/dev/stdout``, ``/dev/fd/3``): a
    reader that has gone (a closed pipe) is an ordinary condition, as for printed text."""
    if fd == 1:
        try:
            sys.stdout.flush()
        except (OSError, ValueError):
            pass
    view = memoryview(data)
    try:
        while view:
            n = os.write(fd, view)
            view = view[n:]
    except BrokenPipeError:
        return
    except OSError as exc:
        what = f"{label} " if label else ""
        raise InputError(f"cannot write {what}{_show(path)}: {exc.strerror or type(exc).__name__}") from None


def _place(tmp: str, target: Path, force: bool, label: str | None = None) -> None:
    """Rename ``tmp`` to ``target``. Without ``force`` a file that appeared at ``target`` since
    the checks is never replaced: the new file is linked in only where nothing exists yet.
    ``label`` names the option in messages."""
    what = f"{label} " if label else ""
    try:
        if force:
            owner = _owner_of(target)
            os.replace(tmp, target)
            _give_back(target, owner)
            return
        try:
            os.link(tmp, target)
        except FileExistsError:
            raise InputError(f"cannot write {what}{_show(target)}: it already exists; use --force to overwrite it") from None
        except OSError:  # a file system without hard links
            if os.path.lexists(target):
                raise InputError(f"cannot write {what}{_show(target)}: it already exists; use --force to overwrite it") from None
            os.replace(tmp, target)
        else:
            _unlink(tmp)
    except OSError as exc:
        raise InputError(f"cannot write {what}{_show(target)}: {exc.strerror or type(exc).__name__}") from None


def _unlink(path) -> None:
    try:
        os.unlink(path)
    except OSError:
        pass


@contextlib.contextmanager
def output_transaction(inputs=(), labels=None):
    """All-or-nothing outputs: inside the block :func:`write_output` writes each file to a
    temporary file next to its target; when the block ends normally every one is renamed into
    place, and when it raises every temporary file is removed, so a failed command leaves
    nothing behind. No output may be one of ``inputs`` (the same file, also through a symbolic
    or hard link), ``--force`` or not. ``labels`` maps output paths to the options that named
    them, for error messages.
    """
    tx = _Transaction(inputs, labels)
    token = _TRANSACTION.set(tx)
    reset_commit_state()
    try:
        yield tx
        tx.commit()  # inside: an interrupt before the commit begins still removes the temporary files
    except BaseException:
        tx.discard()
        raise
    finally:
        _TRANSACTION.reset(token)


def register_input(path: str | os.PathLike) -> None:
    """Count ``path`` as an input of the running command (inside :func:`output_transaction`):
    no output may name it, ``--force`` or not. :func:`read_input_bytes` registers every file
    it reads; a reader that opens files another way (each file a glob or a directory
    matches) registers them with this."""
    tx = _TRANSACTION.get()
    if tx is not None:
        tx.inputs.append(Path(path))


def _same_file(a: Path, b: Path) -> bool:
    try:
        if os.path.samefile(a, b):
            return True
    except OSError:
        pass
    try:
        return a.resolve() == b.resolve()
    except (OSError, RuntimeError):
        return False


def output_stream(path: str | os.PathLike) -> int | None:
    """The open file descriptor that ``path`` names, or None: ``/dev/stdout`` (1),
    ``/dev/stderr`` (2), ``/dev/fd/N``, ``/proc/self/fd/N`` and any symbolic link leading to
    one of them. Such an output is written through the descriptor (whatever it is open on: a
    terminal, a pipe, the file the shell redirected to), never replaced by a file.

    >>> output_stream("/dev/stdout")
    1
    >>> output_stream("out.json") is None
    True
    """
    import re

    p = os.path.abspath(os.fspath(path))
    mine = re.compile(rf"/proc/(self|thread-self|{os.getpid()}|{os.getpid()}/task/\d+)/fd")
    for _ in range(40):  # the kernel's own limit on a chain of symbolic links
        head, name = os.path.split(p)
        try:
            head = os.path.realpath(head)
        except (OSError, ValueError):
            return None
        if name.isdigit() and mine.fullmatch(head):
            return int(name)
        try:
            if not os.path.islink(p):
                return None
            p = os.path.normpath(os.path.join(head, os.readlink(p)))
        except (OSError, ValueError):
            return None
    return None


def _shipped_file(p: Path) -> str | None:
    """``data/NAME`` when ``p`` is (also through a link) one of the data files shipped in the
    package (``rsm_lrg/data``: the parameter defaults, the calibration, the paper's tables),
    which commands read without naming them; else None."""
    here = Path(__file__).resolve().parent / "data"
    try:
        names = os.listdir(here)
    except OSError:
        return None
    if not os.path.lexists(p):
        return None
    for name in names:
        if _same_file(p, here / name) and (here / name).is_file():
            return f"data/{name}"
    return None


def _kind_of(mode: int) -> str:
    """What a file mode says a file is, for a message: ``"a regular file"``, ``"a directory"`` ..."""
    import stat

    for test, word in ((stat.S_ISREG, "a regular file"), (stat.S_ISDIR, "a directory"), (stat.S_ISFIFO, "a pipe"),
                       (stat.S_ISSOCK, "a socket"), (stat.S_ISCHR, "a device"), (stat.S_ISBLK, "a block device")):
        if test(mode):
            return word
    return "a special file"


def _stream_name(fd: int) -> str:
    return {0: "standard input", 1: "standard output", 2: "standard error"}.get(fd, f"descriptor {fd}")


def check_output(path: str | os.PathLike, *, force: bool = False, inputs=(), option: str | None = None,
                 probe: bool = False) -> Path:
    """Check that ``path`` can be written as an output, or raise :class:`InputError`.

    ``cannot write OPTION PATH: REASON`` where the reason is one of: the path is empty; it is
    a directory or not a regular file (a device, a named pipe, a socket, or a symbolic link
    to one: never replaced, ``--force`` or not); it already exists (without ``force``); it is
    one of ``inputs`` or of the files the command has read (same file, through links too,
    whatever ``force``); its directory does not exist, is not a directory or is not writable.
    A path naming an open descriptor (``/dev/stdout``, :func:`output_stream`) passes when the
    descriptor is open and is standard output (written as ``-`` is) or a terminal, a device or
    a pipe (written through). A symbolic link at ``path`` (to a regular file, or dangling) is
    an existing file: with ``force`` the link itself is replaced, atomically; the file it
    leads to is never written.
    Nothing is left behind: with ``probe`` a temporary file is created in the directory and
    removed, to be sure it can be written.
    """
    import stat

    what = f"{option} " if option else ""
    if not str(path).strip():
        raise InputError(f"cannot write {what}'': an empty path was given" + (f" to {option}" if option else ""))
    p = Path(path)
    head = f"cannot write {what}{_show(p)}"
    if "\0" in str(path):
        raise InputError(f"{head}: not a valid file name (it contains a NUL character)")
    if str(path).endswith(("/", os.sep)):
        raise InputError(f"cannot write {what}{_show(path)}: the path ends with '/', so it names a directory; "
                         f"give a file name")
    tx = _TRANSACTION.get()
    for inp in list(inputs) + (tx.inputs if tx is not None else []):
        if _same_file(p, Path(inp)):
            shown = "read from standard input" if str(inp) == "/dev/stdin" else _show(inp)
            raise InputError(f"{head}: it is the input file {shown}; an input is never overwritten")
    shipped = _shipped_file(p)
    if shipped is not None:
        raise InputError(f"{head}: it is the file {shipped} shipped with rsm-lrg, which its commands read (defaults, "
                         f"the calibration, the paper's tables); it is never overwritten: write elsewhere")
    fd = output_stream(p)
    if fd is not None:
        try:
            mode = os.fstat(fd).st_mode
        except OSError:
            raise InputError(f"{head}: it names {_stream_name(fd)}, which is closed") from None
        if fd != 1 and not (stat.S_ISCHR(mode) or stat.S_ISFIFO(mode)):
            raise InputError(f"{head}: it names {_stream_name(fd)}, which is open on {_kind_of(mode)}; only a "
                             f"terminal, a device or a pipe is written through (give the file's own name)")
        return p
    try:
        st = os.stat(p)
    except (FileNotFoundError, NotADirectoryError):
        st = None
        if os.path.islink(p) and not force:  # a dangling symbolic link is replaced, not followed
            raise InputError(f"{head}: it already exists (a symbolic link); use --force to overwrite it") from None
    except OSError as exc:
        raise InputError(f"{head}: {exc.strerror or type(exc).__name__}") from None
    if st is not None:
        link = " (through a symbolic link)" if os.path.islink(p) else ""
        if stat.S_ISDIR(st.st_mode):
            raise InputError(f"{head}: it is a directory{link}")
        if not stat.S_ISREG(st.st_mode):
            kind = ("a named pipe" if stat.S_ISFIFO(st.st_mode) else "a socket" if stat.S_ISSOCK(st.st_mode)
                    else "a device")
            raise InputError(f"{head}: it is not a regular file but {kind}{link}; it is never replaced")
        if not force:
            raise InputError(f"{head}: it already exists; use --force to overwrite it")
    parent = p.parent if str(p.parent) else Path(".")
    if not parent.exists():
        raise InputError(f"{head}: the directory {_show(parent)} does not exist")
    if not parent.is_dir():
        raise InputError(f"{head}: {_show(parent)} is not a directory")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise InputError(f"{head}: the directory {_show(parent)} is not writable")
    if probe:  # the only sure test (read-only file systems, /proc, root's permissions)
        try:
            _probe_directory(parent)
        except OSError as exc:
            raise InputError(f"{head}: the directory {_show(parent)} is not writable "
                             f"({exc.strerror or type(exc).__name__})") from None
    return p


def write_output(path: str | os.PathLike, data: str | bytes | Callable[[BinaryIO], None], *,
                 force: bool = False) -> Path:
    """Write ``data`` to ``path`` atomically; refuse to replace a file unless ``force``.

    ``data`` is text, bytes, or a function that writes the bytes to the binary file it is
    given (a large output written piece by piece, never held whole).

    The text goes to a temporary file in the target directory, is flushed and synced,
    then renamed over the target, so a reader never sees half a file. Every check of
    :func:`check_output` applies. Inside :func:`output_transaction` the rename waits for the
    end of the block (all outputs of a command appear together, or none). A path naming an
    open descriptor (``/dev/stdout``) is written through it, after the files.
    """
    tx = _TRANSACTION.get()
    label = tx.label(path) if tx is not None else None
    p = check_output(path, force=force, option=label)
    fd = output_stream(p)
    if fd is not None:
        if callable(data):
            import io as _io

            buf = _io.BytesIO()
            data(buf)
            raw = buf.getvalue()
        else:
            raw = data if isinstance(data, bytes) else data.encode("utf-8")
        if tx is not None:
            tx.streams.append((fd, raw, p))
        else:
            _write_stream(fd, raw, p, None)
        return p
    target = p  # the named path itself: a symbolic link there is replaced, never written through
    parent = target.parent if str(target.parent) else Path(".")
    tmp = None
    try:
        tfd, tmp = _temporary_file(parent, target.name, tx)
        with os.fdopen(tfd, "wb") as fh:
            if callable(data):
                data(fh)
            else:  # text as written (UTF-8, no newline translation)
                fh.write(data.encode("utf-8") if isinstance(data, str) else data)
            fh.flush()
            os.fsync(fh.fileno())
        _take_mode(tmp, target)
        if tx is not None:
            tx.staged.append((tmp, target, force))
        else:
            _place(tmp, target, force)
    except OSError as exc:
        if tmp is not None:
            _unlink(tmp)
        what = f"{label} " if label else ""
        raise InputError(f"cannot write {what}{_show(p)}: {exc.strerror or type(exc).__name__}") from None
    except BaseException:
        if tmp is not None:
            _unlink(tmp)
        raise
    return p


def _probe_directory(parent: Path) -> None:
    """Create and remove a file in ``parent`` (raises OSError where that fails); its path is
    known before it is created, so an interrupt at any moment still removes it."""
    import secrets

    path: str | None = os.path.join(parent, f".rsm-lrg-probe.{secrets.token_hex(6)}.tmp")
    try:
        os.close(os.open(str(path), os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0), 0o600))
    except FileExistsError:
        path = None  # another's file: never removed
        raise
    finally:
        if path is not None:
            _unlink(path)


def _temporary_file(parent: Path, name: str, tx: _Transaction | None) -> tuple[int, str]:
    """``(descriptor, path)`` of a new temporary file beside the output ``name`` in ``parent``,
    created exclusively (mode 0600). Inside a transaction its path is recorded *before* the
    file is created, so that an interrupt at any moment leaves no temporary file behind (the
    transaction removes every path it recorded)."""
    import secrets

    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0) | getattr(os, "O_NOFOLLOW", 0)
    for _ in range(100):
        path = os.path.join(parent, f".{name[:60]}.{secrets.token_hex(6)}.tmp")
        if tx is not None:
            tx.temporaries.append(path)
        try:
            return os.open(path, flags, 0o600), path
        except FileExistsError:
            if tx is not None:
                tx.temporaries.remove(path)  # another's file: never removed
    raise FileExistsError(errno.EEXIST, "no unused temporary file name", str(parent))


def _umask() -> int:
    """The process's file-mode creation mask (read from /proc where it can be, so that it is
    never changed, even for an instant)."""
    try:
        with open("/proc/self/status", encoding="ascii", errors="replace") as fh:
            for line in fh:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def _take_mode(tmp: str, target: Path) -> None:
    """Give the new file ``tmp`` the permissions it replaces: those of the file at ``target``
    when there is one (``--force`` never makes a private ``0600`` file world-readable; its
    owner is given back by :func:`_place`), else ``0666`` less the umask, as any new file."""
    import stat

    try:
        st = os.lstat(target)  # a symbolic link replaced gives nothing of the file it led to
    except OSError:
        st = None
    if st is not None and stat.S_ISREG(st.st_mode):
        os.chmod(tmp, stat.S_IMODE(st.st_mode) & 0o777)
        return
    os.chmod(tmp, 0o666 & ~_umask())


def _owner_of(target: Path) -> tuple[int, int] | None:
    """``(uid, gid)`` of the regular file at ``target`` when it is not this process's own."""
    import stat

    try:
        st = os.lstat(target)
    except OSError:
        return None
    if not stat.S_ISREG(st.st_mode) or not hasattr(os, "getuid") or (st.st_uid, st.st_gid) == (os.getuid(),
                                                                                                  os.getgid()):
        return None
    return st.st_uid, st.st_gid


def _give_back(target: Path, owner: tuple[int, int] | None) -> None:
    """Once the new file is in place, give it the owner of the file it replaced where this
    process may (root replacing a user's file leaves it theirs); done after the rename, so
    that a temporary file is always this process's to remove."""
    if owner is not None:
        try:
            os.chown(target, *owner)
        except OSError:
            pass


def to_jsonable(obj: Any) -> Any:
    """Plain Python for ``json``: NumPy scalars to floats, NaN/inf to ``None``."""
    import numpy as np

    if isinstance(obj, dict):
        return {str(k): to_jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [to_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return [to_jsonable(v) for v in obj.tolist()]
    if isinstance(obj, (np.bool_, bool)):
        return bool(obj)
    if isinstance(obj, (np.integer,)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        x = float(obj)
        return x if math.isfinite(x) else None
    return obj


def dump_json(obj: Any, dest: str | os.PathLike, *, force: bool = False) -> None:
    """Write ``obj`` as JSON to ``dest``; ``"-"`` means standard output."""
    import json

    text = json.dumps(to_jsonable(obj), indent=2, allow_nan=False) + "\n"
    if str(dest) == "-":
        sys.stdout.write(text)
        sys.stdout.flush()
    else:
        write_output(dest, text, force=force)
