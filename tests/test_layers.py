"""Issue 11, item 2: the layers are one-way and the contract is enforced.

The contract is ``[tool.importlinter]`` in pyproject.toml (../shared/STYLE.md, "The house");
``lint-imports`` reads every import statement of every module, those inside functions too.
Independently of import-linter, a fresh interpreter that imports ``rsm_lrg.model`` (and fits
the paper's Table 4) must not load the optimize, report, cli, paper, surrogate or physics
layers.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _fresh(code: str) -> dict:
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.strip().splitlines()[-1])


@pytest.mark.skipif(shutil.which("lint-imports") is None, reason="import-linter is not installed (test extra)")
@pytest.mark.parametrize("module, target, arrow", [
    (("model", "build", "terms.py"), "...optimize", "rsm_lrg.model.build.terms -> rsm_lrg.optimize"),  # across layers
    (("model", "engines", "mixed.py"), "..results.result", "rsm_lrg.model.engines.mixed -> rsm_lrg.model.results.result"),  # model's floors
])
def test_contract_counts_imports_inside_functions(tmp_path, module, target, arrow):
    # a copy of the package with one import inside a function that reverses the layers (model ->
    # optimize, or an engine -> the results above it) must break a contract; the package is untouched
    shutil.copytree(ROOT / "rsm_lrg", tmp_path / "rsm_lrg", ignore=shutil.ignore_patterns("__pycache__", "data"))
    shutil.copy(ROOT / "pyproject.toml", tmp_path / "pyproject.toml")
    path = tmp_path.joinpath("rsm_lrg", *module)
    assert path.is_file()
    with open(path, "a", encoding="utf-8") as fh:
        fh.write(f"\n\ndef _reversed():\n    from {target} import __name__ as n\n\n    return n\n")
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"} | {"PYTHONPATH": str(tmp_path)}
    out = subprocess.run(["lint-imports", "--no-cache"], capture_output=True, text=True, cwd=tmp_path, env=env,
                         timeout=300)
    assert out.returncode != 0
    assert arrow in out.stdout


# -- issue 21, "the house": no import circle anywhere in the package ----------------------------

#: The known circle around rsm_lrg/model/fit.py, edge by edge (importer, imported), allowed only
#: until the model core is rewritten (issue 21, items 1-3). Empty this when the rewrite lands; no
#: other edge of a circle is allowed, and an edge listed here that no longer exists fails too.
FIT_HUB_CYCLE_EDGES: frozenset[tuple[str, str]] = frozenset()


GRAPH = """
import json, grimp
graph = grimp.build_graph("rsm_lrg", cache_dir=None)
print(json.dumps({m: sorted(graph.find_modules_directly_imported_by(m)) for m in graph.modules}))
"""


def _import_graph(root: Path = ROOT) -> dict[str, set[str]]:
    """``{module: modules of rsm_lrg it imports}`` for the package under ``root``, every import
    statement counted (those inside functions and ``if TYPE_CHECKING`` blocks too), as grimp
    (import-linter's graph) reads the source; built in a fresh interpreter."""
    pytest.importorskip("grimp", reason="grimp comes with import-linter (test extra)")
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"} | {"PYTHONPATH": str(root)}
    out = subprocess.run([sys.executable, "-c", GRAPH], capture_output=True, text=True, cwd=root, env=env,
                         timeout=300)
    assert out.returncode == 0, out.stderr
    return {m: set(v) for m, v in json.loads(out.stdout).items()}


def _cycles(edges: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module, or of a module importing
    itself (Tarjan's algorithm, iterative), each sorted; every circle lies inside one."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    on_stack: set[str] = set()
    stack: list[str] = []
    out: list[list[str]] = []
    for root in sorted(edges):
        if root in index:
            continue
        work = [(root, iter(sorted(edges[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            v, it = work[-1]
            w = next(it, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = len(index)
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, iter(sorted(edges.get(w, ())))))
                elif w in on_stack:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on_stack.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                if len(comp) > 1 or v in edges.get(v, ()):
                    out.append(sorted(comp))
    return out


def _cycle_edges(edges: dict[str, set[str]]) -> set[tuple[str, str]]:
    """Every import edge that lies on a circle (both ends in one component)."""
    out = set()
    for comp in _cycles(edges):
        members = set(comp)
        out |= {(a, b) for a in comp for b in edges[a] if b in members}
    return out


def test_cycle_finder_finds_circles_through_function_level_imports():
    # the finder itself: a circle of three, a self-import, and a chain that is no circle
    edges = {"a": {"b"}, "b": {"c"}, "c": {"a", "d"}, "d": set(), "e": {"e"}, "f": {"a"}}
    assert sorted(_cycles(edges)) == [["a", "b", "c"], ["e"]]
    assert _cycle_edges(edges) == {("a", "b"), ("b", "c"), ("c", "a"), ("e", "e")}
    assert _cycles({"a": {"b"}, "b": set()}) == []


def test_no_import_circle_in_the_package():
    edges = _import_graph()
    assert "rsm_lrg.io" in edges and "rsm_lrg.factors.space" in edges
    found = _cycle_edges(edges)
    unexpected = sorted(found - FIT_HUB_CYCLE_EDGES)
    assert unexpected == [], "import circle(s): " + "; ".join(f"{a} -> {b}" for a, b in unexpected)
    stale = sorted(FIT_HUB_CYCLE_EDGES - found)
    assert stale == [], "FIT_HUB_CYCLE_EDGES lists edges no longer on a circle: remove " + repr(stale)


def test_the_circle_guard_counts_imports_inside_functions(tmp_path):
    # a copy of the package with one import inside a function that closes a circle
    # (io -> factors, while factors imports io) must be found; the real package is untouched
    shutil.copytree(ROOT / "rsm_lrg", tmp_path / "rsm_lrg", ignore=shutil.ignore_patterns("__pycache__", "data"))
    with open(tmp_path / "rsm_lrg" / "io.py", "a", encoding="utf-8") as fh:
        fh.write("\n\ndef _closing():\n    from .factors import FactorSpace\n\n    return FactorSpace\n")
    found = _cycle_edges(_import_graph(tmp_path))
    assert ("rsm_lrg.io", "rsm_lrg.factors") in found
    assert ("rsm_lrg.io", "rsm_lrg.factors") not in _cycle_edges(_import_graph())
