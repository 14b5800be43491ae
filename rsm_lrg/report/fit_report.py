"""The HTML face of a fit: :func:`to_html` and :func:`write_report`.

A report is a view of a :class:`~rsm_lrg.model.FitResult` (and of its optimum, an
:class:`~rsm_lrg.optimize.OptimumResult`). Every number on the page is read from those
objects: the ANOVA laid out like the paper's Table 5 with significant terms marked and the
Design-Expert notes, the fit statistics, the coefficients with their confidence intervals
and VIFs, the equation in coded and in actual units (Eq. 19 for the paper's data), the six
diagnostic plots, a 3-D surface and a contour for every pair of factors, the stationary
point and the optimum with its confidence and prediction intervals.

The only arithmetic here is presentation: predictions of the fitted model on a plotting
grid (through :meth:`FitResult.predict_coded`), the classes of p values under the note of
Table 5, and hiding round-off (a sum of squares below 1e-12 of the total, or a coefficient
below 1e-12 of the largest, is shown as 0, as Design-Expert prints it).
"""

from __future__ import annotations

import itertools
import math
from pathlib import Path
from typing import Any

import numpy as np

from ..model.faces.summary_data import summary_data
from ..model.readings.anova import TOTAL_ROWS
from ..present import ROUND_OFF, clean
from .html import SIGNIFICANCE_NOTE, fmt_f, fmt_num, fmt_p, render_page, significance

__all__ = ["to_html", "write_report", "report_context", "notebook_html", "SECTION_IDS"]

#: ``id`` of every section of a fit report, in page order.
SECTION_IDS = (
    "summary", "data", "anova", "statistics", "coefficients", "equation", "diagnostics",
    "surfaces", "stationary-point", "optimum",
)

_SECTION_TITLES = {
    "summary": "Summary", "data": "Data", "anova": "ANOVA", "statistics": "Fit statistics",
    "coefficients": "Coefficients", "equation": "Equation", "diagnostics": "Diagnostics",
    "surfaces": "Surfaces", "stationary-point": "Stationary point", "optimum": "Optimum",
}

#: Relative size below which a sum of squares or coefficient is round-off (shown as 0).
ROUNDOFF = ROUND_OFF

_RUN_COLUMNS = ("run_order", "run", "order")


# -- small views ---------------------------------------------------------------------------

def _zero_if_roundoff(x: float | None, scale: float) -> float | None:
    """The round-off rule of :func:`rsm_lrg.present.clean` (shown as 0; missing stays None)."""
    v = clean(x, scale)
    return v if v is None else float(v)


def _term_label(term, labels: list[str], sep: str) -> str:
    """``A``, ``AB``, ``A²`` (coded, ``sep=""``) or ``thickness_m·stroke_m`` (actual, ``sep="·"``)."""
    sup = str.maketrans("0123456789", "⁰¹²³⁴⁵⁶⁷⁸⁹")
    parts = [labels[i] + (str(p).translate(sup) if p > 1 else "") for i, p in enumerate(term.powers) if p]
    return sep.join(parts)


def _equation_terms(result, units: str, labels: list[str], sep: str = "") -> list[str]:
    """The right-hand side of the fitted equation, one signed term per item (pages keep
    each item on one line).

    Which terms appear and with how many digits is the model's one rule for every equation
    writer (:func:`rsm_lrg.model.faces.text.equation_terms`: round-off coded terms are 0, every
    actual-units coefficient not exactly zero is kept, with the digits that reproduce the
    predictions); numbers are written in the page's format (``0.00075``, ``4.16667 × 10⁻⁵``).
    """
    from ..model.faces.text import equation_terms
    from ..present import format_number

    out: list[str] = []
    for t in equation_terms(result, units):
        mantissa = t.text.lower().split("e")[0].replace(".", "").lstrip("-0")
        num = format_number(abs(t.value), max(len(mantissa), 1))  # the digits the rule chose
        lab = _term_label(t, labels, sep)
        piece = f"{num}·{lab}" if (lab and sep) else (f"{num} {lab}" if lab else num)
        if not out:
            out.append(("−" if t.value < 0 else "") + piece)
        else:
            out.append(("− " if t.value < 0 else "+ ") + piece)
    return out or ["0"]


