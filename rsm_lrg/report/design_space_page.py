"""The design-space page: the probability maps and the operating window of
:func:`rsm_lrg.optimize.design_space.design_space`, as one self-contained HTML page (no
script; the maps are PNG ``data:`` URIs). Given the per-setting variance attribution of
``design-space --surrogate`` (:mod:`rsm_lrg.paper.surrogate_space`), the page also shows
it: a table of the shares per setting, with the dominant source marked, a count of the
settings each source dominates, and a stacked bar chart of the shares per setting."""

from __future__ import annotations

from pathlib import Path
from typing import Any

__all__ = ["design_space_html", "write_design_space_page", "ATTRIBUTION_SOURCES"]

#: The sources of the attribution as the page names them: (key in the node's attribution, label).
ATTRIBUTION_SOURCES = (("parameters", "calibration"), ("tolerances", "tolerances"), ("noise", "run noise"),
                       ("interaction", "interaction"))
_COLOURS = {"parameters": "#4c72b0", "tolerances": "#dd8452", "noise": "#55a868", "interaction": "#8c8c8c"}


def _attribution_figure(nodes: list, response: str, factors: list) -> Any:
    """Stacked bars: each setting's variance shares (calibration, tolerances, run noise, and
    the interaction when positive) of ``response``."""
    import numpy as np
    from matplotlib.figure import Figure

    from .html import fmt_num

    n = len(nodes)
    fig = Figure(figsize=(max(4.6, min(12.0, 0.32 * n + 2.0)), 3.4))
    ax = fig.add_subplot(1, 1, 1)
    x = np.arange(n)
    bottom = np.zeros(n)
    for key, label in ATTRIBUTION_SOURCES:
        v = np.array([max(0.0, float(nd["attribution"][response][key])) for nd in nodes])
        ax.bar(x, v, bottom=bottom, color=_COLOURS[key], label=label, width=0.8)
        bottom += v
    ax.set_ylim(0.0, max(1.0, float(bottom.max()) * 1.02))
    ax.set_ylabel("share of the variance")
    ax.set_xticks(x)
    ax.set_xticklabels([" ".join(fmt_num(nd["setting"][f], 3) for f in factors) for nd in nodes],
                       rotation=90, fontsize=7)
    ax.set_xlabel(("setting: " + ", ".join(factors)).replace("$", r"\$"), fontsize=8)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    fig.tight_layout()
    return fig


def _attribution(nodes: list, factors: list, specs: dict | None = None, target: float | None = None) -> dict | None:
    """The attribution section's data: per response the rows and the count of settings each
    source dominates, and the figures."""
    from .html import fmt_num
    from .plots import to_data_uri

    if not nodes or "attribution" not in nodes[0]:
        return None
    responses = list(nodes[0]["attribution"])
    labels = dict(ATTRIBUTION_SOURCES)
    # the limit each setting's runs stay within with the target probability: the upper one, or the
    # lower one for a specification with a lower limit only
    side = {}
    for r in responses:
        lo, hi = (specs or {}).get(r, (None, None))
        side[r] = "lower" if hi is None and lo is not None else "upper"
    out = []
    for r in responses:
        rows = []
        counts = {k: 0 for k, _ in ATTRIBUTION_SOURCES[:3]}
        for nd in nodes:
            a = nd["attribution"][r]
            counts[a["dominant"]] = counts.get(a["dominant"], 0) + 1
            rows.append({"setting": [fmt_num(nd["setting"][f]) for f in factors],
                         "p": f"{nd['p']:.3f} ± {nd['p_se']:.3f}", "variance": fmt_num(a["variance"]),
                         "limit": fmt_num((nd.get("limits") or {}).get(r, {}).get(side.get(r, "upper"))),
                         "shares": [(k, f"{a[k]:.3f}") for k, _ in ATTRIBUTION_SOURCES],
                         "dominant": a["dominant"], "dominant_label": labels[a["dominant"]]})
        fig = _attribution_figure(nodes, r, factors)
        width = int(round(float(fig.get_size_inches()[0]) * 96))  # its natural size in CSS pixels
        out.append({"response": r, "rows": rows, "limit_label": f"{side[r]} limit, p {target:g}"
                    if target is not None else f"{side[r]} limit",
                    "counts": [(labels[k], c) for k, c in counts.items()],
                    "figure": {"uri": to_data_uri(fig), "title": f"Variance shares of {r} per setting",
                               "width": width}})
    return {"factors": factors, "sources": [lab for _, lab in ATTRIBUTION_SOURCES], "responses": out}


