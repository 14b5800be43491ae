"""Figures for the reports: plain arrays (or a predict callable) in, a matplotlib Figure out.

Every function here draws what it is given and computes no statistics of its own: the
residuals, leverages, Cook's distances and predictions come from the model layer
(:class:`rsm_lrg.model.FitResult`). The only arithmetic is presentation: normal plotting
positions for the probability plot, and evaluating a caller's ``predict`` callable on a
grid for surfaces and contours.

Figures are built with :class:`matplotlib.figure.Figure` directly (Agg canvas), never with
``pyplot``: no global figure registry, nothing to close, safe in threads and notebooks.
:func:`to_data_uri` turns a figure into a ``data:`` URI (PNG or SVG) for a self-contained
HTML page.

User text (column names, labels) is drawn literally: ``$`` is escaped so that matplotlib's
mathtext never interprets it.

Examples
--------
>>> import numpy as np
>>> fig = residuals_vs_predicted(np.arange(5.0), np.array([0.1, -0.2, 0.0, 0.3, -0.1]))
>>> to_data_uri(fig, "svg").startswith("data:image/svg+xml;base64,")
True
"""

from __future__ import annotations

import base64
import io
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from ..present import format_number

__all__ = [
    "Rendered",
    "render",
    "to_data_uri",
    "figure_bytes",
    "normal_probability_plot",
    "residuals_vs_predicted",
    "residuals_vs_run",
    "predicted_vs_actual",
    "cooks_distance_plot",
    "leverage_plot",
    "half_normal_plot",
    "evaluate_on_grid",
    "surface_3d",
    "contour_plot",
    "temperature_history",
    "grouped_bars",
    "grouped_curves",
    "ternary_contour",
    "trace_plot",
    "DEFAULT_DPI",
]

#: Resolution of PNG figures [dots per inch]: twice the 96 px/inch of a CSS pixel, so a
#: figure shown at its nominal size (:attr:`Rendered.width_px`, never more: the pages cap it)
#: has two image pixels per CSS pixel and stays sharp on high-density screens.
DEFAULT_DPI = 192

#: Figure size of a single panel [inch].
PANEL_SIZE = (5.0, 3.6)

_POINT_STYLE: dict[str, Any] = dict(color="#b5261e", edgecolor="black", linewidth=0.5, zorder=5)
_LINE_COLOR = "#1f4e79"


def _t(text) -> str:
    """Literal text for matplotlib: escape ``$`` so that mathtext never parses it."""
    return str(text).replace("$", r"\$")


def _vector(values, what: str) -> np.ndarray:
    a = np.asarray(values, dtype=float).ravel()
    if a.size == 0:
        raise ValueError(f"{what}: no values to plot")
    return a


def _same_length(a: np.ndarray, b: np.ndarray, what_a: str, what_b: str) -> None:
    if a.shape != b.shape:
        raise ValueError(f"{what_a} has {a.size} values but {what_b} has {b.size}; they must match")


def _paired(a, b, what_a: str, what_b: str) -> tuple[np.ndarray, np.ndarray]:
    """``a`` and ``b`` as float vectors of the same length (errors name ``what_a``/``what_b``)."""
    a, b = _vector(a, what_a), _vector(b, what_b)
    _same_length(a, b, what_a, what_b)
    return a, b


def run_numbers(run_order, y: np.ndarray, what: str) -> np.ndarray:
    """The x axis of a plot in run order: ``run_order``, or 1..n when it is None, one per
    value of ``y`` (``what``)."""
    x = np.arange(1, y.size + 1, dtype=float) if run_order is None else _vector(run_order, "run order")
    _same_length(x, y, "run order", what)
    return x


def _new_figure(size=PANEL_SIZE) -> Figure:
    # Fixed margins rather than a layout engine: constrained layout costs more than the
    # drawing itself, and these panels all have the same furniture.
    fig = Figure(figsize=size)
    fig.subplots_adjust(left=0.15, right=0.97, bottom=0.14, top=0.91)
    return fig


def _finish(ax, title: str | None, xlabel: str | None, ylabel: str | None) -> None:
    if title:
        ax.set_title(_t(title), fontsize=10)
    if xlabel:
        ax.set_xlabel(_t(xlabel))
    if ylabel:
        ax.set_ylabel(_t(ylabel))
    ax.grid(True, color="#dddddd", linewidth=0.6)
    ax.set_axisbelow(True)


# -- output -------------------------------------------------------------------------------