def run_numbers(result) -> tuple[np.ndarray, str]:
    if getattr(result, "data", None) is None:  # a fit that keeps no data frame (a Gaussian process)
        return np.arange(1, result.n + 1, dtype=float), "row order of the data"
    cols = {str(c).lower(): c for c in result.data.columns}
    for name in _RUN_COLUMNS:
        if name in cols:
            try:
                v = np.asarray(result.data[cols[name]], dtype=float)
                if np.isfinite(v).all():
                    return v, f"column {cols[name]!r}"
            except (TypeError, ValueError):
                pass
    return np.arange(1, result.n + 1, dtype=float), "row order of the data"


def _anova_rows(result) -> tuple[list[dict], list[str]]:
    a = result.anova
    total = float(a.loc[a["source"].isin(TOTAL_ROWS), "sum_sq"].iloc[0]) if a["source"].isin(TOTAL_ROWS).any() else 1.0
    term_names = set(result.term_names)
    rows = []
    for r in a.itertuples(index=False):
        ss = _zero_if_roundoff(r.sum_sq, total)
        ms = _zero_if_roundoff(r.mean_sq, total)
        f = r.f
        if ss == 0.0 and np.isfinite(f):
            f = 0.0
        sig = significance(r.p)
        is_term = r.source in term_names
        if r.source == "Lack of Fit" and np.isfinite(r.p):
            verdict = ("not significant relative to pure error" if r.p >= 0.05
                       else "significant relative to pure error")
            mark, p_class = "", ("" if r.p >= 0.05 else "sig")
        else:
            verdict, mark, p_class = sig.label, sig.mark, sig.css
        kind = "model" if r.source == "Model" else ("term" if is_term else "error")
        row_class = {"model": "summary-row", "term": "", "error": "group"}[kind]
        if r.source in ("Residual", "Block") or r.source in TOTAL_ROWS:
            row_class = "group" + (" summary-row" if r.source in TOTAL_ROWS else "")
        rows.append({
            "source": _pretty_term(r.source), "sum_sq": ss, "df": r.df, "mean_sq": ms, "f": f,
            "p": r.p, "mark": mark, "p_class": p_class, "verdict": verdict, "row_class": row_class,
        })
    return rows, _anova_notes(result, rows)


def _pretty_term(name: str) -> str:
    """``A^2`` → ``A²`` for display (the data keep Design-Expert's ASCII names)."""
    sup = str.maketrans("0123456789", "⁰¹²³⁴⁵⁶⁷⁸⁹")
    out, i = [], 0
    while i < len(name):
        if name[i] == "^" and i + 1 < len(name) and name[i + 1].isdigit():
            j = i + 1
            while j < len(name) and name[j].isdigit():
                j += 1
            out.append(name[i + 1:j].translate(sup))
            i = j
        else:
            out.append(name[i])
            i += 1
    return "".join(out)


def _anova_notes(result, rows) -> list[str]:
    """Design-Expert's sentences under the ANOVA (:func:`rsm_lrg.model.faces.summary_data.summary_data`,
    the same as the text face's), powers shown as superscripts, and the legend of the marks."""
    notes = [_pretty_term(n) for n in summary_data(result).anova_notes]
    notes.append("Significance classes (** and * marks): " + SIGNIFICANCE_NOTE)
    return notes


def _statistics(result) -> tuple[list, list[str]]:
    sd = summary_data(result)
    return list(sd.statistics), list(sd.statistics_notes)


def _coefficients(result) -> list[dict]:
    c = result.coefficients
    scale = float(np.nanmax(np.abs(c["coded"].to_numpy(dtype=float)))) or 1.0
    rows = []
    for name, r in c.iterrows():
        z = _zero_if_roundoff(float(r["coded"]), scale)
        sig = significance(r["p"]) if name != "Intercept" else significance(None)
        rows.append({"term": _pretty_term(str(name)), "estimate": z, "df": 1, "se": r["std_error"],
                     "ci_low": r["ci_low"], "ci_high": r["ci_high"], "vif": r["vif"], "p": r["p"],
                     "p_class": sig.css})
    return rows


