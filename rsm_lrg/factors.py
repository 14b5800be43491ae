"""Factors and their coding: the space a design lives in.

A :class:`FactorSpace` holds named factors with a low and a high level and a letter
(A, B, C, ...). It codes actual values to the [-1, +1] scale of response-surface work,

    coded = (x - (low + high) / 2) / ((high - low) / 2),

and back. It follows the shape of scikit-learn's ``MinMaxScaler`` and of R ``rsm``'s
``coded.data``: the coding travels with the data, so every later result (coefficients,
stationary point, optimum) can be given in coded and in actual units.

The low and high levels map to exactly -1 and +1 and back; coded values are rounded to
12 decimals so that a centre level given in a CSV (0.0003 between 0.0001 and 0.0005, say)
codes to exactly 0 and replicate detection does not trip over the last bit.
"""

from __future__ import annotations

import math
import re
import string
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

__all__ = ["Factor", "CategoricFactor", "FactorSpace", "FactorChoice", "choose_factors", "letters_for",
           "parse_factor_spec", "parse_factor", "level_text", "check_factor_name", "quote_value", "CODED_DECIMALS"]

#: Decimals kept in coded values (see the module docstring).
CODED_DECIMALS = 12


def letters_for(k: int) -> list[str]:
    """Design-Expert's factor letters: A, B, ..., H, J, ... (no I), then A1, B1, ...

    >>> letters_for(4)
    ['A', 'B', 'C', 'D']
    >>> letters_for(10)[-2:]
    ['J', 'K']
    """
    if k < 0:
        raise ValueError("the number of factors must not be negative")
    alphabet = [c for c in string.ascii_uppercase if c != "I"]
    out = []
    for i in range(k):
        base = alphabet[i % len(alphabet)]
        rnd = i // len(alphabet)
        out.append(base if rnd == 0 else f"{base}{rnd}")
    return out


#: Longest piece of user data quoted in a message (characters).
QUOTE_LIMIT = 40


def quote_value(value: Any, limit: int = QUOTE_LIMIT) -> str:
    """A user's value quoted for an error message, cut to about ``limit`` characters with '…'
    (:func:`rsm_lrg.io.quote_user_value`; a 10 MB cell or a 300-digit number stays short).

    >>> quote_value("fast")
    "'fast'"
    >>> len(quote_value("9" * 300)) <= QUOTE_LIMIT + 2
    True
    """
    from .io import quote_user_value

    return quote_user_value(value, limit)


def finite_float(value: Any, what: str) -> float:
    """``float(value)``, or a ValueError naming ``what`` if it is not a finite number."""
    try:
        x = float(value)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"{what}: {quote_value(value)} is not a number") from None
    if not math.isfinite(x):
        raise ValueError(f"{what}: {quote_value(value)} is not a finite number")
    return x


#: Names a factor may not take (any case): a design CSV's own columns.
RESERVED_FACTOR_NAMES = ("std_order", "run_order", "block", "run", "order", "std")


def check_factor_name(name: Any) -> str:
    """``name`` if it can name a factor, else a ValueError saying why.

    A factor may not be named like a column a design CSV writes for itself
    (``std_order``, ``run_order``, ``block``, ``coded_A``, ...) or like a bookkeeping
    column (``run``, ``order``, ``std``): such a factor would be written and then not read
    back as a factor.

    >>> check_factor_name("stroke_m")
    'stroke_m'
    """
    if not isinstance(name, str) or not name.strip():
        raise ValueError("a factor needs a non-empty name")
    low = name.strip().lower()
    if low in RESERVED_FACTOR_NAMES or low.startswith("coded_"):
        raise ValueError(
            f"factor name {quote_value(name)} is reserved for a design's own columns "
            "(std_order, run_order, block, coded_A, ...; also run, order, std); choose another name"
        )
    return name


