"""Factor choice: the factors of a data frame with notes on what was inferred and what is
left out (:func:`choose_factors`, :class:`FactorChoice`).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

from ..io import float_values
from ..table import is_column_table
from .columns import COLUMNS_LEFT_OUT, Note, column_dtypes, column_kind, constant_number, infer_items, is_bookkeeping
from .space import FactorSpace, inferred_space
from .values import name_list, quote_value

__all__ = ["FactorChoice", "choose_factors"]


@dataclass(frozen=True)
class FactorChoice:
    """Which columns are the factors, and what was left out (see :func:`choose_factors`).

    Attributes
    ----------
    space : FactorSpace
        The factors with their coding.
    how : {"given", "design", "numeric"}
        Factors as given; inferred from a design's coded columns; inferred as the
        numeric columns.
    coded_columns : tuple of str
        With ``how == "design"``: the coded column of each factor (``coded_A`` ...).
    unused : tuple of str
        Columns that are neither a factor, excluded (response, block) nor bookkeeping.
    text_columns : tuple of str
        The non-numeric columns among ``unused``.
    notes : tuple of str
        Sentences for the user: which columns are the factors (when inferred) and which
        columns are left out.
    blend_total : float or None
        When the factors were inferred and every numeric factor column is a non-negative
        share of one constant row total (a mixture design's components): that total.
    """

    space: FactorSpace
    how: str
    coded_columns: tuple = ()
    unused: tuple = ()
    text_columns: tuple = ()
    notes: tuple = ()
    blend_total: float | None = None

    @property
    def inferred(self) -> bool:
        """True when the factors were not given."""
        return self.how != "given"

    def hint(self) -> str:
        """A clause naming the inferred factors and suggesting ``--factor`` (empty when given).

        Returns
        -------
        str
            The clause, or ``""``.
        """
        if not self.inferred:
            return ""
        listed = name_list([f"{f.letter} {f.name}" for f in self.space.factors])
        if self.blend_total is not None:  # said first: the error line is cut at 300 characters
            comps = " ".join(f"--component {f.name}" for f in self.space.factors)
            return (f"; the factors {listed} sum to {self.blend_total:g} on every row, as mixture components do: "
                    f"give {comps} and a mixture --model")
        return f"; factors inferred: {listed} (if wrong, name them with --factor NAME)"


def choose_factors(data, factors: Any = None, *, exclude: Iterable[str] = ()) -> FactorChoice:
    """The factors of a data frame, inferred when not given, with notes on what is left out.

    Parameters
    ----------
    data : pandas.DataFrame or rsm_lrg.table.ColumnTable
    factors : None, sequence or FactorSpace
        ``None`` infers the factors:

        * data carrying a design's coded columns (``coded_`` and a letter: ``coded_A``,
          ``coded_B``, ...; a design CSV, or a file made from one such as ``simulate``'s
          output): one factor per coded column, the numeric column that is a rising linear map of it (``x = centre +
          half_range * coded`` on every row; the columns right after the coded ones are
          tried first, so column order settles a tie), coded as the design codes it
          (the actual values at coded -1 and +1, so axial points stay at ±alpha);
        * otherwise every numeric column that is not excluded and not bookkeeping
          (``run``, ``order``, ``std``, ``std_order``, ``run_order``, ``block``),
          coded from its observed minimum and maximum.

        Otherwise as for :meth:`FactorSpace.from_data`.
    exclude : iterable of str
        The response and block columns: never factors, never listed as unused.

    Returns
    -------
    FactorChoice
    """
    exclude = set(exclude)
    cols = list(data.columns)
    if isinstance(factors, FactorSpace):
        factors.require_columns(data)
        coded_used: list = []
        how, space = "given", factors
    else:
        how, items, coded_used = infer_items(data, factors, exclude)
        space = inferred_space(how, items)
    used = set(space.names) | exclude
    unused = [c for c in cols if c not in used and not is_bookkeeping(c)]
    text = [c for c in unused if column_kind(data, c) == "other"]
    notes = []
    if how == "design":
        pairs = [f"{f.letter} {f.name} ({cc})" for f, cc in zip(space.factors, coded_used)]
        notes.append(f"Factors taken from the design's coded columns: {name_list(pairs)}; coded as the design codes "
                     "them (name other factors with --factor).")
    elif how == "numeric":
        notes.append(f"Factors taken to be the numeric columns: {name_list([f'{f.letter} {f.name}' for f in space])} "
                     "(name other factors with --factor).")
    for f in space.factors if how == "given" else ():
        if f.kind == "categoric" and f.name in data.columns and column_kind(data, f.name) != "other":
            notes.append(f"Categoric factor {quote_value(str(f.name))} is read from a column of numbers: its levels "
                         f"are the numbers, written {name_list(list(f.levels))} (whole numbers without .0, others "
                         "to 15 digits); codes that differ only in their text (1.0 and 1) are one level.")
    numeric_unused = [c for c in unused if c not in text]
    constant = {c: constant_number(data[c]) for c in numeric_unused} if how == "numeric" else {}
    constant = {c: v for c, v in constant.items() if v is not None}
    if constant:
        shown = name_list([f"{quote_value(str(c))} ({v:g} on every row)" for c, v in constant.items()])
        notes.append(Note(f"Constant numeric column{'s' if len(constant) > 1 else ''} left out (a factor needs at "
                          f"least two levels): {shown}.", COLUMNS_LEFT_OUT))
        numeric_unused = [c for c in numeric_unused if c not in constant]
    if numeric_unused:
        notes.append(Note(f"Numeric column{'s' if len(numeric_unused) > 1 else ''} left out (not a factor, response "
                          f"or block): {name_list(numeric_unused)}.", COLUMNS_LEFT_OUT))
    blocks = [c for c in numeric_unused if str(c).lower() == "block"]
    if blocks:
        notes.append(f"Column {blocks[0]} looks like a design's block column; give --block {blocks[0]} to fit "
                     "block effects.")
    if text:
        notes.append(Note(f"Text column{'s' if len(text) > 1 else ''} left out (not a factor, response or block): "
                          f"{name_list(text)}.", COLUMNS_LEFT_OUT))
    return FactorChoice(space=space, how=how, coded_columns=tuple(coded_used), unused=tuple(unused),
                        text_columns=tuple(text), notes=tuple(notes),
                        blend_total=_blend_total(data, space) if how != "given" else None)


def _blend_total(data, space: FactorSpace) -> float | None:
    """The constant row total of the factor columns when they look like a mixture's components
    (two or more numeric columns, no negative value, every row summing to the same positive
    total within 1e-6 of it), else None."""
    import numpy as np

    names = [f.name for f in space.factors]
    if len(names) < 2 or any(f.kind != "numeric" for f in space.factors) or len(data) == 0:
        return None
    x = None
    dtypes = column_dtypes(data)
    if dtypes is not None and all(dtypes[n].kind in "fiu" for n in names):
        try:  # number columns: as float_column reads them (once per fit inside remembered_float_columns)
            x = np.column_stack([float_values(data, n) for n in names])
        except ValueError:  # a value that is not finite: as below
            x = None
    if x is None:
        if is_column_table(data):
            return None  # a value that is not finite
        try:
            x = data[names].to_numpy(dtype=float)
        except (TypeError, ValueError):
            return None
    if not np.isfinite(x).all() or (x < 0).any():
        return None
    sums = x.sum(axis=1)
    total = float(sums[0])
    if total <= 0 or not np.all(np.abs(sums - total) <= 1e-6 * total):
        return None
    return total
