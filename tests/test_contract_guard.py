"""The prediction contract holds in the code (issue 31): no consumer asks a fitted model
which kind it is by ``getattr(result, "mixture" | "mixed")``; a mixture region is asked of the
factor space (``space.has_components``) and a REML fit's parts of ``result.mixed`` or
``result.estimation``."""

import re
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "rsm_lrg"
KIND_PROBE = re.compile(r"""getattr\(\s*\w+\s*,\s*["'](mixture|mixed)["']""")


def test_no_consumer_probes_the_kind_of_a_fit():
    found = [f"{p.relative_to(PACKAGE)}:{i}" for p in PACKAGE.rglob("*.py")
             for i, line in enumerate(p.read_text(encoding="utf-8").splitlines(), start=1) if KIND_PROBE.search(line)]
    assert found == []


KIND_BRANCH = re.compile(r"""\.mixed\s+is\s+(not\s+)?None|\bif\s+(not\s+)?[\w.]*\bresult\.mixture\b|self\.mixture\b""")


def test_no_method_above_the_engines_branches_on_the_kind():
    # the result reads through the reading and form chosen when it was assembled
    # (rsm_lrg.model.results.kinds); faces and commands ask those, never result.mixed / .mixture
    # (the specification, model/build, says what is fitted; the engines are the kinds)
    found = [f"{p.relative_to(PACKAGE)}:{i}" for p in PACKAGE.rglob("*.py")
             if not {"engines", "build"} & set(p.parts) and p.name != "kinds.py"
             for i, line in enumerate(p.read_text(encoding="utf-8").splitlines(), start=1)
             if KIND_BRANCH.search(line) and not line.lstrip().startswith("#")]
    assert found == []