@dataclass(frozen=True)
class Factor:
    """One factor: a name, its low and high level in actual units, its letter.

    Parameters
    ----------
    name : str
        Column name in the data (for the paper's guide e.g. ``"thickness_m"``).
    low, high : float
        Levels coded -1 and +1, in the factor's actual units; ``low < high``.
    letter : str
        Short name used in model terms (``"A"``, ``"AB"``, ``"A^2"``).
    """

    name: str
    low: float
    high: float
    letter: str

    #: The factor's kind (``"numeric"``; :class:`CategoricFactor` is ``"categoric"``).
    kind: ClassVar[str] = "numeric"

    def __post_init__(self) -> None:
        check_factor_name(self.name)
        low = finite_float(self.low, f"factor {quote_value(self.name)}: low level")
        high = finite_float(self.high, f"factor {quote_value(self.name)}: high level")
        if not low < high:
            raise ValueError(
                f"factor {quote_value(self.name)}: LOW must be below HIGH (got {low:g} >= {high:g})"
            )
        object.__setattr__(self, "low", low)
        object.__setattr__(self, "high", high)

    @property
    def center(self) -> float:
        """Level coded 0 [actual units]."""
        return (self.low + self.high) / 2.0

    @property
    def half_range(self) -> float:
        """Actual units per coded unit."""
        return (self.high - self.low) / 2.0

    def encode(self, x):
        """Actual value(s) to coded value(s); low -> -1 and high -> +1 exactly."""
        x = np.asarray(x, dtype=float)
        c = ((x - self.low) - (self.high - x)) / (self.high - self.low)
        c = np.round(c, CODED_DECIMALS) + 0.0  # + 0.0 turns -0.0 into 0.0
        return c if c.ndim else float(c)

    def decode(self, c):
        """Coded value(s) to actual value(s); -1 -> low and +1 -> high exactly."""
        c = np.asarray(c, dtype=float)
        x = ((1.0 - c) * self.low + (1.0 + c) * self.high) / 2.0
        return x if x.ndim else float(x)

    def to_dict(self) -> dict:
        return {"letter": self.letter, "name": self.name, "kind": "numeric", "low": self.low, "high": self.high}


def level_text(value: Any) -> str:
    """A categoric level as written: text as it is, whole numbers without ``.0``, other
    numbers with up to 15 significant digits.

    >>> level_text("rms"), level_text(2), level_text(2.0), level_text(0.1)
    ('rms', '2', '2', '0.1')
    """
    if isinstance(value, str):
        return value
    if isinstance(value, (bool, np.bool_)):
        return str(bool(value))
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        v = float(value)
        return str(int(v)) if v.is_integer() and abs(v) < 1e15 else f"{v:.15g}"
    return str(value)


@dataclass(frozen=True)
class CategoricFactor:
    """A categoric (nominal) factor: a name, its levels in order, its letter.

    In a coded settings array the factor holds its level index (0 .. L-1); in the model it
    has L - 1 sum-to-zero (effect) columns, one per level but the last
    (:func:`rsm_lrg.terms.effect_codes`), as Design-Expert and R's ``contr.sum`` code it.

    Parameters
    ----------
    name : str
        Column name (e.g. ``"stage"``).
    levels : sequence of str
        The levels as written in the data, in order (at least two, distinct).
    letter : str

    >>> f = CategoricFactor("stage", ("rfcms", "rms"), "E")
    >>> f.encode(["rms", "rfcms"]).tolist(), f.decode(1.0)
    ([1.0, 0.0], 'rms')
    """

    name: str
    levels: tuple
    letter: str

    kind: ClassVar[str] = "categoric"

    def __post_init__(self) -> None:
        check_factor_name(self.name)
        levels = tuple(level_text(v) for v in self.levels)
        if len(levels) < 2:
            raise ValueError(f"categoric factor {quote_value(self.name)} needs at least two levels")
        if len(set(levels)) != len(levels):
            dup = next(v for v in levels if levels.count(v) > 1)
            raise ValueError(f"categoric factor {quote_value(self.name)}: level {quote_value(dup)} is given twice")
        if any(not v.strip() for v in levels):
            raise ValueError(f"categoric factor {quote_value(self.name)}: a level is empty")
        object.__setattr__(self, "levels", levels)

    @property
    def n_levels(self) -> int:
        return len(self.levels)

    def index(self, value: Any) -> int:
        """Level index of ``value`` (a level as written, or its text), or a ValueError."""
        key = level_text(value)
        try:
            return self.levels.index(key)
        except ValueError:
            raise ValueError(f"factor {quote_value(self.name)}: {quote_value(key)} is not one of its levels "
                             f"({', '.join(self.levels)})") from None

    def encode(self, x):
        """Level(s) to level index (float; an array for an array)."""
        if isinstance(x, (str, bytes)) or np.ndim(x) == 0:
            return float(self.index(x.item() if isinstance(x, np.generic) else x))
        vals = np.asarray(x, dtype=object).ravel()
        lut = {v: float(i) for i, v in enumerate(self.levels)}
        out = np.empty(vals.size)
        for j, v in enumerate(vals):
            key = level_text(v)
            if key not in lut:
                self.index(key)  # raises, naming the value
            out[j] = lut[key]
        return out.reshape(np.shape(x))

    def decode(self, c):
        """Level index (indices) to level name(s)."""
        if np.ndim(c) == 0:
            return self.levels[self._checked(c)]
        return np.array([self.levels[self._checked(v)] for v in np.ravel(c)], dtype=object).reshape(np.shape(c))

    def _checked(self, c) -> int:
        v = float(c)
        if not (v.is_integer() and 0 <= v < len(self.levels)):
            raise ValueError(f"factor {quote_value(self.name)}: {c!r} is not a level index 0..{len(self.levels) - 1}")
        return int(v)

    def to_dict(self) -> dict:
        return {"letter": self.letter, "name": self.name, "kind": "categoric", "levels": list(self.levels)}


