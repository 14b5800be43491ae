"""Several input files read as one table: ``rsm-lrg fit DIR`` or ``rsm-lrg fit 'parts/*.csv'``.

The DATA argument names several files when it is a directory (its files) or, only when no
file of that name exists, a glob pattern (``run[1].csv`` that exists is read as that one file,
brackets and all). The files then keep the one-file contract (:func:`rsm_lrg.io.read_table`)
file by file:

- lock, hidden and backup files (``~$a.csv``, ``.~lock.a.csv#``, ``.a.csv``, ``a.csv~``) and
  files of another kind are skipped with a note naming them;
- every file is a regular, readable file within the size limit of one table
  (:data:`rsm_lrg.io.MAX_TABLE_BYTES`, per file), else exit 2 naming it;
- every file has the columns of the first one (a CSV header, a Parquet schema: the same
  names, and for Parquet numbers where the first has numbers), else an error naming the file
  and the columns that differ;
- each file is read, when the fit reaches it, by the one-file reader, so that an error in a
  cell names the file, the row and the column.

Every file read is registered as an input (:func:`rsm_lrg.io.register_input`): no output may
name it.
"""

from __future__ import annotations

import glob
import os
from typing import Any

__all__ = ["expand_data_path", "read_file_set", "skipped_reason", "locate_empty_cell", "TABLE_SUFFIXES"]

#: The most data [bytes] one Parquet file may hold once decompressed (its row groups'
#: uncompressed size, and at least 8 bytes a cell): a small file that unpacks to gigabytes
#: is refused before it is read.
MAX_PARQUET_UNPACKED = 1024 * 1024 * 1024

#: File kinds read from a directory or a pattern, by suffix.
TABLE_SUFFIXES = {".csv": "csv", ".parquet": "parquet", ".pq": "parquet"}


def expand_data_path(path: str) -> list[str] | None:
    """The files ``path`` names when it names several, sorted, or None when it names one file
    (or nothing: the one-file reader then says so).

    A directory gives its files (not those of its sub-directories); a path that does not
    exist and holds a glob character (``*``, ``?``, ``[``) gives the files it matches; a path
    that exists is one file, glob characters and all. A directory that cannot be listed (its
    permissions) is :class:`rsm_lrg.io.InputError` naming it, not "no files".
    """
    try:
        directory = os.path.isdir(path)
    except (OSError, ValueError):
        return None
    if directory:
        _listable(path)
    try:
        if directory:
            return sorted(glob.glob(os.path.join(glob.escape(path), "*"))
                          + glob.glob(os.path.join(glob.escape(path), ".*")))
        if os.path.lexists(path) or not any(c in path for c in "*?["):
            return None
        found = sorted(glob.glob(path))
    except (OSError, ValueError):
        return None
    if not found:  # a pattern in a directory that cannot be listed matches nothing: say why
        head = os.path.dirname(path)
        if head and not any(c in head for c in "*?[") and os.path.isdir(head):
            _listable(head)
    return found


def _listable(directory: str) -> None:
    """A directory whose entries can be listed, or InputError naming it (glob says nothing)."""
    from ..io import InputError, show_path

    try:
        os.listdir(directory)
    except OSError as exc:
        raise InputError(f"{show_path(directory)}: the directory cannot be read "
                         f"({exc.strerror or type(exc).__name__})") from None


def skipped_reason(name: str) -> str | None:
    """Why a file of a directory or pattern is not read: ``"lock"`` (``~$a.csv``, an Office lock
    file; ``.~lock.a.csv#``, LibreOffice's), ``"hidden"`` (``.a.csv``), ``"backup"``
    (``a.csv~``, ``#a.csv#``), ``"kind"`` (not CSV or Parquet), ``"directory"`` (a
    sub-directory: not searched); None when it is read.

    >>> [skipped_reason(n) for n in ("a.csv", "~$a.csv", ".a.csv", "a.csv~", "a.txt", "b.PQ")]
    [None, 'lock', 'hidden', 'backup', 'kind', None]
    """
    base = os.path.basename(name)
    if os.path.isdir(name):
        return "directory"
    if base.startswith("~$") or base.startswith(".~lock."):
        return "lock"
    if base.startswith("."):
        return "hidden"
    if base.endswith("~") or (base.startswith("#") and base.endswith("#")):
        return "backup"
    if os.path.splitext(base)[1].lower() not in TABLE_SUFFIXES:
        return "kind"
    return None


def _names(paths: list[str], limit: int = 5) -> str:
    from ..io import show_path

    shown = [show_path(os.path.basename(p), 60) for p in paths[:limit]]
    return ", ".join(shown) + (f" and {len(paths) - limit} more" if len(paths) > limit else "")