def data_table(result, runs_label: str) -> dict:
    """Every row as read, in file order: the runs used with their coded settings, and the rows
    left out for want of a response marked "not run" in the response column."""
    d = result.data
    cols = [str(c) for c in d.columns]
    coded = result.coded
    letters = list(result.space.letters)

    def clean(row):
        return [None if (isinstance(v, float) and math.isnan(v)) else (v.item() if hasattr(v, "item") else v)
                for v in row]

    rows = []
    for i, row_no in enumerate(result.run_rows):
        row = [d.iloc[i, j] for j in range(d.shape[1])] + [float(coded.iloc[i][L]) for L in letters]
        rows.append((row_no, [row_no] + clean(row)))
    left = result.omitted_data
    if left is not None and len(left):
        j_resp = cols.index(str(result.response))
        for k, row_no in enumerate(result.omitted_rows):  # column by column: dtypes kept
            row = clean([left[c].iloc[k] for c in d.columns]) + [None] * len(letters)
            row[j_resp] = "not run"
            rows.append((row_no, [row_no] + row))
    rows.sort(key=lambda t: t[0])
    n_left = len(result.omitted_rows)
    if result.space.has_components:  # coded components are L-pseudo proportions, 0 ... 1
        from ..factors import MixtureComponent

        process = not all(isinstance(f, MixtureComponent) for f in result.space.factors)
        caption = (f"{len(d)} runs as read, with the components as L-pseudo proportions (0 at a component's lower "
                   f"bound, 1 when it makes up the whole blend above the lower bounds)"
                   + (" and the process factors coded (−1 low, 0 centre, +1 high)." if process else "."))
    else:
        caption = f"{len(d)} runs as read, with the coded factor settings (−1 low, 0 centre, +1 high)."
    if n_left:
        caption += (f" {n_left} row{'s' if n_left > 1 else ''} without a response "
                    f"{'are' if n_left > 1 else 'is'} shown as \"not run\" and left out of the fit.")
    return {
        "columns": ["row"] + cols + [f"coded {L}" for L in letters],
        "rows": [r for _, r in rows],
        "caption": caption,
    }


# -- figures --------------------------------------------------------------------------------

def diagnostics_section(result) -> tuple[list, str]:
    from . import plots as P

    ext = np.asarray(result.externally_studentized_residuals, dtype=float)
    runs, runs_from = run_numbers(result)
    p = result.design_matrix.shape[1]
    n = result.n
    resp = result.response
    figs = []
    finite = np.isfinite(ext)
    if finite.sum() >= 2:
        figs.append(P.render(P.normal_probability_plot(ext[finite]), "normal-plot", "Normal plot of residuals",
                             "Externally studentized residuals against normal % probability (Blom positions); "
                             "a straight line means normally distributed errors.", "svg"))
        figs.append(P.render(P.residuals_vs_predicted(np.asarray(result.fitted)[finite], ext[finite], limits=3.0,
                                                      label="Externally studentized residuals"),
                             "residuals-vs-predicted", "Residuals vs predicted",
                             "Externally studentized residuals against predicted values; dashed lines at ±3.", "svg"))
        figs.append(P.render(P.residuals_vs_run(ext[finite], runs[finite], limits=3.0,
                                                label="Externally studentized residuals"),
                             "residuals-vs-run", "Residuals vs run order",
                             f"Externally studentized residuals in run order (run numbers from the {runs_from}); "
                             "dashed lines at ±3.", "svg"))
    figs.append(P.render(P.predicted_vs_actual(result.y, result.fitted, response=resp), "predicted-vs-actual",
                         "Predicted vs actual", "Fitted values against the observed response; the line is y = x.", "svg"))
    cooks = np.asarray(result.cooks_distance, dtype=float)
    figs.append(P.render(P.cooks_distance_plot(np.where(np.isfinite(cooks), cooks, 0.0), runs, threshold=1.0),
                         "cooks-distance", "Cook's distance",
                         "Cook's distance of each run; the dashed line at 1 is the usual flag for an influential run.", "svg"))
    ref = 2.0 * p / n
    figs.append(P.render(P.leverage_plot(result.hat, runs, threshold=ref if ref < 1.0 else None), "leverage",
                         "Leverage", f"Leverage (hat diagonal) of each run; average leverage p/n = {p}/{n}"
                         + ("; the dashed line is twice that (2p/n)." if ref < 1.0 else
                            "; twice the average exceeds 1, so no reference line is drawn."), "svg"))
    note = "" if finite.sum() >= 2 else "Residual plots are omitted: the model leaves no residual degrees of freedom."
    return figs, note


def _runs(n: int) -> str:
    return "1 run" if n == 1 else f"{n} runs"


