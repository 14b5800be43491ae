"""The mixture report in real headless Chromium: the profiler keeps every blend on the simplex
and inside the bounds, its numbers are the model's, and the ternary contour and trace plot
carry the model's numbers.

Data: a four-component constrained region (oil 0.1..0.6, additive 0.05..0.4, thickener
0..0.5, filler 0.1..0.4, oil + additive <= 0.7; the extreme vertices with their centroids,
``rsm_lrg.extreme_vertices``) with a response from a Scheffé special cubic plus noise, fitted
by a special cubic on L-pseudo components; and Myers & Montgomery's plasma-etch blends
(three components) fitted by a quadratic. Every slider is moved to its ends, past them and to
random values; after each move the blend read back from the sliders must sum to the total
within 1e-9 and lie inside every component's bounds, and the displayed prediction, CI and PI
must equal ``FitResult.predict`` at that blend (1e-9 relative).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.model.readings.mixture_trace import mixture_trace
from rsm_lrg.report.interactive import write_interactive_report

pytestmark = [pytest.mark.browser, pytest.mark.slow]

BOUNDS = {"oil": (0.1, 0.6), "additive": (0.05, 0.4), "thickener": (0.0, 0.5), "filler": (0.1, 0.4)}
RTOL = 1e-9
ETCH = Path(__file__).parents[1] / "model" / "r" / "mixture_etch.csv"

READ_JS = """() => ({
  setting: Array.from(document.querySelectorAll('[data-factor]')).map(e => [e.dataset.factor, parseFloat(e.value)]),
  rows: Array.from(document.querySelectorAll('[data-prediction]')).map(e => ({
      response: e.dataset.response, value: parseFloat(e.dataset.value), ci_low: parseFloat(e.dataset.ciLow),
      ci_high: parseFloat(e.dataset.ciHigh), pi_low: parseFloat(e.dataset.piLow), pi_high: parseFloat(e.dataset.piHigh)}))
})"""

# (the setting leaves the page as (name, value) pairs: a name such as __proto__ does not survive
# as an object key on its way out of the page; _read makes them a dict)
SET = """([name, value, kind]) => {
  const el = Array.from(document.querySelectorAll('[data-factor]')).find(e => e.dataset.factor === name);
  el.value = String(value);
  el.dispatchEvent(new Event(kind, {bubbles: true}));
}"""

FIGURE = """([id, kind]) => {
  const el = document.getElementById(id);
  return (el.data || []).filter(t => t.meta && t.meta.kind === kind).map(t => ({
    x: Array.from(t.x), y: Array.from(t.y), z: t.z ? t.z.map(r => Array.from(r)) : null, meta: t.meta}));
}"""


def _read(page) -> dict:
    state = page.evaluate(READ_JS)
    state["setting"] = dict(state["setting"])
    return state


def _four_component_data() -> pd.DataFrame:
    d = rsm_lrg.extreme_vertices(BOUNDS, constraints=["oil + additive <= 0.7"], centroids=True)
    df = d.to_frame()[list(BOUNDS)].copy()
    rng = np.random.default_rng(22)
    L = np.array([b[0] for b in BOUNDS.values()])
    Z = (df.to_numpy() - L) / (1 - L.sum())
    y = Z @ np.array([40.0, 65.0, 30.0, 50.0]) + 90 * Z[:, 0] * Z[:, 1] - 60 * Z[:, 1] * Z[:, 2] \
        + 400 * Z[:, 0] * Z[:, 2] * Z[:, 3]
    df["hardness"] = y + rng.normal(0, 1.0, len(y))
    return df


@pytest.fixture(scope="module")
def mixture_pages(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("mix")
    df = _four_component_data()
    fit4 = rsm_lrg.fit(df, "hardness", components=[f"{k}={a}:{b}" for k, (a, b) in BOUNDS.items()],
                       model="special-cubic")
    p4 = write_interactive_report(fit4, tmp / "four.html", goals="maximize", source_name="extreme vertices")
    etch = pd.read_csv(ETCH)
    fit3 = rsm_lrg.fit(etch, "erate", components=["x1", "x2", "x3"], model="mixture-quadratic")
    p3 = write_interactive_report(fit3, tmp / "three.html", goals="maximize", source_name="etch")
    lat = rsm_lrg.simplex_lattice(["a", "b", "c"], 3, center=True, axial=True).to_frame()[["a", "b", "c"]]
    rng = np.random.default_rng(9)
    z = lat.to_numpy()
    lat["y"] = z @ [10.0, 14.0, 8.0] + 12 * z[:, 0] * z[:, 1] * (z[:, 0] - z[:, 1]) + 20 * z[:, 1] * z[:, 2] \
        + rng.normal(0, 0.3, len(z))
    fitc = rsm_lrg.fit(lat, "y", components=["a", "b", "c"], model="mixture-cubic")  # with AB(A-B) terms
    pc = write_interactive_report(fitc, tmp / "cubic.html", goals="minimize", source_name="etch")
    return {"four": (p4, fit4), "three": (p3, fit3), "cubic": (pc, fitc)}


def _open(chromium, path):
    url = path.resolve().as_uri()
    ctx = chromium.new_context(viewport={"width": 1280, "height": 900}, offline=True)
    page = ctx.new_page()
    errors = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    page.route("**/*", lambda route: route.continue_() if route.request.url == url else route.abort())
    page.goto(url, wait_until="load")
    page.wait_for_function("() => window.rsmReport !== undefined")
    page.evaluate("() => window.rsmReport.drawNow()")
    return ctx, page, errors


def _check_state(fit, state) -> None:
    comps = [f for f in fit.space.factors]
    blend = {f.name: state["setting"][f.name] for f in comps}
    total = comps[0].total
    assert abs(sum(blend.values()) - total) <= 1e-9, blend
    for f in comps:
        hi = min(f.upper, f.total)
        assert f.lower - 1e-12 <= blend[f.name] <= hi + 1e-12, (f.name, blend[f.name], f.lower, hi)
    ref = fit.predict(pd.DataFrame({k: [v] for k, v in blend.items()}), interval="both").iloc[0]
    (row,) = state["rows"]
    got = np.array([row[k] for k in ("value", "ci_low", "ci_high", "pi_low", "pi_high")])
    want = ref[["predicted", "ci_low", "ci_high", "pi_low", "pi_high"]].to_numpy(dtype=float)
    np.testing.assert_allclose(got, want, rtol=RTOL, atol=0)


@pytest.mark.parametrize("which", ["four", "three", "cubic"])
def test_sliders_keep_the_blend_on_the_simplex_and_inside_the_bounds(chromium, mixture_pages, which):
    path, fit = mixture_pages[which]
    ctx, page, errors = _open(chromium, path)
    try:
        controls = page.evaluate("() => Array.from(document.querySelectorAll('[data-factor]')).map(e => "
                                 "({name: e.dataset.factor, min: parseFloat(e.min), max: parseFloat(e.max)}))")
        assert [c["name"] for c in controls] == fit.space.names
        _check_state(fit, _read(page))  # the start: the region's centroid
        rng = np.random.default_rng(5)
        moved = 0
        for rnd in range(5):
            for c in controls:
                lo, hi = c["min"], c["max"]
                v = [lo, hi, lo - 0.3, hi + 0.3, float(rng.uniform(lo, hi))][rnd]
                page.evaluate(SET, [c["name"], repr(v), "input" if rnd % 2 == 0 else "change"])
                state = _read(page)
                _check_state(fit, state)
                if lo <= v <= hi:  # the moved component takes the value unless the others' bounds forbid it
                    others = [f for f in fit.space.factors if f.name != c["name"]]
                    floor = fit.space.factors[0].total - sum(min(f.upper, f.total) for f in others)
                    ceil = fit.space.factors[0].total - sum(f.lower for f in others)
                    want = min(max(v, floor), ceil)
                    assert state["setting"][c["name"]] == pytest.approx(want, abs=1e-12)
                moved += 1
        # the number boxes move the blend the same way
        name = controls[0]["name"]
        page.evaluate("""([name, v]) => { const el = Array.from(document.querySelectorAll('[data-factor-text]'))
            .find(e => e.dataset.factorText === name); el.value = String(v); el.dispatchEvent(new Event('change')); }""",
                      [name, controls[0]["min"] + 0.37 * (controls[0]["max"] - controls[0]["min"])])
        _check_state(fit, _read(page))
        # the jump buttons: the optimum blend, then the centre (the region's centroid)
        page.click("[data-jump=optimum]")
        state = _read(page)
        _check_state(fit, state)
        best = fit.optimize(goal="minimize" if which == "cubic" else "maximize")
        for k, v in best.actual.items():
            assert state["setting"][k] == pytest.approx(v, abs=1e-12)
        assert moved == 5 * len(controls)
        assert errors == []
    finally:
        ctx.close()


def _blend_at(cell_x, cell_y, meta, held):
    h3 = np.sqrt(3) / 2
    fa = cell_y / h3
    fc = cell_x - fa / 2
    fb = 1 - fa - fc
    out = dict(held)
    a, b, c = meta["components"]
    s = meta["share"]
    out[a], out[b], out[c] = s * max(fa, 0.0), s * max(fb, 0.0), s * max(fc, 0.0)
    return out


@pytest.mark.parametrize("which", ["four", "three", "cubic"])
def test_ternary_contour_and_trace_carry_the_model(chromium, mixture_pages, which):
    path, fit = mixture_pages[which]
    ctx, page, errors = _open(chromium, path)
    try:
        page.evaluate(SET, [fit.space.names[0], repr(0.35), "input"])  # off the centroid: the slice moves too
        page.evaluate("() => window.rsmReport.drawNow()")
        setting = _read(page)["setting"]
        (fig,) = page.evaluate(FIGURE, ["ternary-plot", "ternary-contour"])
        a, b, c = fig["meta"]["components"]
        assert [a, b, c] == fit.space.names[:3]
        held = {k: v for k, v in setting.items() if k not in (a, b, c)}
        assert fig["meta"]["share"] == pytest.approx(1.0 - sum(held.values()), abs=1e-12)
        Z = np.array([[np.nan if v is None else v for v in row] for row in fig["z"]], dtype=float)
        cells = np.argwhere(np.isfinite(Z))
        assert len(cells) > 200  # the region covers part of the triangle
        rng = np.random.default_rng(3)
        pick = cells[rng.choice(len(cells), size=60, replace=False)]
        blends = pd.DataFrame([_blend_at(fig["x"][i], fig["y"][j], fig["meta"], held) for j, i in pick])
        want = fit.predict(blends[fit.space.names])["predicted"].to_numpy()
        np.testing.assert_allclose(Z[pick[:, 0], pick[:, 1]], want, rtol=RTOL, atol=0)
        # a cell is drawn exactly where its blend lies in the region of the bounds (and constraints)
        from rsm_lrg.model.build.mixture_region import mixture_region

        region = mixture_region(fit.space)
        h3 = np.sqrt(3) / 2
        for j, i in pick.tolist() + np.argwhere(~np.isfinite(Z)).tolist()[:: max(1, (~np.isfinite(Z)).sum() // 80)]:
            fa = fig["y"][j] / h3
            fc = fig["x"][i] - fa / 2
            if min(fa, fc, 1 - fa - fc) < -1e-12:
                assert not np.isfinite(Z[j, i])  # outside the triangle
                continue
            blend = _blend_at(fig["x"][i], fig["y"][j], fig["meta"], held)
            coded = np.array([f.encode(blend[f.name]) for f in fit.space.factors])
            assert bool(region.contains(coded)[0]) == bool(np.isfinite(Z[j, i])), blend
        if which == "four":  # a slice of the simplex, said on the figure
            notes = page.evaluate("() => document.getElementById('ternary-plot').layout.annotations.map(a => a.text)")
            assert any(t.startswith("Slice: D: filler = ") for t in notes), notes
        # the trace plot: the Cox-direction curves of FitResult from the region's centroid
        curves = page.evaluate(FIGURE, ["trace-plot", "trace"])
        tr = mixture_trace(fit)
        assert [cv["meta"]["component"] for cv in curves] == fit.space.names
        for cv in curves:
            name = cv["meta"]["component"]
            np.testing.assert_allclose(cv["x"], tr.deviation[name], rtol=0, atol=1e-15)
            np.testing.assert_allclose(cv["y"], tr.predicted[name], rtol=1e-12)
            assert cv["x"][0] < 0 < cv["x"][-1]
        # the 3-D surface over the triangle and the overlay exist with the same grid
        (surf,) = page.evaluate(FIGURE, ["ternary-surface", "ternary-surface"])
        np.testing.assert_array_equal(np.isfinite(np.array(surf["z"], dtype=float)), np.isfinite(Z))
        assert page.evaluate(FIGURE, ["ternary-overlay", "ternary-overlay"])
        assert errors == []
    finally:
        ctx.close()


def test_component_names_are_data(chromium, tmp_path):
    """Components named like Object.prototype's members or with markup: the page keeps them as
    data (prototype-free objects, arrays of records), so the blend still sums to the total."""
    names = ["__proto__", "constructor", "a<b>&c"]
    etch = pd.read_csv(ETCH).rename(columns=dict(zip(["x1", "x2", "x3"], names)))
    fit = rsm_lrg.fit(etch, "erate", components=names, model="mixture-quadratic")
    path = write_interactive_report(fit, tmp_path / "names.html", goals="maximize")
    ctx, page, errors = _open(chromium, path)
    try:
        for name, v in zip(names, (0.6, 0.1, 0.45)):
            page.evaluate(SET, [name, repr(v), "input"])
            state = _read(page)
            assert list(state["setting"]) == names
            _check_state(fit, state)
        (fig,) = page.evaluate(FIGURE, ["ternary-plot", "ternary-contour"])
        assert fig["meta"]["components"] == names
        assert errors == []
    finally:
        ctx.close()