def _check_file(f: str) -> None:
    """A regular, readable file within the size limit, or InputError naming it."""
    import stat

    from ..io import MAX_TABLE_BYTES, InputError, show_path

    try:
        st = os.stat(f)
    except OSError as exc:
        raise InputError(f"{show_path(f)}: cannot be read ({exc.strerror or type(exc).__name__})") from None
    if not stat.S_ISREG(st.st_mode):
        raise InputError(f"{show_path(f)}: is not a regular file (a device, pipe or socket)")
    if st.st_size > MAX_TABLE_BYTES:
        raise InputError(f"{show_path(f)}: is {st.st_size / 2**20:g} MiB, larger than the limit of "
                         f"{MAX_TABLE_BYTES / 2**20:g} MiB for one file")
    if st.st_size == 0:
        raise InputError(f"{show_path(f)}: the file is empty")
    try:
        fd = os.open(f, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0))
        os.close(fd)
    except OSError as exc:
        raise InputError(f"{show_path(f)}: cannot be read ({exc.strerror or type(exc).__name__})") from None


def _csv_columns(f: str, sep: str | None, decimal: str):
    """The column names of a CSV file as the one-file reader reads them (the same separator
    detection, ``--sep`` and ``--decimal``, names kept as written) and its
    :class:`rsm_lrg.readers.ReadAs`, from the file's first lines only (those the separator
    is detected from), read in a bounded way; the whole file (bounded by
    :func:`rsm_lrg.io.read_table_as`) where those lines alone cannot be parsed."""
    from .. import readers
    from ..io import MAX_LINE_BYTES, InputError, read_table_as, show_path

    lines: list[bytes] = []
    try:
        with open(f, "rb") as fh:
            for _ in range(readers.SNIFF_LINES + 1):
                line = fh.readline(MAX_LINE_BYTES + 1)
                if not line:
                    break
                if len(line) > MAX_LINE_BYTES:
                    raise InputError(f"{show_path(f)}: line {len(lines) + 1} is longer than the limit of "
                                     f"{MAX_LINE_BYTES / 2**20:g} MiB")
                lines.append(line)
            whole = not fh.read(1)
    except OSError as exc:
        raise InputError(f"{show_path(f)}: cannot be read ({exc.strerror or type(exc).__name__})") from None
    head = b"".join(lines)
    if not whole and not head.startswith((b"\xff\xfe", b"\xfe\xff")):
        try:
            df, how = readers.parse_csv(head, sep=sep, decimal=decimal)
            return [str(c) for c in df.columns], how
        except readers.TableError:
            pass  # a quoted cell across the cut, ...: the whole file says what is wrong, or reads
    df, how = read_table_as(f, sep=sep, decimal=decimal)
    return [str(c) for c in df.columns], how


def _parquet_schema(f: str) -> dict[str, str]:
    """``{column: "number" | "text" | "other"}`` from a Parquet file's schema, after checking its
    metadata against the limits of one table (rows, columns, decompressed size)."""
    from ..io import MAX_COLUMNS, MAX_ROWS, InputError, show_path

    try:
        import pyarrow as pa  # type: ignore[import-untyped]
        import pyarrow.parquet as pq  # type: ignore[import-untyped]
    except ImportError as exc:
        raise InputError(f"{show_path(f)}: reading Parquet files needs pyarrow ({exc})") from None
    try:
        meta = pq.read_metadata(f)
        schema = pq.read_schema(f)
    except Exception as exc:  # pyarrow raises its own ArrowInvalid, OSError, ...
        first = (str(exc).strip().splitlines() or [type(exc).__name__])[0][:120]
        raise InputError(f"{show_path(f)}: is not a readable Parquet file ({first})") from None
    # the limits of one table apply to what the file decompresses to, not only to its size
    if meta.num_rows > MAX_ROWS:
        raise InputError(f"{show_path(f)}: has {meta.num_rows} rows, more than the limit of {MAX_ROWS}")
    if meta.num_columns > MAX_COLUMNS:
        raise InputError(f"{show_path(f)}: has {meta.num_columns} columns, more than the limit of {MAX_COLUMNS}")
    # in memory at least 8 bytes a cell (a float column; text takes more: its encoded size)
    unpacked = max(sum(meta.row_group(i).total_byte_size for i in range(meta.num_row_groups)),
                   8 * meta.num_rows * meta.num_columns)
    if unpacked > MAX_PARQUET_UNPACKED:
        raise InputError(f"{show_path(f)}: holds {unpacked / 2**20:g} MiB of data once decompressed, more than "
                         f"the limit of {MAX_PARQUET_UNPACKED / 2**20:g} MiB for one file")
    out = {}
    for field in schema:
        t = field.type
        kind = ("number" if pa.types.is_integer(t) or pa.types.is_floating(t) or pa.types.is_decimal(t)
                else "text" if pa.types.is_string(t) or pa.types.is_large_string(t) or pa.types.is_dictionary(t)
                else "other")
        out[str(field.name)] = kind
    return out


