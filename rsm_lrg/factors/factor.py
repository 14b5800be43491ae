"""One factor: numeric (:class:`Factor`, coded -1 .. +1) or categoric (:class:`CategoricFactor`,
coded to its level index); :class:`FactorLike` is what both offer.

A numeric factor codes actual values to the [-1, +1] scale of response-surface work,

    coded = (x - (low + high) / 2) / ((high - low) / 2),

and back; the low and high levels map to exactly -1 and +1 and back, and coded values are
rounded to :data:`CODED_DECIMALS` decimals (see :mod:`rsm_lrg.factors`).
"""

from __future__ import annotations

import string
from dataclasses import dataclass
from typing import Any, ClassVar, Literal, Protocol, runtime_checkable

import numpy as np

from ..readers import column_name_problem
from .values import finite_float, quote_value

__all__ = ["CODED_DECIMALS", "RESERVED_FACTOR_NAMES", "FactorLike", "Factor", "CategoricFactor", "letters_for",
           "level_text", "check_factor_name"]

#: Decimals kept in coded values (see the module docstring).
CODED_DECIMALS = 12


def letters_for(k: int) -> list[str]:
    """Design-Expert's factor letters: A, B, ..., H, J, ... (no I), then A1, B1, ...

    >>> letters_for(4)
    ['A', 'B', 'C', 'D']
    >>> letters_for(10)[-2:]
    ['J', 'K']

    Parameters
    ----------
    k : int
        The number of factors.

    Returns
    -------
    list of str
        k letters.
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


#: Names a factor may not take (any case): a design CSV's own columns.
RESERVED_FACTOR_NAMES = ("std_order", "run_order", "block", "run", "order", "std")


def check_factor_name(name: Any) -> str:
    """``name`` if it can name a factor, else a ValueError saying why.

    A factor may not be named like a column a design CSV writes for itself
    (``std_order``, ``run_order``, ``block``, ``coded_A``, ...) or like a bookkeeping
    column (``run``, ``order``, ``std``): such a factor would be written and then not read
    back as a factor. Nor may it hold a control character
    (:func:`rsm_lrg.readers.column_name_problem`, the rule of every reader).

    >>> check_factor_name("stroke_m")
    'stroke_m'

    Parameters
    ----------
    name : object
        The proposed name.

    Returns
    -------
    str
        ``name``, checked.
    """
    if not isinstance(name, str) or not name.strip():
        raise ValueError("a factor needs a non-empty name")
    problem = column_name_problem(name)  # the readers' own rule: a design writes what the others read
    if problem:
        raise ValueError(problem)
    low = name.strip().lower()
    if low in RESERVED_FACTOR_NAMES or low.startswith("coded_"):
        raise ValueError(
            f"factor name {quote_value(name)} is reserved for a design's own columns "
            "(std_order, run_order, block, coded_A, ...; also run, order, std); choose another name"
        )
    return name


@runtime_checkable
class FactorLike(Protocol):
    """What every factor offers, numeric (:class:`Factor`) or categoric (:class:`CategoricFactor`).

    A factor has a ``name`` (its data column), a ``letter`` (its name in model terms), a
    ``kind`` (``"numeric"`` or ``"categoric"``), codes actual values with :meth:`encode`
    (numeric: to -1 .. +1; categoric: to the level index 0 .. L-1) and back with
    :meth:`decode`, and describes itself as the fit JSON does with :meth:`to_dict`.

    >>> isinstance(Factor("v", 0.4, 0.6, "A"), FactorLike)
    True
    >>> isinstance(CategoricFactor("stage", ("rfcms", "rms"), "B"), FactorLike)
    True
    """

    kind: ClassVar[str]

    @property
    def name(self) -> str:
        """The data column."""
        ...

    @property
    def letter(self) -> str:
        """The letter in model terms (A, B, ...)."""
        ...

    def encode(self, x: Any) -> Any:
        """Actual value(s) to coded value(s).

        Parameters
        ----------
        x : object or array_like
            Actual value(s): numbers in the factor's units, or levels.

        Returns
        -------
        object
            The coded value(s).
        """
        ...

    def decode(self, c: Any) -> Any:
        """Coded value(s) to actual value(s).

        Parameters
        ----------
        c : object or array_like
            Coded value(s).

        Returns
        -------
        object
            The actual value(s): numbers in the factor's units, or levels.
        """
        ...

    def to_dict(self) -> dict:
        """The factor as in the fit JSON's ``factors`` list.

        Returns
        -------
        dict
            ``{"letter", "name", "kind", ...}``.
        """
        ...


#: The widest factor range [actual units] that coding can handle: LOW, HIGH and HIGH - LOW at
#: most this large, so that the points a design places far beyond the range stay finite.
MAX_RANGE_WIDTH = 1e300


def check_range_width(name: str, low: float, high: float) -> None:
    """ValueError when the range ``low .. high`` is too wide to code (``-1e308:1e308``, whose
    width HIGH - LOW overflows to inf; see :data:`MAX_RANGE_WIDTH`)."""
    with np.errstate(over="ignore"):
        width = float(np.float64(high) - np.float64(low))
    if not (np.isfinite(width) and width <= MAX_RANGE_WIDTH and max(abs(low), abs(high)) <= MAX_RANGE_WIDTH):
        raise ValueError(f"factor {quote_value(name)}: the range {low:g} .. {high:g} is too wide to compute with "
                         f"(LOW, HIGH and HIGH - LOW must be at most {MAX_RANGE_WIDTH:g} in size)")


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
    kind: ClassVar[Literal["numeric"]] = "numeric"

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
        """Actual value(s) to coded value(s); low -> -1 and high -> +1 exactly.

        Parameters
        ----------
        x : float or array_like
            Actual value(s) [the factor's units].

        Returns
        -------
        float or numpy.ndarray
            Coded value(s) [coded units, -1 .. +1 across the range].
        """
        x = np.asarray(x, dtype=float)
        c = ((x - self.low) - (self.high - x)) / (self.high - self.low)
        c = np.round(c, CODED_DECIMALS) + 0.0  # + 0.0 turns -0.0 into 0.0
        return c if c.ndim else float(c)

    def decode(self, c):
        """Coded value(s) to actual value(s); -1 -> low and +1 -> high exactly.

        Parameters
        ----------
        c : float or array_like
            Coded value(s).

        Returns
        -------
        float or numpy.ndarray
            Actual value(s) [the factor's units].
        """
        c = np.asarray(c, dtype=float)
        x = ((1.0 - c) * self.low + (1.0 + c) * self.high) / 2.0
        return x if x.ndim else float(x)

    def to_dict(self) -> dict:
        """The factor as plain data.

        Returns
        -------
        dict
            JSON-safe: numbers, strings, lists and dicts.
        """
        return {"letter": self.letter, "name": self.name, "kind": "numeric", "low": self.low, "high": self.high}


def level_text(value: Any) -> str:
    """A categoric level as written: text as it is, whole numbers without ``.0``, other
    numbers with up to 15 significant digits.

    >>> level_text("rms"), level_text(2), level_text(2.0), level_text(0.1)
    ('rms', '2', '2', '0.1')

    Parameters
    ----------
    value : object
        The level.

    Returns
    -------
    str
        The level as written.
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

    kind: ClassVar[Literal["categoric"]] = "categoric"

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
        """The number of levels."""
        return len(self.levels)

    def index(self, value: Any) -> int:
        """Level index of ``value`` (a level as written, or its text), or a ValueError.

        Parameters
        ----------
        level : object
            A level, as written in the data.

        Returns
        -------
        int
            Its position among the levels (0-based).
        """
        key = level_text(value)
        try:
            return self.levels.index(key)
        except ValueError:
            raise ValueError(f"factor {quote_value(self.name)}: {quote_value(key)} is not one of its levels "
                             f"({', '.join(self.levels)})") from None

    def encode(self, x):
        """Level(s) to level index (float; an array for an array).

        Parameters
        ----------
        x : object or array_like
            Level(s).

        Returns
        -------
        numpy.ndarray
            The effect-coded columns (sum-to-zero, last level omitted).
        """
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
        """Level index (indices) to level name(s).

        Parameters
        ----------
        c : array_like
            Effect-coded columns or level indices.

        Returns
        -------
        object or numpy.ndarray
            The level(s).
        """
        if np.ndim(c) == 0:
            return self.levels[self._checked(c)]
        return np.array([self.levels[self._checked(v)] for v in np.ravel(c)], dtype=object).reshape(np.shape(c))

    def _checked(self, c) -> int:
        v = float(c)
        if not (v.is_integer() and 0 <= v < len(self.levels)):
            raise ValueError(f"factor {quote_value(self.name)}: {c!r} is not a level index 0..{len(self.levels) - 1}")
        return int(v)

    def to_dict(self) -> dict:
        """The factor as plain data.

        Returns
        -------
        dict
            JSON-safe: numbers, strings, lists and dicts.
        """
        return {"letter": self.letter, "name": self.name, "kind": "categoric", "levels": list(self.levels)}