def figure_bytes(fig: Figure, fmt: str = "png", *, dpi: int = DEFAULT_DPI) -> bytes:
    """A figure as PNG or SVG bytes, free of dates (reproducible files).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
    fmt : {"png", "svg"}
        PNG suits 3-D surfaces and dense contours (small, fast); SVG suits line and
        scatter plots (sharp at any zoom).
    dpi : int
        Resolution of PNG output [dots per inch].
    """
    if fmt not in ("png", "svg"):
        raise ValueError(f"figure format {fmt!r} is not supported; use 'png' or 'svg'")
    buf = io.BytesIO()
    # metadata=None-like settings keep the output free of dates, so reports are reproducible
    meta = {"Software": None} if fmt == "png" else {"Date": None, "Creator": None}
    import matplotlib

    with matplotlib.rc_context({"svg.hashsalt": "rsm-lrg"}):  # stable SVG ids
        fig.savefig(buf, format=fmt, dpi=dpi, metadata=meta)
    return buf.getvalue()


def to_data_uri(fig: Figure, fmt: str = "png", *, dpi: int = DEFAULT_DPI) -> str:
    """A figure as a ``data:`` URI (:func:`figure_bytes` in base64)."""
    data = figure_bytes(fig, fmt, dpi=dpi)
    mime = "image/png" if fmt == "png" else "image/svg+xml"
    return f"data:{mime};base64,{base64.b64encode(data).decode('ascii')}"


@dataclass(frozen=True)
class Rendered:
    """A figure ready for a page: its ``data:`` URI plus the text around it.

    Attributes
    ----------
    key : str
        Stable identifier (used for the HTML ``id``), e.g. ``"surface-AB"``.
    title : str
        Short heading.
    caption : str
        Full caption (what is held fixed, what the markers are).
    uri : str
        ``data:image/...;base64,...``.
    width_px, height_px : int
        Nominal size of the image [CSS pixels].
    """

    key: str
    title: str
    caption: str
    uri: str
    width_px: int
    height_px: int

    def to_dict(self) -> dict:
        return {"key": self.key, "title": self.title, "caption": self.caption,
                "width_px": self.width_px, "height_px": self.height_px}


def render(fig: Figure, key: str, title: str, caption: str = "", fmt: str = "png",
           *, dpi: int = DEFAULT_DPI) -> Rendered:
    """Render ``fig`` to a :class:`Rendered` (``data:`` URI, nominal size at 96 px/inch)."""
    w, h = fig.get_size_inches()
    return Rendered(key=key, title=title, caption=caption, uri=to_data_uri(fig, fmt, dpi=dpi),
                    width_px=int(round(w * 96)), height_px=int(round(h * 96)))


# -- diagnostics (Design-Expert's six) -------------------------------------------------------

_PROB_TICKS = [1, 5, 10, 20, 30, 50, 70, 80, 90, 95, 99]


def _residual_lines(ax, limits: float | None) -> None:
    """The zero line of a residual plot and, when given, dashed lines at ±``limits``."""
    ax.axhline(0.0, color=_LINE_COLOR, linewidth=1)
    if limits is not None:
        for s in (-limits, limits):
            ax.axhline(s, color="#b5261e", linewidth=0.8, linestyle="--")


def normal_probability_plot(residuals, *, label: str = "Externally studentized residuals",
                            title: str | None = "Normal plot of residuals") -> Figure:
    """Normal probability plot: sorted residuals against normal % probability.

    Plotting positions are Blom's, ``p_i = (i − 3/8) / (n + 1/4)`` (Montgomery, *Design and
    Analysis of Experiments*, 8th ed., Sec. 3.4.1); the y axis is the standard normal
    quantile of ``p_i`` labelled in percent, as Design-Expert draws it. Points on a straight
    line mean normally distributed residuals.

    Parameters
    ----------
    residuals : array_like
        Residuals (raw or studentized) from the model layer.
    label : str
        x-axis label.
    """
    from statistics import NormalDist  # the normal quantile without importing scipy.stats

    ppf = np.vectorize(NormalDist().inv_cdf, otypes=[float])
    r = _vector(residuals, "residuals")
    ok = np.isfinite(r)
    r = np.sort(r[ok])
    if r.size == 0:
        raise ValueError("residuals: no finite values to plot")
    n = r.size
    p = (np.arange(1, n + 1) - 0.375) / (n + 0.25)
    q = ppf(p)
    fig = _new_figure()
    ax = fig.add_subplot()
    ax.scatter(r, q, s=22, **_POINT_STYLE)
    if n >= 2 and np.ptp(r) > 0:
        # reference line through the quartiles (as R's qqline)
        q1, q3 = np.percentile(r, [25, 75])
        z1, z3 = ppf([0.25, 0.75])
        if q3 > q1:
            slope = (z3 - z1) / (q3 - q1)
            xs = np.array([r[0], r[-1]])
            ax.plot(xs, z1 + slope * (xs - q1), color=_LINE_COLOR, linewidth=1)
    ticks = [t for t in _PROB_TICKS if ppf(t / 100) >= q[0] - 0.6 and ppf(t / 100) <= q[-1] + 0.6]
    ax.set_yticks(ppf(np.array(ticks) / 100.0))
    ax.set_yticklabels([str(t) for t in ticks])
    _finish(ax, title, label, "Normal % probability")
    return fig


