"""Column inference: which columns of a data frame are the factors, read from the columns.

A design's coded columns (``coded_A``, ...) are paired with the factor columns they code
(:func:`design_factors`); otherwise the factors as given, or every numeric column that is not
bookkeeping (:data:`BOOKKEEPING`), with levels from the data (:func:`infer_items`). The factor
space and the notes for the user are made from these items by
:func:`rsm_lrg.factors.choose_factors`.
"""

from __future__ import annotations

import math
import re
from typing import Any

import numpy as np

from ..io import COMMA_NUMBER, cell_error, float_column, float_values, is_empty_cell
from ..table import is_column_table
from .factor import check_factor_name, level_text
from .spec import given_items
from .values import name_list, quote_value

__all__ = ["BOOKKEEPING", "CODED_COLUMN_PREFIX", "PAIR_RTOL", "DESIGN_CODED", "COLUMNS_LEFT_OUT", "Note",
           "is_bookkeeping", "design_factors", "infer_items", "constant_number",
           "check_frame", "check_label_column", "column_dtypes", "column_kind"]

#: Column names that are never factors (case-insensitive).
BOOKKEEPING = frozenset({"run", "order", "std", "std_order", "run_order"})

#: Columns whose lower-cased name starts with this are a design CSV's coded copies of the
#: factors (``coded_A``, ...); never picked as factors by default.
CODED_COLUMN_PREFIX = "coded_"

#: Relative tolerance of the coded/actual pairing (a design written with 10 significant
#: digits, as ``simulate`` writes it, pairs well inside it).
PAIR_RTOL = 1e-7

#: A design's coded column: ``coded_`` and a factor letter (``coded_A``, ``coded_B1``; any case).
DESIGN_CODED = re.compile(r"^coded_[a-z][0-9]*$", re.IGNORECASE)


def is_bookkeeping(column) -> bool:
    """A design's or a lab sheet's own column: never a factor and never listed as unused
    (``run``, ``order``, ``std``, ``std_order``, ``run_order``, ``coded_*``; any case).

    Parameters
    ----------
    column : object
        The column's name.

    Returns
    -------
    bool
        Whether it is a bookkeeping column.
    """
    low = str(column).lower()
    return low in BOOKKEEPING or low.startswith(CODED_COLUMN_PREFIX)


class Note(str):
    """A note on the input (plain text) that also says what it is about in ``kind``, so that a
    command can pick notes by kind rather than by their wording.

    >>> n = Note("Text column x left out (not a factor, response or block): x.", "columns_left_out")
    >>> n.kind, n.startswith("Text")
    ('columns_left_out', True)
    """

    kind: str

    def __new__(cls, text: str, kind: str = ""):
        self = super().__new__(cls, text)
        self.kind = kind
        return self

    def __reduce__(self):  # keep the kind through pickling (Dask workers, process pools)
        return (Note, (str(self), self.kind))


#: ``Note.kind`` of the notes that list the data columns a fit left out.
COLUMNS_LEFT_OUT = "columns_left_out"

