"""Presentation of the paper reproduction (:mod:`rsm_lrg.paper.reproduction`): the terminal
table, the verdict banner and the self-contained HTML page with Figs. 5, 9, 10, 11.

Everything here renders what it is given (a reproduction's rows and results, and the
paper's settings for the figure captions); it computes nothing of its own. The report layer
sits below the paper layer and does not import it: the reproduction object is read by its
attributes (``rows``, ``counts()``, ``thermal``, ``fig9``, ``surrogate_table4``, ``optimum``,
``fit``, ``notes``, ``seconds``, ``ok``).
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import numpy as np

from ..present import format_number

__all__ = ["reproduction_text", "reproduction_page", "write_page", "banner", "display_number"]


def reproduction_text(rep, width: int = 38) -> str:
    """The side-by-side table for a terminal.

    Long cells wrap onto continuation lines (nothing is cut): the quantity column is
    ``width`` characters wide, the paper, toolkit and tolerance columns 22.
    """
    import textwrap

    head = ["quantity", "paper", "toolkit", "rel. diff", "tolerance", "verdict"]
    caps = [width, 22, 22, 10, 22, 7]
    cells = []
    for r in rep.rows:
        rd = "" if r.rel_diff is None else f"{100 * r.rel_diff:+.2f} %"
        cells.append([r.quantity, display_number(r.paper), r.toolkit, rd, r.tolerance, r.verdict])
    wrapped = [[textwrap.wrap(str(c), cap, break_long_words=True, break_on_hyphens=False) or [""]
                for c, cap in zip(row, caps)] for row in cells]
    widths = [max(len(h), *(len(line) for w in wrapped for line in w[i])) for i, h in enumerate(head)]
    fmt = "  ".join(f"{{:{'<' if i in (0, 4, 5) else '>'}{w}}}" for i, w in enumerate(widths))
    lines = [fmt.format(*head).rstrip(), "  ".join("-" * w for w in widths)]
    section = None
    for r, w in zip(rep.rows, wrapped):
        if r.section != section:
            section = r.section
            lines.append(f"[{section}]")
        for k in range(max(len(c) for c in w)):
            lines.append(fmt.format(*(c[k] if k < len(c) else "" for c in w)).rstrip())
    c = rep.counts()
    lines.append("")
    lines.append(f"{c['pass']} pass (within tolerance), {c['not yet']} not yet reached, {c['FAIL']} FAIL, "
                 f"{c['info']} info  ({rep.seconds:.1f} s)")
    why = [r for r in rep.rows if r.verdict in ("not yet", "FAIL")]
    if why:
        lines.append("")
        lines.append("Rows that do not match, and why:")
        for r in why:
            lines.append(f"- {r.quantity} [{r.verdict}]: {r.note or 'no known reason'}")
    lines.append("")
    lines.append("Tolerance: one unit in the last digit the paper prints, unless the row says otherwise.")
    return "\n".join(lines) + "\n"


def banner(counts: dict) -> dict:
    """Headline, colour and CSS class of the page's verdict (red: a failure, amber: rows not
    yet reached, green: every checked row within its tolerance).

    >>> banner({"pass": 88, "FAIL": 0, "not yet": 2, "info": 3})["colour"]
    'amber'
    """
    n_fail, n_open, n_pass = counts["FAIL"], counts["not yet"], counts["pass"]
    if n_fail:
        return {"colour": "red", "css": "verdict-fail",
                "headline": f"{n_fail} checked row{'s' if n_fail > 1 else ''} outside tolerance with no known "
                            f"reason; {n_pass} within tolerance, {n_open} not yet reached."}
    if n_open:
        return {"colour": "amber", "css": "verdict-notyet",
                "headline": f"Not everything is reached yet: {n_open} row{'s' if n_open > 1 else ''} outside "
                            "tolerance for a stated reason (listed below); no row fails."}
    return {"colour": "green", "css": "verdict-pass",
            "headline": f"Every checked row is within its tolerance ({n_pass} rows) · 0 not yet reached · 0 failed."}


def display_number(text: str) -> str:
    """A number printed as ``1.61e-4`` shown as the paper prints it, ``1.61 × 10⁻⁴``; other text as is.

    >>> display_number("1.61e-4"), display_number("5.6e5"), display_number("0.0880")
    ('1.61 × 10⁻⁴', '5.6 × 10⁵', '0.0880')
    """
    from ..present import unicode_number

    return unicode_number(text)


_NUMBER_TEXT = re.compile(r"[<>≤≥±+−-]?\s*\d[\d.]*(?: × 10[⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+)?")


def _cell_css(text: str) -> str:
    """``"num"`` (right-aligned) for a cell that is one number, ``"text"`` for words."""
    return "num" if _NUMBER_TEXT.fullmatch(str(text).strip()) else "text"


# -- the page -----------------------------------------------------------------------------------

def _figures(rep, fig9: dict, confirmation: dict, measured) -> dict:
    from . import plots as P
    from .fit_report import surface_figures

    strokes, velocity, acceleration = fig9["strokes"], fig9["velocity"], fig9["acceleration"]
    rise_c, minutes = confirmation["rise_c"], confirmation["minutes"]
    figs: dict[str, Any] = {}
    th = rep.thermal
    if th is not None:
        curves = {"toolkit: 3-D finite volume": (th.times_h, th.history_k_fv),
                  "toolkit: reduced network": (th.times_h, th.history_k_network)}
        figs["fig5"] = P.render(
            P.temperature_history(curves, hlines={"paper: steady rise 4.038 K (FEM)": 4.038},
                                  xlabel="Time [h]", ylabel="Temperature rise at the carriage [K]"),
            "fig5", "Fig. 5: temperature rise of the guide",
            f"Thermocouple rise (mean of two) after start-up at {th.ambient_c:g} °C ambient, heat "
            f"{format_number(th.heat_w)} W. Dashed: the paper's FEM steady rise.", "svg")
    if rep.fig9 is not None:
        f = rep.fig9
        series = {st.upper(): [float(f.loc[(f["stroke_m"] == s) & (f["stage"] == st), "tcr_c_per_min"].iloc[0])
                               for s in strokes] for st in ("rms", "rfcms")}
        figs["fig9"] = P.render(
            P.grouped_bars([f"{s:g} m" for s in strokes], series, xlabel="Stroke",
                           ylabel="TCR κ [°C/min]"),
            "fig9", "Fig. 9: RMS vs RFCMS",
            f"Surrogate TCR over {minutes:g} min at v = {velocity} m/s, a = {acceleration} m/s², "
            "for the three strokes of the comparative test (deterministic, no reading noise).", "svg")
    if rep.surrogate_table4 is not None and measured is not None:
        meas = np.asarray(measured, dtype=float)
        figs["surrogate"] = P.render(
            P.predicted_vs_actual(meas, rep.surrogate_table4["tcr_c_per_min"].to_numpy(dtype=float),
                                  response="κ [°C/min]", title="Surrogate vs Table 4"),
            "surrogate-vs-table4", "Surrogate vs the 27 measured runs",
            "Deterministic surrogate (default calibration) at the Table 4 settings against the measured κ; "
            "if that calibration was fitted to these runs, the comparison is in-sample.", "svg")
    # Fig. 11: the confirmation run against the model's prediction at the optimum
    opt = rep.optimum
    t = np.linspace(0.0, minutes, 51)
    curves = {f"model: κ̂ = {format_number(opt.predicted)} °C/min at the optimum": (t, opt.predicted * t)}
    for lab, (lo, hi) in (("95 % PI", opt.pi),):
        curves[f"model {lab} (low)"] = (t, lo * t)
        curves[f"model {lab} (high)"] = (t, hi * t)
    figs["fig11"] = P.render(
        P.temperature_history(curves, measured={f"paper: confirmation run ({rise_c:g} °C in {minutes:g} min)":
                                                ([0.0, minutes], [0.0, rise_c])},
                              xlabel="Time [min]", ylabel="Temperature rise [°C]"),
        "fig11", "Fig. 11: verification at the optimum",
        "Temperature rise implied by the fitted κ at the optimum (A = 0.0001 m, B = 0.04 m, C = 0.4 m/s, "
        "D = 20 m/s²) with its 95 % prediction interval, and the paper's confirmation run (its end points: "
        "the paper gives the rise and duration, not the recorded curve).", "svg")
    surfaces, note = surface_figures(rep.fit, "center", opt)
    figs["fig10"] = surfaces
    figs["fig10_note"] = note
    return figs


def reproduction_page(rep, *, fig9: dict, confirmation: dict, measured=None) -> str:
    """The self-contained HTML page of a reproduction (table and figures).

    Parameters
    ----------
    rep : rsm_lrg.paper.reproduction.Reproduction
    fig9 : dict
        ``{"strokes": (...) [m], "velocity": [m/s], "acceleration": [m/s²]}`` of the Fig. 9 runs.
    confirmation : dict
        ``{"rise_c": [°C], "minutes": [min]}`` of the confirmation run (Fig. 11).
    measured : array, optional
        The measured κ of Table 4 [°C/min], for the surrogate figure.
    """
    from .html import render_page

    figs = _figures(rep, fig9, confirmation, measured)
    c = rep.counts()
    css = {"pass": "pass", "FAIL": "fail", "not yet": "notyet", "info": ""}
    rows = [r.to_dict() | {"rel_text": "" if r.rel_diff is None else f"{100 * r.rel_diff:+.2f} %",
                           "paper": display_number(r.paper), "toolkit": display_number(r.toolkit),
                           "toolkit_lines": display_number(r.toolkit).split("; "),
                           "paper_css": _cell_css(display_number(r.paper)),
                           "toolkit_css": _cell_css(display_number(r.toolkit)),
                           "css": css[r.verdict]}
            for r in rep.rows]
    return render_page(
        "reproduction.html.j2",
        title="Su, Zhang & Yang (2023) reproduced by rsm-lrg",
        subtitle=("Combined Thermal and Wear Analysis of Linear Rolling Guide Subjected to Rigid–Flexible "
                  "Coupling Motion Stage, Machines 11(3), 358 — every number the paper reports, recomputed "
                  "from the embedded data."),
        toc=[("verdict", "Verdict"), ("comparison", "Paper vs toolkit"), ("fig5", "Fig. 5"), ("fig9", "Fig. 9"),
             ("fig10", "Fig. 10"), ("fig11", "Fig. 11"), ("surrogate", "Surrogate vs Table 4")],
        rows=rows, banner=banner(c), open_rows=[r for r in rows if r["verdict"] in ("not yet", "FAIL")],
        counts=c, ok=rep.ok, notes=list(rep.notes), seconds=rep.seconds,
        fig5=figs.get("fig5"), fig9=figs.get("fig9"), fig11=figs["fig11"], fig10=figs["fig10"],
        fig10_note=figs["fig10_note"], surrogate=figs.get("surrogate"),
        missing_surrogate=next((r.note for r in rep.rows if r.section.startswith("Section 4.2") and r.verdict == "not yet"), ""),
    )


def write_page(rep, directory, *, force: bool = False, **settings) -> Path:
    """Write ``DIR/paper-reproduction.html`` (:func:`reproduction_page`) atomically; an
    existing file is kept unless ``force``."""
    from ..io import InputError, write_output

    d = Path(directory)
    if d.exists() and not d.is_dir():
        raise InputError(f"{d}: is not a directory")
    d.mkdir(parents=True, exist_ok=True)
    out = d / "paper-reproduction.html"
    if out.exists() and not force:
        raise InputError(f"{out}: already exists; use --force to overwrite it")
    return write_output(out, reproduction_page(rep, **settings), force=force)