def _on_slice(optimum, space, held, i: int, j: int) -> bool:
    """Whether the optimum lies on the slice of pair (i, j): every other factor at its held value."""
    def code(f, v) -> float:  # a categoric factor's coded value is its level index
        return float(f.levels.index(v)) if isinstance(v, str) else float(v)

    return all(abs(code(f, optimum.coded[f.letter]) - held[m]) <= 1e-6
               for m, f in enumerate(space.factors) if m not in (i, j))


def surface_figures(result, hold: str, optimum) -> tuple[list[dict], str]:
    """A 3-D surface (PNG at twice the shown size) and a contour (SVG) for every factor pair.

    The figures are slices of the fitted model with the other factors held at their centre
    (``hold="center"``) or at the optimum (``hold="optimum"``); every figure says so in its
    caption and on the figure. The optimum's star is drawn only on slices that contain it.
    """
    if result.space.has_components:  # components are not free: a ternary contour and the trace instead
        return mixture_figures(result, optimum)
    from . import plots as P

    space = result.space
    k = len(space)
    categoric = [getattr(f, "kind", "numeric") == "categoric" for f in space.factors]
    numeric = [m for m in range(k) if not categoric[m]]
    if len(numeric) < 2:
        return [], "Surfaces need at least two numeric factors."

    def code(f, v) -> float:  # a categoric factor's coded value is its level index
        return float(f.levels.index(v)) if isinstance(v, str) else float(v)

    if hold == "optimum" and optimum is not None:
        held = np.array([code(f, optimum.coded[f.letter]) for f in space.factors])
        held_text = "at the optimum"
    else:
        held = np.zeros(k)
        held_text = "at their centre (coded 0)"
    coded = result.coded[space.letters].to_numpy(dtype=float)
    y = np.asarray(result.y, dtype=float)
    out = []
    off_slice = 0
    for i, j in itertools.combinations(numeric, 2):
        fi, fj = space.factors[i], space.factors[j]
        others = [f for m, f in enumerate(space.factors) if m not in (i, j)]

        def predict(X, Y, i=i, j=j, fi=fi, fj=fj):
            pts = np.tile(held, (X.size, 1))
            pts[:, i] = fi.encode(X.ravel())
            pts[:, j] = fj.encode(Y.ravel())
            return result.predict_coded(pts)

        X, Y, Z = P.evaluate_on_grid(predict, (fi.low, fi.high), (fj.low, fj.high), n=30)
        at_held = np.ones(len(y), dtype=bool)
        for m in range(k):
            if m not in (i, j):
                at_held &= np.abs(coded[:, m] - held[m]) < 1e-9
        pts3 = np.column_stack([result.data[fi.name].to_numpy(dtype=float)[at_held],
                                result.data[fj.name].to_numpy(dtype=float)[at_held], y[at_held]])
        pts2 = np.column_stack([result.data[fi.name].to_numpy(dtype=float),
                                result.data[fj.name].to_numpy(dtype=float)])
        held_values = [(f, f.levels[int(held[space.letters.index(f.letter)])] if categoric[space.letters.index(f.letter)]
                        else float(f.decode(held[space.letters.index(f.letter)]))) for f in others]
        held_desc = ", ".join(f"{f.letter} ({f.name}) = {fmt_num(v)}" for f, v in held_values)
        hold_sentence = (f"Other factors held {held_text}: {held_desc}." if others else "")
        fig_note = ("held: " + ", ".join(f"{f.letter} = {fmt_num(v)}" for f, v in held_values)) if others else None
        pair = f"{fi.letter}{fj.letter}"
        title = f"{result.response} over {fi.letter} ({fi.name}) and {fj.letter} ({fj.name})"
        mark = mark3 = None
        star = ""
        if optimum is not None:
            ox, oy = float(optimum.actual[fi.name]), float(optimum.actual[fj.name])
            if _on_slice(optimum, space, held, i, j):
                mark, mark3 = (ox, oy), (ox, oy, float(optimum.predicted))
                star = " Star: the optimum, which lies on this slice."
            else:
                off_slice += 1
                where = ", ".join(f"{f.letter} = {fmt_num(optimum.actual[f.name])}" for f in others)
                star = (f" The optimum is not on this slice (it has {where}), so it is not marked here; "
                        "hold the other factors at the optimum to see it.")
        surf = P.render(
            P.surface_3d(X, Y, Z, points=pts3, xlabel=f"{fi.letter}: {fi.name}", ylabel=f"{fj.letter}: {fj.name}",
                         zlabel=result.response, note=fig_note, mark=mark3, mark_label="optimum"),
            f"surface-{pair}", f"3-D surface, {title}",
            f"{hold_sentence} Red points: the {_runs(int(at_held.sum()))} made at those settings of the other "
            f"factors, at their observed response.{star}", "png")
        cont = P.render(
            P.contour_plot(X, Y, Z, points=pts2, xlabel=f"{fi.letter}: {fi.name}", ylabel=f"{fj.letter}: {fj.name}",
                           zlabel=result.response, mark=mark, mark_label="optimum", note=fig_note),
            f"contour-{pair}", f"Contour, {title}",
            f"{hold_sentence} Red points: all {len(y)} design points projected onto this pair.{star}", "svg")
        out.append({"pair": pair, "surface": surf, "contour": cont})
    note = (f"Every pair of the {len(numeric)} numeric factors: {len(out)} surfaces and {len(out)} contours of the fitted model, "
            f"with the other factors held {held_text}.")
    if optimum is not None and off_slice:
        note += (f" The optimum's star appears only on slices that contain it ({len(out) - off_slice} of "
                 f"{len(out)} here).")
    return out, note


