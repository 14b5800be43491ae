"""A table of numeric columns held without pandas: what ``rsm-lrg fit`` reads a plain CSV file
into, so that a least-squares fit of a small file does not import pandas (about 0.5 s of CPU
at start-up, twice R's whole ``rsm()`` + ``summary()``; issue 37, item 6).

A :class:`ColumnTable` holds only what :func:`rsm_lrg.readers.parse_plain_csv` accepts:
columns of whole numbers (``int64``) or decimal numbers (``float64``), none empty, each the
column ``pandas.read_csv`` would have made of the same text, value for value. The routines of
the fit path read a table through :func:`column_names`, :func:`column_values` and
:func:`take_rows`, which take a ``pandas.DataFrame`` or a :class:`ColumnTable` alike; anything
else (text or empty cells, a Python caller's frame) stays a DataFrame.

>>> import numpy as np
>>> t = ColumnTable({"x": np.array([-1, 0, 1]), "y": np.array([1.5, 2.0, 2.5])})
>>> t.shape, list(t.columns), "x" in t.columns
((3, 2), ['x', 'y'], True)
>>> column_values(take_rows(t, np.array([0, 2])), "y").tolist()
[1.5, 2.5]
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

__all__ = ["ColumnTable", "column_names", "column_values", "take_rows", "n_rows", "is_column_table",
           "check_table"]


class ColumnTable:
    """Named numeric columns of one length, read-only (a plain CSV file read without pandas).

    Parameters
    ----------
    columns : mapping of str to numpy.ndarray
        The columns in file order: 1-D arrays of dtype ``int64`` or ``float64``, all of one
        length. The arrays are copied and made read-only.

    Raises
    ------
    ValueError
        No columns, a column that is not 1-D ``int64``/``float64``, or columns of different
        lengths.
    """

    __slots__ = ("_cols", "_n")

    def __init__(self, columns: Mapping[str, Any]):
        cols: dict[str, np.ndarray] = {}
        for name, values in columns.items():
            a = np.array(values)
            if a.ndim != 1 or a.dtype not in (np.dtype(np.int64), np.dtype(np.float64)):
                raise ValueError(f"column {name!r}: a ColumnTable holds 1-D int64 or float64 columns, got "
                                 f"{a.ndim}-D {a.dtype}")
            a.flags.writeable = False
            cols[str(name)] = a
        if not cols:
            raise ValueError("a ColumnTable needs at least one column")
        lengths = {a.shape[0] for a in cols.values()}
        if len(lengths) != 1:
            raise ValueError(f"the columns of a ColumnTable have different lengths {sorted(lengths)}")
        self._cols = cols
        self._n = lengths.pop()

    @property
    def columns(self) -> tuple[str, ...]:
        """The column names in file order."""
        return tuple(self._cols)

    @property
    def shape(self) -> tuple[int, int]:
        """``(rows, columns)``, as ``DataFrame.shape``."""
        return self._n, len(self._cols)

    def __len__(self) -> int:
        return self._n

    def __getitem__(self, name: str) -> np.ndarray:
        return self._cols[name]

    def __repr__(self) -> str:
        return f"ColumnTable({self._n} rows: {', '.join(self._cols)})"

    def take(self, rows: Any) -> ColumnTable:
        """The rows at the positions ``rows`` (0-based), in that order.

        Parameters
        ----------
        rows : array_like of int
            Row positions.

        Returns
        -------
        ColumnTable
        """
        idx = np.asarray(rows, dtype=np.intp)
        return ColumnTable({k: v[idx] for k, v in self._cols.items()})

    def to_numpy(self, dtype: Any = None) -> np.ndarray:
        """The columns side by side, as ``DataFrame.to_numpy``.

        Parameters
        ----------
        dtype : numpy dtype, optional
            The array's dtype (default: the columns' common type).

        Returns
        -------
        numpy.ndarray (rows, columns)
            A new array.
        """
        return np.column_stack(list(self._cols.values())).astype(dtype if dtype is not None else
                                                                 np.result_type(*self._cols.values()))

    def copy(self) -> ColumnTable:
        """The table itself: it is read-only, so a copy would change nothing (as ``DataFrame.copy``).

        Returns
        -------
        ColumnTable
        """
        return self

    def to_frame(self) -> Any:
        """The same table as a ``pandas.DataFrame`` (imports pandas).

        Returns
        -------
        pandas.DataFrame
            One column per column, the same dtypes and values, a default index.
        """
        import pandas as pd

        return pd.DataFrame({k: v.copy() for k, v in self._cols.items()})


def is_column_table(data: Any) -> bool:
    """Whether ``data`` is a :class:`ColumnTable` (and not a pandas or Dask frame).

    Parameters
    ----------
    data : object

    Returns
    -------
    bool
    """
    return isinstance(data, ColumnTable)


def check_table(data: Any) -> None:
    """The data of an in-memory fit: a ``pandas.DataFrame`` or a :class:`ColumnTable` (pandas is
    imported only to tell the rest apart).

    Parameters
    ----------
    data : object

    Returns
    -------
    None
        Raises ``TypeError("data must be a pandas DataFrame")`` for anything else.
    """
    if isinstance(data, ColumnTable):
        return
    import pandas as pd

    if not isinstance(data, pd.DataFrame):
        raise TypeError("data must be a pandas DataFrame")


def column_names(data: Any) -> list[str]:
    """The column names of a ``pandas.DataFrame`` or a :class:`ColumnTable`, as given.

    Parameters
    ----------
    data : pandas.DataFrame or ColumnTable

    Returns
    -------
    list
        The names in column order (a DataFrame's as they are, not made strings).
    """
    return list(data.columns)


def column_values(data: Any, name: str) -> np.ndarray:
    """One column as a NumPy array: ``data[name].to_numpy()`` of a DataFrame, the column itself
    (read-only) of a :class:`ColumnTable`.

    Parameters
    ----------
    data : pandas.DataFrame or ColumnTable
    name : str
        The column.

    Returns
    -------
    numpy.ndarray
        1-D.
    """
    if isinstance(data, ColumnTable):
        return data[name]
    return data[name].to_numpy()


def take_rows(data: Any, rows: Any) -> Any:
    """The rows at positions ``rows`` of a DataFrame (a new frame with a default index) or of a
    :class:`ColumnTable`.

    Parameters
    ----------
    data : pandas.DataFrame or ColumnTable
    rows : array_like of int
        0-based positions.

    Returns
    -------
    pandas.DataFrame or ColumnTable
        Of the type given.
    """
    if isinstance(data, ColumnTable):
        return data.take(rows)
    return data.iloc[np.asarray(rows, dtype=np.intp)].reset_index(drop=True)


def n_rows(data: Any) -> int:
    """The number of rows of a DataFrame or a :class:`ColumnTable`.

    Parameters
    ----------
    data : pandas.DataFrame or ColumnTable

    Returns
    -------
    int
    """
    return int(len(data))
