"""A user's values in messages: quoted short, checked to be finite numbers, names listed.

Shared by the factor space, the spec parser and the column inference of :mod:`rsm_lrg.factors`.
"""

from __future__ import annotations

import math
from typing import Any

from ..io import quote_user_value

__all__ = ["QUOTE_LIMIT", "LIST_LIMIT", "quote_value", "finite_float", "name_list"]

#: Longest piece of user data quoted in a message (characters).
QUOTE_LIMIT = 40


def quote_value(value: Any, limit: int = QUOTE_LIMIT) -> str:
    """A user's value quoted for an error message, cut to about ``limit`` characters with '…'
    (:func:`rsm_lrg.io.quote_user_value`; a 10 MB cell or a 300-digit number stays short).

    >>> quote_value("fast")
    "'fast'"
    >>> len(quote_value("9" * 300)) <= QUOTE_LIMIT + 2
    True

    Parameters
    ----------
    value : object
        The user's value.
    limit : int, default 40
        About how many characters to keep.

    Returns
    -------
    str
        The value quoted.
    """
    return quote_user_value(value, limit)


def finite_float(value: Any, what: str) -> float:
    """``float(value)``, or a ValueError naming ``what`` if it is not a finite number.

    Parameters
    ----------
    value : object
        The value.
    what : str
        What it is, for the message.

    Returns
    -------
    float
        The number.
    """
    try:
        x = float(value)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"{what}: {quote_value(value)} is not a number") from None
    if not math.isfinite(x):
        raise ValueError(f"{what}: {quote_value(value)} is not a finite number")
    return x


#: At most this many names are listed in one note (then "and N more").
LIST_LIMIT = 20


def name_list(cols, limit: int = LIST_LIMIT) -> str:
    """``a, b, c and 3 more``; each name cut to QUOTE_LIMIT characters.

    Parameters
    ----------
    cols : iterable of str
        The names.
    limit : int, default 20
        How many to list before ``and N more``.

    Returns
    -------
    str
        The list as text.
    """
    shown = [str(c) if len(str(c)) <= QUOTE_LIMIT else str(c)[:QUOTE_LIMIT] + "…" for c in cols[:limit]]
    more = len(cols) - limit
    return ", ".join(shown) + (f" and {more} more" if more > 0 else "")

