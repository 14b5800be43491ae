"""HTML pages through Jinja2: one environment, autoescaping on, number formats as filters.

Every piece of text that reaches a page goes through Jinja2 with autoescaping, so column
names, labels and file names are shown as text, whatever characters they hold. Pages carry a
Content-Security-Policy that forbids scripts and every network request; images are
``data:`` URIs and the CSS is inline, so a report opens offline in any browser.

Number formats live in :mod:`rsm_lrg.present` (one format for every face); these are
the page's names for them. They follow the paper's Table 5 (Design-Expert): sums of squares as ``1.61 × 10⁻⁴``,
F values with two decimals, p values with four (``<0.0001`` below that).

>>> fmt_sci(1.61e-4), fmt_p(3e-7), fmt_p(0.088), fmt_f(26.0312)
('1.61 × 10⁻⁴', '<0.0001', '0.0880', '26.03')
>>> significance(0.0241).label
'less significant'
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

from .. import present as _present

__all__ = [
    "environment",
    "render_page",
    "fmt_num",
    "fmt_sci",
    "fmt_p",
    "fmt_f",
    "fmt_cell",
    "Significance",
    "significance",
    "SIGNIFICANCE_NOTE",
]

#: The note under the paper's Table 5, verbatim in substance.
SIGNIFICANCE_NOTE = (
    "p < 0.0100: significant effect (**); 0.0100 ≤ p < 0.0500: less significant effect (*); "
    "0.0500 ≤ p < 0.1000: no significant effect; p ≥ 0.1000: insignificant effect "
    "(the classes of the note under Table 5 of Su, Zhang & Yang 2023)."
)

DASH = _present.DASH


def _missing(x) -> bool:
    return _present.is_missing(x)


def fmt_num(x, sig: int = 4) -> str:
    """A number with ``sig`` significant figures (``—`` when missing); text passes through.

    The one number format of every page (:func:`rsm_lrg.present.format_number`): plain
    decimals from 1e-4 up to 1e5, otherwise ``6.972 × 10⁻⁵``.

    >>> fmt_num(0.0336667), fmt_num(27), fmt_num(None), fmt_num(1.5e-7), fmt_num(6.972e-05)
    ('0.03367', '27', '—', '1.5 × 10⁻⁷', '6.972 × 10⁻⁵')
    """
    return _present.format_number(x, sig, missing=DASH)


def fmt_sci(x, sig: int = 3) -> str:
    """Table 5 style: ``1.61 × 10⁻⁴``; zero as ``0.000``; plain decimals for 0.01 ≤ |x| < 1000.

    >>> fmt_sci(0.0), fmt_sci(1.108e-3), fmt_sci(12.5)
    ('0.000', '1.11 × 10⁻³', '12.5')
    """
    return _present.format_sci(x, sig)


def fmt_f(x) -> str:
    """F value: two decimals from 0.1 up, two significant digits down to 0.01, else ``sci``.

    >>> fmt_f(221.918), fmt_f(0.0822), fmt_f(0.00304), fmt_f(0.0)
    ('221.92', '0.082', '3.04 × 10⁻³', '0.00')
    """
    return _present.format_f(x)


def fmt_p(p) -> str:
    """p value with four decimals, ``<0.0001`` below that (Design-Expert)."""
    return _present.format_p(p)


def fmt_cell(x) -> str:
    """A data-table cell: numbers with up to 6 significant digits, text as is."""
    return _present.format_cell(x)


def fmt_input(x, sig: int = 4) -> str:
    """A number for the value of an ``<input type="number">``: :func:`rsm_lrg.present.format_number`
    in the ASCII style (``4.099e-11``, a number the input accepts); ``""`` when missing.

    >>> fmt_input(4.099382513e-11), fmt_input(0.0336667), fmt_input(None), fmt_input(0.5, 6)
    ('4.099e-11', '0.03367', '', '0.5')
    """
    return _present.format_number(x, sig, style="ascii", missing="")


def fmt_dof(x) -> str:
    if _missing(x):
        return ""
    xf = float(x)
    return str(int(xf)) if xf.is_integer() else f"{xf:.3g}"


@dataclass(frozen=True)
class Significance:
    """A p value's class under the note of the paper's Table 5 (a view, not a test).

    Attributes
    ----------
    label : str
        ``"significant"``, ``"less significant"``, ``"not significant"``, ``"insignificant"``
        or ``""`` when there is no p value.
    mark : str
        ``"**"``, ``"*"`` or ``""``.
    css : str
        CSS class of the p-value cell (``"sig"``, ``"less"`` or ``""``).
    """

    label: str
    mark: str
    css: str


def significance(p) -> Significance:
    """Class of a p value: < 0.01 significant (**), < 0.05 less significant (*), < 0.1 not
    significant, otherwise insignificant (note under Table 5 of the paper)."""
    if _missing(p):
        return Significance("", "", "")
    pf = float(p)
    if pf < 0.01:
        return Significance("significant", "**", "sig")
    if pf < 0.05:
        return Significance("less significant", "*", "less")
    if pf < 0.1:
        return Significance("not significant", "", "")
    return Significance("insignificant", "", "")


@lru_cache(maxsize=1)
def environment():
    """The Jinja2 environment of the report package (autoescaping always on, strict undefined)."""
    import jinja2

    env = jinja2.Environment(
        loader=jinja2.PackageLoader("rsm_lrg.report", "templates"),
        # explicit: HTML templates escape, and so does everything else, strings included
        autoescape=jinja2.select_autoescape(
            enabled_extensions=("html", "htm", "j2", "xml", "svg"),
            default_for_string=True,
            default=True,
        ),
        undefined=jinja2.StrictUndefined,
        trim_blocks=False,
        lstrip_blocks=False,
        keep_trailing_newline=True,
    )
    env.filters["num"] = fmt_num
    env.filters["sci"] = fmt_sci
    env.filters["fval"] = fmt_f
    env.filters["pval"] = fmt_p
    env.filters["cell"] = fmt_cell
    env.filters["dof"] = fmt_dof
    env.filters["num_input"] = fmt_input
    return env


def render_page(template: str, **context) -> str:
    """Render ``template`` (a file in ``rsm_lrg/report/templates``) with ``context``.

    ``generator`` and ``footer`` default to the toolkit's name and version; ``toc`` to none.
    """
    from .. import __version__

    context.setdefault("generator", f"rsm-lrg {__version__}")
    context.setdefault("footer", f"Made by rsm-lrg {__version__}. Self-contained: no scripts, no network requests.")
    context.setdefault("toc", [])
    context.setdefault("subtitle", "")
    return environment().get_template(template).render(**context)