#: ``NAME=cat`` or ``NAME=cat:L1,L2,...`` (a categoric factor spec).
_CAT_SPEC = re.compile(r"^\s*(?P<name>[^=]+?)\s*=\s*cat(?:egoric)?\s*(?::(?P<levels>.*))?$", re.IGNORECASE | re.DOTALL)


def parse_factor(spec: str) -> tuple:
    """Parse a ``--factor`` spec of either kind.

    Returns ``("numeric", name, low, high)`` (``low``/``high`` None for a bare name) or
    ``("categoric", name, levels)`` (``levels`` None for ``NAME=cat``: in order of appearance).

    >>> parse_factor("stage=cat:rfcms,rms")
    ('categoric', 'stage', ('rfcms', 'rms'))
    >>> parse_factor("stage=cat"), parse_factor("v=0.4:0.6")
    (('categoric', 'stage', None), ('numeric', 'v', 0.4, 0.6))
    """
    if isinstance(spec, str):
        m = _CAT_SPEC.match(spec)
        if m:
            name = m.group("name")
            if m.group("levels") is None:
                return "categoric", name, None
            levels = tuple(v.strip() for v in m.group("levels").split(","))
            if len(levels) < 2 or any(not v for v in levels):
                raise ValueError(f"factor {quote_value(name)}: expected NAME=cat:L1,L2,... with two or more "
                                 "non-empty levels")
            if len(set(levels)) != len(levels):
                raise ValueError(f"factor {quote_value(name)}: a level is given twice")
            return "categoric", name, levels
    return ("numeric", *parse_factor_spec(spec))


_SPEC = re.compile(r"^\s*(?P<name>[^=]+?)\s*(=\s*(?P<low>[^:]+?)\s*:\s*(?P<high>.+?)\s*)?$")


def parse_factor_spec(spec: str) -> tuple[str, float | None, float | None]:
    """Parse ``NAME`` or ``NAME=LOW:HIGH`` (the CLI's ``--factor``).

    >>> parse_factor_spec("velocity_m_s=0.4:0.6")
    ('velocity_m_s', 0.4, 0.6)
    >>> parse_factor_spec("stroke_m")
    ('stroke_m', None, None)
    """
    if not isinstance(spec, str) or not spec.strip():
        raise ValueError("empty factor specification; expected NAME, NAME=LOW:HIGH or NAME=cat[:L1,L2,...]")
    if "=" in spec and ":" not in spec.split("=", 1)[1]:
        raise ValueError(f"factor {quote_value(spec)}: expected NAME=LOW:HIGH (or NAME=cat for a categoric factor)")
    m = _SPEC.match(spec)
    if not m:
        raise ValueError(f"factor {quote_value(spec)}: expected NAME or NAME=LOW:HIGH")
    name = m.group("name")
    if m.group("low") is None:
        return name, None, None
    low = finite_float(m.group("low"), f"factor {quote_value(name)}: LOW")
    high = finite_float(m.group("high"), f"factor {quote_value(name)}: HIGH")
    if not low < high:
        raise ValueError(f"factor {quote_value(name)}: LOW must be below HIGH (got {low:g} >= {high:g})")
    return name, low, high