def _compare_columns(f: str, cols: list[str], first: str, ref: list[str]) -> None:
    from ..io import InputError, quote_user_value, show_path

    if cols == ref:
        return
    missing = [c for c in ref if c not in cols]
    extra = [c for c in cols if c not in ref]
    if not missing and not extra:
        return  # the same columns in another order: read by name
    parts = []
    if missing:
        parts.append("missing " + ", ".join(quote_user_value(c, 30) for c in missing[:5]))
    if extra:
        parts.append("extra " + ", ".join(quote_user_value(c, 30) for c in extra[:5]))
    raise InputError(f"{show_path(f)}: its columns differ from those of {show_path(os.path.basename(first), 60)} "
                     f"({'; '.join(parts)}); every file must hold the same columns")


def _read_csv_part(f: str, columns: list[str], sep: str | None = None, decimal: str = "."):
    """One CSV file by the one-file reader (with ``--sep`` and ``--decimal``), its columns in
    the first file's order, whole numbers as floats (a file of whole numbers next to one of
    decimals reads alike)."""
    import numpy as np

    from ..io import InputError, read_table, show_path

    df = read_table(f, sep=sep, decimal=decimal)
    if sorted(map(str, df.columns)) != sorted(columns):  # changed since its header was checked
        raise InputError(f"{show_path(f)}: its columns changed while it was read")
    df = df[columns]
    for c in columns:
        if df[c].dtype.kind in "iub":
            df[c] = df[c].astype(np.float64)
    return df


def _read_parquet_part(f: str, columns: list[str]):
    """One Parquet file read in a bounded way (:func:`rsm_lrg.io.read_input_bytes`)."""
    import io as _io

    import numpy as np
    import pandas as pd

    from .. import readers
    from ..io import InputError, read_input_bytes, show_path

    raw = read_input_bytes(f, "Parquet file")
    try:
        df = pd.read_parquet(_io.BytesIO(raw))
    except Exception as exc:  # pyarrow's own errors
        first = (str(exc).strip().splitlines() or [type(exc).__name__])[0][:120]
        raise InputError(f"{show_path(f)}: is not a readable Parquet file ({first})") from None
    df.columns = [str(c) for c in df.columns]
    try:
        readers.check_control_characters(df)
    except readers.TableError as exc:
        raise InputError(f"{show_path(f)}: {exc}") from None
    if sorted(df.columns) != sorted(columns):
        raise InputError(f"{show_path(f)}: its columns changed while it was read")
    df = df[columns].reset_index(drop=True)
    for c in columns:
        if df[c].dtype.kind in "iub":
            df[c] = df[c].astype(np.float64)
    return df


def _conform(df, meta, f: str):
    """A partition with the first file's column types: a text cell where the first file has
    numbers is an error naming the file, the row and the column."""
    import pandas as pd

    from ..io import InputError, quote_user_value, show_path
    from ..readers import LEADING_ZERO

    for c in meta.columns:
        want, have = meta[c].dtype, df[c].dtype
        if want == have:
            continue
        if want.kind == "f":
            text = df[c].astype(str).str.strip()
            coded = text.str.match(LEADING_ZERO)
            if coded.any():  # 01 here, plain numbers in the first file: 01 and 1 would merge
                i = int(coded.to_numpy().nonzero()[0][0])
                raise InputError(f"{show_path(f)}: column {quote_user_value(c)}, row {i + 1}: "
                                 f"{quote_user_value(df[c].iloc[i])} is a code written with a leading zero, but "
                                 "the first file writes this column as plain numbers; write the codes alike in "
                                 "every file (01 and 1 are different levels)")
            num = pd.to_numeric(df[c], errors="coerce")
            bad = num.isna() & df[c].notna() & (df[c].astype(str).str.strip() != "")
            if bad.any():
                i = int(bad.to_numpy().nonzero()[0][0])
                raise InputError(f"{show_path(f)}: column {quote_user_value(c)}, row {i + 1}: "
                                 f"{quote_user_value(df[c].iloc[i])} is not a number (it holds numbers in "
                                 f"the first file)")
            df[c] = num.astype(want)
        else:
            df[c] = df[c].astype(want)
    return df


def _read_part(f: str, kind: str, names: list[str], like, sep: str | None = None, decimal: str = "."):
    """One file as a partition, conformed to ``like`` (the first file's empty frame) when given."""
    df = _read_csv_part(f, names, sep, decimal) if kind == "csv" else _read_parquet_part(f, names)
    return df if like is None else _conform(df, like, f)


