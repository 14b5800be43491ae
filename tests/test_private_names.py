"""Issue 21, "the house": no private (underscore) name is imported from another module.

Every module of rsm_lrg is read as source (imports inside functions count): a
``from X import _name`` of a module X of the package, or ``X._name`` where X is a module of
the package, is a private name crossing a module boundary. A helper two modules share is
made public in a named seam module (``rsm_lrg.design.exchange``: the exchange step of
optimal designs; ``rsm_lrg.io``: the cell checks; ``rsm_lrg.surrogate.progress``: the
progress bar). The uses left are in, or reach into, the files being rewritten for the
model core (issue 21, items 1-3); they are listed by name in :data:`LEAD_FILES_PRIVATE_IMPORTS`,
to be emptied by that rewrite.
"""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: ``(importer, "module:name")`` of the private imports left for the rewrite of model/fit.py,
#: model/text.py, model/transform.py and report/fit_report.py (the names are defined or used
#: there). Remove an entry when its use goes; an entry with no use left fails the test.
LEAD_FILES_PRIVATE_IMPORTS: frozenset[tuple[str, str]] = frozenset()


def _private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def _module_name(path: Path, root: Path) -> str:
    parts = list(path.relative_to(root).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def private_imports(root: Path = ROOT, package: str = "rsm_lrg") -> set[tuple[str, str]]:
    """``{(importer, "module:name")}``: every private name a module of ``package`` (under
    ``root``) takes from another module of the package, by ``from X import _name`` or as
    ``X._name`` with X bound to a module of the package (imports inside functions count)."""
    files = sorted((root / package).rglob("*.py"))
    modules = {_module_name(p, root) for p in files}
    found: set[tuple[str, str]] = set()
    for path in files:
        mod = _module_name(path, root)
        base = mod.split(".") if path.name == "__init__.py" else mod.split(".")[:-1]
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        bound: dict[str, str] = {}  # local name -> module of the package it is bound to
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                if node.level:
                    up = base[: len(base) - (node.level - 1)]
                    src = ".".join(up + ([node.module] if node.module else []))
                else:
                    src = node.module or ""
                if src != package and not src.startswith(package + "."):
                    continue
                for alias in node.names:
                    if _private(alias.name) and src != mod:
                        found.add((mod, f"{src}:{alias.name}"))
                    elif f"{src}.{alias.name}" in modules:
                        bound[alias.asname or alias.name] = f"{src}.{alias.name}"
            elif isinstance(node, ast.Import):
                for alias in node.names:
                    if alias.name in modules and alias.asname:
                        bound[alias.asname] = alias.name
                    elif alias.name.split(".")[0] == package and not alias.asname:
                        bound[package] = package
        for node in ast.walk(tree):
            if not (isinstance(node, ast.Attribute) and _private(node.attr)):
                continue
            chain, value = [], node.value
            while isinstance(value, ast.Attribute):
                chain.append(value.attr)
                value = value.value
            if isinstance(value, ast.Name) and value.id in bound:
                target = ".".join([bound[value.id], *reversed(chain)])
                if target in modules and target != mod:
                    found.add((mod, f"{target}:{node.attr}"))
    return found


def test_the_checker_finds_private_names_taken_from_other_modules(tmp_path):
    pkg = tmp_path / "rsm_lrg"
    (pkg / "sub").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "sub" / "__init__.py").write_text("")
    (pkg / "base.py").write_text("def _helper():\n    return 1\n\n\ndef helper():\n    return _helper()\n")
    (pkg / "sub" / "a.py").write_text(
        "from .. import base as _b\nfrom ..base import helper\n\n\n"
        "def f():\n    from ..base import _helper\n\n    return _helper() + _b._helper() + helper()\n")
    (pkg / "sub" / "b.py").write_text("import rsm_lrg.base\nfrom os import _exit  # noqa\n\n\n"
                                      "def g():\n    return rsm_lrg.base._helper()\n")
    assert private_imports(tmp_path) == {("rsm_lrg.sub.a", "rsm_lrg.base:_helper"),
                                         ("rsm_lrg.sub.b", "rsm_lrg.base:_helper")}


def test_no_private_name_is_imported_from_another_module():
    found = private_imports()
    unexpected = sorted(found - LEAD_FILES_PRIVATE_IMPORTS)
    assert unexpected == [], "private names taken from another module: " + "; ".join(
        f"{imp} takes {name}" for imp, name in unexpected)
    stale = sorted(LEAD_FILES_PRIVATE_IMPORTS - found)
    assert stale == [], "LEAD_FILES_PRIVATE_IMPORTS lists uses that are gone: remove " + repr(stale)
