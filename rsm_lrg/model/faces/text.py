"""The text face of a fit: Design-Expert style tables (the paper's Table 5 layout).

Computes nothing of its own; it formats what :class:`~rsm_lrg.model.fit.FitResult` holds.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ...present import ROUND_OFF, format_g, format_p, table_records, text_table
from ...present import clean as _clean
from ..readings.anova import TOTAL_ROWS
from .summary_data import summary_data

__all__ = ["format_summary", "format_anova", "format_equation", "equation_terms", "EquationTerm", "format_g",
           "EQUATION_ACCURACY"]


def _p(p) -> str:
    return format_p(p, style="ascii")


def format_anova(result, alpha: float = 0.05, records=None) -> str:
    """The ANOVA (Type III partial sums of squares) like Table 5, with significance notes
    (``records``: the rows of ``result.anova_rows`` as :func:`rsm_lrg.present.table_records` gives
    them, when already read)."""
    rows = []
    records = table_records(result.anova_rows) if records is None else records
    total = [r.sum_sq for r in records if r.source in TOTAL_ROWS]
    scale = float(total[0]) if total else 0.0
    for r in records:
        mark = ""
        if r.p == r.p and r.source not in ("Residual", "Pure Error", "Block", *TOTAL_ROWS):
            if r.source == "Lack of Fit":
                mark = "not significant" if r.p >= alpha else "significant"
            elif r.source == "Model":
                mark = "significant" if r.p < alpha else "not significant"
            else:
                mark = "*" if r.p < alpha else ""
        ss, ms = _clean(r.sum_sq, scale), _clean(r.mean_sq, scale)
        f = 0.0 if (ss == 0.0 and r.f == r.f) else r.f
        rows.append([r.source, format_g(ss), r.df, format_g(ms), format_g(f), _p(r.p), mark])
    head = ["Source", "Sum of Squares", "df", "Mean Square", "F-value", "p-value", ""]
    return text_table(head, rows, ["<", ">", ">", ">", ">", ">", "<"])


def format_mixed(result, alpha: float = 0.05) -> list[str]:
    """The REML part of the text: variance components and the Kenward–Roger F tests of the
    model terms (in place of the least-squares ANOVA)."""
    mm = result.mixed
    if mm.kind in ("whole_plot", "block"):
        out = [f"REML variance components (random intercept per {'whole plot' if mm.kind == 'whole_plot' else 'block'}: "
               f"{mm.column!r}, {mm.n_groups} groups; 95 % CI Wald on the log scale)"]
    else:
        out = [f"REML variance components ({mm.describe()}; 95 % CI Wald on the log scale)"]
    rows = []
    for name, c in mm.variance_components.items():
        rows.append([name, format_g(c.variance), format_g(math.sqrt(c.variance)), format_g(c.ci_low),
                     format_g(c.ci_high)])
    out.append(text_table(["Component", "Variance", "Std Dev", "95% CI Low", "95% CI High"], rows))
    out.append("")
    out.append("Fixed effects: Kenward-Roger F tests (Type III, each term's columns jointly)")
    rows = [[t.term, t.num_df, format_g(t.den_df), format_g(t.f), _p(t.p), "*" if t.p == t.p and t.p < alpha else ""]
            for t in result.tests]
    out.append(text_table(["Term", "num df", "den df", "F-value", "p-value", ""], rows,
                          ["<", ">", ">", ">", ">", "<"]))
    out.append("")
    return out


#: Accuracy the printed equations promise: evaluated anywhere in the factor box, they
#: reproduce the model's prediction to ``EQUATION_ACCURACY`` times the largest fitted
#: response (so to 1e-6 relative wherever the prediction is a tenth of that or more).
EQUATION_ACCURACY = 1e-7


@dataclass(frozen=True)
class EquationTerm:
    """One printed term of a fitted equation.

    Attributes
    ----------
    name : str
        Design-Expert term name (``"Intercept"``, ``"A"``, ``"AB"``, ``"A^2"``).
    powers : tuple of int
        Exponent of each factor.
    value : float
        Coefficient [response units per unit of the term].
    text : str
        ``|value|`` with as many significant digits as :data:`EQUATION_ACCURACY` needs
        (6 to 17), trailing zeros dropped.
    diff : tuple of int
        ``(i, j)`` for a Scheffé full-cubic term ``AB(A-B)``: the monomial of ``powers``
        times ``x_i - x_j`` (:attr:`rsm_lrg.terms.Term.diff`); ``()`` otherwise.
    """

    name: str
    powers: tuple
    value: float
    text: str
    diff: tuple = ()


def _coefficient_columns(result) -> dict:
    """``term`` (names) and the coefficient columns of a fit, from ``coefficient_columns``
    (no DataFrame, no actual units) where the result has it, else from its ``coefficients``."""
    cols = getattr(result, "coefficient_columns", None)
    if cols is not None:
        return cols
    co = result.coefficients
    return {"term": co.index.tolist(), **{c: co[c].to_numpy() for c in co.columns}}


def equation_terms(result, units: str = "coded", level=None) -> list[EquationTerm]:
    """The terms of the fitted equation in ``"coded"`` or ``"actual"`` units — the one rule
    every equation writer uses (issue 10, item 4).

    Coded coefficients that are round-off (``|b| <= ROUND_OFF * max |b|``; all coded terms
    share the response's units, so that comparison means something) are set to zero; the
    actual-units coefficients are the exact expansion of that coded polynomial
    (:func:`~rsm_lrg.model.fit.actual_coefficients`), so a term is left out only when its
    coefficient is exactly zero by construction — never by comparing coefficients across
    units. Each coefficient gets ``d`` significant digits, the least (6 to 17) with
    ``5·10^-d · p · |c| · Π M_i^e_i <= EQUATION_ACCURACY · Y``, where ``M_i`` is the largest
    ``|x_i|`` in the factor box (1 when coded), ``p`` the number of terms and ``Y`` the largest
    ``|ŷ|`` over the runs: the rounding of all printed coefficients together then moves a
    prediction in the box by at most ``EQUATION_ACCURACY · Y``.

    With categoric factors the coded equation has one term per effect-coded column
    (``"C[rms]"``) and the actual-units equation is the polynomial in the numeric factors
    at one combination of levels, ``level`` (``{"stage": "rms"}``; the first levels by
    default), as Design-Expert prints one equation per level.
    """
    from ..build.terms import parse_term
    from ..readings.actual import actual_coefficients, actual_equations

    if units not in ("coded", "actual"):
        raise ValueError(f"units must be 'coded' or 'actual', not {units!r}")
    co = _coefficient_columns(result)
    coded = {k: float(v) for k, v in zip(co["term"], co["coded"].tolist())}
    big = max((abs(v) for v in coded.values() if math.isfinite(v)), default=0.0)
    coded = {k: (0.0 if abs(v) <= ROUND_OFF * big else v) for k, v in coded.items()}
    letters = result.space.letters
    col_terms = {c: t for t in result.terms for c in t.columns}
    if units == "coded":
        values, mags = coded, [1.0] * len(letters)
    else:
        if result.space.has_components:  # the Scheffé polynomial in real proportions
            from ..build.mixture import pseudo_to_actual

            values = pseudo_to_actual(coded, result.terms, result.space)
        elif result.space.has_categoric:
            chosen = dict(level or {})
            values = next(eq for setting, eq in actual_equations(result, coded)
                          if all(setting[k] == v for k, v in chosen.items()))
        else:
            values = actual_coefficients(coded, result.terms, result.space)
        mags = []
        for f in result.space.factors:  # the box and the runs (a CCD's axial runs lie outside the box)
            if f.kind == "categoric":
                mags.append(1.0)
                continue
            # the box and the runs beyond it (a CCD's axial runs)
            mags.append(max(abs(f.low), abs(f.high), result.run_extent[f.letter] * f.half_range + abs(f.center)))
    if result.fitted is not None:
        fitted = [abs(float(v)) for v in result.fitted if math.isfinite(float(v))]
        scale = max(fitted, default=0.0)
    else:  # the range of the fitted values from the second pass
        sums = result.least_squares.pass_sums
        scale = max(abs(sums.fitted_min), abs(sums.fitted_max))
    out = []
    for name, v in values.items():
        term = col_terms[name] if name in col_terms else parse_term(name, letters)
        powers, diff = term.powers, term.diff
        if v == 0.0 and name != "Intercept":
            continue
        # a full-cubic AB(A-B) is as large as A^2B (each of its two monomials)
        size = abs(v) * math.prod(m ** e for m, e in zip(mags, term.monomials[0][1]))
        if v == 0.0 or not math.isfinite(v):
            digits = 6
        elif scale > 0 and math.isfinite(size):
            need = 5.0 * len(values) * size / (EQUATION_ACCURACY * scale)
            digits = min(max(math.ceil(math.log10(need)), 6), 17) if need > 0 else 6
        else:
            digits = 17
        out.append(EquationTerm(name=name, powers=tuple(powers), value=float(v), text=format_g(abs(v), digits, trim=True),
                                diff=tuple(diff)))
    return out


def format_equation(result, units: str = "coded") -> str:
    """The fitted equation in ``"coded"`` (letters) or ``"actual"`` (factor names) terms,
    one term a line, as :func:`equation_terms` gives them; in actual units with categoric
    factors, one equation per combination of their levels ("stage = rfcms:")."""
    if units == "actual" and result.space.has_categoric:
        blocks = []
        for setting in result.space.level_combinations():
            head = ", ".join(f"{k} = {v}" for k, v in setting.items())
            blocks.append(f"{head}:\n" + _equation_lines(result, units, setting))
        return "\n".join(blocks)
    return _equation_lines(result, units, None)


def _equation_lines(result, units: str, level) -> str:
    lines = [f"{result.response} ="]
    for t in equation_terms(result, units, level):
        if t.name == "Intercept":
            label = ""
        elif units == "coded":
            label = f" * {t.name}"
        else:
            parts = [f.name if e == 1 else f"{f.name}^{e}" for e, f in zip(t.powers, result.space.factors) if e]
            if t.diff:  # x1 * x2 * (x1 - x2)
                a, b = (result.space.factors[i].name for i in t.diff)
                parts.append(f"({a} - {b})")
            label = " * " + " * ".join(parts)
        sign = "-" if t.value < 0 else "+"
        lines.append(f"  {sign} {t.text}{label}")
    return "\n".join(lines)


def _anova_lines(result, sd) -> list[str]:
    """The least-squares ANOVA with its title and notes."""
    return [sd.anova_title, format_anova(result, records=sd.anova_records or None), "", *sd.anova_notes, ""]


def _statistics_lines(result, sd) -> list[str]:
    """The fit statistics under the ANOVA (R², PRESS, adequate precision ...)."""
    s = result.statistics
    stat_rows = [
        ["Std. Dev.", format_g(s.std_dev), "R²", format_g(s.r2)],
        ["Mean", format_g(s.mean), "Adjusted R²", format_g(s.adj_r2)],
        ["C.V. %", format_g(s.cv_percent), "Predicted R²", format_g(s.pred_r2)],
        ["PRESS", format_g(s.press), "Adeq Precision", format_g(s.adeq_precision)],
    ]
    return ["Fit statistics", text_table(["", "", "", ""], stat_rows, ["<", ">", "<", ">"]).split("\n", 2)[2],
            *sd.statistics_notes, ""]


def _mixed_lines(result, sd) -> list[str]:
    """A REML fit's Kenward-Roger tests and variance components with the notes."""
    return [*format_mixed(result), *sd.anova_notes, ""]


#: The text of each section a fit's reading lists (``result.reading.text_sections``).
_SECTIONS = {"anova": _anova_lines, "statistics": _statistics_lines, "mixed": _mixed_lines}


def format_summary(result) -> str:
    """The whole text report of a fit."""
    out = []
    sp = result.space
    out.append(f"Response: {result.response}   runs: {result.n}   model: {result.model}"
               + (f"   blocks: {result.block} ({len(result.block_effects)})" if result.block else ""))
    mixture = result.space.has_components
    if mixture:
        f0 = sp.factors[0]
        out.append(f"Mixture components (total {format_g(getattr(f0, 'total', 1.0), 6)}; coded as L-pseudo components "
                   f"(x - L) / {format_g(getattr(f0, 'pseudo_range', 1.0), 6)}):")
    else:
        out.append("Factors (coded -1 .. +1):")
    for f in sp.factors:
        if mixture and not hasattr(f, "pseudo_range"):
            out.append(f"  {f.letter}: {f.name}  process factor, coded -1 .. +1 from {format_g(f.low, 6)} .. "
                       f"{format_g(f.high, 6)}")
        elif mixture:
            out.append(f"  {f.letter}: {f.name}  L = {format_g(getattr(f, 'lower', 0.0), 6)}, "
                       f"upper {format_g(getattr(f, 'upper', 1.0), 6)}")
        elif f.kind == "categoric":
            out.append(f"  {f.letter}: {f.name}  categoric, levels {', '.join(f.levels)} (effect coded)")
        else:
            out.append(f"  {f.letter}: {f.name}  {format_g(f.low, 6, trim=True)} .. {format_g(f.high, 6, trim=True)}")
    out.append("")
    sd = summary_data(result)  # the one summary every face renders
    for section in result.reading.text_sections:  # what the fit's reading has: its ANOVA and statistics,
        out.extend(_SECTIONS[section](result, sd))  # or the Kenward-Roger tests and variance components
    out.append("Coefficients in terms of coded factors (95 % CI)")
    rows = []
    co = _coefficient_columns(result)
    cscale = max((abs(v) for v in co["coded"].tolist() if v == v), default=math.nan)  # as pandas' max: NaN left out
    for name, b, se, lo, hi, vif, p in zip(co["term"], *(co[c].tolist() for c in
                                                         ("coded", "std_error", "ci_low", "ci_high", "vif", "p"))):
        rows.append([name, format_g(_clean(b, cscale)), format_g(se), format_g(lo), format_g(hi),
                     (f"{vif:.2f}" if vif == vif else ""), _p(p)])
    out.append(text_table(["Term", "Estimate", "Std Error", "95% CI Low", "95% CI High", "VIF", "p-value"], rows))
    multi = {k: v for k, v in (getattr(result, "term_vif", None) or {}).items()
             if next(t for t in result.terms if t.name == k).df > 1}
    if multi:
        out.append("Generalised VIF of the multi-df terms (Fox & Monette): "
                   + ", ".join(f"{k} {v:.2f}" for k, v in multi.items()))
    if result.block_effects:
        out.append("Block effects (sum to zero): " + ", ".join(
            f"{k} ({result.block_levels[k]}) {format_g(v)}" for k, v in result.block_effects.items()))
    out.append("")
    out.append("Final equation in terms of L-pseudo components" if mixture else "Final equation in terms of coded factors")
    out.append(format_equation(result, "coded"))
    out.append("")
    out.append("Final equation in terms of real proportions" if mixture else "Final equation in terms of actual factors")
    out.append(format_equation(result, "actual"))
    out.append("")
    sp_ = result.stationary_point
    out.append("Canonical analysis")
    if mixture:
        out.append("  not applicable to a mixture model (the components are not free: they sum to the total)")
    elif sp_.eigenvalues is None:
        out.append(f"  {sp_.note}")
    else:
        if sp_.coded is None:
            out.append(f"  {sp_.note}")
        else:
            out.append("  Stationary point (coded):  " + ", ".join(f"{k} = {format_g(v, 6, trim=True)}" for k, v in sp_.coded.items()))
            out.append("  Stationary point (actual): " + ", ".join(f"{k} = {format_g(v, 6, trim=True)}" for k, v in sp_.actual.items()))
            out.append(f"  Predicted response there:  {format_g(sp_.predicted, 6, trim=True)}"
                       + ("" if sp_.inside else "  (outside the coded cube: extrapolation)"))
            out.append(f"  Kind: {sp_.kind}")
            if sp_.note:
                out.append(f"  Note: {sp_.note}")
        out.append("  Eigenvalues: " + ", ".join(format_g(v, 6, trim=True) for v in sp_.eigenvalues))
    return "\n".join(out) + "\n"