def read_file_set(path: str, files: list[str], *, sep: str | None = None, decimal: str = ".",
                  sheet: str | None = None) -> tuple[Any, list[str]]:
    """The files of a directory or pattern (:func:`expand_data_path`) as one Dask DataFrame,
    one partition per file, and the notes on the files skipped and on how the CSV files were
    read (a separator other than a comma, as the one-file reader says).

    ``sep`` and ``decimal`` (``--sep``, ``--decimal``) apply to every CSV file as to one file;
    they and ``sheet`` (``--sheet``) are refused where they cannot apply, never ignored.

    Raises :class:`rsm_lrg.io.InputError` naming the file at fault: none left to read, CSV and
    Parquet files mixed, a file that is not a regular readable file or is larger than the
    limit, or one whose columns differ from the first file's.
    """
    from ..io import InputError, register_input, show_path

    skipped: dict[str, list[str]] = {}
    keep = []
    for f in files:
        why = skipped_reason(f)
        if why is None:
            keep.append(f)
        else:
            skipped.setdefault(why, []).append(f)
    notes = []
    words = {"lock": "lock file(s)", "hidden": "hidden file(s)", "backup": "backup file(s)",
             "kind": "file(s) that are not CSV or Parquet", "directory": "sub-directory(ies) (not searched)"}
    for why, fs in skipped.items():
        notes.append(f"{show_path(path)}: {len(fs)} {words[why]} skipped: {_names(fs)}.")
    what = "directory" if os.path.isdir(path) else "pattern"
    if not keep:
        raise InputError(f"{show_path(path)}: a {what} with no CSV or Parquet files to read")
    kinds = {TABLE_SUFFIXES[os.path.splitext(f)[1].lower()] for f in keep}
    if len(kinds) > 1:
        raise InputError(f"{show_path(path)}: holds both CSV and Parquet files; give a pattern that picks one kind")
    kind = kinds.pop()
    if sheet is not None:
        raise InputError(f"--sheet is for an Excel workbook; {show_path(path)} names {kind.upper()} files")
    if kind != "csv" and (sep is not None or decimal != "."):
        raise InputError(f"--sep and --decimal are for CSV text; {show_path(path)} names {kind.upper()} files")
    for f in keep:
        register_input(f)
        _check_file(f)
    first = keep[0]
    if kind == "csv":
        ref, how = _csv_columns(first, sep, decimal)
        read_as = {} if how is None or how.plain else {how.describe(): [first]}
        for f in keep[1:]:
            cols, how = _csv_columns(f, sep, decimal)
            _compare_columns(f, cols, first, ref)
            if how is not None and not how.plain:
                read_as.setdefault(how.describe(), []).append(f)
        for said, fs in read_as.items():
            notes.append(f"read {show_path(path)}: {len(fs)} file(s) as {said}: {_names(fs)}.")
    else:
        schema = _parquet_schema(first)
        ref = list(schema)
        for f in keep[1:]:
            other = _parquet_schema(f)
            _compare_columns(f, list(other), first, ref)
            for c, k in schema.items():
                if other[c] != k:
                    raise InputError(f"{show_path(f)}: column {c!r} holds {other[c]} values, but "
                                     f"{k} values in {show_path(os.path.basename(first), 60)}; every file "
                                     f"must hold the same kind of values per column")
    try:
        import dask.dataframe as dd
    except ImportError as exc:
        raise InputError(f"{show_path(path)}: fitting several files needs Dask, which a plain install does not "
                         f"include: pip install 'rsm-lrg[parallel]' ({exc})") from None
    meta = _read_part(first, kind, ref, None, sep, decimal)
    if kind == "csv" and len(set(map(str, meta.columns))) != len(meta.columns):
        raise InputError(f"{show_path(first)}: a column appears more than once in the header")
    columns = [str(c) for c in meta.columns]
    empty = meta.iloc[:0]
    ddf = dd.from_map(_read_part, keep, kind=kind, names=columns, like=empty, sep=sep, decimal=decimal, meta=empty,
                      enforce_metadata=False)
    return ddf, notes


def locate_empty_cell(files: list[str], columns: list[str], *, sep: str | None = None,
                      decimal: str = ".") -> tuple[str, str] | None:
    """The first empty cell of ``columns`` in ``files`` (read one at a time) as ``(file,
    "column 'x', row N is empty")``, or None: to name the file behind a fit's "a cell is empty"."""
    from ..io import quote_user_value, read_table, show_path

    for f in files:
        if skipped_reason(f) is not None:
            continue
        try:
            df = read_table(f, sep=sep, decimal=decimal)
        except ValueError:
            continue
        for c in columns:
            if c in df.columns:
                col = df[c]
                empty = col.isna() | (col.astype(str).str.strip() == "")
                if empty.any():
                    i = int(empty.to_numpy().nonzero()[0][0])
                    return show_path(f), f"column {quote_user_value(c)}, row {i + 1} is empty"
    return None
