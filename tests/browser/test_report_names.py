"""Names are data in the interactive page (issue 26 item 3): a factor, level or response named
``__proto__``, ``constructor`` or ``toString`` is an ordinary name.

A factor named ``__proto__`` once made every profiler prediction NaN (the page kept the
setting in a plain ``{}``, whose ``__proto__`` key is the prototype). Here such pages are
opened in real headless Chromium, every control is moved, and each displayed prediction, CI
and PI equals ``FitResult.predict`` (1e-9 relative); nothing is NaN and no script error shows.
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.report.interactive import write_interactive_report

pytestmark = [pytest.mark.browser, pytest.mark.slow]

NAMES = ["__proto__", "constructor", "toString"]
RTOL = 1e-9
COLS = ("predicted", "ci_low", "ci_high", "pi_low", "pi_high")
ATTRS = ("value", "ciLow", "ciHigh", "piLow", "piHigh")

SET = """([name, value, kind]) => {
  const el = Array.from(document.querySelectorAll('[data-factor]')).find(e => e.dataset.factor === name);
  el.value = String(value);
  el.dispatchEvent(new Event(kind, {bubbles: true}));
  return el.value;
}"""

READ = """() => ({
  setting: Array.from(document.querySelectorAll('[data-factor]')).map(
      e => [e.dataset.factor, e.tagName === 'SELECT' ? e.value : parseFloat(e.value)]),
  rows: Array.from(document.querySelectorAll('[data-prediction]')).map(e => ({
      response: e.dataset.response, value: e.dataset.value, ciLow: e.dataset.ciLow, ciHigh: e.dataset.ciHigh,
      piLow: e.dataset.piLow, piHigh: e.dataset.piHigh, text: e.innerText}))
})"""


def _frame(factor_names, level_names, responses, seed=3) -> pd.DataFrame:
    """Two numeric factors, one categoric factor (three levels), a face-centred grid run
    twice; each response a quadratic in the numeric factors plus a level effect, with noise."""
    rng = np.random.default_rng(seed)
    rows = [(a, b, lv) for a in (-1.0, 0.0, 1.0) for b in (-1.0, 0.0, 1.0) for lv in level_names] * 2
    df = pd.DataFrame(rows, columns=factor_names)
    a, b = df[factor_names[0]].to_numpy(), df[factor_names[1]].to_numpy()
    lev = df[factor_names[2]].map({lv: i for i, lv in enumerate(level_names)}).to_numpy()
    for k, r in enumerate(responses):
        df[r] = 5 + (k + 1) * a - 0.5 * b + 0.3 * a * b + 0.4 * a * a + 0.2 * lev + 0.05 * rng.standard_normal(len(df))
    return df


CASES = {
    # factor names, level names, response names
    "factors": (["__proto__", "constructor", "toString"], ["x", "y", "z"], ["valueOf"]),
    "levels": (["a", "b", "lot"], NAMES, ["y"]),
    "responses": (["a", "b", "lot"], ["p", "q", "r"], NAMES),
}


def _page(tmp_path, case):
    fnames, levels, responses = CASES[case]
    df = _frame(fnames, levels, responses)
    fits = {r: rsm_lrg.fit(df, r, factors=[fnames[0], fnames[1], f"{fnames[2]}=cat"], model="quadratic")
            for r in responses}
    path = write_interactive_report(fits, tmp_path / f"{case}.html", goals=["minimize"] * len(responses))
    return path, fits


@pytest.mark.parametrize("case", sorted(CASES))
def test_page_data_keeps_the_names(case, tmp_path):
    # without a browser: the names reach the page data as plain strings, in lists and values
    path, fits = _page(tmp_path, case)
    html = path.read_text(encoding="utf-8")
    start = html.index('id="rsm-data"')
    body = html[html.index(">", start) + 1: html.index("</script>", start)]
    data = json.loads(body)
    assert [m["response"] for m in data["models"]] == list(fits)
    names = [c["name"] for c in data["controls"]]
    assert names == list(CASES[case][0])
    cat = [c for c in data["controls"] if c["kind"] == "categoric"][0]
    assert cat["levels"] == list(CASES[case][1])


@pytest.mark.parametrize("case", sorted(CASES))
def test_names_like_object_keys_predict_as_python(case, chromium, tmp_path):
    path, fits = _page(tmp_path, case)
    url = path.resolve().as_uri()
    ctx = chromium.new_context(viewport={"width": 1280, "height": 900}, offline=True)
    try:
        page = ctx.new_page()
        errors: list = []
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
        page.route("**/*", lambda route: route.continue_() if route.request.url == url else route.abort())
        page.goto(url, wait_until="load")
        page.wait_for_function("() => window.rsmReport !== undefined")
        fnames, levels, _ = CASES[case]
        moves = [(fnames[0], "0.35"), (fnames[1], "-0.8"), (fnames[2], levels[1]), (fnames[2], levels[2]),
                 (fnames[0], "-1"), (fnames[2], levels[0])]
        checked = 0
        for name, value in [(None, None), *moves]:
            if name is not None:
                page.evaluate(SET, [name, value, "input"])
            state = page.evaluate(READ)
            setting = dict(state["setting"])
            assert list(setting) == list(fnames)
            point = pd.DataFrame({k: [v] for k, v in setting.items()})
            assert sorted(r["response"] for r in state["rows"]) == sorted(fits)
            for row in state["rows"]:
                ref = fits[row["response"]].predict(point, interval="both").iloc[0]
                got = np.array([float(row[a]) for a in ATTRS])
                assert np.all(np.isfinite(got)), (row, setting)
                np.testing.assert_allclose(got, ref[list(COLS)].to_numpy(dtype=float), rtol=RTOL, atol=0)
                checked += 1
        assert checked == 7 * len(fits)
        # the page's own predict, called with a setting keyed by these names
        got = page.evaluate("([r, s]) => window.rsmReport.predict(r, Object.fromEntries(s)).predicted",
                            [list(fits)[0], [[fnames[0], 0.1], [fnames[1], 0.2], [fnames[2], levels[1]]]])
        want = fits[list(fits)[0]].predict(pd.DataFrame({fnames[0]: [0.1], fnames[1]: [0.2], fnames[2]: [levels[1]]}))
        assert got == pytest.approx(float(np.asarray(want["predicted"] if hasattr(want, "columns") else want)[0]),
                                    rel=RTOL)
        assert errors == []
    finally:
        ctx.close()
