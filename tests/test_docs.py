"""Docstrings of the public names (issue 37): every public function, class and public method
documents its parameters (a numpydoc ``Parameters`` section) and what it returns (``Returns`` or
``Yields``), as the API reference of the documentation site shows them.

The public names are those the reference documents (``docs/_ext/rsm_api.py``): ``rsm_lrg.__all__``
and the ``__all__`` of the sub-packages. The site itself is built by ``.ci/run`` (``python -m
sphinx -W --keep-going -b html docs docs/_build/html``: warnings are errors and every example of
``docs/examples/`` runs).
"""

from __future__ import annotations

import inspect
import sys
from pathlib import Path

import pytest

DOCS = Path(__file__).resolve().parents[1] / "docs"
sys.path.insert(0, str(DOCS / "_ext"))

import rsm_api  # noqa: E402
import rsm_guide  # noqa: E402


def gaps() -> set[str]:
    """Every missing docstring or section of a public name, as ``"qualified.name: what"``."""
    out = set()
    for n in rsm_api.public_names():
        if n.kind == "data":
            continue
        for what in rsm_api.missing_sections(n.obj):
            out.add(f"{n.qualname}: {what}")
        if n.kind == "class":
            for member, value in rsm_api.members(n.obj):
                prop = not inspect.isfunction(value)
                for what in rsm_api.missing_sections(value, is_property=prop):
                    out.add(f"{n.qualname}.{member}: {what}")
    return out


def test_public_names_cover_the_top_level_and_the_packages():
    names = {n.qualname for n in rsm_api.public_names()}
    assert {"rsm_lrg.fit", "rsm_lrg.box_behnken", "rsm_lrg.optimize", "rsm_lrg.simulate", "rsm_lrg.FitResult",
            "rsm_lrg.model.Regression", "rsm_lrg.paper.reproduce"} <= names
    assert "rsm_lrg.model.fit" not in names  # the same function as rsm_lrg.fit: documented once
    assert len(names) >= 130


def test_every_public_name_has_parameters_and_returns_sections():
    missing = sorted(gaps())
    assert not missing, "public names without a docstring or a Parameters/Returns section:\n" + "\n".join(missing)


def _undocumented(x, y=1):
    """Adds."""
    return x + y


def _documented(x: float) -> float:
    """Doubles.

    Parameters
    ----------
    x : float
        A length [m].

    Returns
    -------
    float
        Twice ``x`` [m].
    """
    return 2 * x


def _returns_nothing(x: float) -> None:
    """Nothing back.

    Parameters
    ----------
    x : float
        Ignored.
    """


def test_the_check_finds_a_missing_section():
    assert rsm_api.missing_sections(_undocumented) == ["Parameters", "Returns"]
    assert rsm_api.missing_sections(_documented) == []
    assert rsm_api.missing_sections(_returns_nothing) == []
    assert rsm_api.missing_sections(lambda: 1) == ["docstring"]
    assert rsm_api.sections(inspect.getdoc(_documented)) == {"Parameters", "Returns"}


def test_the_guide_places_every_readme_section_on_one_page():
    # the same placement the docs build makes (rsm_guide needs no Sphinx, so this runs everywhere)
    intro, sections = rsm_guide.readme_sections((DOCS.parent / "README.md").read_text(encoding="utf-8"))
    assert "Su, Zhang & Yang" in intro
    headings = [h for h, _ in sections]
    assert "Quick start" in headings and "Design space: where the rig stays in specification" in headings
    pages = rsm_guide.place_sections(sections)
    placed = [h for _, _, on in pages for h, _ in on]
    assert sorted(placed) == sorted(headings)  # each section once, none left


def test_the_guide_refuses_a_section_it_cannot_place():
    sections = rsm_guide.readme_sections((DOCS.parent / "README.md").read_text(encoding="utf-8"))[1]
    with pytest.raises(ValueError, match=r"on no guide page: \['A section of nobody'\]"):
        rsm_guide.place_sections(sections + [("A section of nobody", [])])
    with pytest.raises(ValueError, match="2 README sections start with 'Screening:'"):
        rsm_guide.place_sections(sections + [("Screening: again", [])])
