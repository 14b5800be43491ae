"""The plotting module: arrays in, Figures out, data: URIs; no pyplot state, literal labels."""

from __future__ import annotations

import base64
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from matplotlib.figure import Figure

from rsm_lrg.report import plots as P


def _decode(uri: str) -> tuple[str, bytes]:
    head, b64 = uri.split(",", 1)
    return head, base64.b64decode(b64)


def test_png_and_svg_data_uris_are_valid_images():
    fig = P.residuals_vs_predicted(np.arange(5.0), np.array([0.1, -0.2, 0.0, 0.3, -0.1]))
    head, raw = _decode(P.to_data_uri(fig, "png"))
    assert head == "data:image/png;base64" and raw[:8] == b"\x89PNG\r\n\x1a\n"
    head, raw = _decode(P.to_data_uri(fig, "svg"))
    assert head == "data:image/svg+xml;base64" and b"<svg" in raw[:400]
    with pytest.raises(ValueError, match="not supported"):
        P.to_data_uri(fig, "gif")


def test_output_is_reproducible():
    """No dates or other run-dependent metadata: the same figure gives the same bytes."""
    r = np.linspace(-1, 1, 9)
    a = P.to_data_uri(P.normal_probability_plot(r), "svg")
    b = P.to_data_uri(P.normal_probability_plot(r), "svg")
    assert a == b


@pytest.mark.slow
def test_every_plot_returns_a_figure():
    rng = np.random.default_rng(0)
    r = rng.normal(size=20)
    X, Y, Z = P.evaluate_on_grid(lambda x, y: x * y, (0.0, 1.0), (0.0, 2.0), n=6)
    figs = [
        P.normal_probability_plot(r),
        P.residuals_vs_predicted(r + 5, r, limits=3.0),
        P.residuals_vs_run(r, np.arange(20, 0, -1), limits=3.0),
        P.predicted_vs_actual(r, 0.9 * r),
        P.cooks_distance_plot(np.abs(r), threshold=1.0),
        P.leverage_plot(np.abs(r) / 4, threshold=0.5),
        P.surface_3d(X, Y, Z, points=[[0.5, 1.0, 0.5]]),
        P.surface_3d(X, Y, Z, points=[[0.5, 1.0]]),
        P.contour_plot(X, Y, Z, points=[[0.5, 1.0]], mark=(0.1, 0.1)),
        P.contour_plot(X, Y, np.ones_like(Z)),  # flat surface: no contour levels, still a figure
        P.temperature_history({"model": ([0, 1, 2], [0, 3, 4])}, measured={"rig": ([0, 1], [0, 2.9])},
                              hlines={"paper": 4.038}),
        P.grouped_bars([0.04, 0.06, 0.075], {"RMS": [1, 2, 3], "RFCMS": [0.5, 1, np.nan]}),
        P.grouped_curves({"RMS": ([0, 1], [0, 1]), "RFCMS": ([0, 1], [0, 0.5])}),
    ]
    for f in figs:
        assert isinstance(f, Figure)
        assert P.to_data_uri(f).startswith("data:image/png;base64,")


