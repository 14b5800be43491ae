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
from typing import Any

import numpy as np

__all__ = ["Factor", "FactorSpace", "FactorChoice", "choose_factors", "letters_for", "parse_factor_spec",
           "check_factor_name", "quote_value", "CODED_DECIMALS"]

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
        return {"letter": self.letter, "name": self.name, "low": self.low, "high": self.high}


_SPEC = re.compile(r"^\s*(?P<name>[^=]+?)\s*(=\s*(?P<low>[^:]+?)\s*:\s*(?P<high>.+?)\s*)?$")


def parse_factor_spec(spec: str) -> tuple[str, float | None, float | None]:
    """Parse ``NAME`` or ``NAME=LOW:HIGH`` (the CLI's ``--factor``).

    >>> parse_factor_spec("velocity_m_s=0.4:0.6")
    ('velocity_m_s', 0.4, 0.6)
    >>> parse_factor_spec("stroke_m")
    ('stroke_m', None, None)
    """
    if not isinstance(spec, str) or not spec.strip():
        raise ValueError("empty factor specification; expected NAME or NAME=LOW:HIGH")
    if "=" in spec and ":" not in spec.split("=", 1)[1]:
        raise ValueError(f"factor {quote_value(spec)}: expected NAME=LOW:HIGH")
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
        """From ``{name: (low, high)}`` or ``[(name, low, high), ...]``, in order."""
        items = list(ranges.items()) if isinstance(ranges, Mapping) else [(n, (lo, hi)) for n, lo, hi in ranges]
        letters = letters_for(len(items))
        return cls(tuple(Factor(n, lo, hi, L) for (n, (lo, hi)), L in zip(items, letters)))

    @classmethod
    def from_specs(cls, specs: Sequence[str]) -> FactorSpace:
        """From ``["NAME=LOW:HIGH", ...]``; every spec must carry its levels."""
        items = []
        for s in specs:
            name, low, high = parse_factor_spec(s)
            if low is None:
                raise ValueError(f"factor {quote_value(name)}: levels are needed here; write NAME=LOW:HIGH")
            items.append((name, low, high))
        return cls.from_ranges(items)

    @classmethod
    def from_data(cls, data, factors: Sequence[Any] | None = None, *, exclude: Iterable[str] = ()) -> FactorSpace:
        """Factor space for a data frame (the ``space`` of :func:`choose_factors`).

        Parameters
        ----------
        data : pandas.DataFrame
        factors : sequence, FactorSpace or None
            ``None``: inferred (see :func:`choose_factors`): a design's factors when the
            data carry a design's ``coded_A``, ``coded_B``, ... columns, else every numeric
            column that is not in ``exclude``, not a bookkeeping column (``run``,
            ``order``, ``std``, ``std_order``, ``run_order``, ``block``). Otherwise items
            that are names, ``"NAME=LOW:HIGH"`` strings, ``(name, low, high)`` tuples or
            :class:`Factor` objects; a name without levels takes the observed minimum and
            maximum of its column.
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
        return np.array([f.low for f in self.factors])

    @property
    def highs(self) -> np.ndarray:
        return np.array([f.high for f in self.factors])

    # -- coding ---------------------------------------------------------------------
    def encode(self, actual):
        """Actual -> coded.

        ``actual`` is an (n, k) array (columns in factor order), a mapping
        ``{name: value}``, or a DataFrame with the factor names as columns. Arrays give
        arrays, mappings give ``{letter: value}``, frames give a frame whose columns are
        the letters.
        """
        import pandas as pd

        if isinstance(actual, pd.DataFrame):
            return pd.DataFrame({f.letter: f.encode(_numeric(actual, f.name).to_numpy()) for f in self.factors}, index=actual.index)
        if isinstance(actual, Mapping):
            return {f.letter: f.encode(actual[f.name]) for f in self.factors}
        a = np.asarray(actual, dtype=float)
        cols = [f.encode(a[..., i]) for i, f in enumerate(self.factors)]
        return np.stack(cols, axis=-1)

    def decode(self, coded):
        """Coded -> actual; the inverse of :meth:`encode` (frames keyed by letter)."""
        import pandas as pd

        if isinstance(coded, pd.DataFrame):
            return pd.DataFrame({f.name: f.decode(coded[f.letter].to_numpy(dtype=float)) for f in self.factors}, index=coded.index)
        if isinstance(coded, Mapping):
            return {f.name: f.decode(coded[f.letter]) for f in self.factors}
        c = np.asarray(coded, dtype=float)
        cols = [f.decode(c[..., i]) for i, f in enumerate(self.factors)]
        return np.stack(cols, axis=-1)

    def to_list(self) -> list[dict]:
        """``[{"letter", "name", "low", "high"}, ...]`` as in the fit JSON."""
        return [f.to_dict() for f in self.factors]


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
        how, space = "design", FactorSpace.from_ranges(out)
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
            items: list[Any] = [(n, None, None) for n in names]  # column names, never NAME=LOW:HIGH specs
            if not items:
                raise ValueError("no numeric factor columns found in the data")
        else:
            how = "given"
            if isinstance(factors, str):
                factors = [factors]
            items = list(factors)
        parsed: list[tuple[str, float | None, float | None]] = []
        for it in items:
            if isinstance(it, Factor):
                parsed.append((it.name, it.low, it.high))
            elif isinstance(it, str):
                parsed.append(parse_factor_spec(it) if "=" in it else (it, None, None))
            else:
                n, lo, hi = it
                parsed.append((n, lo, hi))
        ranged = []
        for name, low, high in parsed:
            if name not in data.columns:
                raise ValueError(f"factor column {quote_value(str(name))} is not in the data")
            if name in exclude:
                raise ValueError(f"column {quote_value(str(name))} cannot be both a factor and the response or block")
            if low is None:
                check_factor_name(name)
                col = _numeric(data, name)
                low, high = float(col.min()), float(col.max())
                if not low < high:
                    raise ValueError(f"factor column {quote_value(str(name))} is constant ({low:g}); "
                                     "a factor needs at least two levels")
            ranged.append((name, low, high))
        space = FactorSpace.from_ranges(ranged)
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
        notes.append(f"Numeric column{'s' if len(numeric_unused) > 1 else ''} left out (not a factor, response or "
                     f"block): {_names(numeric_unused)}.")
    blocks = [c for c in numeric_unused if str(c).lower() == "block"]
    if blocks:
        notes.append(f"Column {blocks[0]} looks like a design's block column; give --block {blocks[0]} to fit "
                     "block effects.")
    if text:
        notes.append(f"Text column{'s' if len(text) > 1 else ''} left out (not a factor, response or block): "
                     f"{_names(text)}.")
    return FactorChoice(space=space, how=how, coded_columns=tuple(coded_used), unused=tuple(unused),
                        text_columns=tuple(text), notes=tuple(notes))
