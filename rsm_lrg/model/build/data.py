"""Data preparation for a fit: the factors, the response, the runs left out, the notes.

:func:`prepare` is the first step of :func:`rsm_lrg.fit` (and so of every command that
fits: ``fit``, ``optimize``, ``report``, ``fit-summary``, ``ridge``, ``confirm``). It

* chooses the factors (:func:`rsm_lrg.factors.choose_factors`: as given, or inferred from
  a design's coded columns, or the numeric columns), with a note naming them when inferred
  and a note listing every column that is neither factor, response, block nor bookkeeping;
* checks every factor cell and block cell on every row (an empty or non-numeric cell is an
  error naming the 1-based data row);
* leaves out the runs whose response cell is empty, as R and Design-Expert do, and says
  which (1-based data rows); a response cell that is not a number is an error naming the row.

>>> import pandas as pd
>>> df = pd.DataFrame({"x": [-1, 0, 1, 0], "y": [1.0, None, 3.0, 2.0], "who": list("abcd")})
>>> p = prepare(df, "y")
>>> p.omitted_rows, p.y.tolist()
((2,), [1.0, 3.0, 2.0])
>>> print(p.notes[-1])
1 run without a response left out of the fit (not run): row 2.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ...factors import FactorChoice, FactorSpace, choose_factors, quote_value
from ...factors.columns import check_frame
from ...factors.space import encode_column
from ...io import cell_error, check_number_kinds, float_values
from ...table import check_table, is_column_table, take_rows

__all__ = ["PreparedData", "prepare", "response_values", "CHUNK_ROWS"]

#: Rows per chunk of the model matrix (about 17 MB for the 66 terms of a 10-factor quadratic).
CHUNK_ROWS = 32768

#: At most this many row numbers are listed in a note.
_ROW_LIMIT = 20


@dataclass(frozen=True)
class PreparedData:
    """The inputs of a fit after :func:`prepare`.

    Attributes
    ----------
    data : pandas.DataFrame or rsm_lrg.table.ColumnTable
        The rows used (every row when none is left out; else a copy, index 0..n-1).
    y : ndarray
        Response of the rows used [response units].
    space : FactorSpace
        The factors with their coding.
    choice : FactorChoice
        How the factors were chosen and which columns were left out.
    omitted_rows : tuple of int
        1-based data rows left out because their response cell is empty ("not run").
    omitted_data : pandas.DataFrame or rsm_lrg.table.ColumnTable
        Those rows as given (index = 0-based position in the input).
    notes : tuple of str
        The sentences for the user (factor choice, columns left out, runs left out).
    """

    data: Any
    y: np.ndarray
    space: FactorSpace
    choice: FactorChoice
    omitted_rows: tuple
    omitted_data: Any
    notes: tuple


def columns_text(data) -> str:
    """The column names of ``data`` for an error message (at most 30, long names cut)."""
    cols = [str(c) for c in data.columns]
    shown = ", ".join(c if len(c) <= 40 else c[:40] + "…" for c in cols[:30])
    return shown + (f" and {len(cols) - 30} more" if len(cols) > 30 else "")


def empty_cells(col) -> np.ndarray:
    """Mask of the empty cells of a column: missing, or text of blanks only (vectorised); a
    column of a :class:`~rsm_lrg.table.ColumnTable` (a NumPy array of numbers): its NaNs."""
    if isinstance(col, np.ndarray) and col.dtype.kind in "iuf":
        return np.isnan(col) if col.dtype.kind == "f" else np.zeros(col.shape, dtype=bool)
    import pandas as pd

    if pd.api.types.is_numeric_dtype(col) or pd.api.types.is_bool_dtype(col):
        return col.isna().to_numpy(dtype=bool)
    txt = col.astype("string")
    return (txt.isna() | (txt.str.strip() == "")).fillna(True).to_numpy(dtype=bool)


def response_values(data, response: str) -> tuple[np.ndarray, np.ndarray]:
    """The response as floats (NaN where the cell is empty) and the mask of empty cells.

    A cell that is neither empty nor a finite number is a ValueError naming its row (1-based).
    """
    if is_column_table(data):  # numbers already (rsm_lrg.table)
        col_values = np.asarray(data[response], dtype=float)
        empty = np.isnan(col_values)
        bad_rows = np.flatnonzero(~empty & ~np.isfinite(col_values))
        if bad_rows.size:
            raise cell_error(response, int(bad_rows[0]) + 1, col_values[bad_rows[0]])
        return col_values, empty
    import pandas as pd

    col = data[response]
    check_number_kinds(col, response)  # True is no 1.0, a complex number no response
    empty = empty_cells(col)
    num = pd.to_numeric(col.where(~empty) if empty.any() else col, errors="coerce").to_numpy(dtype=float,
                                                                                                 na_value=np.nan)
    bad = ~empty & ~np.isfinite(num)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise cell_error(response, i + 1, col.iloc[i])
    y = np.where(empty, np.nan, num)
    return y, empty


def _rows(rows) -> str:
    shown = ", ".join(str(r) for r in rows[:_ROW_LIMIT])
    return shown + (f" and {len(rows) - _ROW_LIMIT} more" if len(rows) > _ROW_LIMIT else "")


def check_response_block(data, response: str, block: str | None) -> None:
    """The response and block columns are in ``data`` (a pandas or Dask DataFrame) and differ."""
    if response not in data.columns:
        raise ValueError(f"response column {quote_value(str(response))} not found (columns: {columns_text(data)})")
    if block is not None and block not in data.columns:
        raise ValueError(f"block column {quote_value(str(block))} not found (columns: {columns_text(data)})")
    if block is not None and block == response:
        raise ValueError(f"column {quote_value(str(response))} cannot be both the response and the block")


def check_group_column(data, col: str, response: str, what: str, role: str) -> None:
    """A grouping column (a whole plot, a random block, a random effect) is in ``data``, is
    not the response, has no empty cell and holds labels (no list in a cell).

    Parameters
    ----------
    data : pandas.DataFrame
        The runs.
    col : str
        The grouping column.
    response : str
        The response column.
    what : str
        The column's kind in messages ("whole-plot", "random-effect").
    role : str
        The column's role after "the response and" ("the whole-plot column").

    Returns
    -------
    None
        Raises ``ValueError`` naming the column (and the first empty row) otherwise.
    """
    from ...factors.columns import check_label_column

    if col not in data.columns:
        raise ValueError(f"{what} column {quote_value(col)} not found (columns: {columns_text(data)})")
    if col == response:
        raise ValueError(f"column {quote_value(col)} cannot be both the response and {role}")
    empty = empty_cells(data[col])
    if empty.any():
        raise ValueError(f"{what} column {quote_value(col)}, row {int(empty.argmax()) + 1}: is empty")
    check_label_column(data, col)  # a list in a cell is no group


def prepare(data, response: str, factors=None, block: str | None = None, *,
            exclude: Sequence[str] = ()) -> PreparedData:
    """Check the columns, choose the factors and leave out the runs without a response.

    Parameters
    ----------
    data : pandas.DataFrame or rsm_lrg.table.ColumnTable
        One row per run.
    response : str
        Response column; an empty cell leaves its run out of the fit.
    factors : None, sequence or FactorSpace
        As for :func:`rsm_lrg.fit` (``None`` infers them, see
        :func:`rsm_lrg.factors.choose_factors`).
    block : str, optional
        Block column (every cell must be filled).
    exclude : sequence of str
        Further columns that are never inferred as factors (random-effect columns).

    Returns
    -------
    PreparedData

    Raises
    ------
    ValueError
        Unknown columns, an empty or non-numeric factor cell, an empty block cell, a
        response cell that is not a number (each naming the 1-based row), no response at all.
    """
    check_table(data)
    check_frame(data, [response] + ([block] if block is not None else []))
    check_response_block(data, response, block)
    exclude = [response] + ([block] if block is not None else []) + [c for c in exclude if c in data.columns]
    choice = choose_factors(data, factors, exclude=exclude)
    for f in choice.space.factors:  # every row, the runs left out too: errors name the input row
        float_values(data, f.name) if f.kind == "numeric" else encode_column(data, f)
    if block is not None:
        empty_b = np.flatnonzero(empty_cells(data[block]))
        if empty_b.size:
            raise ValueError(f"block column {quote_value(str(block))}, row {int(empty_b[0]) + 1}: is empty")
    y, empty = response_values(data, response)
    notes = list(choice.notes)
    if empty.all():
        raise ValueError(f"response column {quote_value(str(response))} is empty on every row: there is nothing to fit")
    if empty.any():
        rows = tuple(int(i) + 1 for i in np.flatnonzero(empty))
        omitted = data.iloc[np.flatnonzero(empty)].copy() if not is_column_table(data) else data.take(
            np.flatnonzero(empty))  # index = position in the input
        used = take_rows(data, np.flatnonzero(~empty))
        y = y[~empty]
        k = len(rows)
        notes.append(f"{k} run{'s' if k > 1 else ''} without a response left out of the fit (not run): "
                     f"row{'s' if k > 1 else ''} {_rows(rows)}.")
    else:
        rows, omitted, used = (), (data.take([]) if is_column_table(data) else data.iloc[:0].copy()), data
    return PreparedData(data=used, y=np.asarray(y, dtype=float), space=choice.space, choice=choice,
                        omitted_rows=rows, omitted_data=omitted, notes=tuple(notes))