def residuals_vs_predicted(predicted, residuals, *, limits: float | None = None,
                           label: str = "Residuals", title: str | None = "Residuals vs predicted") -> Figure:
    """Residuals against predicted values; optional ±``limits`` lines (e.g. ±3 for studentized)."""
    x, y = _paired(predicted, residuals, "predicted", "residuals")
    fig = _new_figure()
    ax = fig.add_subplot()
    ax.scatter(x, y, s=22, **_POINT_STYLE)
    _residual_lines(ax, limits)
    _finish(ax, title, "Predicted", label)
    return fig


def residuals_vs_run(residuals, run_order=None, *, limits: float | None = None,
                     label: str = "Residuals", title: str | None = "Residuals vs run order") -> Figure:
    """Residuals in run order (connected), to show drift or time effects."""
    y = _vector(residuals, "residuals")
    x = run_numbers(run_order, y, "residuals")
    o = np.argsort(x, kind="stable")
    fig = _new_figure()
    ax = fig.add_subplot()
    ax.plot(x[o], y[o], color="#888888", linewidth=0.8, zorder=3)
    ax.scatter(x[o], y[o], s=22, **_POINT_STYLE)
    _residual_lines(ax, limits)
    _finish(ax, title, "Run number", label)
    return fig


def predicted_vs_actual(actual, predicted, *, response: str = "response",
                        title: str | None = "Predicted vs actual") -> Figure:
    """Predicted against actual values with the 45° line of perfect prediction."""
    x, y = _paired(actual, predicted, "actual", "predicted")
    fig = _new_figure()
    ax = fig.add_subplot()
    lo = float(np.nanmin([x.min(), y.min()]))
    hi = float(np.nanmax([x.max(), y.max()]))
    pad = 0.05 * (hi - lo) if hi > lo else 1.0
    ax.plot([lo - pad, hi + pad], [lo - pad, hi + pad], color=_LINE_COLOR, linewidth=1)
    ax.scatter(x, y, s=22, **_POINT_STYLE)
    ax.set_xlim(lo - pad, hi + pad)
    ax.set_ylim(lo - pad, hi + pad)
    _finish(ax, title, f"Actual {response}", f"Predicted {response}")
    return fig


def _index_bars(values, run_order, threshold, ylabel, title, what) -> Figure:
    y = _vector(values, what)
    x = run_numbers(run_order, y, what)
    fig = _new_figure()
    ax = fig.add_subplot()
    ax.vlines(x, 0.0, y, color=_LINE_COLOR, linewidth=1.2)
    ax.scatter(x, y, s=18, **_POINT_STYLE)
    if threshold is not None and math.isfinite(threshold):
        ax.axhline(threshold, color="#b5261e", linewidth=0.8, linestyle="--",
                   label=f"reference {format_number(threshold, 3)}")
        ax.legend(loc="upper right", fontsize=8, frameon=False)
    ax.set_ylim(bottom=0.0)
    _finish(ax, title, "Run number", ylabel)
    return fig


def cooks_distance_plot(cooks, run_order=None, *, threshold: float | None = None,
                        title: str | None = "Cook's distance") -> Figure:
    """Cook's distance per run (as given by the model layer), optional reference line."""
    return _index_bars(cooks, run_order, threshold, "Cook's distance", title, "Cook's distance")


def leverage_plot(leverage, run_order=None, *, threshold: float | None = None,
                  title: str | None = "Leverage") -> Figure:
    """Leverage (hat diagonal) per run, optional reference line (e.g. 2p/n)."""
    return _index_bars(leverage, run_order, threshold, "Leverage", title, "leverage")


# -- response surfaces --------------------------------------------------------------------

