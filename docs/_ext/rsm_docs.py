"""Sphinx extension of the rsm-lrg documentation: at ``builder-inited`` it writes, under
``docs/_generated/`` (git-ignored), the pages that are produced from the project itself:

- the user guide, split from the README's sections (:data:`rsm_guide.GUIDE`; every section of the README
  must land on exactly one page, else the build stops),
- the command-line reference, the ``--help`` of every command and sub-command as argparse
  prints it,
- the API reference, one page per package of :data:`rsm_api.PACKAGES`,
- the gallery: every ``docs/examples/*.py`` run in a fresh process (its output shown under the
  code); an example that fails, or prints a traceback, stops the build.
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import rsm_api
import rsm_guide
from rsm_guide import place_sections, readme_sections
from sphinx.errors import ExtensionError
from sphinx.util import logging

LOG = logging.getLogger(__name__)
DOCS = Path(__file__).resolve().parents[1]
ROOT = DOCS.parent
OUT = DOCS / "_generated"

def _write(path: Path, text: str) -> None:
    """Write ``text`` unless the file holds it already (keeps incremental builds incremental)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.exists() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")


def _relink(line: str) -> str:
    """A README link to ``docs/...`` as a link from ``docs/_generated/guide/``."""
    return re.sub(r"\]\(docs/", "](../../", line)


def write_guide() -> list[str]:
    """Write the guide pages from the README (:func:`rsm_guide.place_sections` decides which
    section goes on which page and stops the build on one it cannot place).

    Returns
    -------
    list of str
        The page names, in order.
    """
    intro, sections = readme_sections((ROOT / "README.md").read_text(encoding="utf-8"))
    _write(OUT / "intro.md", intro.strip() + "\n")
    try:
        pages = place_sections(sections)
    except ValueError as exc:
        raise ExtensionError(f"{exc} (the page map is GUIDE in {rsm_guide.__file__})") from None
    for page, title, placed in pages:
        body = [f"# {title}", ""]
        for heading, lines in placed:
            body += [f"## {heading}", ""] + [_relink(line) for line in lines] + [""]
        _write(OUT / "guide" / f"{page}.md", "\n".join(body).rstrip() + "\n")
    return [page for page, _, _ in pages]


def _parsers(parser: argparse.ArgumentParser, prog: str) -> list[tuple[str, argparse.ArgumentParser]]:
    out = [(prog, parser)]
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, child in action.choices.items():
                out += _parsers(child, f"{prog} {name}")
    return out


def write_cli() -> int:
    """Write the command-line reference: the ``--help`` text of every command.

    Returns
    -------
    int
        How many commands and sub-commands it holds.
    """
    os.environ["COLUMNS"] = "100"  # argparse wraps to the terminal: a fixed width
    from rsm_lrg.cli import build_parser

    lines = ["Command-line reference", "======================", "",
             "The ``--help`` of every command and sub-command, as ``rsm-lrg`` prints it (generated from",
             "the argument parsers when the documentation is built). ``rsm-lrg`` and",
             "``python -m rsm_lrg`` are the same program; exit status 0 on success, 2 on bad usage or",
             "bad input (one ``error:`` line), 1 on an internal fault.", ""]
    parsers = _parsers(build_parser(), "rsm-lrg")
    for prog, parser in parsers:
        lines += [f".. _cli-{prog.replace(' ', '-')}:", "", f"``{prog}``", "-" * (len(prog) + 4), "",
                  ".. code-block:: text", ""]
        lines += ["   " + line if line.strip() else "" for line in parser.format_help().splitlines()]
        lines.append("")
    _write(OUT / "cli.rst", "\n".join(lines))
    return len(parsers)


def _title(text: str, ch: str) -> list[str]:
    return [text, ch * len(text), ""]


def _data_doc(package: str, name: str) -> list[str]:
    """The ``#:`` comment of a constant, from the module of ``package`` that defines it."""
    from sphinx.pycode import ModuleAnalyzer

    for modname in sorted(m for m in sys.modules if m == package or m.startswith(package + ".")):
        try:
            docs = ModuleAnalyzer.for_module(modname).find_attr_docs()
        except Exception:  # a module without source (a compiled one)
            continue
        if ("", name) in docs:
            return [line for line in docs[("", name)] if line is not None]
    return []


