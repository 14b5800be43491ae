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
