"""Factor specifications: ``NAME``, ``NAME=LOW:HIGH``, ``NAME=cat`` and ``NAME=cat:L1,L2,...``
(the CLI's ``--factor``), and the factors as given in Python (names, specs, tuples, factors,
mappings), as items ``("numeric", name, low, high)`` / ``("categoric", name, levels)``.
"""

from __future__ import annotations

import re
from collections.abc import Mapping

import numpy as np

from .factor import CategoricFactor, Factor, check_range_width, level_text
from .values import finite_float, quote_value

__all__ = ["parse_factor", "parse_factor_spec", "spec_with_levels", "given_items"]

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

    Parameters
    ----------
    spec : str
        ``NAME``, ``NAME=LOW:HIGH``, ``NAME=cat`` or ``NAME=cat:L1,L2,...``.

    Returns
    -------
    tuple
        ``("numeric", name, low, high)`` or ``("categoric", name, levels)``.
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

    Parameters
    ----------
    spec : str
        ``NAME`` or ``NAME=LOW:HIGH``.

    Returns
    -------
    tuple
        ``(name, low, high)``, ``low``/``high`` None for a bare name [the factor's units].
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
    check_range_width(name, low, high)
    return name, low, high


def spec_with_levels(spec) -> tuple:
    """:func:`parse_factor` of a spec that must carry its levels (``NAME=LOW:HIGH`` or
    ``NAME=cat:L1,L2,...``), for a design's factors.

    Parameters
    ----------
    spec : str
        ``NAME=LOW:HIGH`` or ``NAME=cat:L1,L2,...``.

    Returns
    -------
    tuple
        As :func:`parse_factor`.
    """
    parsed = parse_factor(spec)
    if parsed[2] is None:
        how = "NAME=cat:L1,L2,..." if parsed[0] == "categoric" else "NAME=LOW:HIGH"
        raise ValueError(f"factor {quote_value(parsed[1])}: levels are needed here; write {how}")
    return parsed


def given_items(factors, *, need_levels: bool = False) -> list[tuple]:
    """The factors as given, as ``("numeric", name, low, high)`` / ``("categoric", name, levels)``.

    ``need_levels=False`` (factors of data, :func:`choose_factors`): a bare name, a mapping
    value ``None`` or ``"categoric"`` leave the levels (``None``) to the data, a mapping
    value is ``(low, high)`` only as a tuple of two numbers, any other sequence is levels.
    ``need_levels=True`` (a design's factors, :func:`rsm_lrg.design.as_factor_space`):
    every factor must carry its levels, and a mapping value that is not a list of texts is
    ``(low, high)``.

    Parameters
    ----------
    factors : sequence or mapping
        The factors as given (specs, names, or a mapping).
    need_levels : bool, default False
        Every factor must carry its levels (a design's factors).

    Returns
    -------
    list of tuple
        The items.
    """
    if isinstance(factors, str):
        factors = [factors]
    out: list[tuple] = []
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
                out.append(spec_with_levels(it))
            else:
                out.append(parse_factor(it) if "=" in it else ("numeric", it, None, None))
        else:
            try:
                name, low, high = it
            except (TypeError, ValueError):
                raise ValueError(f"factor {it!r}: expected 'NAME=LOW:HIGH' or (name, low, high)") from None
            out.append(("numeric", name, low, high))
    return out