@dataclass(frozen=True)
class FactorSpace:
    """An ordered set of factors with letters A, B, C, ...

    Build it with :meth:`from_ranges` (names and levels), :meth:`from_specs` (CLI-style
    ``NAME=LOW:HIGH`` strings) or :meth:`from_data` (levels from the data's observed
    minimum and maximum where not given).
    """

    factors: tuple[Factor, ...]

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
        """From ``{name: (low, high)}`` or ``[(name, low, high), ...]``, in order (numeric factors)."""
        items = list(ranges.items()) if isinstance(ranges, Mapping) else [(n, (lo, hi)) for n, lo, hi in ranges]
        letters = letters_for(len(items))
        return cls(tuple(Factor(n, lo, hi, L) for (n, (lo, hi)), L in zip(items, letters)))

    @classmethod
    def from_items(cls, items: Iterable[tuple]) -> FactorSpace:
        """From ``("numeric", name, low, high)`` and ``("categoric", name, levels)`` items.

        Letters go to the numeric factors first, in the order given, then to the categoric
        ones (Design-Expert's convention), and the factors are held in letter order.
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
        """From ``["NAME=LOW:HIGH", "NAME=cat:L1,L2", ...]``; every spec must carry its levels."""
        return cls.from_items([_spec_with_levels(s) for s in specs])

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
        """
        return choose_factors(data, factors, exclude=exclude).space

    # -- views ----------------------------------------------------------------------
    def __len__(self) -> int:
        return len(self.factors)

    def __iter__(self):
        return iter(self.factors)

    def __getitem__(self, key: int | str) -> Factor:
        if isinstance(key, int):
            return self.factors[key]
        for f in self.factors:
            if key in (f.name, f.letter):
                return f
        raise KeyError(key)

    @property
    def names(self) -> list[str]:
        return [f.name for f in self.factors]

    @property
    def letters(self) -> list[str]:
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
        return {i: f.levels for i, f in enumerate(self.factors) if f.kind == "categoric"}

    @property
    def has_categoric(self) -> bool:
        return any(f.kind == "categoric" for f in self.factors)

    def level_combinations(self) -> list[dict]:
        """Every combination of the categoric factors' levels, ``[{name: level}, ...]``
        (the first factor's level changing slowest; ``[{}]`` when there is none)."""
        import itertools

        cats = [f for f in self.factors if f.kind == "categoric"]
        return [dict(zip([f.name for f in cats], combo)) for combo in itertools.product(*[f.levels for f in cats])]

    # -- coding ---------------------------------------------------------------------
    def encode(self, actual):
        """Actual -> coded.

        ``actual`` is an (n, k) array (columns in factor order; an object array holding the
        levels of categoric factors), a mapping ``{name: value}``, or a DataFrame with the
        factor names as columns. Arrays give arrays, mappings give ``{letter: value}``,
        frames give a frame whose columns are the letters. A categoric factor codes to its
        level index (0 .. L-1).
        """
        import pandas as pd

        if isinstance(actual, pd.DataFrame):
            return pd.DataFrame({f.letter: _encode_column(actual, f) for f in self.factors}, index=actual.index)
        if isinstance(actual, Mapping):
            return {f.letter: f.encode(actual[f.name]) for f in self.factors}
        a = np.asarray(actual, dtype=object if self.has_categoric else float)
        cols = [f.encode(a[..., i] if f.kind == "categoric" else np.asarray(a[..., i], dtype=float))
                for i, f in enumerate(self.factors)]
        return np.stack(cols, axis=-1).astype(float)

    def decode(self, coded):
        """Coded -> actual; the inverse of :meth:`encode` (frames keyed by letter; a
        categoric factor decodes to its level, so arrays with one are object arrays)."""
        import pandas as pd

        if isinstance(coded, pd.DataFrame):
            return pd.DataFrame({f.name: f.decode(coded[f.letter].to_numpy(dtype=float)) for f in self.factors}, index=coded.index)
        if isinstance(coded, Mapping):
            return {f.name: f.decode(coded[f.letter]) for f in self.factors}
        c = np.asarray(coded, dtype=float)
        cols = [f.decode(c[..., i]) for i, f in enumerate(self.factors)]
        return np.stack(cols, axis=-1)

    def to_list(self) -> list[dict]:
        """``[{"letter", "name", "kind", "low", "high"} or {..., "levels"}, ...]`` as in the fit JSON."""
        return [f.to_dict() for f in self.factors]