def _pair_levels(c: np.ndarray, x: np.ndarray) -> tuple[float, float] | None:
    """Low and high levels of the linear map ``x = centre + half_range * c``, or None.

    Rows where ``x`` is not a finite number are skipped (an empty factor cell is reported
    later, with its row). The levels are the actual values at coded -1 and +1 where the
    design has them (most common value), else a least-squares line; every row must lie on
    the line to ``PAIR_RTOL`` of the factor's scale and the line must rise.
    """
    ok = np.isfinite(x) & np.isfinite(c)
    if ok.sum() < max(2, (c.size + 1) // 2):
        return None
    c, x = c[ok], x[ok]
    if np.unique(c).size < 2:
        return None
    at_lo, at_hi = x[c == -1.0], x[c == 1.0]
    if at_lo.size and at_hi.size:
        lv, nlo = np.unique(at_lo, return_counts=True)
        hv, nhi = np.unique(at_hi, return_counts=True)
        low, high = float(lv[np.argmax(nlo)]), float(hv[np.argmax(nhi)])
        m, h = (low + high) / 2.0, (high - low) / 2.0
    else:
        A = np.column_stack([np.ones_like(c), c])
        (m, h), *_ = np.linalg.lstsq(A, x, rcond=None)
        m, h = float(m), float(h)
        low, high = _tidy(m - h), _tidy(m + h)
    if not (h > 0 and math.isfinite(m) and math.isfinite(h) and low < high):
        return None
    scale = max(abs(m) + abs(h), float(np.max(np.abs(x))))
    if np.max(np.abs(x - (m + h * c))) > PAIR_RTOL * scale:
        return None
    return low, high


def _tidy(v: float) -> float:
    """0.0001 rather than 0.00010000000000000002 (a least-squares level)."""
    r = float(f"{v:.12g}")
    return r if math.isclose(r, v, rel_tol=1e-11, abs_tol=0.0) else v

def design_factors(data, coded: list, exclude: set) -> tuple[list, list]:
    """Pair each coded column with its actual column: ``([(name, low, high)], [coded col])``.

    Parameters
    ----------
    data : pandas.DataFrame or rsm_lrg.table.ColumnTable
        The table.
    coded : list of str
        The coded columns (``coded_A``, ...).
    exclude : set of str
        Columns that cannot be factors (the response, the block).

    Returns
    -------
    tuple of list
        ``([(name, low, high)], [coded column])``.
    """
    cols = list(data.columns)
    last = max(cols.index(c) for c in coded)
    cand = [c for c in cols if c not in exclude and not is_bookkeeping(c) and str(c).lower() != "block"
            and column_kind(data, c) == "number"]
    # the design writes the actual columns right after the coded ones, in the same order:
    # those are tried first, so column order settles any tie
    order = [c for c in cand if cols.index(c) > last] + [c for c in cand if cols.index(c) < last]
    used: set = set()
    out = []
    for cc in coded:
        if column_kind(data, cc) == "other":
            # a categoric factor: its coded column holds the level (Design-Expert's layout), the
            # same text as its actual column; levels in order of first appearance in std_order
            levels_of = _design_categoric(data, cc, cols, last, exclude, used)
            used.add(levels_of[0])
            out.append(levels_of)
            continue
        cv = float_values(data, cc)
        match: tuple | None = None
        for name in order:
            if name in used:
                continue
            levels = _pair_levels(cv, np.asarray(data[name], dtype=float) if is_column_table(data)
                                  else data[name].to_numpy(dtype=float, na_value=np.nan))
            if levels is not None:
                match = (name, *levels)
                break
        if match is None:
            raise ValueError(
                f"the design column {quote_value(str(cc))} matches no factor column (none is a rising linear "
                f"map of it); name the factors with --factor NAME"
            )
        used.add(match[0])
        out.append(match)
    return out, list(coded)


def _design_categoric(data, cc, cols: list, last: int, exclude: set, used: set) -> tuple:
    """``(name, levels)`` of the text column that equals the categoric coded column ``cc``."""
    import pandas as pd

    text = [level_text(v) if not is_empty_cell(v) else None for v in data[cc].tolist()]
    if any(v is None for v in text):
        raise ValueError(f"the design column {quote_value(str(cc))} has an empty cell")
    cand = [c for c in cols if c not in exclude and c not in used and not is_bookkeeping(c)
            and str(c).lower() != "block"]
    cand = [c for c in cand if cols.index(c) > last] + [c for c in cand if cols.index(c) < last]
    for name in cand:
        vals = [level_text(v) if not is_empty_cell(v) else None for v in data[name].tolist()]
        if vals == text:
            order: Any = range(len(text))
            if "std_order" in cols and pd.api.types.is_numeric_dtype(data["std_order"]):
                order = np.argsort(data["std_order"].to_numpy(), kind="stable")
            levels: list = []
            for i in order:
                if text[i] not in levels:
                    levels.append(text[i])
            if len(levels) < 2:
                raise ValueError(f"the design column {quote_value(str(cc))} holds a single level; a factor needs "
                                 "at least two")
            return name, tuple(levels)
    raise ValueError(f"the design column {quote_value(str(cc))} (a categoric factor's levels) matches no factor "
                     "column holding the same levels; name the factors with --factor NAME")


def check_frame(data, labels=()) -> None:
    """A DataFrame given to a fit, checked before anything is taken from it: at least one row;
    column names that can be told apart (none twice, none alike once Unicode-normalised, no
    control character: :func:`rsm_lrg.readers.check_column_names`, the readers' own rule); the
    ``labels`` columns (block, whole plot) holding one label per cell (not a list, a dict, a
    set or an array). A ValueError naming the column (and the row).

    >>> import pandas as pd
    >>> check_frame(pd.DataFrame({"a": [], "y": []}))
    Traceback (most recent call last):
    ...
    ValueError: the data have no rows (an empty DataFrame): there is nothing to fit
    """
    from ..readers import TableError, check_column_names

    try:
        check_column_names(list(data.columns))
    except TableError as exc:
        raise ValueError(str(exc)) from None
    if data.shape[0] == 0:
        raise ValueError("the data have no rows (an empty DataFrame): there is nothing to fit")
    for name in labels:
        if name in data.columns:
            check_label_column(data, name)


def check_label_column(data, name: str) -> None:
    """Every cell of the label column ``name`` (a block, a whole plot) is one label: a list, a
    dict, a set or an array (unhashable: no label) is a ValueError naming the row."""
    for i, v in enumerate(data[name].tolist()):
        try:
            hash(v)
        except TypeError:
            raise ValueError(f"column {quote_value(str(name))}, row {i + 1}: holds a {type(v).__name__}, not a label "
                             "(a number or a text)") from None


def column_dtypes(data) -> dict | None:
    """``{column: dtype}`` of a frame whose column names are unique (one look-up of the
    dtypes instead of a column built per name), else None (a repeated name selects a frame).

    Parameters
    ----------
    data : pandas.DataFrame or rsm_lrg.table.ColumnTable
        The table.

    Returns
    -------
    dict or None
        The dtype of each column.
    """
    if is_column_table(data):  # names unique, numbers only
        return {c: data[c].dtype for c in data.columns}
    if not data.columns.is_unique:
        return None
    return dict(zip(data.columns, data.dtypes))


def column_kind(data, name, dtypes: dict | None = None) -> str:
    """What a column holds for the factor choice: ``"number"``, ``"bool"`` (truth values) or
    ``"other"`` (text, mixed objects, categories), by its dtype; every column of a
    :class:`~rsm_lrg.table.ColumnTable` is a number column (pandas is not imported for it).

    Parameters
    ----------
    data : pandas.DataFrame or rsm_lrg.table.ColumnTable
        The table.
    name : str
        The column.
    dtypes : dict, optional
        :func:`column_dtypes` of ``data`` (a look-up instead of building the column).

    Returns
    -------
    str
        ``"number"``, ``"bool"`` or ``"other"``.
    """
    if is_column_table(data):
        return "number"
    import pandas as pd

    what = dtypes[name] if dtypes else data[name]
    if pd.api.types.is_bool_dtype(what):
        return "bool"
    return "number" if pd.api.types.is_numeric_dtype(what) else "other"


def _check_text_columns(data, exclude) -> None:
    """A text column that holds numbers is a typo or a locale problem (``1,234``), not a
    label: a ValueError names the column and the row. Nor is a column of numbers that pandas
    does not hold as numbers (Python objects with a number among them, a ``Categorical`` of
    numbers) left out as text without a word: refused, naming it."""
    if is_column_table(data):
        return  # numbers only
    import pandas as pd

    dtypes = column_dtypes(data)
    for c in data.columns:
        if c in exclude or is_bookkeeping(c) or column_kind(data, c, dtypes) != "other":
            continue
        col = data[c]
        if isinstance(col.dtype, pd.CategoricalDtype):
            cats = pd.Series(col.cat.categories)
            if len(cats) and pd.api.types.is_numeric_dtype(cats):
                raise ValueError(f"column {quote_value(str(c))} is a pandas Categorical of numbers: convert it to "
                                 f"numbers (.astype(float)) or name it as a categoric factor ('{c}=cat')")
            continue
        commas = np.flatnonzero(col.astype("string").str.match(COMMA_NUMBER.pattern).fillna(False).to_numpy(bool))
        if commas.size:
            i = int(commas[0])
            raise cell_error(str(c), i + 1, col.iloc[i])
        num = pd.to_numeric(col, errors="coerce")
        if num.notna().sum() >= max(1, data.shape[0] // 2):
            float_column(data, c)  # raises "column 'c', row i: holds 'text', not a finite number"
        cells = col.tolist()
        if any(isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, (bool, np.bool_))
               and not is_empty_cell(v) for v in cells):  # every cell a number, some held as text
            text = next(((i, v) for i, v in enumerate(cells) if isinstance(v, str) and not is_empty_cell(v)), None)
            where = f" (row {text[0] + 1} holds the text {quote_value(text[1])})" if text else ""
            raise ValueError(f"column {quote_value(str(c))} holds numbers as Python objects{where}: convert it to "
                             "numbers (pandas.to_numeric) or name the factors")


def constant_number(col) -> float | None:
    """The one value of a numeric column that holds the same finite number on every row, else
    None (a column with an empty or non-finite cell is not constant: its fit says which row)."""
    if np.iscomplexobj(col):
        return None  # refused by its fit, naming it
    v = np.asarray(col, dtype=float)
    if v.size == 0 or not np.isfinite(v).all() or not (v == v[0]).all():
        return None
    return float(v[0])


def _constant_number(col) -> bool:
    return constant_number(col) is not None


def _is_number_column(col) -> bool:
    if isinstance(col, np.ndarray) and col.dtype.kind in "iuf":  # a ColumnTable's column
        return True
    import pandas as pd

    if pd.api.types.is_bool_dtype(col):
        return False
    if pd.api.types.is_numeric_dtype(col):
        return True
    # mostly numbers (a typo in one cell is then an error naming its row, not a new level)
    vals = col[~np.array([is_empty_cell(v) for v in col.tolist()], dtype=bool)]
    return bool(len(vals)) and pd.to_numeric(vals, errors="coerce").notna().sum() * 2 >= len(vals)

def _categoric_levels(data, name: str, levels) -> tuple:
    """The levels of a categoric factor column: as given (every cell must be one), or in
    order of first appearance; errors name the 1-based row."""
    col = data[name].tolist()
    seen: list = []
    for j, v in enumerate(col):
        if is_empty_cell(v):
            raise ValueError(f"column {quote_value(name)}, row {j + 1}: is empty")
        key = level_text(v)
        if levels is not None and key not in levels:
            raise ValueError(f"column {quote_value(name)}, row {j + 1}: holds {quote_value(key)}, not one of the "
                             f"levels given for categoric factor {quote_value(name)} ({name_list(list(levels))})")
        if key not in seen:
            seen.append(key)
    missing = [lv for lv in (levels or ()) if lv not in seen]
    if missing:  # its effect could not be estimated: say so by name, not as an aliased model term
        raise ValueError(f"categoric factor {quote_value(name)}: the level {quote_value(missing[0])} is given but no "
                         f"row holds it (levels in the data: {name_list(seen)}); give only levels the data hold")
    if levels is None:
        if len(seen) < 2:
            raise ValueError(f"categoric factor column {quote_value(name)} has only one level; a factor needs at "
                             "least two")
        return tuple(seen)
    return tuple(levels)



def infer_items(data, factors: Any, exclude: set) -> tuple[str, list, list]:
    """The factors of a data frame as items, inferred when not given (the work of
    :func:`rsm_lrg.factors.choose_factors` but for a given :class:`~rsm_lrg.factors.FactorSpace`).

    Parameters
    ----------
    data : pandas.DataFrame or rsm_lrg.table.ColumnTable
        The table.
    factors : object
        The factors as given, or ``None`` to infer them.
    exclude : set of str
        Columns that cannot be factors.

    Returns
    -------
    how : {"design", "numeric", "given"}
    items : list of tuple
        With ``how == "design"``: ``(name, low, high)`` / ``(name, levels)`` in coded-column
        order (:func:`design_factors`); otherwise ``("numeric", name, low, high)`` /
        ``("categoric", name, levels)`` with the levels filled in from the data.
    coded_columns : list of str
        With ``how == "design"``: the coded column of each factor; else empty.
    """
    cols = list(data.columns)
    coded_cols = [c for c in cols if DESIGN_CODED.match(str(c))]
    if factors is None and coded_cols:
        _check_text_columns(data, exclude)
        found, coded_used = design_factors(data, coded_cols, exclude)
        return "design", found, coded_used
    if factors is None:
        how = "numeric"
        _check_text_columns(data, exclude)
        dtypes = column_dtypes(data)
        names = [
            c for c in cols
            if c not in exclude and not is_bookkeeping(c) and str(c).lower() != "block"
            and column_kind(data, c, dtypes) == "number"
        ]
        constant = [n for n in names if _constant_number(data[n])]  # left out with a note (choose_factors)
        items: list[Any] = [("numeric", n, None, None) for n in names if n not in constant]  # names, never specs
        if not items:
            raise ValueError("no numeric factor columns found in the data" + (
                f" (every numeric column is constant: {name_list([quote_value(str(c)) for c in constant])}; a factor needs at "
                "least two levels)" if constant else ""))
    else:
        how = "given"
        items = given_items(factors)
    ranged: list[tuple] = []
    for kind, name, *levels in items:
        if name not in data.columns:
            raise ValueError(f"factor column {quote_value(str(name))} is not in the data")
        if name in exclude:
            raise ValueError(f"column {quote_value(str(name))} cannot be both a factor and the response or block")
        check_factor_name(name)
        if kind == "numeric" and levels[0] is None and how == "given" and not _is_number_column(data[name]):
            kind, levels = "categoric", [None]  # a text column among the factors is categoric
        if kind == "categoric":
            ranged.append(("categoric", name, _categoric_levels(data, name, levels[0])))
            continue
        low, high = levels
        if low is None:
            col = float_values(data, name)  # finite floats (checked): NumPy's min and max
            low, high = float(col.min()), float(col.max())
            if not low < high:
                raise ValueError(f"factor column {quote_value(str(name))} is constant ({low:g}); "
                                 "a factor needs at least two levels")
        ranged.append(("numeric", name, low, high))
    return how, ranged, []