def mixture_figures(result, optimum) -> tuple[list[dict], str]:
    """A mixture fit's static figures: the ternary contour of the first three components (a
    slice through the region's centroid for more than three, said on the figure and in the
    caption; process factors at their centre) and the trace plot along the Cox direction
    from the region's centroid (:mod:`rsm_lrg.model.readings.mixture_trace`)."""
    from ..factors import MixtureComponent
    from ..model.readings.mixture_trace import mixture_trace, ternary_slice
    from . import plots as P

    space = result.space
    comps = [f for f in space.factors if isinstance(f, MixtureComponent)]
    out = []
    tr = mixture_trace(result)
    ref = ", ".join(f"{k} = {fmt_num(v)}" for k, v in tr.reference.items())
    trace = P.render(
        P.trace_plot({f"{f.letter}: {f.name}": (tr.deviation[f.name], tr.predicted[f.name]) for f in comps},
                     xlabel="Deviation from the reference blend (real proportion)", ylabel=str(result.response)),
        "trace", f"Trace plot of {result.response} (Cox direction)",
        f"Each component moved from the reference blend ({ref}; the centroid of the region) along its Cox "
        "direction, the others giving way in proportion to their shares, over the range the region allows.", "svg")
    if len(comps) >= 3:
        sl = ternary_slice(result, n=60)
        a, b, c = sl["components"]
        held = [(k, v) for k, v in sl["held"].items()]
        note = ("slice: " + ", ".join(f"{k} = {fmt_num(v)}" for k, v in held)) if held else None
        X = result.data
        pts = None
        if X is not None and all(n in X.columns for n in (a, b, c)):
            share = X[a].to_numpy(dtype=float) + X[b].to_numpy(dtype=float) + X[c].to_numpy(dtype=float)
            on = np.ones(len(X), dtype=bool)
            for k, v in held:
                on &= np.abs(X[k].to_numpy(dtype=float) - v) <= 1e-9 * max(abs(v), 1.0)
            if on.any():
                pts = np.column_stack([X[n].to_numpy(dtype=float)[on] for n in (a, b, c)]) / share[on, None]
        mark = None
        if optimum is not None and all(abs(float(optimum.actual[k]) - v) <= 1e-9 for k, v in held):
            mark = np.array([float(optimum.actual[n]) for n in (a, b, c)]) / sl["share"]
        letter = {f.name: f.letter for f in space.factors}
        tern = P.render(
            P.ternary_contour(sl["fractions"], sl["predicted"], labels=[f"{letter[n]}: {n}" for n in (a, b, c)],
                              share=sl["share"], points=pts, zlabel=str(result.response), mark=mark, note=note),
            "ternary", f"Ternary contour of {result.response}",
            ("The fitted model over the triangle of the three components; white: outside the region of the bounds. "
             + (f"A slice of the simplex: {', '.join(f'{k} = {fmt_num(v)}' for k, v in held)} (the region's centroid). "
                if held else "") + ("Star: the optimum." if mark is not None else "")), "png")
        out.append({"pair": "ternary", "surface": tern, "contour": trace})
        note_text = "The ternary contour of the fitted blend model and its trace plot."
    else:
        out.append({"pair": "trace", "surface": trace, "contour": None})
        note_text = "A two-component blend: the trace plot (a ternary contour needs three components)."
    return out, note_text


