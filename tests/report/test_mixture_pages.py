"""The report of a mixture fit (static page, interactive page data, notebook fragment): the
ternary contour and the trace plot are there, with the numbers of rsm_lrg.model.readings.mixture_trace
and rsm_lrg.model.build.mixture_region (Myers & Montgomery's plasma-etch blends, ``r/mixture_etch*.csv``).
The browser side (sliders, figures drawn) is tests/browser/test_mixture_browser.py."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.model.build.mixture_region import mixture_region
from rsm_lrg.model.readings.mixture_trace import mixture_trace
from rsm_lrg.report.interactive import interactive_html

R = Path(__file__).parents[1] / "model" / "r"


@pytest.fixture(scope="module")
def fit():
    return rsm_lrg.fit(pd.read_csv(R / "mixture_etch_l.csv"), "erate", components=["x1=0.1:1", "x2=0.2:1", "x3=0.05:1"],
                       model="mixture-quadratic")


def test_static_report_has_ternary_and_trace(fit):
    html = fit.to_html(goal="maximize")
    assert 'id="fig-ternary"' in html and 'id="fig-trace"' in html
    assert "pairs of the" not in html  # no factor-pair surfaces of components
    assert re.search(r'id="fig-ternary".*?<img src="data:image/png;base64,', html, re.S)


def test_two_components_give_the_trace_only():
    d = pd.DataFrame({"a": [1, 0.75, 0.5, 0.25, 0, 0.5], "b": [0, 0.25, 0.5, 0.75, 1, 0.5],
                      "y": [3.0, 4.1, 5.3, 4.8, 2.9, 5.1]})
    f = rsm_lrg.fit(d, "y", components=["a", "b"], model="mixture-quadratic")
    html = f.to_html(goal="maximize")
    assert 'id="fig-trace"' in html and 'id="fig-ternary"' not in html


def test_interactive_page_data(fit):
    html = interactive_html(fit, goals="maximize")
    data = json.loads(re.search(r'<script type="application/json" id="rsm-data">(.*?)</script>', html, re.S).group(1))
    mix = data["mixture"]
    region = mixture_region(fit.space)
    np.testing.assert_array_equal(np.array(mix["G"]), region.G)
    np.testing.assert_array_equal(np.array(mix["h"]), region.h)
    ref = region.to_actual(region.centroid())
    assert mix["reference"] == [ref[n] for n in fit.space.names]
    for c, ctl in zip(mix["components"], data["controls"]):
        assert ctl["component"] and ctl["value"] == ref[c["name"]]
        assert c["lower"] <= c["low"] < c["high"] <= c["upper"]
    tr = mixture_trace(fit)
    (t,) = mix["traces"]
    for cv in t["curves"]:
        assert cv["deviation"] == list(tr.deviation[cv["name"]])
        assert cv["effect"] == tr.effects[cv["name"]]
    for div in ("ternary-plot", "ternary-surface", "ternary-overlay", "trace-plot", "mixture-effects"):
        assert f'id="{div}"' in html
    assert 'id="overlay-plot"' not in html  # no x-y overlay over components


def test_notebook_shows_the_effects(fit):
    frag = fit._repr_html_()
    tr = mixture_trace(fit)
    assert "Component effects (Cox direction" in frag
    from rsm_lrg.present import format_number

    for c in tr.effects:
        assert format_number(tr.effects[c], 5) in frag
