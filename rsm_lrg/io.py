"""Reading input tables and writing outputs safely.

Every command reads its data through :func:`read_table` (clear errors that name the file,
the column and the row; the file is only ever opened for reading) and writes through
:func:`write_output` (atomic: a temporary file in the same directory, then ``os.replace``;
an existing file is kept unless ``force=True``).
"""

from __future__ import annotations

import json
import math
import os
import sys
import tempfile
from pathlib import Path
from typing import Any

__all__ = ["InputError", "quote_user_value", "read_table", "read_toml", "toml_value", "write_output", "dump_json", "to_jsonable",
           "numeric_column"]


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
        if len(value) <= limit:
            return repr(value)
        shown = repr(value[: limit - 1])  # escapes newlines and control characters
        quote, body = shown[-1], shown[:-1][: limit]
        return body + "\u2026" + quote
    try:
        text = repr(value)
    except Exception:  # any object must be quotable (str of a 5000-digit int raises)
        text = f"<{type(value).__name__} too long to show>"
    return text if len(text) <= limit else text[: limit - 1] + "\u2026"


def read_table(path: str | os.PathLike):
    """Read a CSV file into a DataFrame, or raise :class:`InputError` naming the problem.

    Checks: the file exists and is a file, is not empty, parses as CSV with a header
    row and at least one data row, and has no duplicated or blank column names.
    """
    import pandas as pd

    p = Path(path)
    if not p.exists():
        raise InputError(f"{p}: no such file")
    if p.is_dir():
        raise InputError(f"{p}: is a directory, not a CSV file")
    try:
        raw = p.read_bytes()
    except OSError as exc:
        raise InputError(f"{p}: cannot be read ({exc.strerror or exc})") from None
    if not raw.strip():
        raise InputError(f"{p}: the file is empty")
    if b"\x00" in raw[:4096]:
        raise InputError(f"{p}: is not a CSV text file")
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise InputError(f"{p}: is not a UTF-8 CSV text file") from None
    import io as _io

    try:
        df = pd.read_csv(_io.StringIO(text), skipinitialspace=True)
    except (pd.errors.ParserError, pd.errors.EmptyDataError, ValueError) as exc:
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise InputError(f"{p}: is not a valid CSV file ({first})") from None
    cols = [str(c) for c in df.columns]
    if any(c.startswith("Unnamed:") or not c.strip() for c in cols):
        raise InputError(f"{p}: the header row has a blank column name")
    seen = set()
    for c in cols:
        if c.rsplit(".", 1)[0] in seen and c.rsplit(".", 1)[-1].isdigit():
            raise InputError(f"{p}: column {c.rsplit('.', 1)[0]!r} appears more than once")
        seen.add(c)
    if df.shape[0] == 0:
        raise InputError(f"{p}: has a header but no data rows")
    if df.shape[1] < 2:
        raise InputError(f"{p}: is not a CSV table (found a single column {cols[0]!r}); expected comma-separated columns")
    df.columns = cols
    return df


def read_toml(path: str | os.PathLike, what: str = "file") -> dict:
    """Parse a TOML file, or raise :class:`InputError` naming it (missing, a directory, or not
    valid TOML with the parser's line and column). ``what`` names the kind of file in the
    "no such ..." message (``"calibration file"``)."""
    import tomllib

    p = Path(path)
    if not p.exists():
        raise InputError(f"{p}: no such {what}")
    if p.is_dir():
        raise InputError(f"{p}: is a directory, not a TOML file")
    try:
        with open(p, "rb") as fh:
            return tomllib.load(fh)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{p}: not valid TOML ({exc})") from None
    except UnicodeDecodeError:
        raise InputError(f"{p}: not valid TOML (not UTF-8 text)") from None


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


def numeric_column(df, name: str, where: str = ""):
    """Column ``name`` of ``df`` as float, or InputError naming the first bad row (1-based)."""
    from .factors import _numeric

    if name not in df.columns:
        raise InputError(f"{where}column {name!r} not found (columns: {', '.join(map(str, df.columns))})")
    try:
        return _numeric(df, name)
    except ValueError as exc:
        raise InputError(f"{where}{exc}") from None


def write_output(path: str | os.PathLike, data: str | bytes, *, force: bool = False) -> Path:
    """Write ``data`` to ``path`` atomically; refuse to replace a file unless ``force``.

    The text goes to a temporary file in the target directory, is flushed and synced,
    then renamed over the target, so a reader never sees half a file.
    """
    p = Path(path)
    if p.exists() and not force:
        raise InputError(f"{p}: already exists; use --force to overwrite it")
    if p.exists() and p.is_dir():
        raise InputError(f"{p}: is a directory")
    parent = p.parent if str(p.parent) else Path(".")
    if not parent.exists():
        raise InputError(f"{p}: the directory {parent} does not exist")
    mode = "wb" if isinstance(data, bytes) else "w"
    fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", suffix=".tmp", dir=parent)
    try:
        with os.fdopen(fd, mode, **({} if mode == "wb" else {"encoding": "utf-8", "newline": ""})) as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.chmod(tmp, 0o644)
        os.replace(tmp, p)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise
    return p


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
    text = json.dumps(to_jsonable(obj), indent=2, allow_nan=False) + "\n"
    if str(dest) == "-":
        sys.stdout.write(text)
        sys.stdout.flush()
    else:
        write_output(dest, text, force=force)
