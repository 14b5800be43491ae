"""How numbers are shown: one number format, one p-value text, one round-off rule.

Every face of a result (the text of the CLI, the HTML report, the notebook display and the
``repr`` of result objects) formats its numbers here, so that a value reads the same
wherever it appears. This module imports nothing from the rest of the package, so every
layer (``model``, ``optimize``, ``report``, ``cli``) may use it.

The rules
---------
- **Number** (:func:`format_number`): ``digits`` significant figures; plain decimals for
  ``1e-4 <= |x| < 1e5``, otherwise scientific notation, written ``6.972 × 10⁻⁵`` in the
  ``"unicode"`` style (HTML, notebook, repr) and ``6.972e-05`` in the ``"ascii"`` style.
  Trailing zeros are dropped unless ``trim=False`` (tables that align digits).
- **Text face** (:func:`format_g`: the CLI's tables and ``summary()`` text, monospaced):
  the same rule in the ASCII style, with trailing zeros kept so that columns align
  (``0.0001613``, ``6.972e-05``); ``trim=True`` for single values and equation coefficients.
- **p value** (:func:`format_p`): four decimals, ``<0.0001`` below that (Design-Expert);
  ``style="ascii"`` writes ``< 0.0001`` for the text face.
- **Round-off** (:func:`clean`): a value whose size is at most :data:`ROUND_OFF` times its
  scale (a sum of squares against the corrected total, a coefficient against the largest
  one) is shown as exactly 0, as Design-Expert prints the AB and BC rows of the paper's
  Table 5. Stored results keep the computed values; only what is shown is cleaned.

>>> format_number(6.972e-05), format_sci(1.61e-4), format_number(0.0336667)
('6.972 × 10⁻⁵', '1.61 × 10⁻⁴', '0.03367')
>>> format_number(6.972e-05, style="ascii"), format_number(26.0312, 4), format_number(27)
('6.972e-05', '26.03', '27')
>>> format_p(3e-7), format_p(0.088), clean(2.5e-34, 1.14e-3), clean(1.6e-4, 1.14e-3)
('<0.0001', '0.0880', 0.0, 0.00016)
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from numbers import Number
from types import SimpleNamespace
from typing import Any

__all__ = ["ROUND_OFF", "DASH", "clean", "format_number", "format_g", "format_sci", "format_p", "format_f",
           "format_cell", "clean_anova", "anova_rows", "unicode_number", "is_missing", "table_records",
           "clean_anova_records"]

#: Relative size at or below which a value is round-off and shown as 0.
ROUND_OFF = 1e-12

#: What a missing value (None, NaN) shows as where a blank would be ambiguous.
DASH = "—"

_SUPERSCRIPT = str.maketrans("0123456789-+", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺")


def _is_real(x) -> bool:
    """Whether ``x`` is a real number (Python or NumPy; not a truth value, not complex):
    a :class:`numbers.Number` with ``__float__`` (``typing.SupportsFloat``, checked on the type,
    which is what the protocol's ``isinstance`` does, at a fraction of its cost)."""
    t = type(x)
    if t is float or t is int:
        return True
    return isinstance(x, Number) and hasattr(t, "__float__") and not isinstance(x, bool)


def is_missing(x) -> bool:
    """Whether ``x`` is shown as a dash: None, or a number that is not finite (NaN, ±inf)."""
    if x is None:
        return True
    if type(x) is float:
        return not math.isfinite(x)
    if _is_real(x):
        try:
            return not math.isfinite(float(x))
        except (TypeError, ValueError, OverflowError):
            return False
    return False


def clean(x, scale):
    """``x``, or ``0.0`` when ``|x| <= ROUND_OFF · |scale|`` (round-off); missing passes through.

    >>> clean(-3e-20, 1.0), clean(0.5, 1.0), clean(None, 1.0)
    (0.0, 0.5, None)
    """
    if is_missing(x) or is_missing(scale):
        return x
    return 0.0 if abs(float(x)) <= ROUND_OFF * abs(float(scale)) else x


def _mantissa_exponent(x: float, digits: int) -> tuple[str, int]:
    mant, exp = f"{x:.{max(digits, 1) - 1}e}".split("e")
    return mant, int(exp)


def _trim(s: str) -> str:
    return s.rstrip("0").rstrip(".") if "." in s else s


def format_number(x, digits: int = 4, *, style: str = "unicode", trim: bool = True,
                  missing: str = "") -> str:
    """A number with ``digits`` significant figures (see the module docstring for the rule).

    Parameters
    ----------
    x : number or None
        Integers (Python or NumPy ``int``) are shown whole; booleans as ``yes``/``no``;
        anything that is not a number is returned as ``str(x)``.
    digits : int
        Significant figures.
    style : {"unicode", "ascii"}
        ``6.972 × 10⁻⁵`` or ``6.972e-05``.
    trim : bool
        Drop trailing zeros (``0.0880`` → ``0.088``); ``False`` keeps ``digits`` figures.
    missing : str
        Text for ``None``, NaN and infinities.

    >>> format_number(0.0), format_number(-1234567.0), format_number(1.5e-7, style="ascii", trim=False)
    ('0', '-1.235 × 10⁶', '1.500e-07')
    >>> format_number(0.0880, 4, trim=False), format_number(float("nan"), missing="—")
    ('0.08800', '—')
    """
    if style not in ("unicode", "ascii"):
        raise ValueError(f"style must be 'unicode' or 'ascii', not {style!r}")
    if is_missing(x):
        return missing
    if isinstance(x, bool):
        return "yes" if x else "no"
    if not _is_real(x):
        return str(x)
    xf = float(x)
    if not isinstance(x, float) and xf.is_integer() and abs(xf) < 1e15:
        return str(int(xf))  # exact: a whole number below 1e15 is exact in a float
    if xf == 0.0:
        return "0" if trim else f"{0.0:.{max(digits - 1, 0)}f}"
    return _format_float(xf, digits, style, trim)


def _format_float(xf: float, digits: int, style: str, trim: bool) -> str:
    """:func:`format_number` of a finite, non-zero float."""
    a = abs(xf)
    sign = "-" if xf < 0 else ""
    r = float(f"{a:.{max(digits, 1) - 1}e}")  # rounded to the significant figures first
    if 1e-4 <= r < 1e5:
        decimals = max(digits - 1 - math.floor(math.log10(r)), 0)
        s = f"{r:.{decimals}f}"
        return sign + (_trim(s) if trim else s)
    return sign + _sci(a, digits, style, trim)


def format_g(x, digits: int = 4, *, trim: bool = False) -> str:
    """A number for the text face (CLI tables, ``summary()``): :func:`format_number` in the
    ASCII style (``digits`` significant figures; plain decimals for ``1e-4 <= |x| < 1e5``,
    otherwise ``1.613e-05``), with trailing zeros kept so that columns align; ``"0"`` for
    zero, ``""`` for None, NaN and infinities, text (a categoric level) as it is.
    ``trim=True`` drops trailing zeros (single values and equation coefficients: ``0.0075``
    rather than ``0.007500``).

    >>> format_g(0.0880), format_g(1.6133e-4), format_g(26.0312), format_g(0.0), format_g(None)
    ('0.08800', '0.0001613', '26.03', '0', '')
    >>> format_g(0.99999, 4), format_g(0.0075, 6, trim=True), format_g(4.1667e-05, 5, trim=True)
    ('1.000', '0.0075', '4.1667e-05')
    >>> format_g(9.0466e-4), format_g(1e-4, 6), format_g(1e-4, 6, trim=True), format_g(123456.0)
    ('0.0009047', '0.000100000', '0.0001', '1.235e+05')
    """
    if isinstance(x, str):  # a categoric level, shown as it is
        return x
    if type(x) is float:  # the usual case: the checks below, for a float
        if x == 0:
            return "0"
        return _format_float(x, digits, "ascii", trim) if math.isfinite(x) else ""
    if x is None or is_missing(x):
        return ""
    x = float(x)
    if x == 0:
        return "0"
    return format_number(x, digits, style="ascii", trim=trim)


def _sci(a: float, digits: int, style: str, trim: bool) -> str:
    mant, exp = _mantissa_exponent(a, digits)
    if trim:
        mant = _trim(mant)
    if style == "ascii":
        return f"{mant}e{'-' if exp < 0 else '+'}{abs(exp):02d}"
    return f"{mant} × 10{str(exp).translate(_SUPERSCRIPT)}"


_E_NOTATION = re.compile(r"([-+−]?\d+(?:\.\d*)?)[eE]([-+]?\d+)")


def unicode_number(text: str) -> str:
    """A number written in ASCII e-notation (``1.2e-05``) rewritten in the unicode style
    (``1.2 × 10⁻⁵``); any other text is returned unchanged.

    >>> unicode_number("4.16667e-05"), unicode_number("-3E+06"), unicode_number("0.0075"), unicode_number("n/a")
    ('4.16667 × 10⁻⁵', '-3 × 10⁶', '0.0075', 'n/a')
    """
    m = _E_NOTATION.fullmatch(str(text).strip())
    if not m:
        return str(text)
    return f"{m.group(1)} × 10{str(int(m.group(2))).translate(_SUPERSCRIPT)}"


def format_sci(x, digits: int = 3) -> str:
    """A sum of squares or mean square as the paper's Table 5 prints it: ``1.61 × 10⁻⁴``;
    zero as ``0.000``; plain decimals for ``0.01 <= |x| < 1000``.

    >>> format_sci(0.0), format_sci(1.108e-3), format_sci(12.5)
    ('0.000', '1.11 × 10⁻³', '12.5')
    """
    if is_missing(x):
        return ""
    xf = float(x)
    if xf == 0.0:
        return "0.000"
    if 0.01 <= abs(xf) < 1000:
        return format_number(xf, digits)
    return ("-" if xf < 0 else "") + _sci(abs(xf), digits, "unicode", trim=False)


def format_f(x) -> str:
    """An F value: two decimals from 0.1 up, two significant figures down to 0.01, else
    Table 5's scientific form.

    >>> format_f(221.918), format_f(0.0822), format_f(0.00304), format_f(0.0)
    ('221.92', '0.082', '3.04 × 10⁻³', '0.00')
    """
    if is_missing(x):
        return ""
    xf = float(x)
    if xf == 0.0 or abs(xf) >= 0.1:
        return f"{xf:.2f}"
    if abs(xf) >= 0.01:
        return f"{xf:.2g}"
    return format_sci(xf)


def format_p(p, *, style: str = "unicode") -> str:
    """A p value with four decimals, ``<0.0001`` below that (Design-Expert); ``""`` if missing.

    ``style="ascii"`` writes ``< 0.0001`` (the CLI's text tables)."""
    if is_missing(p):
        return ""
    pf = float(p)
    if pf < 1e-4:
        return "<0.0001" if style == "unicode" else "< 0.0001"
    return f"{pf:.4f}"


def format_cell(x) -> str:
    """A data-table cell: numbers with up to 6 significant figures, text as is, blank if missing."""
    return format_number(x, 6)


def table_records(frame) -> list[SimpleNamespace]:
    """The rows of a small DataFrame as records with one attribute per column (as
    ``itertuples(index=False)`` gives them: Python scalars), read column by column (a
    namedtuple class per call and a cell look-up per value cost more than a summary's text);
    rows given as a list of dicts (an ANOVA's rows) become records as they are.

    Parameters
    ----------
    frame : pandas.DataFrame or list of dict
        A table whose column names are identifiers (an ANOVA: ``source, sum_sq, df, ...``).

    Returns
    -------
    list of types.SimpleNamespace
        One record per row, in order.

    >>> import pandas as pd
    >>> [(r.source, r.df) for r in table_records(pd.DataFrame({"source": ["A", "B"], "df": [1, 2]}))]
    [('A', 1), ('B', 2)]
    """
    if isinstance(frame, list):
        return [SimpleNamespace(**row) for row in frame]
    cols = {str(c): frame[c].tolist() for c in frame.columns}
    return [SimpleNamespace(**dict(zip(cols, vals))) for vals in zip(*cols.values())]


def clean_anova(anova):
    """A copy of an ANOVA DataFrame (``source, sum_sq, df, mean_sq, f, p``) as it is shown:
    sums of squares and mean squares that are round-off against the corrected total
    (``|ss| <= ROUND_OFF · SS_total``) set to 0, and their F to 0 and p to 1.

    :func:`rsm_lrg.model.fit` stores its ANOVA through this (the AB row of Table 4's fit is
    computed as 2.5e-34 and stored as 0), so the DataFrame, the CLI, the report and the
    notebook show the same numbers.
    """
    a = anova.copy()
    sources, ss = a["source"].tolist(), a["sum_sq"].tolist()  # a small frame: plain lists, not cell look-ups
    scale = _anova_scale(sources, ss)
    if scale is None:
        scale = float(a["sum_sq"].abs().max())
    changes = _round_off_cells(ss, a["mean_sq"].tolist(), a["f"].tolist(), scale)
    for col, at in changes.items():
        if not at:
            continue
        value = 1.0 if col == "p" else 0.0
        if a[col].dtype.kind == "f":
            arr = a[col].to_numpy(copy=True)
            arr[at] = value
            a[col] = arr
        else:
            for i in at:
                a.at[a.index[i], col] = value
    return a


def _anova_scale(sources: list, ss: list) -> float | None:
    """The corrected (or, without an intercept, uncorrected) total sum of squares, None without a total row."""
    tot = [v for src, v in zip(sources, ss) if src in ("Cor Total", "Uncor Total")]
    return float(tot[0]) if tot else None


def _round_off_cells(ss: list, ms: list, f: list, scale: float) -> dict[str, list[int]]:
    """The rows whose sum of squares is round-off against ``scale``: ``{column: row numbers}`` of
    the cells :func:`clean_anova` sets (``sum_sq``, ``mean_sq`` to 0 where not missing; ``f`` to
    0 and ``p`` to 1 where F is not missing)."""
    rows = [i for i, v in enumerate(ss) if not is_missing(v) and clean(v, scale) == 0.0]
    out = {"sum_sq": rows, "mean_sq": [i for i in rows if not is_missing(ms[i])],
           "f": [i for i in rows if not is_missing(f[i])]}
    out["p"] = out["f"]
    return out


def clean_anova_records(rows: list[dict]) -> list[dict]:
    """:func:`clean_anova` on the rows of an ANOVA before it is a DataFrame (dicts with the keys
    ``source, sum_sq, df, mean_sq, f, p``): the same cells set, in place.

    Parameters
    ----------
    rows : list of dict
        The ANOVA's rows, in order.

    Returns
    -------
    list of dict
        ``rows``, cleaned.

    >>> rows = [{"source": "A", "sum_sq": 1e-30, "df": 1, "mean_sq": 1e-30, "f": 1e-25, "p": 0.9},
    ...         {"source": "Cor Total", "sum_sq": 2.0, "df": 1, "mean_sq": float("nan"), "f": float("nan"),
    ...          "p": float("nan")}]
    >>> [(r["sum_sq"], r["f"], r["p"]) for r in clean_anova_records(rows)][0]
    (0.0, 0.0, 1.0)
    """
    sources, ss = [r["source"] for r in rows], [r["sum_sq"] for r in rows]
    scale = _anova_scale(sources, ss)
    if scale is None:
        sizes = [abs(v) for v in ss if v == v]  # as pandas' max: NaN left out
        scale = float(max(sizes)) if sizes else math.nan
    changes = _round_off_cells(ss, [r["mean_sq"] for r in rows], [r["f"] for r in rows], scale)
    for col, at in changes.items():
        for i in at:
            rows[i][col] = 1.0 if col == "p" else 0.0
    return rows


def anova_rows(anova, *, style: str = "unicode") -> list[list[str]]:
    """The rows of an ANOVA as shown (header first): cleaned (:func:`clean_anova`), sums of
    squares with 4 significant figures, F with two decimals, p by :func:`format_p`."""
    a = clean_anova(anova)
    out = [["Source", "Sum of squares", "df", "Mean square", "F-value", "p-value"]]
    for r in a.itertuples(index=False):
        out.append([str(r.source), format_number(r.sum_sq, 4, style=style), format_number(int(r.df)),
                    format_number(r.mean_sq, 4, style=style), format_f(r.f) if style == "unicode" else
                    format_number(r.f, 4, style=style), format_p(r.p, style=style)])
    return out


def text_table(header: Sequence[Any], rows: Sequence[Sequence[Any]], align: Sequence[str] | None = None) -> str:
    """A plain-text table: the header, a rule, the rows; columns padded to their widest cell,
    the first left-aligned and the rest right-aligned unless ``align`` (``"<"``/``">"``) says."""
    widths = [max(len(str(h)), *(len(str(r[i])) for r in rows)) for i, h in enumerate(header)]
    align = align or ["<"] + [">"] * (len(header) - 1)
    fmt = "  ".join(f"{{:{a}{w}}}" for a, w in zip(align, widths))
    lines = [fmt.format(*header), "  ".join("-" * w for w in widths)]
    lines += [fmt.format(*map(str, r)) for r in rows]
    return "\n".join(lines)