def _encode_column(data, f) -> np.ndarray:
    """One factor column of a frame coded; errors name the column and the 1-based row."""
    if f.kind == "numeric":
        return f.encode(_numeric(data, f.name).to_numpy())
    col = data[f.name]
    lut = {v: float(i) for i, v in enumerate(f.levels)}
    out = np.empty(len(col))
    for j, v in enumerate(col.tolist()):
        key = None if _is_empty(v) else level_text(v)
        if key not in lut:
            where = f"column {quote_value(f.name)}, row {j + 1}"
            if key is None:
                raise ValueError(f"{where}: is empty")
            raise ValueError(f"{where}: holds {quote_value(key)}, not one of the levels of categoric factor "
                             f"{quote_value(f.name)} ({_names(list(f.levels))})")
        out[j] = lut[key]
    return out


#: Column names that are never factors (case-insensitive).
BOOKKEEPING = frozenset({"run", "order", "std", "std_order", "run_order"})

#: Columns whose lower-cased name starts with this are a design CSV's coded copies of the
#: factors (``coded_A``, ...); never picked as factors by default.
CODED_COLUMN_PREFIX = "coded_"

#: Relative tolerance of the coded/actual pairing (a design written with 10 significant
#: digits, as ``simulate`` writes it, pairs well inside it).
PAIR_RTOL = 1e-7

#: At most this many names are listed in one note (then "and N more").
_LIST_LIMIT = 20

#: A design's coded column: ``coded_`` and a factor letter (``coded_A``, ``coded_B1``; any case).
_DESIGN_CODED = re.compile(r"^coded_[a-z][0-9]*$", re.IGNORECASE)

_COMMA_NUMBER = re.compile(r"^\s*[+-]?(\d{1,3}(,\d{3})+(\.\d*)?|\d*,\d+)\s*$")


def _is_empty(raw) -> bool:
    return raw is None or (isinstance(raw, float) and math.isnan(raw)) or str(raw).strip() == "" \
        or type(raw).__name__ in ("NAType", "NaTType")


def _bad_cell(name: str, row: int, raw) -> ValueError:
    """The error for one bad cell (row is 1-based): empty, a comma number, or not a number."""
    where = f"column {quote_value(name)}, row {row}"
    if _is_empty(raw):
        return ValueError(f"{where}: is empty")
    if isinstance(raw, str) and _COMMA_NUMBER.match(raw):
        return ValueError(f"{where}: holds {quote_value(raw.strip())}, a number with a comma (a thousands "
                          "separator or a decimal comma is ambiguous); write it with a decimal point and no commas")
    return ValueError(f"{where}: holds {quote_value(raw)}, not a finite number")


def _numeric(data, name: str):
    """The column ``name`` as floats, or a ValueError naming the first bad row (1-based)."""
    import pandas as pd

    col = data[name]
    num = pd.to_numeric(col, errors="coerce")
    bad = num.isna() | ~np.isfinite(num.to_numpy(dtype=float, na_value=np.nan))
    if bad.any():
        i = int(np.flatnonzero(bad.to_numpy())[0])
        raise _bad_cell(name, i + 1, col.iloc[i])
    return num.astype(float)