def half_normal_plot(abs_effects, scores, labels, *, me: float | None = None, sme: float | None = None,
                     title: str | None = "Half-normal plot of effects") -> Figure:
    """Half-normal plot (Daniel 1959): ``|effect|`` against its half-normal score.

    Parameters
    ----------
    abs_effects, scores : array_like
        ``|effect|`` of each term and its half-normal score, both from the model layer
        (:func:`rsm_lrg.model.readings.effects.screening_effects`) [response units, -].
    labels : sequence of str
        Term names; the effects beyond ``me`` are labelled on the plot.
    me, sme : float, optional
        Lenth's margin and simultaneous margin of error, drawn as dashed vertical lines.
    """
    x, y = _paired(abs_effects, scores, "abs_effects", "scores")
    labels = [str(s) for s in labels]
    if len(labels) != x.size:
        raise ValueError(f"labels: {len(labels)} given for {x.size} effects")
    fig = _new_figure()
    ax = fig.add_subplot()
    ax.scatter(x, y, s=22, **_POINT_STYLE)
    small = x <= (me if me is not None else np.inf)
    if small.sum() >= 2 and np.any(x[small] > 0):  # the line through the origin of the inactive effects
        slope = float(np.sum(x[small] * y[small]) / np.sum(x[small] ** 2))
        xs = np.array([0.0, min(float(x.max()), float(y.max()) / slope)])
        ax.plot(xs, slope * xs, color=_LINE_COLOR, linewidth=1)
    # ME and SME are named in a legend (two lines a hair apart would put their names on one spot)
    for value, name, style in ((me, "ME", "--"), (sme, "SME", ":")):
        if value is not None and math.isfinite(value):
            ax.axvline(value, color="#b5261e", linewidth=0.8, linestyle=style, label=f"{name} {format_number(value)}")
    _finish(ax, title, "|Effect|", "Half-normal quantile")
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="lower right", fontsize=7, frameon=True, framealpha=0.9, edgecolor="none")
    active = [(float(xi), float(yi), lab) for xi, yi, lab in zip(x, y, labels) if me is not None and xi > me]
    _place_labels(fig, ax, active)
    return fig


#: Offsets tried for a point's label [points], in order: right, right above, right below, left,
#: left above, left below, then further above and below.
_LABEL_OFFSETS = [(4, -3, "left"), (4, 5, "left"), (4, -11, "left"), (-4, -3, "right"), (-4, 5, "right"),
                  (-4, -11, "right")] + [(dx, dy, ha) for k in (2, 3, 4) for dy in (-3 + 8 * k, -3 - 8 * k)
                                         for dx, ha in ((4, "left"), (-4, "right"))]


def _drawn_tick_labels(ax) -> list:
    """The tick labels of ``ax`` that are drawn: with text, at a tick inside the view."""
    out = []
    for axis, (lo, hi) in ((ax.xaxis, ax.get_xlim()), (ax.yaxis, ax.get_ylim())):
        lo, hi = min(lo, hi), max(lo, hi)
        for tick in axis.get_major_ticks():
            if lo <= tick.get_loc() <= hi and tick.label1.get_visible() and tick.label1.get_text():
                out.append(tick.label1)
    return out


def _place_labels(fig: Figure, ax, points: Sequence[tuple[float, float, str]]) -> None:
    """Label points so that no two labels, the legend or the tick labels overlap: each label
    (largest ``x`` first) takes the first of :data:`_LABEL_OFFSETS` whose box, as drawn, is
    inside the axes and clear of everything placed before (else the first offset)."""
    if not points:
        return
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    renderer = FigureCanvasAgg(fig).get_renderer()
    fig.draw(renderer)  # the tick labels as they will be drawn
    frame = ax.get_window_extent(renderer)
    taken = [t.get_window_extent(renderer) for t in _drawn_tick_labels(ax)]
    legend = ax.get_legend()
    if legend is not None:
        taken.append(legend.get_window_extent(renderer))
    for xi, yi, lab in sorted(points, key=lambda p: (-p[0], -p[1])):
        note = None
        for dx, dy, ha in _LABEL_OFFSETS:
            if note is not None:
                note.remove()
            note = ax.annotate(_t(lab), (xi, yi), xytext=(dx, dy), textcoords="offset points", fontsize=8,
                               ha=ha, va="baseline")
            box = note.get_window_extent(renderer)
            if (frame.x0 <= box.x0 and box.x1 <= frame.x1 and frame.y0 <= box.y0 and box.y1 <= frame.y1
                    and not any(box.overlaps(t) for t in taken)):
                break
        else:
            if note is not None:
                note.remove()
            dx, dy, ha = _LABEL_OFFSETS[0]
            note = ax.annotate(_t(lab), (xi, yi), xytext=(dx, dy), textcoords="offset points", fontsize=8, ha=ha)
            box = note.get_window_extent(renderer)
        taken.append(box)