# -- sections: stationary point and optimum ------------------------------------------------------

def _stationary(result) -> tuple[dict | None, str]:
    sp = result.stationary_point
    if sp is None or sp.coded is None:
        why = getattr(sp, "note", "") or "The model has no unique stationary point."
        return None, why
    rows = []
    for f in result.space.factors:
        if f.letter not in sp.coded:  # a categoric factor: the surface is at one level (see the note)
            continue
        c = float(sp.coded[f.letter])
        rows.append({"letter": f.letter, "name": f.name, "coded": c, "actual": float(sp.actual[f.name]),
                     "inside": "yes" if -1.0 <= c <= 1.0 else "no (extrapolation)"})
    kind = sp.kind or "undetermined"
    sentence = f"The stationary point of the fitted surface is a {kind}"
    sentence += ("" if sp.inside is None else (", inside the design box." if sp.inside else
                 ", outside the design box (coded cube [−1, 1]): the surface there is an extrapolation."))
    facts = [("Kind", kind), ("Predicted response there", fmt_num(sp.predicted, 5)),
             ("Eigenvalues (decreasing)", ", ".join(fmt_num(e, 4) for e in (sp.eigenvalues or ())))]
    if sp.note:
        facts.append(("Note", sp.note))
    return {"rows": rows, "sentence": sentence, "facts": facts}, ""


def _number_or_level(v):
    """A setting as shown: a float, or the level of a categoric factor as text."""
    return v if isinstance(v, str) else float(v)


def optimum_section(result, optimum) -> tuple[dict | None, str]:
    if optimum is None:
        return None, "No optimum was computed."
    rows = [{"letter": f.letter, "name": f.name, "coded": _number_or_level(optimum.coded[f.letter]),
             "actual": _number_or_level(optimum.actual[f.name])} for f in result.space.factors]
    conf = 100 * float(optimum.confidence)
    goal = optimum.goal + (f" (target {fmt_num(optimum.target)})" if getattr(optimum, "target", None) is not None else "")
    sentence = (f"Goal: {goal} {result.response} inside the factor box. Predicted {result.response} at the "
                f"optimum: {fmt_num(optimum.predicted, 5)}.")
    facts = [("Predicted", fmt_num(optimum.predicted, 5)),
             (f"{conf:g} % confidence interval (mean)", f"{fmt_num(optimum.ci[0], 5)} … {fmt_num(optimum.ci[1], 5)}"),
             (f"{conf:g} % prediction interval (one new run)", f"{fmt_num(optimum.pi[0], 5)} … {fmt_num(optimum.pi[1], 5)}")]
    for w in getattr(optimum, "warnings", ()) or ():
        facts.append(("Note", w))
    return {"rows": rows, "sentence": sentence, "facts": facts}, ""


# -- the page -----------------------------------------------------------------------------------