def _names(cols, limit: int = _LIST_LIMIT) -> str:
    """``a, b, c and 3 more``; each name cut to QUOTE_LIMIT characters."""
    shown = [str(c) if len(str(c)) <= QUOTE_LIMIT else str(c)[:QUOTE_LIMIT] + "…" for c in cols[:limit]]
    more = len(cols) - limit
    return ", ".join(shown) + (f" and {more} more" if more > 0 else "")


def is_bookkeeping(column) -> bool:
    """A design's or a lab sheet's own column: never a factor and never listed as unused
    (``run``, ``order``, ``std``, ``std_order``, ``run_order``, ``coded_*``; any case)."""
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
    """

    space: FactorSpace
    how: str
    coded_columns: tuple = ()
    unused: tuple = ()
    text_columns: tuple = ()
    notes: tuple = ()

    @property
    def inferred(self) -> bool:
        """True when the factors were not given."""
        return self.how != "given"

    def hint(self) -> str:
        """A clause naming the inferred factors and suggesting ``--factor`` (empty when given)."""
        if not self.inferred:
            return ""
        listed = _names([f"{f.letter} {f.name}" for f in self.space.factors])
        return f"; the factors were taken to be {listed}: if that is wrong, name them with --factor NAME"


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


def _design_factors(data, coded: list, exclude: set) -> tuple[list, list]:
    """Pair each coded column with its actual column: ``([(name, low, high)], [coded col])``."""
    import pandas as pd

    cols = list(data.columns)
    last = max(cols.index(c) for c in coded)
    cand = [c for c in cols if c not in exclude and not is_bookkeeping(c) and str(c).lower() != "block"
            and pd.api.types.is_numeric_dtype(data[c]) and not pd.api.types.is_bool_dtype(data[c])]
    # the design writes the actual columns right after the coded ones, in the same order:
    # those are tried first, so column order settles any tie
    order = [c for c in cand if cols.index(c) > last] + [c for c in cand if cols.index(c) < last]
    used: set = set()
    out = []
    for cc in coded:
        if not pd.api.types.is_numeric_dtype(data[cc]) and not pd.api.types.is_bool_dtype(data[cc]):
            # a categoric factor: its coded column holds the level (Design-Expert's layout), the
            # same text as its actual column; levels in order of first appearance in std_order
            match = _design_categoric(data, cc, cols, last, exclude, used)
            used.add(match[0])
            out.append(match)
            continue
        cv = _numeric(data, cc).to_numpy(dtype=float)
        match = None
        for name in order:
            if name in used:
                continue
            levels = _pair_levels(cv, data[name].to_numpy(dtype=float, na_value=np.nan))
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

    text = [level_text(v) if not _is_empty(v) else None for v in data[cc].tolist()]
    if any(v is None for v in text):
        raise ValueError(f"the design column {quote_value(str(cc))} has an empty cell")
    cand = [c for c in cols if c not in exclude and c not in used and not is_bookkeeping(c)
            and str(c).lower() != "block"]
    cand = [c for c in cand if cols.index(c) > last] + [c for c in cand if cols.index(c) < last]
    for name in cand:
        vals = [level_text(v) if not _is_empty(v) else None for v in data[name].tolist()]
        if vals == text:
            order = range(len(text))
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


def _design_space(found: list) -> FactorSpace:
    """The factor space of :func:`_design_factors`' pairs, letters in coded-column order
    (``(name, low, high)`` numeric, ``(name, levels)`` categoric)."""
    letters = letters_for(len(found))
    return FactorSpace(tuple(CategoricFactor(it[0], it[1], L) if len(it) == 2 else Factor(*it, L)
                             for it, L in zip(found, letters)))


def _check_text_columns(data, exclude) -> None:
    """A text column that holds numbers is a typo or a locale problem (``1,234``), not a
    label: a ValueError names the column and the row."""
    import pandas as pd

    for c in data.columns:
        if c in exclude or is_bookkeeping(c) or pd.api.types.is_numeric_dtype(data[c]):
            continue
        col = data[c]
        commas = np.flatnonzero(col.astype("string").str.match(_COMMA_NUMBER.pattern).fillna(False).to_numpy(bool))
        if commas.size:
            i = int(commas[0])
            raise _bad_cell(str(c), i + 1, col.iloc[i])
        num = pd.to_numeric(col, errors="coerce")
        if num.notna().sum() >= max(1, data.shape[0] // 2):
            _numeric(data, c)  # raises "column 'c', row i: holds 'text', not a finite number"


def _is_number_column(col) -> bool:
    import pandas as pd

    if pd.api.types.is_bool_dtype(col):
        return False
    if pd.api.types.is_numeric_dtype(col):
        return True
    # mostly numbers (a typo in one cell is then an error naming its row, not a new level)
    vals = col[~np.array([_is_empty(v) for v in col.tolist()], dtype=bool)]
    return bool(len(vals)) and pd.to_numeric(vals, errors="coerce").notna().sum() * 2 >= len(vals)


def _spec_with_levels(spec) -> tuple:
    """:func:`parse_factor` of a spec that must carry its levels (``NAME=LOW:HIGH`` or
    ``NAME=cat:L1,L2,...``), for a design's factors."""
    parsed = parse_factor(spec)
    if parsed[2] is None:
        how = "NAME=cat:L1,L2,..." if parsed[0] == "categoric" else "NAME=LOW:HIGH"
        raise ValueError(f"factor {quote_value(parsed[1])}: levels are needed here; write {how}")
    return parsed


