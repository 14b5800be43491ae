"""The user guide's page map (issue 37, item 5): which README section goes on which page of
the documentation site. Kept apart from :mod:`rsm_docs` (the Sphinx extension) so that the
placement is checked by the tests without Sphinx installed (``tests/test_docs.py``).
"""

from __future__ import annotations

import re

#: Guide pages: (file, title, README section headings that start with these words).
GUIDE = [
    ("quickstart", "Install and quick start", ["Quick start", "Python"]),
    ("command-line", "Working on the command line", ["The command line"]),
    ("designs", "Designs", ["Designs", "Categoric factors", "Designs beyond the classics"]),
    ("fitting", "Fitting models", ["Fit and optimise", "Any model", "Beyond the fit", "Pass/fail and count",
                                   "Screening:", "Screening with a definitive screening design"]),
    ("optimisation", "Optimisation and prediction", ["Prediction under uncertainty", "Mean and spread from replicates"]),
    ("mixtures", "Mixtures", ["Mixture designs", "Mixtures: Scheffé", "Blocked mixtures", "Mixture study"]),
    ("split-plot", "Split-plot experiments", ["Split-plot study", "Split-split-plot and strip-plot", "Split-plot analysis",
                                              "Power by simulation"]),
    ("design-space", "Design space", ["Design space"]),
    ("gp", "Gaussian processes and the next runs", ["Computer experiments"]),
    ("reports", "Reports", ["Interactive report", "Reports (static sections)"]),
    ("paper", "The paper reproduction and its physics", ["Physics", "Known gaps"]),
    ("surrogate", "The surrogate: virtual runs and calibration", ["Virtual runs and calibration",
                                                                  "Surrogate calibration"]),
    ("development", "Layout, documentation, tests and licence", ["Layout", "Documentation", "Tests and benchmarks",
                                                        "License"]),
]

FENCE = re.compile(r"^```")
HEADING = re.compile(r"^(#{2,4}) (.*)$")


FENCE = re.compile(r"^```")
HEADING = re.compile(r"^(#{2,4}) (.*)$")


def readme_sections(text: str) -> tuple[str, list[tuple[str, list[str]]]]:
    """The README's introduction and its ``##``/``###`` sections, fenced code left alone.

    Parameters
    ----------
    text : str
        The README.

    Returns
    -------
    tuple
        The introduction (after the title, before the first section) and a list of
        ``(heading, lines)``, the lines without the heading.
    """
    intro: list[str] = []
    out: list[tuple[str, list[str]]] = []
    fenced = False
    for line in text.splitlines()[1:]:
        if FENCE.match(line):
            fenced = not fenced
        m = None if fenced else HEADING.match(line)
        if m:
            out.append((m.group(2), []))
        elif out:
            out[-1][1].append(line)
        else:
            intro.append(line)
    return "\n".join(intro), out


def place_sections(sections: list[tuple[str, list[str]]]) -> list[tuple[str, str, list[tuple[str, list[str]]]]]:
    """Place every README section on exactly one guide page of :data:`GUIDE`.

    A start of :data:`GUIDE` names the section whose heading equals it, or else the one
    section whose heading starts with it.

    Parameters
    ----------
    sections : list of tuple
        ``(heading, lines)`` from :func:`readme_sections`.

    Returns
    -------
    list of tuple
        ``(page, title, [(heading, lines), ...])`` per page, in :data:`GUIDE`'s order.

    Raises
    ------
    ValueError
        A start that names no section or several, a section placed twice, or a section on no
        page.
    """
    placed: dict[str, str] = {}
    pages = []
    for page, title, starts in GUIDE:
        mine = []
        for start in starts:
            hits = [(h, lines) for h, lines in sections if h == start] or [
                (h, lines) for h, lines in sections if h.startswith(start)]
            if len(hits) != 1:
                raise ValueError(f"guide page {page!r}: {len(hits)} README sections start with {start!r}")
            heading = hits[0][0]
            if heading in placed:
                raise ValueError(f"README section {heading!r} is on two guide pages: {placed[heading]!r} and {page!r}")
            placed[heading] = page
            mine.append(hits[0])
        pages.append((page, title, mine))
    left = [h for h, _ in sections if h not in placed]
    if left:
        raise ValueError(f"README sections on no guide page: {left}")
    return pages