def write_api() -> int:
    """Write one API page per package of :data:`rsm_api.PACKAGES`.

    Returns
    -------
    int
        How many public names the pages document.
    """
    names = rsm_api.public_names()
    for package in rsm_api.PACKAGES:
        here = [n for n in names if n.package == package]
        lines = _title(f"``{package}``", "=") + [f".. automodule:: {package}", "   :no-members:", ""]
        for kind, heading, directive in (("function", "Functions", "autofunction"), ("class", "Classes", "autoclass"),
                                         ("data", "Constants", "py:data")):
            group = [n for n in here if n.kind == kind]
            if not group:
                continue
            lines += _title(heading, "-")
            for n in group:
                target = n.qualname if not (package == "rsm_lrg" and n.name == "optimize") else "rsm_lrg.optimize.optimize"
                lines.append(f".. {directive}:: {target}")
                if kind == "class":
                    lines.append("   :members:")
                if kind == "data":  # py:data, not autodata: a dict's docstring would be dict's own
                    text = repr(n.obj)
                    if len(text) <= 100:
                        lines.append(f"   :value: {text}")
                    lines += ["", *("   " + line for line in _data_doc(package, n.name))]
                lines.append("")
        _write(OUT / "api" / f"{package}.rst", "\n".join(lines))
    return len(names)


def run_examples() -> list[tuple[str, float]]:
    """Run every ``docs/examples/*.py`` in a fresh process and write its gallery page.

    Returns
    -------
    list of tuple of (str, float)
        Each example's name and its wall time [s].
    """
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]),
               MPLBACKEND="Agg")
    work = OUT / "gallery" / "_work"
    work.mkdir(parents=True, exist_ok=True)
    times = []
    index = _title("Gallery of worked examples", "=") + [
        "Each example below is a script in ``docs/examples/``, run from start to end whenever the",
        "documentation is built; the output shown is the output of that run.", "",
        ".. toctree::", "   :maxdepth: 1", ""]
    for script in sorted((DOCS / "examples").glob("*.py")):
        t0 = time.perf_counter()
        run = subprocess.run([sys.executable, str(script)], cwd=work, env=env, capture_output=True, text=True,
                             timeout=300)
        times.append((script.stem, time.perf_counter() - t0))
        if run.returncode != 0 or "Traceback" in run.stderr:
            raise ExtensionError(f"example {script.name} failed (exit {run.returncode}):\n{run.stderr[-3000:]}")
        source = script.read_text(encoding="utf-8")
        m = re.match(r'\s*"""(.*?)"""\n(.*)', source, re.S)
        if not m:
            raise ExtensionError(f"example {script.name}: begins with no docstring (its title and text)")
        doc, code = m.group(1).strip(), m.group(2).strip("\n")
        title, _, text = doc.partition("\n")
        page = _title(title.strip(), "=") + [text.strip(), "", f"Source: ``docs/examples/{script.name}``", "",
                                              ".. code-block:: python", ""]
        page += ["   " + line if line.strip() else "" for line in code.splitlines()]
        page += ["", "Output", "------", "", ".. code-block:: text", ""]
        page += ["   " + line if line.strip() else "" for line in run.stdout.rstrip().splitlines()]
        _write(OUT / "gallery" / f"{script.stem}.rst", "\n".join(page) + "\n")
        index.append(f"   {script.stem}")
        LOG.info(f"example {script.name}: {times[-1][1]:.1f} s")
    _write(OUT / "gallery" / "index.rst", "\n".join(index) + "\n")
    return times


def builder_inited(app) -> None:
    """Generate the pages (the Sphinx ``builder-inited`` event).

    Parameters
    ----------
    app : sphinx.application.Sphinx
        The application.
    """
    write_guide()
    write_cli()
    write_api()
    run_examples()


def setup(app) -> dict:
    """Register the extension.

    Parameters
    ----------
    app : sphinx.application.Sphinx
        The application.

    Returns
    -------
    dict
        The extension's metadata.
    """
    app.connect("builder-inited", builder_inited)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