def evaluate_on_grid(predict: Callable[[np.ndarray, np.ndarray], np.ndarray],
                     x_range: tuple[float, float], y_range: tuple[float, float], n: int = 31):
    """Evaluate ``predict(X, Y)`` on an ``n × n`` grid over the two ranges.

    Parameters
    ----------
    predict : callable
        Takes two arrays of the same shape (x and y values) and returns predictions of that
        shape (or flat, same size).
    x_range, y_range : (float, float)
        Low and high ends of the grid, in the units the caller wants on the axes.
    n : int
        Points per axis (>= 2).

    Returns
    -------
    X, Y, Z : numpy.ndarray
        ``(n, n)`` arrays.
    """
    if int(n) < 2:
        raise ValueError(f"grid size n must be at least 2 (got {n})")
    for nm, (lo, hi) in (("x_range", x_range), ("y_range", y_range)):
        if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
            raise ValueError(f"{nm} must be two finite numbers, low < high (got {lo!r}, {hi!r})")
    xs = np.linspace(x_range[0], x_range[1], int(n))
    ys = np.linspace(y_range[0], y_range[1], int(n))
    X, Y = np.meshgrid(xs, ys)
    Z = np.asarray(predict(X, Y), dtype=float)
    if Z.size != X.size:
        raise ValueError(f"predict returned {Z.size} values for a {n}x{n} grid")
    return X, Y, Z.reshape(X.shape)


def _points(points, what="design points"):
    if points is None:
        return None
    p = np.asarray(points, dtype=float)
    if p.ndim != 2 or p.shape[1] not in (2, 3):
        raise ValueError(f"{what} must be an (n, 2) or (n, 3) array")
    return p