def _given_items(factors, *, need_levels: bool = False) -> list[tuple]:
    """The factors as given, as ``("numeric", name, low, high)`` / ``("categoric", name, levels)``.

    ``need_levels=False`` (factors of data, :func:`choose_factors`): a bare name, a mapping
    value ``None`` or ``"categoric"`` leave the levels (``None``) to the data, a mapping
    value is ``(low, high)`` only as a tuple of two numbers, any other sequence is levels.
    ``need_levels=True`` (a design's factors, :func:`rsm_lrg.design.as_factor_space`):
    every factor must carry its levels, and a mapping value that is not a list of texts is
    ``(low, high)``.
    """
    if isinstance(factors, str):
        factors = [factors]
    out = []
    if isinstance(factors, Mapping):
        for name, spec in factors.items():
            if isinstance(spec, (list, tuple)) and spec and all(isinstance(v, str) for v in spec):
                out.append(("categoric", name, tuple(spec)))
            elif need_levels:
                try:
                    low, high = spec
                except (TypeError, ValueError):
                    raise ValueError(f"factor {name!r}: expected a (low, high) pair, got {spec!r}") from None
                out.append(("numeric", name, low, high))
            elif spec is None:
                out.append(("numeric", name, None, None))
            elif isinstance(spec, str):
                if spec.strip().lower() not in ("categoric", "cat", "categorical"):
                    raise ValueError(f"factor {quote_value(str(name))}: {quote_value(spec)} is not a factor kind; "
                                     "give 'categoric', a list of levels, (low, high) or None")
                out.append(("categoric", name, None))
            elif isinstance(spec, tuple) and len(spec) == 2 and all(isinstance(v, (int, float, np.number)) for v in spec):
                out.append(("numeric", name, *spec))
            else:
                out.append(("categoric", name, tuple(level_text(v) for v in spec)))
        return out
    for it in factors:
        if isinstance(it, Factor):
            out.append(("numeric", it.name, it.low, it.high))
        elif isinstance(it, CategoricFactor):
            out.append(("categoric", it.name, it.levels))
        elif isinstance(it, str):
            if need_levels:
                out.append(_spec_with_levels(it))
            else:
                out.append(parse_factor(it) if "=" in it else ("numeric", it, None, None))
        else:
            try:
                name, low, high = it
            except (TypeError, ValueError):
                raise ValueError(f"factor {it!r}: expected 'NAME=LOW:HIGH' or (name, low, high)") from None
            out.append(("numeric", name, low, high))
    return out


