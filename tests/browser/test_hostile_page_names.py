"""Names in pages, unseen cases (issue 26): factor, level and response names that differ only
by case or by a trailing blank, that hold U+2028/U+2029 (line breaks to JavaScript before
ES2019, and to Python's ``str.splitlines``), markup (``</script>``, ``<!--``, an ``<img
onerror>``), object-key words, or thousands of characters, written by ``rsm-lrg report`` from
a CSV file (the reader, the command and the page together).

Each page is opened in headless Chromium: nothing the names hold runs (no ``window.__pwned``,
no dialog, no page error), every control shows its name as written, and after each move of
each control every displayed prediction equals ``FitResult.predict`` (1e-9 relative).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.cli import main
from rsm_lrg.io import read_table

pytestmark = [pytest.mark.browser, pytest.mark.slow]

CASES = {
    "case-and-blank": (["A", "a", "lot"], ["X", "x", "x "], ["Y", "y"]),
    "line-separators": (["a\u2028b", "c\u2029d", "l\u2028ot"], ["x\u2028", "y\u2029", "<!--<script>"],
                        ["y\u2028z", "</script><!--"]),
    "markup": (["</script><script>window.__pwned(1)</script>", "<!--", "__proto__"],
               ["toString", "</script>", "hasOwnProperty"], ["<img src=x onerror=window.__pwned=2>", "constructor"]),
    "long": (["f" * 5000, "b", "lot"], ["L" * 3000, "m", "n"], ["y" * 4000]),
}

READ = """() => Array.from(document.querySelectorAll('[data-prediction]')).map(e => ({
  response: e.dataset.response, value: e.dataset.value, ciLow: e.dataset.ciLow, piHigh: e.dataset.piHigh}))"""
SETTING = """() => Array.from(document.querySelectorAll('[data-factor]')).map(
  e => [e.dataset.factor, e.tagName === 'SELECT' ? e.value : parseFloat(e.value)])"""
MOVE = """([i, v]) => { const e = document.querySelectorAll('[data-factor]')[i]; e.value = v;
  e.dispatchEvent(new Event(e.tagName === 'SELECT' ? 'change' : 'input', {bubbles: true})); }"""


def _csv(tmp_path, case):
    factors, levels, responses = CASES[case]
    rng = np.random.default_rng(5)
    rows = [(a, b, lv) for a in (-1.0, 0.0, 1.0) for b in (-1.0, 0.0, 1.0) for lv in levels] * 2
    df = pd.DataFrame(rows, columns=factors)
    a, b = df[factors[0]].to_numpy(), df[factors[1]].to_numpy()
    lev = df[factors[2]].map({lv: i for i, lv in enumerate(levels)}).to_numpy()
    for k, r in enumerate(responses):
        df[r] = 5 + (k + 1) * a - 0.5 * b + 0.3 * a * b + 0.4 * a * a + 0.2 * lev + 0.05 * rng.standard_normal(len(df))
    path = tmp_path / f"{case}.csv"
    df.to_csv(path, index=False)
    return path


@pytest.mark.parametrize("case", sorted(CASES))
def test_hostile_names_through_the_command_line(case, chromium, tmp_path):
    factors, levels, responses = CASES[case]
    data = _csv(tmp_path, case)
    spec = [factors[0], factors[1], f"{factors[2]}=cat"]
    args = ["report", str(data), "-o", str(tmp_path / "page.html")]
    for r in responses:
        args += ["--response", r]
    for f in spec:
        args += ["--factor", f]
    assert main(args) == 0
    frame = read_table(data)
    assert list(frame.columns) == [*factors, *responses]  # the reader keeps every name as written
    fits = {r: rsm_lrg.fit(frame, r, factors=spec, model="quadratic") for r in responses}

    url = (tmp_path / "page.html").resolve().as_uri()
    ctx = chromium.new_context(viewport={"width": 1280, "height": 900}, offline=True)
    try:
        page = ctx.new_page()
        errors: list = []
        dialogs: list = []
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
        page.on("dialog", lambda d: (dialogs.append(d.message), d.dismiss()))
        page.route("**/*", lambda route: route.continue_() if route.request.url == url else route.abort())
        page.goto(url, wait_until="load")
        page.wait_for_function("() => window.rsmReport !== undefined")
        controls = page.evaluate("() => Array.from(document.querySelectorAll('[data-factor]')).map(e => "
                                 "[e.dataset.factor, e.tagName === 'SELECT' ? Array.from(e.options).map(o => o.value)"
                                 " : null])")
        assert [c[0] for c in controls] == factors
        assert controls[2][1] == levels
        moves = [(0, "0.35"), (1, "-0.8"), (2, levels[1]), (2, levels[2]), (0, "-1"), (2, levels[0])]
        checked = 0
        for i, value in [(None, None), *moves]:
            if i is not None:
                page.evaluate(MOVE, [i, value])
            point = pd.DataFrame({k: [v] for k, v in page.evaluate(SETTING)})
            rows = page.evaluate(READ)
            assert sorted(r["response"] for r in rows) == sorted(responses)
            for row in rows:
                ref = fits[row["response"]].predict(point, interval="both").iloc[0]
                got = np.array([float(row[k]) for k in ("value", "ciLow", "piHigh")])
                assert np.all(np.isfinite(got)), row
                np.testing.assert_allclose(got, ref[["predicted", "ci_low", "pi_high"]].to_numpy(dtype=float),
                                           rtol=1e-9, atol=0)
                checked += 1
        assert checked == 7 * len(responses)
        assert page.evaluate("() => window.__pwned === undefined")
        assert errors == [] and dialogs == []
    finally:
        ctx.close()


@pytest.mark.parametrize("case", ["markup", "line-separators"])
def test_hostile_names_in_the_static_pages_run_nothing(case, visit, tmp_path):
    factors, _, responses = CASES[case]
    data = _csv(tmp_path, case)
    spec = ["--factor", factors[0], "--factor", factors[1], "--factor", f"{factors[2]}=cat"]
    assert main(["report", str(data), "--static", "-o", str(tmp_path / "s.html"), "--response", responses[0],
                 *spec]) == 0
    assert main(["fit", str(data), "--report", str(tmp_path / "f.html"), "--response", responses[0], *spec]) == 0
    for name in ("s.html", "f.html"):
        seen = visit(tmp_path / name)
        assert seen.scripts == 0 and seen.dialogs == [] and seen.console_errors == []
        assert seen.foreign_requests == []
        for n in factors[:2] + responses[:1]:
            assert n.replace("\u2028", "").replace("\u2029", "")[:20] in seen.text.replace("\u2028", "").replace(
                "\u2029", "")
