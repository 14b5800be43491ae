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
def test_import_linter_contract_is_kept():
    out = subprocess.run(["lint-imports", "--no-cache"], capture_output=True, text=True, cwd=ROOT, timeout=300)
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-2000:]
    assert "0 broken" in out.stdout


LOADED = """
import json, sys
{body}
print(json.dumps(sorted(m for m in sys.modules if m.startswith("rsm_lrg"))))
"""

ABOVE_MODEL = ("rsm_lrg.optimize", "rsm_lrg.report", "rsm_lrg.cli", "rsm_lrg.paper", "rsm_lrg.surrogate",
               "rsm_lrg.physics")


def _offending(mods, prefixes):
    return [m for m in mods if any(m == p or m.startswith(p + ".") for p in prefixes)]


def test_importing_the_model_loads_no_higher_layer():
    mods = _fresh(LOADED.format(body="import rsm_lrg.model"))
    assert "rsm_lrg.model.fit" in mods
    assert _offending(mods, ABOVE_MODEL) == []


def test_fitting_and_printing_loads_no_higher_layer():
    body = ("import rsm_lrg\nfrom rsm_lrg.model import fit\n"
            "r = fit(rsm_lrg.load_table4(), 'tcr_c_per_min')\nr.summary(); r.to_dict(); r.anova")
    mods = _fresh(LOADED.format(body=body))
    assert _offending(mods, ABOVE_MODEL) == []


def test_conveniences_reach_the_higher_layers_through_the_registry():
    # FitResult.optimize / _repr_html_ work from a fresh process without the caller importing
    # optimize or report: the facade declared the providers (rsm_lrg.registry)
    body = ("import rsm_lrg\nr = rsm_lrg.fit(rsm_lrg.load_table4(), 'tcr_c_per_min')\n"
            "assert abs(r.optimize('minimize').predicted - 0.0228333333) < 1e-9\n"  # paper Sec. 4.3
            "assert '<table' in r._repr_html_()")
    mods = _fresh(LOADED.format(body=body))
    assert "rsm_lrg.optimize.single" in mods and "rsm_lrg.report.fit_report" in mods


@pytest.mark.parametrize("first", ["import rsm_lrg.optimize", "rsm_lrg.optimize", "from rsm_lrg import optimize",
                                   "import rsm_lrg.optimize.confirm", "from rsm_lrg.optimize import optimize"])
def test_rsm_lrg_optimize_is_always_the_callable_package(first):
    # issue 11: it used to be the function or the package depending on import order
    code = (f"import rsm_lrg\n{first}\nimport types, json, rsm_lrg.optimize\n"
            "o = rsm_lrg.optimize\n"
            "print(json.dumps([isinstance(o, types.ModuleType), o.__name__, callable(o),"
            " o.optimize.__module__]))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert out.returncode == 0, out.stderr
    assert json.loads(out.stdout) == [True, "rsm_lrg.optimize", True, "rsm_lrg.optimize.single"]


def test_light_commands_do_not_import_heavy_libraries():
    # issue 11, item 3: --help and the parser load no numpy, pandas, scipy, statsmodels, matplotlib
    code = ("import sys, json\nfrom rsm_lrg.cli import build_parser\nbuild_parser()\n"
            "print(json.dumps(sorted(m for m in sys.modules if m.split('.')[0] in "
            "('numpy', 'pandas', 'scipy', 'statsmodels', 'matplotlib'))))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert out.returncode == 0, out.stderr
    assert json.loads(out.stdout) == []


def test_fit_command_does_not_import_statsmodels_api_or_matplotlib():
    # issue 11, item 3: `rsm-lrg fit data/table4.csv --response tcr_c_per_min` imports only
    # what it needs (statsmodels' formula/api stack and matplotlib are for other commands)
    code = ("import sys, json, io, contextlib\nfrom rsm_lrg.cli import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n"
            "    rc = main(['fit', 'data/table4.csv', '--response', 'tcr_c_per_min'])\n"
            "print(json.dumps([rc, sorted(m for m in sys.modules if m in "
            "('statsmodels.api', 'scipy.stats', 'matplotlib', 'matplotlib.pyplot', 'dask', 'rsm_lrg.report', "
            "'rsm_lrg.optimize'))]))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert out.returncode == 0, out.stderr
    assert json.loads(out.stdout) == [0, []]


@pytest.mark.skipif(shutil.which("lint-imports") is None, reason="import-linter is not installed (test extra)")
def test_contract_counts_imports_inside_functions(tmp_path):
    # a copy of the package with one import inside a function that reverses the layers
    # (model -> optimize) must break the contract; the real package is untouched
    shutil.copytree(ROOT / "rsm_lrg", tmp_path / "rsm_lrg", ignore=shutil.ignore_patterns("__pycache__", "data"))
    shutil.copy(ROOT / "pyproject.toml", tmp_path / "pyproject.toml")
    with open(tmp_path / "rsm_lrg" / "model" / "terms.py", "a", encoding="utf-8") as fh:
        fh.write("\n\ndef _reversed():\n    from ..optimize import optimize\n\n    return optimize\n")
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"} | {"PYTHONPATH": str(tmp_path)}
    out = subprocess.run(["lint-imports", "--no-cache"], capture_output=True, text=True, cwd=tmp_path, env=env,
                         timeout=300)
    assert out.returncode != 0
    assert "rsm_lrg.model.terms -> rsm_lrg.optimize" in out.stdout


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