def table_sections(result, source_name: str | None, optimum) -> dict:
    """The parts of a report that are text and tables (no figures): shared by the full
    report and the notebook face."""
    space = result.space
    letters = space.letters
    anova_rows, anova_notes = _anova_rows(result)
    stats_rows, stats_notes = _statistics(result)
    coded_eq = _equation_terms(result, "coded", list(letters))
    actual_eq = _equation_terms(result, "actual", list(space.names), "·")
    pe_df = result.pure_error.df if result.pure_error is not None else 0
    summary = [
        ("Response", result.response),
        ("Data", source_name or "a DataFrame"),
        ("Runs", str(result.n)),
        ("Factors", ", ".join(f"{f.letter} = {f.name}" for f in space.factors)),
        ("Model", f"{result.model} ({len(result.terms)} terms, fitted by {result.reading.fitted_by(result)})"),
        ("Block", result.block or "none"),
        ("Replicated settings", f"{pe_df} degrees of freedom of pure error" if pe_df else "none (no lack-of-fit test)"),
        ("R² / adjusted R² / predicted R²",
         " / ".join(fmt_num(v, 4) for v in (result.statistics.r2, result.statistics.adj_r2, result.statistics.pred_r2))),
        ("Model F-value, p-value",
         next((f"{fmt_f(r['f'])}, {fmt_p(r['p'])}" for r in anova_rows if r["source"] == "Model"), "—")),
    ]
    reading = result.reading  # least squares, or REML: no sums of squares, the variance components
    if reading.lack_of_fit_note is not None:
        summary[6] = ("Lack of fit", reading.lack_of_fit_note)
    components = reading.variance_components(result)
    if components:
        summary.insert(5, ("Variance components (95 % CI, Wald on the log scale)", "; ".join(
            f"{k} {fmt_num(c.variance, 4)} ({fmt_num(c.ci_low, 3)} .. {fmt_num(c.ci_high, 3)})"
            for k, c in components.items())))
    caption = (f"ANOVA for the {result.model} model of {result.response} "
               "(partial sums of squares, Type III), laid out like Table 5.")
    if result.tests:  # Kenward-Roger tests in the ANOVA's place
        caption = (f"Fixed effects of the REML fit of {result.response}: Kenward–Roger F tests, each term's columns "
                   "jointly (Type III); no sums of squares. df is the numerator df; the Kenward–Roger den df are "
                   + ", ".join(f"{t.term} {fmt_num(t.den_df, 4)}" for t in result.tests) + ".")
    if optimum is not None:
        summary.append(("Optimum (" + optimum.goal + ")",
                        ", ".join(f"{n} = {fmt_num(v, 4)}" for n, v in optimum.actual.items())
                        + f" → {result.response} = {fmt_num(optimum.predicted, 4)}"))
    stationary, stationary_missing = _stationary(result)
    if result.block is not None and result.block_effects:
        summary.append(("Block effects", ", ".join(f"{k} ({result.block_levels.get(k, k)}) = {fmt_num(v, 4)}"
                                                  for k, v in result.block_effects.items())))
    return {
        "summary": summary,
        "factors": [{"letter": f.letter, "name": f.name, "low": f.low, "center": f.center, "high": f.high}
                    if getattr(f, "kind", "numeric") != "categoric" else
                    {"letter": f.letter, "name": f.name, "low": f.levels[0], "center": "categoric: " + ", ".join(f.levels),
                     "high": f.levels[-1]}
                    for f in space.factors],
        "anova": {"rows": anova_rows, "notes": anova_notes,
                  "caption": caption,
                  "legend": "** p < 0.01, * 0.01 ≤ p < 0.05 (see the notes)."},
        "statistics": stats_rows,
        "statistics_notes": stats_notes,
        "coefficients": {"rows": _coefficients(result), "ci_label": "95 % CI"},
        "equations": [
            {"id": "equation-coded", "title": "In terms of coded factors", "lhs": result.response, "rhs": coded_eq,
             "note": "Coded factors: " + ", ".join(
                 f"{f.letter} = ({f.name} − {fmt_num(f.center)}) / {fmt_num(f.half_range)}"
                 if getattr(f, "kind", "numeric") != "categoric" else
                 f"{f.letter} = {f.name} (categoric, effect coded: {f.letter}[level] is 1 at that level, −1 at "
                 f"{f.levels[-1]}, 0 otherwise)"
                 for f in space.factors)
                     + ". Use it to compare effects: the coefficients are on one scale."},
            {"id": "equation-actual", "title": "In terms of actual factors", "lhs": result.response, "rhs": actual_eq,
             "note": "Actual factors in the units of the data columns. The same polynomial; do not compare "
                     "these coefficients with one another (their units differ)."},
        ],
        "stationary": stationary,
        "stationary_missing": stationary_missing,
    }


