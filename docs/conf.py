"""Sphinx configuration of the rsm-lrg documentation (``python -m sphinx -W --keep-going -b html
docs docs/_build/html``; the extra ``docs`` of pyproject.toml installs what it needs)."""

import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
sys.path.insert(0, str(DOCS.parent))  # this checkout's rsm_lrg, not an installed one
sys.path.insert(0, str(DOCS / "_ext"))

import rsm_lrg  # noqa: E402

project = "rsm-lrg"
author = "the rsm-lrg authors"
copyright = "2026, the rsm-lrg authors (MIT)"
release = version = rsm_lrg.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "myst_parser",
    "rsm_docs",
]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "HELPERS.md", "analysis", "screenshots", "examples", "_generated/gallery/_work",
                    "_generated/intro.md"]  # intro.md: included by index.rst
root_doc = "index"

autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_typehints_description_target = "documented_params"
autodoc_preserve_defaults = True
napoleon_numpy_docstring = True
napoleon_google_docstring = False
napoleon_use_rtype = False
myst_heading_anchors = 3
# "more than one target found" for the words of a numpydoc type ("array of shape (n, k)": n is an
# attribute of several classes); a reference that resolves nowhere is not a warning either way
suppress_warnings = ["ref.python"]

html_theme = "alabaster"
html_title = f"rsm-lrg {release}"
html_theme_options = {"description": "Design of experiments and response surfaces", "page_width": "1100px",
                      "sidebar_width": "240px"}
