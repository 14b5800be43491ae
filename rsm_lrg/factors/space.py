"""The factor space: an ordered set of factors with letters A, B, C, ..., coding actual
values to coded ones and back (:class:`FactorSpace`).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..io import float_values, is_empty_cell
from ..table import ColumnTable, is_column_table
from .columns import infer_items
from .component import MixtureComponent
from .factor import CategoricFactor, Factor, letters_for, level_text
from .spec import spec_with_levels
from .values import name_list, quote_value

__all__ = ["FactorSpace", "encode_column", "design_space", "inferred_space"]


@dataclass(frozen=True)
class FactorSpace:
    """An ordered set of factors with letters A, B, C, ...

    Build it with :meth:`from_ranges` (names and levels), :meth:`from_specs` (CLI-style
    ``NAME=LOW:HIGH`` strings) or :meth:`from_data` (levels from the data's observed
    minimum and maximum where not given).

    Parameters
    ----------
    factors : tuple of Factor or CategoricFactor
        The factors, in letter order.
    """

    factors: tuple[Factor | CategoricFactor, ...]

    def __post_init__(self) -> None:
        object.__setattr__(self, "factors", tuple(self.factors))
        names = [f.name for f in self.factors]
        dup = {n for n in names if names.count(n) > 1}
        if dup:
            raise ValueError(f"factor {quote_value(sorted(dup)[0])} is given more than once")
        letters = [f.letter for f in self.factors]
        if len(set(letters)) != len(letters):
            raise ValueError("factor letters must be unique")

    # -- construction -------------------------------------------------------------
    @classmethod
    def from_ranges(cls, ranges: Mapping[str, tuple[float, float]] | Iterable[tuple[str, float, float]]) -> FactorSpace:
        """From ``{name: (low, high)}`` or ``[(name, low, high), ...]``, in order (numeric factors).

        Parameters
        ----------
        ranges : mapping or iterable
            ``{name: (low, high)}`` or ``[(name, low, high), ...]`` [the factors' units].

        Returns
        -------
        FactorSpace
            Numeric factors, letters in the order given.
        """
        items = list(ranges.items()) if isinstance(ranges, Mapping) else [(n, (lo, hi)) for n, lo, hi in ranges]
        letters = letters_for(len(items))
        return cls(tuple(Factor(n, lo, hi, L) for (n, (lo, hi)), L in zip(items, letters)))

    @classmethod
    def from_items(cls, items: Iterable[tuple]) -> FactorSpace:
        """From ``("numeric", name, low, high)`` and ``("categoric", name, levels)`` items.

        Letters go to the numeric factors first, in the order given, then to the categoric
        ones (Design-Expert's convention), and the factors are held in letter order.

        Parameters
        ----------
        items : iterable of tuple
            ``("numeric", name, low, high)`` and ``("categoric", name, levels)``.

        Returns
        -------
        FactorSpace
            The factors in letter order.
        """
        items = list(items)
        num = [it for it in items if it[0] == "numeric"]
        cat = [it for it in items if it[0] == "categoric"]
        letters = letters_for(len(items))
        out: list = [Factor(n, lo, hi, L) for (_, n, lo, hi), L in zip(num, letters)]
        out += [CategoricFactor(n, tuple(lv), L) for (_, n, lv), L in zip(cat, letters[len(num):])]
        return cls(tuple(out))

    @classmethod
    def from_specs(cls, specs: Sequence[str]) -> FactorSpace:
        """From ``["NAME=LOW:HIGH", "NAME=cat:L1,L2", ...]``; every spec must carry its levels.

        Parameters
        ----------
        specs : sequence of str
            ``"NAME=LOW:HIGH"`` and ``"NAME=cat:L1,L2"`` specs.

        Returns
        -------
        FactorSpace
            The factors.
        """
        return cls.from_items([spec_with_levels(s) for s in specs])

    @classmethod
    def from_data(cls, data, factors: Sequence[Any] | None = None, *, exclude: Iterable[str] = ()) -> FactorSpace:
        """Factor space for a data frame (the ``space`` of :func:`choose_factors`).

        Parameters
        ----------
        data : pandas.DataFrame
        factors : sequence, mapping, FactorSpace or None
            ``None``: inferred (see :func:`choose_factors`): a design's factors when the
            data carry a design's ``coded_A``, ``coded_B``, ... columns, else every numeric
            column that is not in ``exclude``, not a bookkeeping column (``run``,
            ``order``, ``std``, ``std_order``, ``run_order``, ``block``). Otherwise items
            that are names, ``"NAME=LOW:HIGH"``, ``"NAME=cat"`` or ``"NAME=cat:L1,L2"``
            strings, ``(name, low, high)`` tuples or :class:`Factor` /
            :class:`CategoricFactor` objects, or a mapping ``{name: None | (low, high) |
            "categoric" | [levels]}``; a numeric name without levels takes the observed
            minimum and maximum of its column, a text column is categoric.
        exclude : iterable of str
            Columns never taken as factors (the response, the block column).

        Returns
        -------
        FactorSpace
            The factors of ``data``.
        """
        if isinstance(factors, FactorSpace):
            factors.require_columns(data)
            return factors
        how, items, _ = infer_items(data, factors, set(exclude))
        return inferred_space(how, items)

    # -- views ----------------------------------------------------------------------
    def require_columns(self, data) -> None:
        """A ValueError naming the first factor whose column is not in ``data``.

        Parameters
        ----------
        data : pandas.DataFrame
            The table that must hold a column per factor.
        """
        for f in self.factors:
            if f.name not in data.columns:
                raise ValueError(f"factor column {quote_value(f.name)} is not in the data")

    def __len__(self) -> int:
        return len(self.factors)

    def __iter__(self):
        return iter(self.factors)

    def __getitem__(self, key: int | str) -> Factor | CategoricFactor:
        if isinstance(key, int):
            return self.factors[key]
        for f in self.factors:
            if key in (f.name, f.letter):
                return f
        raise KeyError(key)

    @property
    def names(self) -> list[str]:
        """The factors' names (data columns), in letter order."""
        return [f.name for f in self.factors]

    @property
    def letters(self) -> list[str]:
        """The factors' letters (A, B, ...), in order."""
        return [f.letter for f in self.factors]

    @property
    def lows(self) -> np.ndarray:
        """Low levels (NaN for a categoric factor)."""
        return np.array([f.low if f.kind == "numeric" else np.nan for f in self.factors])

    @property
    def highs(self) -> np.ndarray:
        """High levels (NaN for a categoric factor)."""
        return np.array([f.high if f.kind == "numeric" else np.nan for f in self.factors])

    @property
    def numeric(self) -> list:
        """The numeric factors, in order."""
        return [f for f in self.factors if f.kind == "numeric"]

    @property
    def numeric_index(self) -> list[int]:
        """Positions of the numeric factors."""
        return [i for i, f in enumerate(self.factors) if f.kind == "numeric"]

    @property
    def categoric(self) -> dict:
        """``{position: levels}`` of the categoric factors (what the model terms need)."""
        return {i: f.levels for i, f in enumerate(self.factors) if isinstance(f, CategoricFactor)}

    @property
    def has_categoric(self) -> bool:
        """Whether any factor is categoric."""
        return any(f.kind == "categoric" for f in self.factors)

    @property
    def components(self) -> list:
        """The mixture components (:class:`~rsm_lrg.factors.component.MixtureComponent`), first
        in the space; empty when the region is a box (no mixture)."""
        return [f for f in self.factors if isinstance(f, MixtureComponent)]

    @property
    def has_components(self) -> bool:
        """Whether the region is (part) a simplex: the space holds mixture components."""
        return bool(self.components)

    def level_combinations(self) -> list[dict]:
        """Every combination of the categoric factors' levels, ``[{name: level}, ...]``
        (the first factor's level changing slowest; ``[{}]`` when there is none).

        Returns
        -------
        list of dict
            ``[{name: level}, ...]``.
        """
        import itertools

        cats = [f for f in self.factors if isinstance(f, CategoricFactor)]
        return [dict(zip([f.name for f in cats], combo)) for combo in itertools.product(*[f.levels for f in cats])]

    # -- coding ---------------------------------------------------------------------
    def encode(self, actual):
        """Actual -> coded.

        ``actual`` is an (n, k) array (columns in factor order; an object array holding the
        levels of categoric factors), a mapping ``{name: value}``, or a DataFrame with the
        factor names as columns. Arrays give arrays, mappings give ``{letter: value}``,
        frames give a frame whose columns are the letters. A categoric factor codes to its
        level index (0 .. L-1).

        Parameters
        ----------
        actual : array_like, mapping, pandas.DataFrame or rsm_lrg.table.ColumnTable
            Settings in actual units: an (n, k) array in factor order, ``{name: value}`` or a
            table with the factor columns.

        Returns
        -------
        numpy.ndarray, dict, pandas.DataFrame or rsm_lrg.table.ColumnTable
            The coded settings (a table of the same kind keyed by letter for a table).
        """
        if is_column_table(actual):  # a plain CSV file read without pandas: a table keyed by letter
            return ColumnTable({f.letter: encode_column(actual, f) for f in self.factors})
        if isinstance(actual, Mapping):
            return {f.letter: f.encode(actual[f.name]) for f in self.factors}
        import pandas as pd

        if isinstance(actual, pd.DataFrame):
            return pd.DataFrame({f.letter: encode_column(actual, f) for f in self.factors}, index=actual.index)
        a = np.asarray(actual, dtype=object if self.has_categoric else float)
        cols = [f.encode(a[..., i] if f.kind == "categoric" else np.asarray(a[..., i], dtype=float))
                for i, f in enumerate(self.factors)]
        return np.stack(cols, axis=-1).astype(float)

    def decode(self, coded):
        """Coded -> actual; the inverse of :meth:`encode` (frames keyed by letter; a
        categoric factor decodes to its level, so arrays with one are object arrays).

        Parameters
        ----------
        coded : array_like or pandas.DataFrame
            Coded settings (an (n, k) array, or a frame keyed by letter).

        Returns
        -------
        numpy.ndarray or pandas.DataFrame
            The actual settings [the factors' units].
        """
        import pandas as pd

        if isinstance(coded, pd.DataFrame):
            return pd.DataFrame({f.name: f.decode(coded[f.letter].to_numpy(dtype=float)) for f in self.factors}, index=coded.index)
        if isinstance(coded, Mapping):
            return {f.name: f.decode(coded[f.letter]) for f in self.factors}
        c = np.asarray(coded, dtype=float)
        cols = [f.decode(c[..., i]) for i, f in enumerate(self.factors)]
        return np.stack(cols, axis=-1)

    def to_list(self) -> list[dict]:
        """``[{"letter", "name", "kind", "low", "high"} or {..., "levels"}, ...]`` as in the fit JSON.

        Returns
        -------
        dict
            Plain JSON-safe data (numbers, strings, lists and dicts).
        """
        return [f.to_dict() for f in self.factors]

def encode_column(data, f) -> np.ndarray:
    """One factor column of a frame coded; errors name the column and the 1-based row.

    Parameters
    ----------
    data : pandas.DataFrame or rsm_lrg.table.ColumnTable
        The table.
    f : FactorLike
        The factor.

    Returns
    -------
    numpy.ndarray
        The coded column(s).
    """
    if f.kind == "numeric":
        return f.encode(float_values(data, f.name))
    col = data[f.name]
    lut = {v: float(i) for i, v in enumerate(f.levels)}
    out = np.empty(len(col))
    for j, v in enumerate(col.tolist()):
        key = None if is_empty_cell(v) else level_text(v)
        if key not in lut:
            where = f"column {quote_value(f.name)}, row {j + 1}"
            if key is None:
                raise ValueError(f"{where}: is empty")
            raise ValueError(f"{where}: holds {quote_value(key)}, not one of the levels of categoric factor "
                             f"{quote_value(f.name)} ({name_list(list(f.levels))})")
        out[j] = lut[key]
    return out

def design_space(found: list) -> FactorSpace:
    """The factor space of :func:`design_factors`' pairs, letters in coded-column order
    (``(name, low, high)`` numeric, ``(name, levels)`` categoric).

    Parameters
    ----------
    found : list
        :func:`design_factors`' pairs.

    Returns
    -------
    FactorSpace
        The design's factors.
    """
    letters = letters_for(len(found))
    factors: list[Any] = [CategoricFactor(it[0], it[1], L) if len(it) == 2 else Factor(it[0], it[1], it[2], L)
                          for it, L in zip(found, letters)]
    return FactorSpace(tuple(factors))


def inferred_space(how: str, items: list) -> FactorSpace:
    """The factor space of :func:`~rsm_lrg.factors.columns.infer_items`' items: a design's
    factors in coded-column order (:func:`design_space`), else numeric factors first
    (:meth:`FactorSpace.from_items`).

    Parameters
    ----------
    how : str
        How the items were found (``"design"`` or otherwise).
    items : list
        The items.

    Returns
    -------
    FactorSpace
        The factors.
    """
    return design_space(items) if how == "design" else FactorSpace.from_items(items)