def _categoric_levels(data, name: str, levels) -> tuple:
    """The levels of a categoric factor column: as given (every cell must be one), or in
    order of first appearance; errors name the 1-based row."""
    col = data[name].tolist()
    seen: list = []
    for j, v in enumerate(col):
        if _is_empty(v):
            raise ValueError(f"column {quote_value(name)}, row {j + 1}: is empty")
        key = level_text(v)
        if levels is not None and key not in levels:
            raise ValueError(f"column {quote_value(name)}, row {j + 1}: holds {quote_value(key)}, not one of the "
                             f"levels given for categoric factor {quote_value(name)} ({_names(list(levels))})")
        if key not in seen:
            seen.append(key)
    if levels is None:
        if len(seen) < 2:
            raise ValueError(f"categoric factor column {quote_value(name)} has only one level; a factor needs at "
                             "least two")
        return tuple(seen)
    return tuple(levels)


def choose_factors(data, factors: Any = None, *, exclude: Iterable[str] = ()) -> FactorChoice:
    """The factors of a data frame, inferred when not given, with notes on what is left out.

    Parameters
    ----------
    data : pandas.DataFrame
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
    import pandas as pd

    exclude = set(exclude)
    cols = list(data.columns)
    coded_cols = [c for c in cols if _DESIGN_CODED.match(str(c))]
    if isinstance(factors, FactorSpace):
        for f in factors.factors:
            if f.name not in data.columns:
                raise ValueError(f"factor column {quote_value(f.name)} is not in the data")
        how, space, coded_used = "given", factors, []
    elif factors is None and coded_cols:
        _check_text_columns(data, exclude)
        out, coded_used = _design_factors(data, coded_cols, exclude)
        how, space = "design", _design_space(out)
    else:
        coded_used = []
        if factors is None:
            how = "numeric"
            _check_text_columns(data, exclude)
            names = [
                c for c in cols
                if c not in exclude and not is_bookkeeping(c) and str(c).lower() != "block"
                and pd.api.types.is_numeric_dtype(data[c]) and not pd.api.types.is_bool_dtype(data[c])
            ]
            items: list[Any] = [("numeric", n, None, None) for n in names]  # column names, never specs
            if not items:
                raise ValueError("no numeric factor columns found in the data")
        else:
            how = "given"
            items = _given_items(factors)
        ranged = []
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
                col = _numeric(data, name)
                low, high = float(col.min()), float(col.max())
                if not low < high:
                    raise ValueError(f"factor column {quote_value(str(name))} is constant ({low:g}); "
                                     "a factor needs at least two levels")
            ranged.append(("numeric", name, low, high))
        space = FactorSpace.from_items(ranged)
    used = set(space.names) | exclude
    unused = [c for c in cols if c not in used and not is_bookkeeping(c)]
    text = [c for c in unused if not pd.api.types.is_numeric_dtype(data[c])]
    notes = []
    if how == "design":
        pairs = [f"{f.letter} {f.name} ({cc})" for f, cc in zip(space.factors, coded_used)]
        notes.append(f"Factors taken from the design's coded columns: {_names(pairs)}; coded as the design codes "
                     "them (name other factors with --factor).")
    elif how == "numeric":
        notes.append(f"Factors taken to be the numeric columns: {_names([f'{f.letter} {f.name}' for f in space])} "
                     "(name other factors with --factor).")
    numeric_unused = [c for c in unused if c not in text]
    if numeric_unused:
        notes.append(Note(f"Numeric column{'s' if len(numeric_unused) > 1 else ''} left out (not a factor, response "
                          f"or block): {_names(numeric_unused)}.", COLUMNS_LEFT_OUT))
    blocks = [c for c in numeric_unused if str(c).lower() == "block"]
    if blocks:
        notes.append(f"Column {blocks[0]} looks like a design's block column; give --block {blocks[0]} to fit "
                     "block effects.")
    if text:
        notes.append(Note(f"Text column{'s' if len(text) > 1 else ''} left out (not a factor, response or block): "
                          f"{_names(text)}.", COLUMNS_LEFT_OUT))
    return FactorChoice(space=space, how=how, coded_columns=tuple(coded_used), unused=tuple(unused),
                        text_columns=tuple(text), notes=tuple(notes))
