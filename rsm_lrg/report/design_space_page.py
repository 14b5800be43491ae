"""The design-space page: the probability maps and the operating window of
:func:`rsm_lrg.optimize.design_space.design_space`, as one self-contained HTML page (no
script; the maps are PNG ``data:`` URIs)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

__all__ = ["design_space_html", "write_design_space_page"]


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


def design_space_html(ds: Any, *, title: str | None = None, source_name: str | None = None) -> str:
    """The page of a :class:`~rsm_lrg.optimize.design_space.DesignSpace` (self-contained)."""
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
    return render_page("design_space.html.j2", title=title or "Design space: " + ", ".join(ds.specs),
                       subtitle=f"P(every response in its specification) ≥ {ds.probability:g}",
                       toc=[("summary", "Summary"), ("window", "Operating window"), ("maps", "Probability maps"),
                            ("notes", "Notes")],
                       summary=summary, window=window, target=f"{ds.probability:g}",
                       window_min=f"{ds.window_min_probability:.4f}", figures=figures, notes=list(ds.notes))


def write_design_space_page(ds: Any, path: str | Path, *, force: bool = False, **kwargs: Any) -> Path:
    """Write :func:`design_space_html` to ``path`` atomically (an existing file only with
    ``force``)."""
    from ..io import check_output, write_output

    p = Path(path)
    check_output(p, force=force)
    return write_output(p, design_space_html(ds, **kwargs), force=force)