@pytest.mark.slow
def test_plots_never_touch_pyplot():
    code = (
        "import sys, numpy as np\n"
        "from rsm_lrg.report import plots as P\n"
        "X, Y, Z = P.evaluate_on_grid(lambda x, y: x + y, (0, 1), (0, 1), 5)\n"
        "P.to_data_uri(P.surface_3d(X, Y, Z)); P.to_data_uri(P.contour_plot(X, Y, Z))\n"
        "P.to_data_uri(P.normal_probability_plot(np.arange(5.0)), 'svg')\n"
        "print('matplotlib.pyplot' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "False"


def test_normal_plot_uses_blom_positions():
    """Independent route: statsmodels ProbPlot with a = 3/8 gives Blom's plotting positions
    (Montgomery, Design and Analysis of Experiments, 8th ed., Sec. 3.4.1); agree to 1e-12."""
    from statsmodels.graphics.gofplots import ProbPlot

    r = np.array([0.3, -1.2, 0.8, 0.05, -0.4, 2.1, -0.9])
    fig = P.normal_probability_plot(r)
    ax = fig.axes[0]
    xy = ax.collections[0].get_offsets()
    np.testing.assert_array_equal(xy[:, 0], np.sort(r))
    np.testing.assert_allclose(xy[:, 1], ProbPlot(r, a=3 / 8).theoretical_quantiles, rtol=0, atol=1e-12)


@pytest.mark.slow
@settings(max_examples=15, deadline=None)
@given(st.lists(st.floats(-1e3, 1e3, allow_nan=False), min_size=1, max_size=40))
def test_normal_plot_any_residuals(values):
    fig = P.normal_probability_plot(values)
    y = fig.axes[0].collections[0].get_offsets()[:, 1]
    assert np.all(np.diff(y) > 0)  # quantiles strictly increase
    assert P.to_data_uri(fig, "png")


def test_evaluate_on_grid_exact():
    X, Y, Z = P.evaluate_on_grid(lambda x, y: 2 * x - y, (0.0, 1.0), (10.0, 20.0), n=3)
    np.testing.assert_array_equal(X[0], [0.0, 0.5, 1.0])
    np.testing.assert_array_equal(Y[:, 0], [10.0, 15.0, 20.0])
    np.testing.assert_array_equal(Z, 2 * X - Y)


@pytest.mark.parametrize("kwargs, match", [
    (dict(x_range=(1.0, 0.0), y_range=(0.0, 1.0)), "low < high"),
    (dict(x_range=(0.0, 1.0), y_range=(0.0, float("nan"))), "finite"),
    (dict(x_range=(0.0, 1.0), y_range=(0.0, 1.0), n=1), "at least 2"),
])
def test_evaluate_on_grid_bad_input(kwargs, match):
    with pytest.raises(ValueError, match=match):
        P.evaluate_on_grid(lambda x, y: x, **kwargs)


def test_mismatched_lengths_and_empty_input_are_value_errors():
    with pytest.raises(ValueError, match="must match"):
        P.residuals_vs_predicted([1, 2, 3], [1, 2])
    with pytest.raises(ValueError, match="no values"):
        P.normal_probability_plot([])
    with pytest.raises(ValueError, match="2 categories"):
        P.grouped_bars(["a", "b"], {"s": [1, 2, 3]})


@pytest.mark.parametrize("name", ["cost_$", "$x^2$ \\alpha", "<script>alert(1)</script>", "a{b}_c^d"])
def test_labels_are_literal_text(name):
    """Column names are drawn as given: '$' never starts mathtext (which would fail or
    reinterpret the name)."""
    fig = P.predicted_vs_actual([1.0, 2.0, 3.0], [1.1, 1.9, 3.2], response=name)
    P.to_data_uri(fig, "svg")
    X, Y, Z = P.evaluate_on_grid(lambda x, y: x + y, (0, 1), (0, 1), 4)
    P.to_data_uri(P.surface_3d(X, Y, Z, xlabel=name, ylabel=name, zlabel=name))
    P.to_data_uri(P.contour_plot(X, Y, Z, xlabel=name, zlabel=name))
    label = fig.axes[0].xaxis.label
    assert label.get_text() == "Actual " + name.replace("$", r"\$")


def test_rendered_carries_size_and_text():
    fig = P.cooks_distance_plot([0.1, 0.2])
    r = P.render(fig, "cooks", "Cook's distance", "caption", "svg")
    assert (r.width_px, r.height_px) == (480, 346)  # 5.0 x 3.6 in at 96 px/in
    assert r.to_dict()["key"] == "cooks"


def _text_boxes(fig):
    """Window boxes of every visible text drawn in a figure's axes (labels, tick labels,
    legend entries), as rendered by Agg."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    renderer = FigureCanvasAgg(fig).get_renderer()
    fig.draw(renderer)
    out = []
    for ax in fig.axes:
        texts = list(ax.texts)
        for axis, (lo, hi) in ((ax.xaxis, ax.get_xlim()), (ax.yaxis, ax.get_ylim())):  # ticks in view
            texts += [t.label1 for t in axis.get_major_ticks() if min(lo, hi) <= t.get_loc() <= max(lo, hi)]
        if ax.get_legend() is not None:
            texts += ax.get_legend().get_texts()
        for t in texts:
            if t.get_visible() and t.get_text():
                out.append((t.get_text(), t.get_window_extent(renderer)))
    return out


@pytest.mark.parametrize("n_active", [3, 9, 15])
def test_half_normal_labels_never_overlap(n_active):
    # long names, many active effects close together, ME and SME a hair apart (issue 25)
    from rsm_lrg.report.plots import half_normal_plot

    rng = np.random.default_rng(n_active)
    names = [f"thickness_of_the_guide_rail_{i}×velocity_of_carriage" if i % 2 else f"T{i}" for i in range(31)]
    small = np.sort(rng.uniform(0, 0.25, 31 - n_active))
    big = 5.0 + np.sort(rng.uniform(0, 0.3, n_active))  # nearly equal effects: points almost on one spot
    x = np.concatenate([small, big])
    y = np.sort(np.abs(rng.normal(0, 1, 31)))
    fig = half_normal_plot(x, y, names, me=0.30, sme=0.31)
    boxes = _text_boxes(fig)
    labelled = [t for t, _ in boxes if t in names]
    assert len(labelled) == n_active
    assert {"ME 0.3", "SME 0.31"} <= {t for t, _ in boxes}
    for i, (ta, a) in enumerate(boxes):
        for tb, b in boxes[i + 1:]:
            assert not a.overlaps(b), (ta, tb)
    frame = fig.bbox
    for t, b in boxes:  # nothing drawn off the figure
        assert frame.x0 <= b.x0 and b.x1 <= frame.x1 and frame.y0 <= b.y0 and b.y1 <= frame.y1, t


@pytest.mark.parametrize("scale", [1e-11, 0.03, 2.5e6])
def test_contour_labels_are_present_format_number(scale):
    # the static contour's line labels are written by the one number format (issue 25)
    from rsm_lrg.present import format_number

    X, Y, Z = P.evaluate_on_grid(lambda a, b: scale * (1 + a * a + 0.5 * b), (-1, 1), (-1, 1))
    fig = P.contour_plot(X, Y, Z)
    labels = [t for t in fig.axes[0].texts if t.get_text()]
    assert len(labels) >= 3
    levels = next(c.levels for c in fig.axes[0].collections if hasattr(c, "levels"))
    for t in labels:
        assert "e" not in t.get_text()  # never %g's 1e-11 or 2.5e+06
        assert t.get_text() in {format_number(float(v)) for v in levels}, t.get_text()
