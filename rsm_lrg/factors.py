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

__all__ = ["Factor", "FactorSpace", "letters_for", "parse_factor_spec", "CODED_DECIMALS"]

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


def finite_float(value: Any, what: str) -> float:
    """``float(value)``, or a ValueError naming ``what`` if it is not a finite number."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{what}: {value!r} is not a number") from None
    if not math.isfinite(x):
        raise ValueError(f"{what}: {value!r} is not a finite number")
    return x


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
        if not isinstance(self.name, str) or not self.name:
            raise ValueError("a factor needs a non-empty name")
        low = finite_float(self.low, f"factor {self.name!r}: low level")
        high = finite_float(self.high, f"factor {self.name!r}: high level")
        if not low < high:
            raise ValueError(
                f"factor {self.name!r}: LOW must be below HIGH (got {low:g} >= {high:g})"
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
        raise ValueError(f"factor {spec!r}: expected NAME=LOW:HIGH")
    m = _SPEC.match(spec)
    if not m:
        raise ValueError(f"factor {spec!r}: expected NAME or NAME=LOW:HIGH")
    name = m.group("name")
    if m.group("low") is None:
        return name, None, None
    low = finite_float(m.group("low"), f"factor {name!r}: LOW")
    high = finite_float(m.group("high"), f"factor {name!r}: HIGH")
    if not low < high:
        raise ValueError(f"factor {name!r}: LOW must be below HIGH (got {low:g} >= {high:g})")
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
            raise ValueError(f"factor {sorted(dup)[0]!r} is given more than once")
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
                raise ValueError(f"factor {name!r}: levels are needed here; write {name}=LOW:HIGH")
            items.append((name, low, high))
        return cls.from_ranges(items)

    @classmethod
    def from_data(cls, data, factors: Sequence[Any] | None = None, *, exclude: Iterable[str] = ()) -> FactorSpace:
        """Factor space for a data frame.

        Parameters
        ----------
        data : pandas.DataFrame
        factors : sequence, FactorSpace or None
            ``None``: every numeric column not in ``exclude``, not a bookkeeping
            column (``run``, ``order``, ``std``, ``std_order``, ``run_order``) and not a
            coded column of a design CSV (name starting ``coded_``). Otherwise
            items that are names, ``"NAME=LOW:HIGH"`` strings, ``(name, low, high)``
            tuples or :class:`Factor` objects; a name without levels takes the observed
            minimum and maximum of its column.
        exclude : iterable of str
            Columns never taken as factors (the response, the block column).
        """
        if isinstance(factors, FactorSpace):
            for f in factors.factors:
                if f.name not in data.columns:
                    raise ValueError(f"factor column {f.name!r} is not in the data")
            return factors
        exclude = set(exclude)
        if factors is None:
            import pandas as pd

            names = [
                c for c in data.columns
                if c not in exclude and str(c).lower() not in BOOKKEEPING
                and not str(c).lower().startswith(CODED_COLUMN_PREFIX)
                and pd.api.types.is_numeric_dtype(data[c]) and not pd.api.types.is_bool_dtype(data[c])
            ]
            items: list[Any] = [(n, None, None) for n in names]  # column names, never NAME=LOW:HIGH specs
            if not items:
                raise ValueError("no numeric factor columns found in the data")
        else:
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
        out = []
        for name, low, high in parsed:
            if name not in data.columns:
                raise ValueError(f"factor column {name!r} is not in the data")
            if name in exclude:
                raise ValueError(f"column {name!r} cannot be both a factor and the response or block")
            if low is None:
                col = _numeric(data, name)
                low, high = float(col.min()), float(col.max())
                if not low < high:
                    raise ValueError(f"factor column {name!r} is constant ({low:g}); a factor needs at least two levels")
            out.append((name, low, high))
        return cls.from_ranges(out)

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


def _numeric(data, name: str):
    """The column ``name`` as floats, or a ValueError naming the first bad row."""
    import pandas as pd

    col = data[name]
    num = pd.to_numeric(col, errors="coerce")
    bad = num.isna() | ~np.isfinite(num.to_numpy(dtype=float, na_value=np.nan))
    if bad.any():
        i = int(np.flatnonzero(bad.to_numpy())[0])
        raw = col.iloc[i]
        what = "is empty" if (raw is None or (isinstance(raw, float) and math.isnan(raw)) or str(raw).strip() == "") else f"holds {raw!r}, not a finite number"
        raise ValueError(f"column {name!r}, row {i + 1}: {what}")
    return num.astype(float)