def _map_figure(m: dict, target: float, window: dict | None) -> Any:
    """One pair's map: the probability as colour, the target as a contour, the window."""
    import numpy as np
    from matplotlib.figure import Figure
    from matplotlib.patches import Rectangle

    fig = Figure(figsize=(4.6, 3.5))
    ax = fig.add_subplot(1, 1, 1)
    x, y, p = np.asarray(m["x_levels"]), np.asarray(m["y_levels"]), np.asarray(m["p"], dtype=float)
    mesh = ax.pcolormesh(x, y, p, shading="nearest", cmap="viridis", vmin=0.0, vmax=1.0)
    fig.colorbar(mesh, ax=ax, label="P(in spec)")
    if np.nanmin(p) < target < np.nanmax(p):
        ax.contour(x, y, p, levels=[target], colors="white", linewidths=1.5)
    if m.get("in_window") is not None:  # a mixture: the window's blends on this slice of the simplex
        inside = np.asarray(m["in_window"], dtype=float)
        if inside.any():
            ax.contour(x, y, inside, levels=[0.5], colors="red", linewidths=1.8)
    elif window is not None:
        (x0, x1), (y0, y1) = window[m["x"]], window[m["y"]]
        ax.add_patch(Rectangle((x0, y0), x1 - x0, y1 - y0, fill=False, edgecolor="red", linewidth=1.8))
    ax.set_xlabel(str(m["x"]).replace("$", r"\$"))
    ax.set_ylabel(str(m["y"]).replace("$", r"\$"))
    fig.tight_layout()
    return fig


def design_space_html(ds: Any, *, title: str | None = None, source_name: str | None = None,
                      attribution: list | None = None) -> str:
    """The page of a :class:`~rsm_lrg.optimize.design_space.DesignSpace` (self-contained).

    Parameters
    ----------
    ds : DesignSpace
        The map and window.
    title : str, optional
        The page's title.
    source_name : str, optional
        What the probabilities were computed from (shown as text).
    attribution : list of dict, optional
        Per grid node ``{"setting", "p", "p_se", "attribution": {response: {"variance",
        "parameters", "tolerances", "noise", "interaction", "dominant"}}}``: the nodes of
        :class:`rsm_lrg.paper.surrogate_space.SurrogateDesignSpace`; shown as the section
        "Variance attribution".

    Returns
    -------
    str
        The HTML.
    """
    from .html import fmt_num, render_page
    from .plots import to_data_uri

    specs = "; ".join(f"{r}: {'−∞' if lo is None else fmt_num(lo)} … {'+∞' if hi is None else fmt_num(hi)}"
                      for r, (lo, hi) in ds.specs.items())
    summary = [("Data", source_name or "a DataFrame"), ("Specifications", specs),
               ("Target probability", f"{ds.probability:g}"),
               ("Most probable setting", ", ".join(f"{k} = {fmt_num(v)}" for k, v in ds.best.items())
                + f" (p = {ds.best_probability:.4f})")]
    if ds.held:
        summary.append(("Held", ", ".join(f"{k} = {v}" for k, v in ds.held.items())))
    if ds.factor_sd:
        summary.append(("Factor noise (SD)", ", ".join(f"{k} {fmt_num(v)}" for k, v in ds.factor_sd.items())))
    figures = []
    for m in ds.maps:
        figures.append({"uri": to_data_uri(_map_figure(m, ds.probability, ds.window)),
                        "title": f"P(every response in spec) over {m['x']} and {m['y']}"})
    window = None if ds.window is None else [(k, fmt_num(lo), fmt_num(hi)) for k, (lo, hi) in ds.window.items()]
    shares = _attribution(list(attribution or []), list(ds.factors), dict(ds.specs), ds.probability)
    toc = [("summary", "Summary"), ("window", "Operating window"), ("maps", "Probability maps")]
    if shares is not None:
        toc.append(("attribution", "Variance attribution"))
    toc.append(("notes", "Notes"))
    return render_page("design_space.html.j2", title=title or "Design space: " + ", ".join(ds.specs),
                       subtitle=f"P(every response in its specification) ≥ {ds.probability:g}",
                       toc=toc, summary=summary, window=window, target=f"{ds.probability:g}",
                       window_min=f"{ds.window_min_probability:.4f}", figures=figures, notes=list(ds.notes),
                       attribution=shares)


def write_design_space_page(ds: Any, path: str | Path, *, force: bool = False, **kwargs: Any) -> Path:
    """Write :func:`design_space_html` to ``path`` atomically (an existing file only with
    ``force``).

    Parameters
    ----------
    ds : DesignSpace
        The map and window.
    path : str or Path
        The page to write.
    force : bool
        Replace an existing file.
    **kwargs
        Passed to :func:`design_space_html` (``title``, ``source_name``, ``attribution``).

    Returns
    -------
    Path
        The page written.
    """
    from ..io import check_output, write_output

    p = Path(path)
    check_output(p, force=force)
    return write_output(p, design_space_html(ds, **kwargs), force=force)