def report_context(result, *, title: str | None = None, source_name: str | None = None,
                   goal: Any = "minimize", hold: str = "center", optimum=None) -> dict:
    """Everything the fit-report template shows, as plain values (no HTML).

    Parameters
    ----------
    result : rsm_lrg.model.FitResult
    title : str, optional
        Page title (default ``"Response surface report: <response>"``).
    source_name : str, optional
        Where the data came from (a file name), shown in the summary.
    goal : str or None
        Goal for the optimum section (``"minimize"``, ``"maximize"``, ``"target=V"``);
        ``None`` leaves the section out. Ignored when ``optimum`` is given.
    hold : {"center", "optimum"}
        Where the factors not on a surface's axes are held.
    optimum : rsm_lrg.optimize.OptimumResult, optional
        A ready optimum (otherwise ``result.optimize(goal)``).

    Returns
    -------
    dict
        The template's values (plain Python, no HTML).
    """
    if hold not in ("center", "optimum"):
        raise ValueError(f"hold must be 'center' or 'optimum', not {hold!r}")
    if optimum is None and goal is not None:
        optimum = result.optimize(goal=goal)
    space = result.space
    _, runs_from = run_numbers(result)
    ctx = table_sections(result, source_name, optimum)
    diagnostics, diag_note = diagnostics_section(result)
    surfaces, surf_note = surface_figures(result, hold, optimum)
    opt, opt_missing = optimum_section(result, optimum)
    return ctx | {
        "title": title or f"Response surface report: {result.response}",
        "subtitle": (f"{result.model.capitalize()} model of {result.response} in {len(space)} factors from "
                     f"{result.n} runs" + (f" ({source_name})" if source_name else "") + "."),
        "toc": [(sid, _SECTION_TITLES[sid]) for sid in SECTION_IDS],
        "data": data_table(result, runs_from),
        "diagnostics": diagnostics,
        "diagnostics_note": diag_note,
        "surfaces": surfaces,
        "surfaces_note": surf_note,
        "optimum": opt,
        "optimum_missing": opt_missing,
    }


def notebook_html(result, *, source_name: str | None = None) -> str:
    """The notebook face of a fit (``FitResult._repr_html_``): summary, ANOVA, fit
    statistics, coefficients, equations and the stationary point, as one HTML fragment with
    its own scoped style. No figures (they are what makes the full report large and slow);
    :func:`to_html` (``result.to_html()``) gives the full report with every figure.

    Parameters
    ----------
    result : FitResult
        The fit.
    source_name : str, optional
        The data's name, as shown.

    Returns
    -------
    str
        The HTML fragment.
    """
    from .html import environment

    ctx = table_sections(result, source_name, None)
    ctx["title"] = f"{result.model.capitalize()} fit of {result.response}: {result.n} runs, {len(result.space)} factors"
    ctx["mixture_effects"] = []
    if result.space.has_components:  # the effects along the Cox direction (rsm_lrg.model.readings.mixture_trace)
        from ..model.readings.mixture_trace import mixture_trace

        tr = mixture_trace(result)
        letter = {f.name: f.letter for f in result.space.factors}
        ctx["mixture_effects"] = [{"component": f"{letter[c]}: {c}", "reference": tr.reference[c], "low": tr.low[c],
                                   "high": tr.high[c], "effect": tr.effects[c], "gradient": tr.gradients[c]}
                                  for c in tr.effects]
    return environment().get_template("notebook.html.j2").render(**ctx)


def to_html(result, *, title: str | None = None, source_name: str | None = None, goal: Any = "minimize",
            hold: str = "center", optimum=None) -> str:
    """The self-contained HTML report of a fit (a string).

    See :func:`report_context` for the parameters. The page has no scripts, makes no
    network requests and inlines its figures (``data:`` URIs) and CSS.

    Parameters
    ----------
    result : FitResult
        The fit.
    title, source_name, goal, hold, optimum
        As for :func:`report_context`.

    Returns
    -------
    str
        The HTML page.
    """
    ctx = report_context(result, title=title, source_name=source_name, goal=goal, hold=hold, optimum=optimum)
    return render_page("fit_report.html.j2", **ctx)


def write_report(result, path, *, force: bool = False, title: str | None = None, source_name: str | None = None,
                 goal: Any = "minimize", hold: str = "center", optimum=None) -> Path:
    """Write :func:`to_html` to ``path`` atomically (:func:`rsm_lrg.io.write_output`).

    An existing file is kept unless ``force=True`` (then ``InputError``, a ValueError).
    Returns the path written.

    Parameters
    ----------
    result : FitResult
        The fit.
    path : str or pathlib.Path
        The page to write.
    force : bool, default False
        Replace an existing file.
    title, source_name, goal, hold, optimum
        As for :func:`report_context`.

    Returns
    -------
    pathlib.Path
        The path written.
    """
    from ..io import check_output, write_output

    p = Path(path)
    check_output(p, force=force)  # fail before the figures are drawn
    html = to_html(result, title=title, source_name=source_name, goal=goal, hold=hold, optimum=optimum)
    return write_output(p, html, force=force)