def _grid(X, Y, Z) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A response grid (:func:`evaluate_on_grid`) as three float arrays, checked to be 2-D
    and of one shape."""
    X, Y, Z = (np.asarray(a, dtype=float) for a in (X, Y, Z))
    if not (X.shape == Y.shape == Z.shape) or X.ndim != 2:
        raise ValueError("X, Y and Z must be 2-D arrays of one shape")
    return X, Y, Z


def surface_3d(X, Y, Z, *, points=None, xlabel: str = "x", ylabel: str = "y", zlabel: str = "response",
               title: str | None = None, size=(5.0, 4.0), note: str | None = None, mark=None,
               mark_label: str | None = None) -> Figure:
    """A 3-D response surface (the paper's Fig. 10 a–f).

    Parameters
    ----------
    X, Y, Z : array_like
        ``(n, n)`` grid from :func:`evaluate_on_grid`.
    points : array_like, optional
        ``(m, 3)`` design points (x, y, observed response) drawn as markers; ``(m, 2)``
        puts them on the floor of the plot.
    note : str, optional
        One line of small text at the top of the figure (e.g. where the other factors are held).
    mark : (float, float, float), optional
        One point to highlight (e.g. the optimum on this slice), drawn as a star.
    """
    X, Y, Z = _grid(X, Y, Z)
    fig = Figure(figsize=size)
    fig.subplots_adjust(left=0.0, right=0.95, bottom=0.03, top=0.95)
    ax = fig.add_subplot(projection="3d")
    ax.plot_surface(X, Y, Z, cmap="viridis", linewidth=0.2, edgecolor="#33333355",
                    antialiased=True, alpha=0.9, rstride=1, cstride=1)
    p = _points(points)
    if p is not None and len(p):
        if p.shape[1] == 3:
            ax.scatter(p[:, 0], p[:, 1], p[:, 2], s=18, depthshade=False, **_POINT_STYLE)
        else:
            ax.scatter(p[:, 0], p[:, 1], np.full(len(p), np.nanmin(Z)), s=18, depthshade=False,
                       **_POINT_STYLE)
    from matplotlib.ticker import MaxNLocator

    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(MaxNLocator(5))
    ax.set_xlabel(_t(xlabel), fontsize=8, labelpad=2)
    ax.set_ylabel(_t(ylabel), fontsize=8, labelpad=2)
    ax.set_zlabel(_t(zlabel), fontsize=8, labelpad=6)
    ax.tick_params(labelsize=7, pad=0)
    if mark is not None:
        ax.scatter([mark[0]], [mark[1]], [mark[2]], s=140, marker="*", color="#ffd21f", edgecolor="black",
                   linewidth=0.7, depthshade=False, zorder=6, label=_t(mark_label or "optimum"))
        ax.legend(loc="upper left", fontsize=7, framealpha=0.8)
    ax.view_init(elev=25, azim=-130)
    if title:
        ax.set_title(_t(title), fontsize=10)
    _note(fig, note)
    return fig


def _note(fig: Figure, note: str | None) -> None:
    if note:
        fig.text(0.5, 0.995, _t(note), ha="center", va="top", fontsize=7, color="#333333")


def contour_plot(X, Y, Z, *, points=None, xlabel: str = "x", ylabel: str = "y",
                 zlabel: str = "response", title: str | None = None, levels: int = 12,
                 size=(5.0, 4.0), mark=None, mark_label: str | None = None, note: str | None = None) -> Figure:
    """Filled contour of a response over a factor pair, design points marked.

    Parameters
    ----------
    X, Y, Z : array_like
        ``(n, n)`` grid from :func:`evaluate_on_grid`.
    points : array_like, optional
        ``(m, 2)`` (or ``(m, 3)``; the third column is ignored) design points.
    mark : (float, float), optional
        One point to highlight (e.g. the optimum), drawn as a star. Draw it only when the
        point lies on the plotted slice (its other factors at the held values).
    note : str, optional
        One line of small text at the top of the figure (e.g. where the other factors are held).
    """
    X, Y, Z = _grid(X, Y, Z)
    fig = Figure(figsize=size)
    fig.subplots_adjust(left=0.15, right=0.98, bottom=0.13, top=0.89)
    ax = fig.add_subplot()
    if np.ptp(Z[np.isfinite(Z)]) > 0:
        cf = ax.contourf(X, Y, Z, levels=levels, cmap="viridis")
        cs = ax.contour(X, Y, Z, levels=cf.levels, colors="k", linewidths=0.4)
        ax.clabel(cs, inline=True, fontsize=6, fmt=format_number)  # the one number format
        cb = fig.colorbar(cf, ax=ax, shrink=0.9)
        cb.set_label(_t(zlabel), fontsize=8)
        cb.ax.tick_params(labelsize=7)
    else:  # a flat surface: contourf would warn; show it as one colour
        ax.pcolormesh(X, Y, Z, cmap="viridis", shading="auto")
    p = _points(points)
    if p is not None and len(p):
        # not clipped: design points and the optimum often sit on the edge of the box
        ax.scatter(p[:, 0], p[:, 1], s=22, marker="o", label="design points", clip_on=False, **_POINT_STYLE)
    if mark is not None:
        ax.scatter([mark[0]], [mark[1]], s=160, marker="*", color="#ffd21f", edgecolor="black",
                   linewidth=0.7, zorder=7, clip_on=False, label=_t(mark_label or "optimum"))
    if (p is not None and len(p)) or mark is not None:
        # above the axes, so it never covers a design point in a corner
        ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncol=2, fontsize=7, frameon=False,
                  borderaxespad=0.2, handletextpad=0.3)
    from matplotlib.ticker import MaxNLocator

    ax.xaxis.set_major_locator(MaxNLocator(5))
    ax.yaxis.set_major_locator(MaxNLocator(6))
    ax.set_xlabel(_t(xlabel), fontsize=9)
    ax.set_ylabel(_t(ylabel), fontsize=9)
    ax.tick_params(labelsize=7)
    if title:
        ax.set_title(_t(title), fontsize=10)
    _note(fig, note)
    return fig


# -- the paper's other figures --------------------------------------------------------------

def temperature_history(curves: Mapping[str, tuple[Sequence[float], Sequence[float]]], *,
                        measured: Mapping[str, tuple[Sequence[float], Sequence[float]]] | None = None,
                        xlabel: str = "Time [h]", ylabel: str = "Temperature rise [K]",
                        title: str | None = None, hlines: Mapping[str, float] | None = None,
                        size=PANEL_SIZE) -> Figure:
    """Temperature (or temperature rise) against time: the paper's Fig. 5 and Fig. 11.

    Parameters
    ----------
    curves : mapping
        ``{label: (t, T)}`` drawn as lines (model results).
    measured : mapping, optional
        ``{label: (t, T)}`` drawn as markers (measurements).
    hlines : mapping, optional
        ``{label: value}`` horizontal reference lines (e.g. the paper's steady rise 4.038 K).
    """
    if not curves and not measured:
        raise ValueError("temperature_history needs at least one curve")
    fig = _new_figure(size)
    ax = fig.add_subplot()
    for label, (t, T) in (curves or {}).items():
        ta, Ta = _paired(t, T, f"time of {label!r}", f"temperature of {label!r}")
        ax.plot(ta, Ta, linewidth=1.5, label=_t(label))
    for label, (t, T) in (measured or {}).items():
        ta, Ta = _paired(t, T, f"time of {label!r}", f"temperature of {label!r}")
        ax.plot(ta, Ta, linestyle="none", marker="o", markersize=4, label=_t(label))
    for label, v in (hlines or {}).items():
        ax.axhline(float(v), color="#777777", linestyle="--", linewidth=0.8, label=_t(label))
    ax.legend(fontsize=8, frameon=False)
    _finish(ax, title, xlabel, ylabel)
    return fig


def grouped_bars(categories: Sequence, groups: Mapping[str, Sequence[float]], *,
                 xlabel: str = "", ylabel: str = "", title: str | None = None,
                 size=PANEL_SIZE) -> Figure:
    """Grouped bars: one group of bars per category, one bar per series (Fig. 9: TCR of
    the RMS and the RFCMS at each stroke).

    Parameters
    ----------
    categories : sequence
        Category labels (e.g. strokes ``[0.04, 0.06, 0.075]``).
    groups : mapping
        ``{series label: values}``; each has one value per category (NaN leaves a gap).
    """
    cats = [str(c) for c in categories]
    if not cats or not groups:
        raise ValueError("grouped_bars needs at least one category and one series")
    k = len(groups)
    width = 0.8 / k
    fig = _new_figure(size)
    ax = fig.add_subplot()
    x = np.arange(len(cats), dtype=float)
    for i, (label, vals) in enumerate(groups.items()):
        v = np.asarray(vals, dtype=float).ravel()
        if v.size != len(cats):
            raise ValueError(f"series {label!r} has {v.size} values for {len(cats)} categories")
        ax.bar(x - 0.4 + width * (i + 0.5), v, width=width * 0.95, label=_t(label))
    ax.set_xticks(x)
    ax.set_xticklabels([_t(c) for c in cats])
    ax.legend(fontsize=8, frameon=False)
    _finish(ax, title, xlabel, ylabel)
    return fig


def grouped_curves(curves: Mapping[str, tuple[Sequence[float], Sequence[float]]], *,
                   xlabel: str = "", ylabel: str = "", title: str | None = None,
                   markers: bool = True, size=PANEL_SIZE) -> Figure:
    """Several curves on one axis, ``{label: (x, y)}`` (Fig. 9 as curves over time)."""
    if not curves:
        raise ValueError("grouped_curves needs at least one curve")
    fig = _new_figure(size)
    ax = fig.add_subplot()
    for label, (x, y) in curves.items():
        xa, ya = _paired(x, y, f"x of {label!r}", f"y of {label!r}")
        ax.plot(xa, ya, marker="o" if markers else None, markersize=3, linewidth=1.2, label=_t(label))
    ax.legend(fontsize=8, frameon=False)
    _finish(ax, title, xlabel, ylabel)
    return fig


# -- mixtures ---------------------------------------------------------------------------------

_H3 = float(np.sqrt(3.0) / 2.0)


def _ternary_xy(fractions) -> tuple[np.ndarray, np.ndarray]:
    """Cartesian place of ``(a, b, c)`` fractions: a at the top, b bottom left, c bottom right."""
    f = np.atleast_2d(np.asarray(fractions, dtype=float))
    return f[:, 2] + f[:, 0] / 2.0, f[:, 0] * _H3


def ternary_contour(fractions, z, *, labels: Sequence[str], share: float = 1.0, points=None,
                    zlabel: str = "response", mark=None, mark_label: str | None = None,
                    note: str | None = None, levels: int = 12, size=(5.2, 4.6)) -> Figure:
    """Filled contour of a response over the triangle of three components.

    Parameters
    ----------
    fractions : array_like
        ``(m, 3)`` shares ``(a, b, c)`` of the three components (each row sums to one).
    z : array_like
        ``(m,)`` predictions; ``nan`` outside the region (left white).
    labels : three str
        The corners: top, bottom left, bottom right.
    share : float
        What the three share in real proportions (``T`` less any held components); the grid
        lines are labelled in real proportions.
    points, mark : array_like, optional
        ``(n, 3)`` fractions of the runs, and one ``(3,)`` point drawn as a star.
    note : str, optional
        One line of small text at the top (a slice: where the other components are held).
    """
    import matplotlib.tri as mtri

    fr = np.atleast_2d(np.asarray(fractions, dtype=float))
    zz = np.asarray(z, dtype=float).ravel()
    x, y = _ternary_xy(fr)
    fig = Figure(figsize=size)
    fig.subplots_adjust(left=0.03, right=0.97, bottom=0.08, top=0.9)
    ax = fig.add_subplot()
    tri = mtri.Triangulation(x, y)
    bad = ~np.isfinite(zz)
    tri.set_mask(np.any(bad[tri.triangles], axis=1))
    if np.isfinite(zz).sum() >= 3 and np.ptp(zz[np.isfinite(zz)]) > 0:
        zf = np.where(np.isfinite(zz), zz, np.nanmean(zz))
        cf = ax.tricontourf(tri, zf, levels=levels, cmap="viridis")
        cs = ax.tricontour(tri, zf, levels=np.asarray(cf.levels), colors="k", linewidths=0.4)
        ax.clabel(cs, inline=True, fontsize=6, fmt="%.4g")
        cb = fig.colorbar(cf, ax=ax, shrink=0.8)
        cb.set_label(_t(zlabel), fontsize=8)
        cb.ax.tick_params(labelsize=7)
    ax.plot([0.5, 0.0, 1.0, 0.5], [_H3, 0.0, 0.0, _H3], color="black", linewidth=1.0)
    for f in (0.2, 0.4, 0.6, 0.8):
        ends = [((f / 2, f * _H3), (1 - f / 2, f * _H3)), (((1 - f) / 2, (1 - f) * _H3), (1 - f, 0.0)),
                ((f, 0.0), ((1 + f) / 2, (1 - f) * _H3))]
        for k, (p0, p1) in enumerate(ends):
            ax.plot([p0[0], p1[0]], [p0[1], p1[1]], color="#999999", linewidth=0.4, zorder=1)
            at = p1 if k == 0 else p0
            ax.text(at[0] + (0.01 if k == 0 else (-0.01 if k == 1 else 0.0)), at[1] - (0.03 if k == 2 else 0.0),
                    format_number(share * f, 3), fontsize=6, color="#555555",
                    ha="left" if k == 0 else ("right" if k == 1 else "center"), va="center")
    ax.text(0.5, _H3 + 0.03, _t(labels[0]), ha="center", va="bottom", fontsize=9)
    ax.text(-0.02, -0.05, _t(labels[1]), ha="center", va="top", fontsize=9)
    ax.text(1.02, -0.05, _t(labels[2]), ha="center", va="top", fontsize=9)
    if points is not None and len(points):
        px, py = _ternary_xy(points)
        ax.scatter(px, py, s=20, marker="o", label="runs", clip_on=False, **_POINT_STYLE)
    if mark is not None:
        mx, my = _ternary_xy(np.asarray(mark, dtype=float)[None, :])
        ax.scatter(mx, my, s=160, marker="*", color="#ffd21f", edgecolor="black", linewidth=0.7, zorder=7,
                   clip_on=False, label=_t(mark_label or "optimum"))
    if (points is not None and len(points)) or mark is not None:
        ax.legend(loc="upper left", fontsize=7, frameon=False)
    ax.set_xlim(-0.1, 1.1)
    ax.set_ylim(-0.12, _H3 + 0.1)
    ax.set_aspect("equal")
    ax.axis("off")
    _note(fig, note)
    return fig


def trace_plot(curves: Mapping[str, tuple[Sequence[float], Sequence[float]]], *, xlabel: str,
               ylabel: str = "response", title: str | None = None, size=(6.0, 3.8)) -> Figure:
    """The trace plot of a mixture: the prediction along each component's direction from the
    reference blend, one line per component (``{label: (deviation, predicted)}``)."""
    fig = _new_figure(size)
    fig.subplots_adjust(right=0.78)
    ax = fig.add_subplot()
    for label, (dx, yy) in curves.items():
        ax.plot(np.asarray(dx, dtype=float), np.asarray(yy, dtype=float), linewidth=1.6, label=_t(label))
    ax.axvline(0.0, color="#888888", linewidth=0.8, linestyle=":")
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7, frameon=False)
    _finish(ax, title, xlabel, ylabel)
    return fig
